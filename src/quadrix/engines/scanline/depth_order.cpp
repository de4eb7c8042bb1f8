#include "quadrix/engines/scanline/depth_order.h"

#include <algorithm>
#include <cmath>

#include "quadrix/math/quadratic.h"

namespace quadrix::scanline {

bool FaceDerivatives(const FlatScene& scene, const FaceRef& f, double x, double y, double& z,
                     double& dz, double& d2z) {
    const FlatHalfSpace& hs = scene.halfSpaces[static_cast<std::size_t>(f.halfSpace)];
    if (hs.isPlane) {
        const Plane& p = hs.plane;
        if (p.c == 0) return false;
        z = -(p.a * x + p.b * y + p.d) / p.c;
        dz = -p.a / p.c;
        d2z = 0;
        return true;
    }
    const Quadric& q = hs.quadric;
    QuadraticRoots r = SolveQuadratic(
        q.C(), q.F() * x + q.E() * y + q.J(),
        q.A() * x * x + q.B() * y * y + 2 * q.D() * x * y + 2 * q.G() * x + 2 * q.H() * y + q.K());
    if (r.kind == RootKind::kNone || r.kind == RootKind::kAll) return false;
    z = (f.sheet == 1 && r.kind == RootKind::kTwo) ? r.t1 : r.t0;
    // F = Q(x, y, z): F_x = 2(A x + D y + F z + G), F_z = 2(F x + E y + C z + J),
    // F_xx = 2A, F_xz = 2F, F_zz = 2C (the common factor 2 cancels).
    double fx = q.A() * x + q.D() * y + q.F() * z + q.G();
    double fz = q.F() * x + q.E() * y + q.C() * z + q.J();
    if (fz == 0) return false;  // on the limb: dz/dx is infinite
    dz = -fx / fz;
    d2z = -(q.A() + 2 * q.F() * dz + q.C() * dz * dz) / fz;
    return true;
}

int CompareFaces(const FlatScene& scene, const FaceRef& f, const FaceRef& g, double x, double y,
                 double tolerance) {
    double zf, sf, cf, zg, sg, cg;
    bool hf = FaceDerivatives(scene, f, x, y, zf, sf, cf);
    bool hg = FaceDerivatives(scene, g, x, y, zg, sg, cg);
    if (!hf || !hg) return hf ? -1 : (hg ? 1 : 0);
    auto tol = [&](double a, double b) {
        return tolerance * (1 + std::max(std::fabs(a), std::fabs(b)));
    };
    if (std::fabs(zf - zg) > tol(zf, zg)) return zf < zg ? -1 : 1;
    // Case (a): equal at P; compare at Q one pixel on.
    double qf, qg, s1, s2, c1, c2;
    if (FaceDerivatives(scene, f, x + 1, y, qf, s1, c1) &&
        FaceDerivatives(scene, g, x + 1, y, qg, s2, c2) && std::fabs(qf - qg) > tol(qf, qg))
        return qf < qg ? -1 : 1;
    // Case (b): equal again: the lesser slope is in front.
    if (std::fabs(sf - sg) > tol(sf, sg)) return sf < sg ? -1 : 1;
    // Case (c): tangent faces: the smaller rate of change of slope is in front.
    if (std::fabs(cf - cg) > tol(cf, cg)) return cf < cg ? -1 : 1;
    return 0;
}

}  // namespace quadrix::scanline
