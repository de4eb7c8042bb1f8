// Engine `patch`: the quadric patch processor of seed 000 (Laporte et al.), in double precision
// (mode=float, default) or as a bit-exact emulation of its fixed-point datapath (mode=fixed).
//
// Every FlatBody that forms a solid on its own and consists of one quadric and at most four planes
// (after redundant planes are dropped) is converted into a patch (patch.h) and scanned over the
// projection of its bounding box; patches are z-buffered into the Frame. CSG solids of more than
// one body cannot be drawn by the patch processor: they are skipped and counted.
//
// Frame contents: depth = ZOUT (device z; in fixed mode the depth word mapped back through the
// frame's depth format), normal = the world-space unit normal obtained from the processor's
// device normal (NX, NY, NZ) by the same covector pull-back as FlatScene::WorldNormal (in fixed
// mode from the emulated normalBits-bit words), surface = the quadric's half-space, body, solid.
//
// Engine options (RenderOptions::engineOptions):
//   mode=float|fixed      the algorithm in double precision, or the fixed-point emulator
//   depth-bits=N          depth word width d (12..30, default 24; the EP2 and SRE use 2d)
//   normal-bits=N         normal and multiplier width n (8..d, default 16)
//   caps=skip|open        bodies whose opaque planes cut them: not drawn (default), or drawn
//                         open with the planes as bounds
//   clock-mhz=X           clock of the timing model (default 50, the paper's)
//   compare=on|off        fixed mode: evaluate the float algorithm too and report the depth
//                         error histogram (default on)
//   verify=on|off         fixed mode: also run the integer reference and count mismatching
//                         pixels (default off; the tests run it)
// RenderStats: counters (patches, pixels, cycles, skipped bodies and solids by reason, ...) and
// a report with the schedule, the frame's time at the clock, the cost tables (Table 1.7 with
// the paper's total) and, in fixed mode, the depth format and error histogram.
#pragma once

#include <memory>

#include "quadrix/engines/engine.h"

namespace quadrix {

std::unique_ptr<Engine> MakePatchEngine();

}  // namespace quadrix
