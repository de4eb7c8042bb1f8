#include "quadrix/math/quartic_roots.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace quadrix {
namespace {

// Coefficients of k ∏ (s − r_i).
std::array<double, 5> FromRoots(const std::vector<double>& roots, double k = 1) {
    std::array<double, 5> c{k, 0, 0, 0, 0};
    int n = 0;
    for (double r : roots) {
        std::array<double, 5> next{};
        for (int i = 0; i <= n; ++i) {
            next[static_cast<std::size_t>(i + 1)] += c[static_cast<std::size_t>(i)];
            next[static_cast<std::size_t>(i)] -= r * c[static_cast<std::size_t>(i)];
        }
        c = next;
        ++n;
    }
    return c;
}

// The error a root of FromRoots(roots) may carry: its coefficients are rounded sums of products
// of the roots, so each is off by a few ulps of the same sum of absolute products, i.e. of the
// coefficients of ∏(s + |r_j|); over |p'(r)| (the root's condition), plus an ulp of r.
double RootTolerance(const std::vector<double>& roots, double r) {
    std::vector<double> neg;
    for (double v : roots) neg.push_back(-std::fabs(v));
    const std::array<double, 5> c = FromRoots(roots), a = FromRoots(neg);
    double mag = 0, d = 0, pw = 1;
    for (int i = 0; i <= 4; ++i) {
        mag += a[static_cast<std::size_t>(i)] * std::fabs(pw);
        if (i < 4) d += (i + 1) * c[static_cast<std::size_t>(i + 1)] * pw;
        pw *= r;
    }
    return 16 * 1.1e-16 * mag / std::fabs(d) + 4e-16 * (1 + std::fabs(r));
}

TEST(MathQuarticRoots, FindsFourSimpleRootsToFullPrecision) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 500; ++trial) {
        std::vector<double> r{u(rng), u(rng), u(rng), u(rng)};
        std::sort(r.begin(), r.end());
        bool separated = true;
        for (int i = 0; i < 3; ++i)
            separated &= r[static_cast<std::size_t>(i + 1)] - r[static_cast<std::size_t>(i)] > 1e-3;
        if (!separated) continue;
        std::array<double, 4> got{};
        const std::array<double, 5> c = FromRoots(r);
        ASSERT_EQ(SignChangeRoots(c, -1.5, 1.5, got), 4);
        for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(got[i], r[i], RootTolerance(r, r[i]));
    }
}

TEST(MathQuarticRoots, OnlyRootsInsideTheInterval) {
    std::array<double, 4> got{};
    EXPECT_EQ(SignChangeRoots(FromRoots({-3, -0.5, 0.25, 2}), -1, 1, got), 2);
    EXPECT_NEAR(got[0], -0.5, 1e-15);
    EXPECT_NEAR(got[1], 0.25, 1e-15);
}

TEST(MathQuarticRoots, DoubleRootGivesNoPointInterval) {
    // (s − 0.3)² (s + 0.5)(s − 0.7): the tangent contact at 0.3 is not part of the set p <= 0.
    std::array<double, 3> lo{}, hi{};
    const int n = NonPositiveSet(FromRoots({0.3, 0.3, -0.5, 0.7}), -1, 1, lo, hi);
    ASSERT_EQ(n, 1);
    EXPECT_NEAR(lo[0], -0.5, 1e-14);
    EXPECT_NEAR(hi[0], 0.7, 1e-14);
    // (s − 0.3)² (s² + 1) >= 0: nothing.
    std::array<double, 5> c = FromRoots({0.3, 0.3});
    const std::array<double, 5> t{c[0], c[1], c[2] + c[0], c[1], c[2]};  // × (s² + 1)
    EXPECT_EQ(NonPositiveSet(t, -1, 1, lo, hi), 0);
}

TEST(MathQuarticRoots, NearlyDoubleRootsAreSeparated) {
    // Two roots 1e-7 apart (a ray grazing a torus): the sign change is found, bracketed.
    std::array<double, 3> lo{}, hi{};
    const std::vector<double> roots{0.2, 0.2 + 1e-7, 0.6, 0.8};
    const std::array<double, 5> c = FromRoots(roots);
    const int n = NonPositiveSet(c, -1, 1, lo, hi);
    ASSERT_EQ(n, 2);
    EXPECT_NEAR(lo[0], 0.2, RootTolerance(roots, 0.2));
    EXPECT_NEAR(hi[0], 0.2 + 1e-7, RootTolerance(roots, 0.2 + 1e-7));
    EXPECT_LT(lo[0], hi[0]);
    EXPECT_NEAR(lo[1], 0.6, RootTolerance(roots, 0.6));
    EXPECT_NEAR(hi[1], 0.8, RootTolerance(roots, 0.8));
}

TEST(MathQuarticRoots, SetTouchesTheEndsAndLowerDegrees) {
    std::array<double, 3> lo{}, hi{};
    // −(s − 0.5)(s + 0.5) <= 0 outside [−0.5, 0.5]: two pieces reaching the ends.
    std::array<double, 5> c = FromRoots({-0.5, 0.5}, -1);
    ASSERT_EQ(NonPositiveSet(c, -1, 1, lo, hi), 2);
    EXPECT_EQ(lo[0], -1);
    EXPECT_NEAR(hi[0], -0.5, 1e-15);
    EXPECT_NEAR(lo[1], 0.5, 1e-15);
    EXPECT_EQ(hi[1], 1);
    // A constant.
    EXPECT_EQ(NonPositiveSet({-1, 0, 0, 0, 0}, -1, 1, lo, hi), 1);
    EXPECT_EQ(NonPositiveSet({1, 0, 0, 0, 0}, -1, 1, lo, hi), 0);
    // A line.
    ASSERT_EQ(NonPositiveSet({0.25, 1, 0, 0, 0}, -1, 1, lo, hi), 1);
    EXPECT_NEAR(hi[0], -0.25, 1e-16);
}

TEST(MathQuarticRoots, ThreePiecesForANegativeLeadingQuartic) {
    std::array<double, 3> lo{}, hi{};
    ASSERT_EQ(NonPositiveSet(FromRoots({-0.6, -0.2, 0.1, 0.5}, -1), -1, 1, lo, hi), 3);
    EXPECT_NEAR(hi[0], -0.6, 1e-14);
    EXPECT_NEAR(lo[1], -0.2, 1e-14);
    EXPECT_NEAR(hi[1], 0.1, 1e-14);
    EXPECT_NEAR(lo[2], 0.5, 1e-14);
}

}  // namespace
}  // namespace quadrix
