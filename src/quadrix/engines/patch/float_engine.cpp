#include "quadrix/engines/patch/float_engine.h"

#include <algorithm>
#include <cmath>

#include "quadrix/math/quadratic.h"

namespace quadrix::patch {

FloatPixel EvaluatePixelFloat(const QuadricPatch& patch, double x, double y) {
    const Quadric& q = patch.quadric;
    FloatPixel px;
    // Along the ray: C z² + 2 hb z + a0 = 0 (UniQuadrix half coefficients; the paper's
    // β = 2 hb, α = a0, c = C).
    const double hb = q.F() * x + q.E() * y + q.J();
    const double a0 =
        q.A() * x * x + q.B() * y * y + 2 * q.D() * x * y + 2 * q.G() * x + 2 * q.H() * y + q.K();
    const double c = q.C();
    px.f1 = -hb / c;
    px.f2 = DifferenceOfProducts(hb, hb, c, a0) / (c * c);
    const QuadraticRoots roots = SolveQuadratic(c, hb, a0);
    const bool f2Negative = roots.kind != RootKind::kTwo && roots.kind != RootKind::kDouble;
    if (!f2Negative) {
        px.zf = roots.t0;
        px.zb = roots.t1;
        px.f2 = std::max(px.f2, 0.0);  // the solver's discriminant decides the sign
    } else {
        px.zf = px.zb = px.f1;
        px.f2 = std::min(px.f2, -0.0);
    }

    // §1.3.2: cut by each plane, then select.
    for (int k = 0; k < patch.planeCount; ++k) {
        const Plane& pl = patch.planes[static_cast<std::size_t>(k)].plane;
        const PlaneKind kind = KindOfPlane(pl.c);
        const double num = -(pl.a * x + pl.b * y + pl.d);
        const double zp = kind == PlaneKind::kPerpendicular ? num : num / pl.c;
        px.zp[static_cast<std::size_t>(k)] = zp;
        CutByPlane(kind, zp, px.zf, px.zb, px.flags);
    }
    px.sheet = SelectSheet(px.flags, f2Negative);
    const double zPrime = px.flags.ef ? px.zf : px.zb;
    px.zout = zPrime;

    // §1.4.3: NXBASE + e Z', NYBASE + f Z', NZBASE + 2c Z' (paper letters, patch.h).
    const double nxBase = 2 * q.A() * x + 2 * q.D() * y + 2 * q.G();
    const double nyBase = 2 * q.D() * x + 2 * q.B() * y + 2 * q.H();
    const double nzBase = 2 * q.F() * x + 2 * q.E() * y + 2 * q.J();
    px.gradient = {nxBase + 2 * q.F() * zPrime, nyBase + 2 * q.E() * zPrime,
                   nzBase + 2 * c * zPrime};
    if (px.sheet == Sheet::kBack) px.gradient = -px.gradient;
    return px;
}

void RenderPatchRowsFloat(const QuadricPatch& patch, const FlatScene& scene, int yBegin, int yEnd,
                          Frame& frame, FloatStats& stats) {
    const PixelWindow& w = patch.window;
    const int y0 = std::max(yBegin, w.y0), y1 = std::min(yEnd, w.y1);
    for (int py = y0; py < y1; ++py) {
        const double y = py + 0.5;
        for (int pxi = w.x0; pxi < w.x1; ++pxi) {
            const double x = pxi + 0.5;
            ++stats.windowPixels;
            const FloatPixel px = EvaluatePixelFloat(patch, x, y);
            if (px.sheet == Sheet::kNone) continue;
            ++stats.surfacePixels;
            if (px.sheet == Sheet::kBack) ++stats.backSheetPixels;
            const std::size_t i = frame.Index(pxi, py);
            if (!frame.Nearer(i, px.zout)) continue;  // z-buffer; skip the normal's cost
            const Vec3 p{x, y, px.zout};
            frame.Offer(i, px.zout, WorldNormalFromDeviceGradient(scene, p, px.gradient),
                        patch.surface, patch.body);
        }
    }
}

}  // namespace quadrix::patch
