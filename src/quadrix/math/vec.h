// Small fixed-size vectors in double precision.
//
// Vec3 is used for points, directions and normals alike; the name of a variable says which it is
// (STYLE.md asks for distinct types; we keep one type for now to keep the math core small and
// name transforms by what they map instead: deviceFromWorld, worldFromObject).
// Vec4 is a homogeneous point (x y z w) or a plane / gradient covector (A B C D).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace quadrix {

struct Vec3 {
    double x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

    constexpr double& operator[](std::size_t i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr double operator[](std::size_t i) const { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3& operator+=(const Vec3& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    constexpr Vec3& operator-=(const Vec3& o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    constexpr Vec3& operator*=(double s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    constexpr bool operator==(const Vec3&) const = default;
};

constexpr Vec3 operator*(double s, const Vec3& v) { return v * s; }
constexpr double Dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 Cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Length and normalisation that are safe at every scale (issue 23): |v|² overflows to +inf for
// components beyond about 1e154 and underflows to 0 below about 1e-154, which made a light
// direction of length 1e200 a zero vector (a black picture) and a tiny vpn "the zero vector".
// Where |v|² is comfortably inside the normal range the plain formula is used (bit-identical to
// before); otherwise v is first divided by its largest component magnitude m, so that the sum of
// squares lies in [1, 3], and |v| = m · |v / m|.
namespace vec_detail {
inline constexpr double kSafeLo = 1e-280, kSafeHi = 1e280;
inline double MaxAbs(const Vec3& v) {
    return std::fmax(std::fabs(v.x), std::fmax(std::fabs(v.y), std::fabs(v.z)));
}
}  // namespace vec_detail

inline double Length(const Vec3& v) {
    const double d = Dot(v, v);
    if (d > vec_detail::kSafeLo && d < vec_detail::kSafeHi) return std::sqrt(d);
    const double m = vec_detail::MaxAbs(v);
    if (!(m > 0) || !std::isfinite(m)) return std::sqrt(d);  // zero, inf or NaN as before
    const Vec3 u = v / m;
    return m * std::sqrt(Dot(u, u));
}
// Returns v / |v|; the zero vector stays zero (callers check Length first where it matters).
inline Vec3 Normalize(const Vec3& v) {
    const double d = Dot(v, v);
    if (d > vec_detail::kSafeLo && d < vec_detail::kSafeHi) return v / std::sqrt(d);
    const double m = vec_detail::MaxAbs(v);
    if (!(m > 0) || !std::isfinite(m)) {
        const double len = std::sqrt(d);
        return len > 0 ? v / len : v;
    }
    const Vec3 u = v / m;
    return u / std::sqrt(Dot(u, u));
}
inline bool IsFinite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

struct Vec4 {
    double x = 0, y = 0, z = 0, w = 0;

    constexpr Vec4() = default;
    constexpr Vec4(double x_, double y_, double z_, double w_) : x(x_), y(y_), z(z_), w(w_) {}
    constexpr Vec4(const Vec3& v, double w_) : x(v.x), y(v.y), z(v.z), w(w_) {}

    constexpr double& operator[](std::size_t i) {
        return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w));
    }
    constexpr double operator[](std::size_t i) const {
        return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w));
    }
    constexpr Vec3 xyz() const { return {x, y, z}; }
    constexpr Vec4 operator+(const Vec4& o) const { return {x + o.x, y + o.y, z + o.z, w + o.w}; }
    constexpr Vec4 operator-(const Vec4& o) const { return {x - o.x, y - o.y, z - o.z, w - o.w}; }
    constexpr Vec4 operator*(double s) const { return {x * s, y * s, z * s, w * s}; }
    constexpr Vec4 operator-() const { return {-x, -y, -z, -w}; }
    constexpr bool operator==(const Vec4&) const = default;
};

constexpr double Dot(const Vec4& a, const Vec4& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
}
// Homogeneous division; w must be non-zero.
constexpr Vec3 Dehomogenize(const Vec4& p) { return {p.x / p.w, p.y / p.w, p.z / p.w}; }

// An axis-aligned box; empty when lo > hi on any axis. Infinite bounds are allowed.
struct Box3 {
    Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL};
    Vec3 hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};

    static Box3 Everything() {
        return {{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, {HUGE_VAL, HUGE_VAL, HUGE_VAL}};
    }
    bool Empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    bool Finite() const { return !Empty() && IsFinite(lo) && IsFinite(hi); }
    void Extend(const Vec3& p) {
        for (std::size_t i = 0; i < 3; ++i) {
            lo[i] = std::fmin(lo[i], p[i]);
            hi[i] = std::fmax(hi[i], p[i]);
        }
    }
    void Extend(const Box3& b) {
        if (b.Empty()) return;
        Extend(b.lo);
        Extend(b.hi);
    }
    Box3 Intersected(const Box3& b) const {
        Box3 r;
        for (std::size_t i = 0; i < 3; ++i) {
            r.lo[i] = std::fmax(lo[i], b.lo[i]);
            r.hi[i] = std::fmin(hi[i], b.hi[i]);
        }
        return r;
    }
    Vec3 Center() const { return (lo + hi) * 0.5; }
    Vec3 Size() const { return hi - lo; }
    // Closed boxes that share a point (touching counts); false when either is empty.
    bool Overlaps(const Box3& b) const {
        return !(hi.x < b.lo.x || b.hi.x < lo.x || hi.y < b.lo.y || b.hi.y < lo.y ||
                 hi.z < b.lo.z || b.hi.z < lo.z);
    }
};

}  // namespace quadrix
