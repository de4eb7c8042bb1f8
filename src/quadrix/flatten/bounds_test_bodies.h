// Bodies with known boxes for the tests of the bounds (bounds_test.cpp, bounds_critical_test.cpp):
// half-spaces from planes and quadrics, random rotations, ellipsoids, mitered pipes and cone
// frustums with their exact boxes, and a body's point membership.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "quadrix/flatten/bounds.h"
#include "quadrix/math/mat4.h"

namespace quadrix::bounds_test {

inline FlatHalfSpace PlaneHs(const Plane& p) {
    FlatHalfSpace h;
    h.isPlane = true;
    h.plane = p;
    return h;
}

inline FlatHalfSpace QuadricHs(const Quadric& q) {
    FlatHalfSpace h;
    h.isPlane = false;
    h.quadric = q;
    return h;
}

// A rotation from a random unit quaternion (uniform over rotations), with its exact transpose as
// the inverse.
inline Transform RandomRotation(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0, 1);
    double w = n(rng), x = n(rng), y = n(rng), z = n(rng);
    double len = std::sqrt(w * w + x * x + y * y + z * z);
    w /= len, x /= len, y /= len, z /= len;
    Mat4 m = Mat4::Identity();
    m.m[0][0] = 1 - 2 * (y * y + z * z);
    m.m[0][1] = 2 * (x * y - w * z);
    m.m[0][2] = 2 * (x * z + w * y);
    m.m[1][0] = 2 * (x * y + w * z);
    m.m[1][1] = 1 - 2 * (x * x + z * z);
    m.m[1][2] = 2 * (y * z - w * x);
    m.m[2][0] = 2 * (x * z - w * y);
    m.m[2][1] = 2 * (y * z + w * x);
    m.m[2][2] = 1 - 2 * (x * x + y * y);
    return Transform(m, m.Transposed());
}

// Unit-radius ellipsoid x²/a² + y²/b² + z²/c² <= 1 in local coordinates.
inline Quadric Ellipsoid(double a, double b, double c) {
    return Quadric::FromCoefficients({1 / (a * a), 1 / (b * b), 1 / (c * c), 0, 0, 0, 0, 0, 0, -1});
}

// Exact box of worldFromLocal(ellipsoid a, b, c): centre t, half-extent_i = |row_i(R diag(a))|.
inline Box3 ExactEllipsoidBox(const Transform& worldFromLocal, double a, double b, double c) {
    const Mat4& m = worldFromLocal.Matrix();
    Box3 box;
    double s[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
        double e = 0;
        for (int j = 0; j < 3; ++j) e += (m.m[i][j] * s[j]) * (m.m[i][j] * s[j]);
        e = std::sqrt(e);
        box.lo[i] = m.m[i][3] - e;
        box.hi[i] = m.m[i][3] + e;
    }
    return box;
}

// Box of an ellipse P0 + U cosθ + V sinθ.
inline void ExtendByEllipse(Box3& box, const Vec3& p0, const Vec3& u, const Vec3& v) {
    for (int i = 0; i < 3; ++i) {
        double e = std::sqrt(u[i] * u[i] + v[i] * v[i]);
        box.lo[i] = std::fmin(box.lo[i], p0[i] - e);
        box.hi[i] = std::fmax(box.hi[i], p0[i] + e);
    }
}

struct Body {
    std::vector<FlatHalfSpace> hs;
    std::vector<bool> complemented;
    std::vector<BoundLiteral> Literals() const {
        std::vector<BoundLiteral> l;
        for (std::size_t i = 0; i < hs.size(); ++i) l.push_back({&hs[i], complemented[i]});
        return l;
    }
    bool Contains(const Vec3& p) const {
        for (std::size_t i = 0; i < hs.size(); ++i) {
            double v = hs[i].Evaluate(p);
            if (complemented[i] ? !(v > 0) : !(v <= 0)) return false;
        }
        return true;
    }
};

// Mitered pipe in local coordinates: radius r along z, cut by z <= top + sx x and
// z >= bottom + sy y; placed by worldFromLocal. Returns the exact box too (the extremes of a
// cylinder segment lie on its two cut ellipses, since it is ruled along its axis).
inline Body MiteredPipe(const Transform& worldFromLocal, double r, double top, double sx,
                        double bottom, double sy, Box3& exact) {
    Body b;
    Quadric cyl = Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -r * r});
    b.hs.push_back(QuadricHs(cyl.Transformed(worldFromLocal)));
    b.hs.push_back(PlaneHs(Plane{-sx, 0, 1, -top}.Transformed(worldFromLocal)));  // z-sx x-top<=0
    b.hs.push_back(
        PlaneHs(Plane{0, sy, -1, bottom}.Transformed(worldFromLocal)));  // z>=bottom+sy y
    b.complemented = {false, false, false};
    // Cut ellipses in local coordinates: (r cosθ, r sinθ, top + sx r cosθ).
    const Transform& t = worldFromLocal;
    Vec3 o = t.MapPoint({0, 0, top});
    Vec3 u = t.MapVector({r, 0, sx * r}), v = t.MapVector({0, r, 0});
    exact = Box3{};
    ExtendByEllipse(exact, o, u, v);
    o = t.MapPoint({0, 0, bottom});
    u = t.MapVector({r, 0, 0});
    v = t.MapVector({0, r, sy * r});
    ExtendByEllipse(exact, o, u, v);
    return b;
}

// Frustum of the cone x² + y² <= (t z)² between z = h0 > 0 and z = h1, placed by worldFromLocal;
// the exact box is that of its two cap circles (a cone is ruled through its apex).
inline Body ConeFrustum(const Transform& worldFromLocal, double t, double h0, double h1,
                        Box3& exact) {
    Body b;
    b.hs.push_back(QuadricHs(Quadric::FromCoefficients({1, 1, -t * t, 0, 0, 0, 0, 0, 0, 0})
                                 .Transformed(worldFromLocal)));
    b.hs.push_back(PlaneHs(Plane{0, 0, 1, -h1}.Transformed(worldFromLocal)));
    b.hs.push_back(PlaneHs(Plane{0, 0, -1, h0}.Transformed(worldFromLocal)));
    b.complemented = {false, false, false};
    exact = Box3{};
    for (double h : {h0, h1})
        ExtendByEllipse(exact, worldFromLocal.MapPoint({0, 0, h}),
                        worldFromLocal.MapVector({t * h, 0, 0}),
                        worldFromLocal.MapVector({0, t * h, 0}));
    return b;
}

}  // namespace quadrix::bounds_test
