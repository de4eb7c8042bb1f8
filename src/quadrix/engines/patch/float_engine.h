// The patch processor's algorithm in double precision (seed 000 §1.2-1.4): per pixel F1, F2, ZF,
// ZB, the plane depths ZP, the bounding-plane algorithm with EF/EB, Z' and ZOUT, and the normal
// from NXBASE/NYBASE/NZBASE plus the Z' terms, negated for the back sheet.
//
// Numerics. F1 ± sqrt(F2) loses the smaller root to cancellation when |F1| >> sqrt(F2); the float
// mode therefore takes ZF and ZB from the stable quadratic solver (math/quadratic.h) applied to
// the same equation c z² + β z + α = 0: the larger-magnitude root is F1 + sign(F1)·sqrt(F2) and
// the other comes from the product of the roots, α / c (Vieta). Its discriminant decides F2 < 0.
// F1 and F2 themselves are reported from their definitions. Everything else is as published.
#pragma once

#include <array>
#include <cstdint>

#include "quadrix/engines/patch/bounding_plane.h"
#include "quadrix/engines/patch/patch.h"
#include "quadrix/frame/frame.h"

namespace quadrix::patch {

struct FloatPixel {
    double f1 = 0, f2 = 0;  // F2 < 0: no root
    double zf = 0, zb = 0;
    std::array<double, kMaxPlanes> zp{};
    DepthFlags flags;
    Sheet sheet = Sheet::kNone;
    double zout = 0;  // Z' when sheet != kNone
    Vec3 gradient;    // device (NX, NY, NZ) at Z', negated for the back sheet
};

// The processor's computation at the device point (x, y) (a pixel centre for the engine).
FloatPixel EvaluatePixelFloat(const QuadricPatch& patch, double x, double y);

struct FloatStats {
    std::int64_t windowPixels = 0;   // pixels scanned
    std::int64_t surfacePixels = 0;  // pixels where ZOUT != ZMAX
    std::int64_t backSheetPixels = 0;
};

// Scans the rows [yBegin, yEnd) of the patch's window and offers every ZOUT != ZMAX to `frame`
// (z-buffered: Frame::Offer keeps the nearest).
void RenderPatchRowsFloat(const QuadricPatch& patch, const FlatScene& scene, int yBegin, int yEnd,
                          Frame& frame, FloatStats& stats);

}  // namespace quadrix::patch
