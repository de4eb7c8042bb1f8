// The straightforward integer reference of the patch processor's arithmetic: the same quantities
// as PatchProcessor (patch_processor.h), computed pixel by pixel from closed forms with wide
// integers, with none of the hardware's structure:
//   EP1:  L0 + i·A + j·B                                 mod 2^d
//   EP2:  q0 + j·r0 + 2B·j(j+1)/2 + i·(s0 + j·c) + 2A·i(i+1)/2   mod 2^2d (fixed_point.h)
//   SRE:  the integer square root (floor) of the unsigned word
//   mul:  floor(a·b / 2^n) by a plain product and an arithmetic shift
//   planes: the if/else algorithm of §1.3.2 with the sign-bit tie rule (a zero difference counts
//           as positive), not the logic equations.
// Its output must equal the emulator's bit for bit on every pixel.
#pragma once

#include <cstdint>

#include "quadrix/engines/patch/patch_processor.h"

namespace quadrix::patch {

// Signals of pixel (i, j) of the window (0-based, relative to the window's corner).
PixelSignals ReferencePixel(const FixedPatch& patch, const DatapathWidths& widths, int i, int j);

// floor(sqrt(v)) for any unsigned 64-bit v.
std::uint64_t IntegerSqrt(std::uint64_t v);

}  // namespace quadrix::patch
