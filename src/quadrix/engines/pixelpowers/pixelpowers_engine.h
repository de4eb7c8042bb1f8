// Engine `pixelpowers`: CSG by tree normalisation and z-buffer paring on a simulated Pixel-Powers
// logic-enhanced frame buffer (seeds 003 and 004; DESIGN.md; docs/pixelpowers.md).
//
// Host: compiler.h (normal form → display-theorem terms → patch programs). Machine: machine.h
// (per-pixel ZTEMP/ZMIN/F1–F3/COLOR, run data-parallel in tiles).
//
// Engine options (RenderOptions::engineOptions, CLI --engine-opt key=value):
//   mode=exact|approx   exact: the extended machine with a per-pixel square root (default);
//                       approx: the paper's machine, depths from parabolic-strip envelopes
//   tolerance=X         approx: depth tolerance of a strip envelope, device z units (default 0.25)
//   shading=exact|paper exact normals at ZMIN, or the paper's approximate shading (seed 004
//                       §III step 4) broadcast as kNLoad (default: paper in approx, else exact)
//   depth-bits=N        fixed-point ZTEMP/ZMIN words of N bits (8..52; default off = doubles)
//   max-products=N      normal-form explosion guard per solid (default 20000)
//   max-instructions=N  program size guard per scene (default 1000000); a solid past it is
//                       not drawn and the report says so
//   max-strips=N        approx: strips per sheet at most (default 64)
//   compare=on|off      also render with raycast and report coverage/solid agreement and the depth
//                       error (default: on in approx mode, off in exact mode)
// RenderStats::warnings names every solid not drawn (normal-form explosion guard, program size
// guard) and every accuracy guard that fired (strips capped, depth-bits without a finite range).
// RenderStats: counters (products, terms, patches, opcodes, equations, instructions executed,
// pixel operations, per-pixel bits, …) and a report laid out like seed 004 Table 1.
#pragma once

#include <memory>

#include "quadrix/engines/engine.h"

namespace quadrix {

std::unique_ptr<Engine> MakePixelPowersEngine();

}  // namespace quadrix
