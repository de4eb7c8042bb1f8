// A unit normal in 32 bits, as the Frame stores it (issue 24 item 3: the normal was 24 of the
// Frame's former 44 bytes a pixel).
//
// Octahedral encoding: n is projected onto the octahedron |x| + |y| + |z| = 1; the upper half
// (z ≥ 0) maps to the square |u| + |v| ≤ 1 by (u, v) = (x, y), and the lower half is folded
// out to the square's corners, (u, v) = ((1 − |y|)·sgn x, (1 − |x|)·sgn y). u and v are then
// stored as 16-bit signed normalised integers (round(u·32767)). The map is continuous and nearly
// uniform in angle: the largest error anywhere on the sphere is 6.5e-5 radians (0.0037 degrees;
// kMaxError bounds it, PackedNormal.ErrorIsBoundedEverywhere measures it); normals along the
// axes, the commonest ones in CAD models, are exact.
//
// The zero vector (the background's normal) has its own code, kZero: both halves −32768, which
// the encoding never produces (it clamps to ±32767).
#pragma once

#include <cmath>
#include <cstdint>

#include "quadrix/math/vec.h"

namespace quadrix {

struct PackedNormal {
    static constexpr std::uint32_t kZero = 0x80008000u;
    // A bound on the angle (radians), and so on the length of the difference, between a unit
    // vector and its decoded packing.
    static constexpr double kMaxError = 7e-5;
    std::uint32_t bits = kZero;

    PackedNormal() = default;
    // Encodes n (any length; a zero or non-finite vector encodes as kZero). Implicit, so that an
    // engine writes frame.normal[i] = n as it did when the Frame held a Vec3.
    PackedNormal(const Vec3& n) : bits(Encode(n)) {}
    // Decodes to a unit vector (the zero vector for kZero).
    operator Vec3() const { return Decode(bits); }
    bool operator==(const PackedNormal&) const = default;

    static std::uint32_t Encode(const Vec3& n) {
        const double l1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
        if (!(l1 > 0) || !std::isfinite(l1)) return kZero;
        double u = n.x / l1, v = n.y / l1;
        if (n.z < 0) {
            const double fu = (1 - std::fabs(v)) * (u < 0 ? -1.0 : 1.0);
            const double fv = (1 - std::fabs(u)) * (v < 0 ? -1.0 : 1.0);
            u = fu;
            v = fv;
        }
        return static_cast<std::uint32_t>(Snorm(u)) << 16 | Snorm(v);
    }
    static Vec3 Decode(std::uint32_t b) {
        if (b == kZero) return {};
        const Vec3 n = OnOctahedron(b);
        const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
        return {n.x / len, n.y / len, n.z / len};
    }
    // The decoded direction before normalisation: the point of the octahedron |x|+|y|+|z| = 1
    // (the zero vector for kZero). For tests of direction that need no unit vector.
    static Vec3 OnOctahedron(std::uint32_t b) {
        if (b == kZero) return {};
        const double u = Unsnorm(b >> 16), v = Unsnorm(b & 0xffffu);
        Vec3 n{u, v, 1 - std::fabs(u) - std::fabs(v)};
        if (n.z < 0) {
            n.x = (1 - std::fabs(v)) * (u < 0 ? -1.0 : 1.0);
            n.y = (1 - std::fabs(u)) * (v < 0 ? -1.0 : 1.0);
        }
        return n;
    }
    // Whether the angle between a and b (neither kZero) exceeds acos(cosLimit), cosLimit > 0,
    // without normalising either: about ten times cheaper than Dot of the decoded vectors.
    static bool AngleExceeds(PackedNormal a, PackedNormal b, double cosLimit) {
        if (a.bits == b.bits) return false;
        const Vec3 p = OnOctahedron(a.bits), q = OnOctahedron(b.bits);
        const double d = p.x * q.x + p.y * q.y + p.z * q.z;
        if (!(d > 0)) return true;
        return d * d < cosLimit * cosLimit * (p.x * p.x + p.y * p.y + p.z * p.z) *
                           (q.x * q.x + q.y * q.y + q.z * q.z);
    }

    // The 16 bits of one half of a code: t (finite) clamped to [-1, 1], times 32767, rounded to
    // the nearest integer (ties to even). Public for the raycast engine's lanes, which pack many
    // normals at once (engines/raycast/quadric_normals.h) and must give Encode's bits.
    static std::uint32_t Snorm(double t) {
        // std::nearbyint (round to nearest, ties to even) without its library call: the
        // baseline x86-64 has no rounding instruction, and this runs for every pixel of a curved
        // surface. Adding and subtracting 1.5 × 2^52 rounds |c| < 2^51 to an integer in the
        // current rounding mode, as nearbyint does (a -0 becomes +0: the same 16 bits below).
        constexpr double kRound = 6755399441055744.0;
        // t is finite (Encode's callers divide finite values by a positive finite l1); the
        // clamp by comparisons is std::fmin(std::fmax(t, -1), 1) without the library calls.
        const double c = (t < -1.0 ? -1.0 : (t > 1.0 ? 1.0 : t)) * 32767.0;
        const double q = (c + kRound) - kRound;
        return static_cast<std::uint16_t>(static_cast<std::int16_t>(q));
    }

  private:
    static double Unsnorm(std::uint32_t h) {
        const auto s = static_cast<std::int16_t>(static_cast<std::uint16_t>(h));
        // std::fmax(v, -1.0) without the library call (v is never NaN).
        const double v = static_cast<double>(s) / 32767.0;
        return v < -1.0 ? -1.0 : v;
    }
};

}  // namespace quadrix
