// 4x4 matrices (double, row-major storage) and rigid/affine/projective transforms.
//
// Convention (DESIGN.md): points are column vectors and map as x' = M x. Planes (covectors) map as
// p' = M^-T p and quadrics as Q' = M^-T Q M^-1. A Transform keeps M and M^-1 together so that the
// inverse is composed, never recomputed (as the UniQuadrix Flattener stores inverses, seed 001
// §3.3).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "quadrix/math/vec.h"

namespace quadrix {

struct Mat4 {
    // m[row][col]
    std::array<std::array<double, 4>, 4> m{};

    static Mat4 Identity();
    static Mat4 Zero() { return Mat4{}; }

    double& operator()(int r, int c) { return m[r][c]; }
    double operator()(int r, int c) const { return m[r][c]; }

    Mat4 operator*(const Mat4& o) const;
    Vec4 operator*(const Vec4& v) const;
    Mat4 Transposed() const;
    bool operator==(const Mat4&) const = default;

    // Maps a point (w = 1) and divides by the resulting w.
    Vec3 MapPoint(const Vec3& p) const;
    // Maps a direction (w = 0), ignoring any projective row.
    Vec3 MapVector(const Vec3& v) const;

    // Inverse by Gauss-Jordan elimination with partial pivoting; nullopt when singular
    // (pivot below 1e-300 or any non-finite entry).
    std::optional<Mat4> Inverse() const;
    bool AllFinite() const;
    std::string ToString() const;
};

// A transform with its inverse. Factories build both exactly, so no inversion is ever needed.
class Transform {
  public:
    Transform() : m_(Mat4::Identity()), inv_(Mat4::Identity()) {}
    Transform(const Mat4& m, const Mat4& inv) : m_(m), inv_(inv) {}
    // nullopt when m is singular.
    static std::optional<Transform> FromMatrix(const Mat4& m);

    static Transform Translate(const Vec3& t);
    // Scale factors must be non-zero (the caller validates).
    static Transform Scale(const Vec3& s);
    // Rotation by `degrees` about axis 0 (x), 1 (y) or 2 (z), the usual matrix: +90° about z takes
    // +x to +y (cyclically: about x, +y to +z; about y, +z to +x). In Quadrix's left-handed
    // pictures that is the left-hand rule (docs/language.md §2). Multiples of 90 degrees are exact
    // (sines and cosines of 0, ±1).
    static Transform Rotate(int axis, double degrees);
    // Shear: coordinate `to` += factor * coordinate `from` (=vxy: x += factor*y... see
    // docs/language.md for the language's naming).
    static Transform Shear(int to, int from, double factor);

    const Mat4& Matrix() const { return m_; }
    const Mat4& Inverse() const { return inv_; }
    Transform Inverted() const { return {inv_, m_}; }

    // (a * b) maps x to a(b(x)): b is applied first.
    Transform operator*(const Transform& o) const { return {m_ * o.m_, o.inv_ * inv_}; }

    Vec3 MapPoint(const Vec3& p) const { return m_.MapPoint(p); }
    Vec3 MapVector(const Vec3& v) const { return m_.MapVector(v); }

  private:
    Mat4 m_;
    Mat4 inv_;
};

// Sine and cosine of an angle in degrees, exact for multiples of 90 and symmetric otherwise.
void SinCosDegrees(double degrees, double& s, double& c);

}  // namespace quadrix
