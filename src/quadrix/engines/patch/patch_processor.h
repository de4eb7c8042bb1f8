// The whole quadric patch processor of seed 000 Fig. 1.4, emulated bit for bit: 8 EP1, 1 EP2,
// the square-root extractor, the bounding-plane logic and 3 multipliers, fed with a FixedPatch
// (the RAM contents the host computes, host_setup.h) and producing one PixelSignals per pixel of
// the window, line by line.
//
// Datapath per pixel (widths d = depthBits, n = normalBits, s = d - n):
//   F2      = EP2                                  (2d bits)
//   root    = SRE(F2 as an unsigned 2d-bit word)   (d bits, unsigned)
//   F1      = EP1                                  (d bits)
//   ZF, ZB  = F1 - root, F1 + root                 (d-bit adders)
//   ZPi     = EP1 of plane unit i; sign bits of ZPi, ZPi - ZF, ZPi - ZB, CPi and the host's
//             (CPi = 0?) flag go to the cutting-plane logic (bounding_plane.h)
//   EF, EB  = AND over the units of the negated disables
//   Z'      = EF ? ZF : ZB;   ZOUT = (EF'·EB' + sgn F2) ? ZMAX : Z'   (ZMAX = 2^(d-1) - 1)
//   NX      = (NXBASE >> s) + mul(Z' >> s, e),  NY with f, NZ with 2c    (n bits; mul keeps the
//             n most significant bits of the 2n-bit product, fixed_point.h); all three are
//             negated when EF = 0 and EB = 1 (the back sheet, §1.4.3).
// Unused plane units hold a perpendicular plane with ZP = 0, which never cuts.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "quadrix/engines/patch/fixed_point.h"
#include "quadrix/engines/patch/patch.h"

namespace quadrix::patch {

struct PlaneUnitProgram {
    Ep1Program zp;
    bool perpendicular = true;  // the host's (CP = 0?) flag
    bool sgnCp = false;         // CP < 0 (a front plane)
    bool operator==(const PlaneUnitProgram&) const = default;
};

// Everything the host loads for one patch.
struct FixedPatch {
    PixelWindow window;
    Ep2Program f2;
    Ep1Program f1;
    std::array<PlaneUnitProgram, kMaxPlanes> planes{};
    Ep1Program nxBase, nyBase, nzBase;    // with NormalGuardBits() fraction bits
    std::int64_t e = 0, f = 0, twoC = 0;  // multiplier coefficients, normalBits wide
};

// The observable signals of one pixel (all words as two's-complement values of their width;
// the root is unsigned).
struct PixelSignals {
    std::int64_t f2 = 0;
    std::int64_t root = 0;
    std::int64_t f1 = 0, zf = 0, zb = 0;
    std::array<std::int64_t, kMaxPlanes> zp{};
    bool ef = false, eb = false, sgnF2 = false;
    std::int64_t zPrime = 0, zout = 0;
    std::int64_t nx = 0, ny = 0, nz = 0;
    bool operator==(const PixelSignals&) const = default;
};

class PatchProcessor {
  public:
    explicit PatchProcessor(const DatapathWidths& widths) : widths_(widths) {}

    // Loads the RAMs and rewinds to the window's first line.
    void Load(const FixedPatch& patch);
    // Advances `lines` lines without scanning them (line steps only), to start a band of rows
    // inside the window; the result is the same as scanning them.
    void SkipLines(int lines);
    // Scans the current line into `out` (resized to the window's width) and steps to the next.
    void ScanLine(std::vector<PixelSignals>& out);
    int CurrentLine() const { return line_; }  // 0-based, relative to the window
    const DatapathWidths& Widths() const { return widths_; }

  private:
    void StepLine();

    DatapathWidths widths_;
    FixedPatch patch_;
    Ep2 f2_;
    Ep1 f1_;
    std::array<Ep1, kMaxPlanes> zp_;
    Ep1 nx_, ny_, nz_;
    int line_ = 0;
};

// ZMAX, the "no surface" depth.
std::int64_t Zmax(const DatapathWidths& widths);

}  // namespace quadrix::patch
