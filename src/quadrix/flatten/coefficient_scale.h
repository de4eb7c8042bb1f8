// Coefficients of any magnitude (issue 23 item 4). A half-space's inequality f <= 0 is unchanged
// by a positive factor, so a plane or quadric whose largest coefficient magnitude lies outside
// [2^-kRescaleExponent, 2^kRescaleExponent] is multiplied by the power of two that brings it into
// [1, 2): exact (a power of two only moves exponents) except for coefficients more than 2^1074
// times smaller than the largest, which underflow to zero where they could not change a double's
// sum anyway. Without it a quadric scaled by 1e308 drew nothing: the depth solve's b² − c·a
// overflowed to inf − inf. Applied by the Flattener before and after each transform, so
// everything downstream (bounds, engines, shading) sees moderate coefficients. Half-spaces of
// moderate magnitude are left bit for bit as they are.
#pragma once

#include <cmath>
#include <tuple>

#include "quadrix/math/quadric.h"

namespace quadrix {

inline constexpr int kRescaleExponent = 64;

// The power-of-two exponent to scale by (0 = leave as is) for a largest magnitude `big`.
inline int RescaleExponent(double big) {
    // The usual case first, without ilogb: ilogb(big) is in [-64, 64] exactly when big is in
    // [2^-64, 2^65).
    static_assert(kRescaleExponent == 64);
    if (big >= 0x1p-64 && big < 0x1p65) return 0;
    if (!(big > 0) || !std::isfinite(big)) return 0;
    const int e = std::ilogb(big);
    return e > kRescaleExponent || e < -kRescaleExponent ? -e : 0;
}

// The largest |v| of the values that are not NaN (0 when none is): what nested std::fmax of the
// magnitudes gives, without a call per value.
template <class... D>
inline double LargestMagnitude(D... v) {
    double big = 0;
    ((big = std::fabs(v) > big ? std::fabs(v) : big), ...);
    return big;
}

inline void RescaleCoefficients(Plane& p) {
    const double big = LargestMagnitude(p.a, p.b, p.c, p.d);
    if (const int e = RescaleExponent(big); e != 0) {
        p.a = std::ldexp(p.a, e);
        p.b = std::ldexp(p.b, e);
        p.c = std::ldexp(p.c, e);
        p.d = std::ldexp(p.d, e);
    }
}

inline void RescaleCoefficients(Quadric& q) {
    const double big = std::apply([](auto... v) { return LargestMagnitude(v...); }, q.k);
    if (const int e = RescaleExponent(big); e != 0)
        for (double& v : q.k) v = std::ldexp(v, e);
}

}  // namespace quadrix
