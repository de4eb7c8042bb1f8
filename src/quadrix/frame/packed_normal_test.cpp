#include "quadrix/frame/packed_normal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace quadrix {
namespace {

double Angle(const Vec3& a, const Vec3& b) { return std::atan2(Length(Cross(a, b)), Dot(a, b)); }

// Random directions (Gaussian, so uniform on the sphere) and the octahedron's folds, where the
// lower half's corners meet: the error stays under kMaxError, and the decoded vector is a unit.
TEST(PackedNormal, ErrorIsBoundedEverywhere) {
    std::mt19937_64 rng(7);
    std::normal_distribution<double> g;
    double worst = 0;
    auto check = [&](const Vec3& raw) {
        const Vec3 n = Normalize(raw);
        const Vec3 d = PackedNormal(n);
        ASSERT_NEAR(Length(d), 1, 1e-15);
        const double e = Angle(n, d);
        worst = std::max(worst, e);
        ASSERT_LE(e, PackedNormal::kMaxError) << n.x << " " << n.y << " " << n.z;
    };
    for (int i = 0; i < 1000000; ++i) check({g(rng), g(rng), g(rng)});
    // Near the equator z = 0 (the fold) and near the lower pole, where the square's corners meet.
    for (int i = 0; i < 100000; ++i) {
        check({g(rng), g(rng), 1e-9 * g(rng)});
        check({1e-6 * g(rng), 1e-6 * g(rng), -1});
    }
    // 16 bits each: the worst error is of the order of the grid, not far below it (the bound is
    // not loose by orders of magnitude, and the encoding uses the grid it claims).
    EXPECT_GT(worst, PackedNormal::kMaxError / 4);
}

// The 16-bit halves are round(u·32767) with ties to even, as std::nearbyint gives them (the
// encoder rounds without the library call): against a reference written with nearbyint, on
// random vectors and on vectors whose u·32767 is an exact tie (k + ½, both parities) or one ulp
// either side of it.
TEST(PackedNormal, HalvesAreRoundedAsNearbyintRoundsThem) {
    auto reference = [](const Vec3& n) {
        const double l1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
        double u = n.x / l1, v = n.y / l1;
        if (n.z < 0) {
            const double fu = (1 - std::fabs(v)) * (u < 0 ? -1.0 : 1.0);
            const double fv = (1 - std::fabs(u)) * (v < 0 ? -1.0 : 1.0);
            u = fu;
            v = fv;
        }
        auto snorm = [](double t) {
            const double q = std::nearbyint(std::fmin(std::fmax(t, -1.0), 1.0) * 32767.0);
            return static_cast<std::uint32_t>(
                static_cast<std::uint16_t>(static_cast<std::int16_t>(q)));
        };
        return snorm(u) << 16 | snorm(v);
    };
    std::mt19937_64 rng(11);
    std::normal_distribution<double> g;
    for (int i = 0; i < 1000000; ++i) {
        const Vec3 n{g(rng), g(rng), g(rng)};
        ASSERT_EQ(PackedNormal::Encode(n), reference(n)) << n.x << " " << n.y << " " << n.z;
    }
    // x / (|x| + |y| + |z|) with |x| + |y| + |z| = 1 exactly (z >= 0) is x itself: x·32767 = k + ½
    // exactly for x = (k + ½) / 32767 when that quotient is exact enough, and the neighbours of x.
    int ties = 0;
    for (int k = -32767; k < 32767; k += 7) {
        const double x = (k + 0.5) / 32767.0;
        for (double xs : {std::nextafter(x, -2.0), x, std::nextafter(x, 2.0)}) {
            const Vec3 n{xs, 0, 1 - std::fabs(xs)};
            if (std::fabs(xs) + (1 - std::fabs(xs)) != 1) continue;
            ties += xs * 32767.0 == k + 0.5;
            ASSERT_EQ(PackedNormal::Encode(n), reference(n)) << k;
            const Vec3 m{0, -xs, 1 - std::fabs(xs)};
            ASSERT_EQ(PackedNormal::Encode(m), reference(m)) << k;
        }
    }
    EXPECT_GT(ties, 1000);  // exact ties were met, so ties to even was tested
}

TEST(PackedNormal, AxesAreExact) {
    for (const Vec3& n : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0},
                          Vec3{0, 0, 1}, Vec3{0, 0, -1}}) {
        EXPECT_EQ(Vec3(PackedNormal(n)), n) << n.x << " " << n.y << " " << n.z;
        EXPECT_EQ(Vec3(PackedNormal(n * 1e-300)), n);  // the length does not matter
        EXPECT_EQ(Vec3(PackedNormal(n * 1e300)), n);
    }
}

TEST(PackedNormal, ZeroAndNonFiniteVectorsAreTheBackgroundsCode) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (const Vec3& v : {Vec3{}, Vec3{nan, 0, 1}, Vec3{0, inf, 0}, Vec3{-0.0, 0, -0.0}}) {
        const PackedNormal p(v);
        EXPECT_EQ(p.bits, PackedNormal::kZero);
        EXPECT_EQ(Vec3(p), Vec3{});
    }
    EXPECT_EQ(PackedNormal{}.bits, PackedNormal::kZero);  // the default is the background's
    // No unit vector packs to the background's code.
    for (const Vec3& n : {Vec3{-1, -1, -1}, Vec3{-1, -1, 1}, Vec3{-1e-9, -1e-9, -1}})
        EXPECT_NE(PackedNormal(n).bits, PackedNormal::kZero);
}

// Decoding then encoding gives the same normal: a Frame's normal passed through Vec3 (the qxf
// dump, an engine's Offer of a decoded normal) is unchanged bit for bit once decoded. (The codes
// themselves may differ on the fold's seam, |v| = 1 in the lower half, where ±u decode alike.)
TEST(PackedNormal, DecodingThenEncodingIsTheIdentity) {
    std::mt19937_64 rng(11);
    std::normal_distribution<double> g;
    int sameBits = 0;
    for (int i = 0; i < 200000; ++i) {
        const PackedNormal p(Vec3{g(rng), g(rng), g(rng)});
        const PackedNormal q{Vec3(p)};
        ASSERT_EQ(Vec3(q), Vec3(p)) << std::hex << p.bits;
        sameBits += q.bits == p.bits;
    }
    EXPECT_GE(sameBits, 199990);
}

// AngleExceeds (no normalisation) answers as the dot product of the decoded unit vectors does,
// away from the limit's own rounding.
TEST(PackedNormal, AngleExceedsIsTheDecodedDotProductsAnswer) {
    std::mt19937_64 rng(5);
    std::normal_distribution<double> g;
    const double cosLimit = std::cos(20 * M_PI / 180);
    int exceeded = 0, within = 0;
    for (int i = 0; i < 200000; ++i) {
        const Vec3 n{g(rng), g(rng), g(rng)};
        // Pairs spread around the limit: a second normal 0..40 degrees from the first.
        const Vec3 m = n + Vec3{g(rng), g(rng), g(rng)} * (0.35 * Length(n) * (i % 7) / 6);
        const PackedNormal a(n), b(m);
        const double dot = Dot(Vec3(a), Vec3(b));
        if (std::fabs(dot - cosLimit) < 1e-12) continue;
        ASSERT_EQ(PackedNormal::AngleExceeds(a, b, cosLimit), dot < cosLimit) << i;
        (dot < cosLimit ? exceeded : within)++;
    }
    EXPECT_GT(exceeded, 10000);
    EXPECT_GT(within, 10000);
    EXPECT_FALSE(PackedNormal::AngleExceeds(PackedNormal(Vec3{0, 0, 1}),
                                            PackedNormal(Vec3{0, 0, 1}), cosLimit));
    EXPECT_TRUE(PackedNormal::AngleExceeds(PackedNormal(Vec3{0, 0, 1}),
                                           PackedNormal(Vec3{0, 0, -1}), cosLimit));
}

}  // namespace
}  // namespace quadrix
