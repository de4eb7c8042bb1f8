// Planes and quadrics as half-space inequalities (HSIs), seed 001 §2.1.1 and DESIGN.md.
//
// Plane <A B C D>:            A x + B y + C z + D <= 0 is inside.
// Quadric <A B C D E F G H J K>:
//   A x² + B y² + C z² + 2D xy + 2E yz + 2F xz + 2G x + 2H y + 2J z + K <= 0 is inside,
// i.e. the symmetric matrix [[A D F G] [D B E H] [F E C J] [G H J K]] with xᵀQx <= 0.
// Note the factor 2 on the cross and linear terms.
#pragma once

#include <array>

#include "quadrix/math/mat4.h"
#include "quadrix/math/vec.h"

namespace quadrix {

struct Plane {
    double a = 0, b = 0, c = 0, d = 0;  // the coefficients <A B C D>

    static Plane FromVec4(const Vec4& v) { return {v.x, v.y, v.z, v.w}; }
    Vec4 AsVec4() const { return {a, b, c, d}; }
    Vec3 Normal() const { return {a, b, c}; }  // the (unnormalised) outward normal
    double Evaluate(const Vec3& p) const { return a * p.x + b * p.y + c * p.z + d; }
    // p' = M^-T p for points mapping x' = M x.
    Plane Transformed(const Transform& t) const;
    bool AllFinite() const;
    bool IsZeroNormal() const { return a == 0 && b == 0 && c == 0; }
    bool operator==(const Plane&) const = default;
};

struct Quadric {
    // UniQuadrix order <A B C D E F G H J K>.
    std::array<double, 10> k{};

    static Quadric FromCoefficients(const std::array<double, 10>& c) { return {c}; }
    static Quadric FromMatrix(const Mat4& q);  // symmetrises (q + qᵀ)/2
    // The product of two planes' equations, p1(x) * p2(x), as a quadric (used by tests and the
    // modeling front end).
    static Quadric FromPlaneProduct(const Plane& p1, const Plane& p2);

    double A() const { return k[0]; }
    double B() const { return k[1]; }
    double C() const { return k[2]; }
    double D() const { return k[3]; }
    double E() const { return k[4]; }
    double F() const { return k[5]; }
    double G() const { return k[6]; }
    double H() const { return k[7]; }
    double J() const { return k[8]; }
    double K() const { return k[9]; }

    Mat4 Matrix() const;
    double Evaluate(const Vec3& p) const;
    // ∇Q = 2 Q x truncated to three components (the outward normal direction at a surface point).
    Vec3 Gradient(const Vec3& p) const;
    // The full homogeneous gradient Q x (without the factor 2): needed to map normals through
    // projective transforms.
    Vec4 HomogeneousGradient(const Vec3& p) const;
    // Q' = M^-T Q M^-1 for points mapping x' = M x.
    Quadric Transformed(const Transform& t) const;
    bool AllFinite() const;
    bool IsZero() const;
    // True when the quadratic part (A..F) vanishes: the "quadric" is a plane or a constant.
    bool IsDegenerateToLinear() const;
    // Largest absolute coefficient (for scale-relative tolerances).
    double MaxAbs() const;
    bool operator==(const Quadric&) const = default;
};

}  // namespace quadrix
