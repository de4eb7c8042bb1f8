#include "quadrix/engines/patch/patch_polynomials.h"

#include <algorithm>
#include <cmath>

namespace quadrix::patch {

PatchPolynomials PolynomialsOf(const QuadricPatch& patch) {
    const Quadric& q = patch.quadric;
    // The paper's letters (patch.h).
    const double a = q.A(), b = q.B(), c = q.C(), d = 2 * q.D(), e = 2 * q.F(), f = 2 * q.E(),
                 g = 2 * q.G(), h = 2 * q.H(), i = 2 * q.J(), j = q.K();
    PatchPolynomials p;
    p.f1 = {-e / (2 * c), -f / (2 * c), -i / (2 * c)};
    const double c2 = c * c;
    p.f2 = {(e * e - 4 * a * c) / (4 * c2), (f * f - 4 * b * c) / (4 * c2),
            (e * f - 2 * c * d) / (2 * c2), (e * i - 2 * c * g) / (2 * c2),
            (f * i - 2 * c * h) / (2 * c2), (i * i - 4 * c * j) / (4 * c2)};
    p.planeCount = patch.planeCount;
    for (int k = 0; k < patch.planeCount; ++k) {
        const Plane& pl = patch.planes[static_cast<std::size_t>(k)].plane;
        p.kind[static_cast<std::size_t>(k)] = KindOfPlane(pl.c);
        // A perpendicular plane's unit holds -(A x + B y + D): ZP >= 0 on the kept side.
        const double div = pl.c != 0 ? pl.c : 1.0;
        p.zp[static_cast<std::size_t>(k)] = {-pl.a / div, -pl.b / div, -pl.d / div};
    }
    p.nxBase = {2 * a, d, g};
    p.nyBase = {d, 2 * b, h};
    p.nzBase = {e, f, i};
    p.e = e;
    p.f = f;
    p.twoC = 2 * c;
    return p;
}

Range RangeOnRectangle(const Linear2& l, double x0, double x1, double y0, double y1) {
    const double v[4] = {l(x0, y0), l(x1, y0), l(x0, y1), l(x1, y1)};
    return {*std::min_element(v, v + 4), *std::max_element(v, v + 4)};
}

Range RangeOnRectangle(const Quadratic2& q, double x0, double x1, double y0, double y1) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    auto take = [&](double x, double y) {
        const double v = q(x, y);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    };
    take(x0, y0);
    take(x1, y0);
    take(x0, y1);
    take(x1, y1);
    // Critical points along the edges: d/dy at fixed x is 2 yy y + xy x + y.
    if (q.yy != 0)
        for (double x : {x0, x1}) {
            const double y = -(q.xy * x + q.y) / (2 * q.yy);
            if (y > y0 && y < y1) take(x, y);
        }
    if (q.xx != 0)
        for (double y : {y0, y1}) {
            const double x = -(q.xy * y + q.x) / (2 * q.xx);
            if (x > x0 && x < x1) take(x, y);
        }
    // Interior critical point: [2xx xy; xy 2yy] (x, y) = -(x, y coefficients). A singular
    // Hessian has its extremes on the boundary.
    const double det = 4 * q.xx * q.yy - q.xy * q.xy;
    if (det != 0) {
        const double x = (-q.x * 2 * q.yy + q.y * q.xy) / det;
        const double y = (-q.y * 2 * q.xx + q.x * q.xy) / det;
        if (x > x0 && x < x1 && y > y0 && y < y1) take(x, y);
    }
    return {lo, hi};
}

}  // namespace quadrix::patch
