#include "quadrix/math/quadric.h"

#include <cmath>

namespace quadrix {

Plane Plane::Transformed(const Transform& t) const {
    // p' = M^-T p: (M^-T p)_i = sum_k inv[k][i] p_k.
    const Mat4& inv = t.Inverse();
    Vec4 p = AsVec4();
    Vec4 r;
    for (int i = 0; i < 4; ++i)
        r[i] = inv.m[0][i] * p.x + inv.m[1][i] * p.y + inv.m[2][i] * p.z + inv.m[3][i] * p.w;
    return FromVec4(r);
}

bool Plane::AllFinite() const {
    return std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d);
}

Mat4 Quadric::Matrix() const {
    Mat4 q;
    q.m = {
        {{A(), D(), F(), G()}, {D(), B(), E(), H()}, {F(), E(), C(), J()}, {G(), H(), J(), K()}}};
    return q;
}

Quadric Quadric::FromMatrix(const Mat4& q) {
    auto s = [&](int i, int j) { return 0.5 * (q.m[i][j] + q.m[j][i]); };
    return {{q.m[0][0], q.m[1][1], q.m[2][2], s(0, 1), s(1, 2), s(0, 2), s(0, 3), s(1, 3), s(2, 3),
             q.m[3][3]}};
}

Quadric Quadric::FromPlaneProduct(const Plane& p1, const Plane& p2) {
    Vec4 u = p1.AsVec4(), v = p2.AsVec4();
    Mat4 q;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) q.m[i][j] = 0.5 * (u[i] * v[j] + u[j] * v[i]);
    return FromMatrix(q);
}

double Quadric::Evaluate(const Vec3& p) const {
    const double x = p.x, y = p.y, z = p.z;
    return A() * x * x + B() * y * y + C() * z * z +
           2.0 * (D() * x * y + E() * y * z + F() * x * z) + 2.0 * (G() * x + H() * y + J() * z) +
           K();
}

Vec4 Quadric::HomogeneousGradient(const Vec3& p) const {
    return {A() * p.x + D() * p.y + F() * p.z + G(), D() * p.x + B() * p.y + E() * p.z + H(),
            F() * p.x + E() * p.y + C() * p.z + J(), G() * p.x + H() * p.y + J() * p.z + K()};
}

Vec3 Quadric::Gradient(const Vec3& p) const { return HomogeneousGradient(p).xyz() * 2.0; }

Quadric Quadric::Transformed(const Transform& t) const {
    const Mat4& inv = t.Inverse();
    return FromMatrix(inv.Transposed() * Matrix() * inv);
}

bool Quadric::AllFinite() const {
    for (double v : k)
        if (!std::isfinite(v)) return false;
    return true;
}

bool Quadric::IsZero() const {
    for (double v : k)
        if (v != 0) return false;
    return true;
}

bool Quadric::IsDegenerateToLinear() const {
    for (int i = 0; i < 6; ++i)
        if (k[i] != 0) return false;
    return true;
}

double Quadric::MaxAbs() const {
    double m = 0;
    for (double v : k) m = std::fmax(m, std::fabs(v));
    return m;
}

}  // namespace quadrix
