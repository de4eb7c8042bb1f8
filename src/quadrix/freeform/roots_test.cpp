#include "quadrix/freeform/roots.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "quadrix/freeform/test_oracles.h"

namespace quadrix::freeform {
namespace {

// Π (t - r_i) on [t0, t1] built from linear Bézier factors.
BezierCurve FromRoots(const std::vector<double>& roots, double t0 = 0, double t1 = 1,
                      double scale = 1) {
    BezierCurve f = BezierCurve::Scalar({scale}, t0, t1);
    for (double r : roots) f = Multiply(BezierCurve::Scalar({t0 - r, t1 - r}, t0, t1), f);
    return f;
}

TEST(FreeformRoots, FindsSimpleRootsOfProducts) {
    std::mt19937_64 rng(31);
    for (int trial = 0; trial < 200; ++trial) {
        int n = 1 + trial % 7;
        std::vector<double> roots;
        for (int i = 0; i < n; ++i) roots.push_back(testing::Uniform(rng, -0.5, 1.5));
        std::sort(roots.begin(), roots.end());
        BezierCurve f = FromRoots(roots, 0, 1, testing::Uniform(rng, 0.1, 10));
        std::vector<double> inside;
        for (double r : roots)
            if (r > 1e-9 && r < 1 - 1e-9) inside.push_back(r);
        // Keep only cases whose roots are separated (a near-double root is a different test).
        bool separated = true;
        for (std::size_t i = 1; i < roots.size(); ++i) separated &= roots[i] - roots[i - 1] > 1e-3;
        if (!separated) continue;
        auto found = SignChanges(f);
        ASSERT_TRUE(found.has_value());
        ASSERT_EQ(found->size(), inside.size()) << "trial " << trial;
        for (std::size_t i = 0; i < inside.size(); ++i)
            // Separation 1e-3 and coefficients O(1): the bisection stops at 1e-12 in t; the
            // conditioning of a root with neighbours ≥ 1e-3 away allows ~1e-9 error from roundoff.
            EXPECT_NEAR((*found)[i], inside[i], 1e-9);
    }
}

TEST(FreeformRoots, DoubleRootIsNotASignChange) {
    BezierCurve f = FromRoots({0.3, 0.3, 0.7});
    auto found = SignChanges(f);
    ASSERT_TRUE(found.has_value());
    ASSERT_EQ(found->size(), 1u);
    EXPECT_NEAR((*found)[0], 0.7, 1e-10);
}

TEST(FreeformRoots, RootAtTheMidpointSplitIsFound) {
    // Roots at 0.25 and 0.5 on [0, 1]: 0.5 is exactly the first split point.
    BezierCurve f = FromRoots({0.25, 0.5, 0.75});
    auto found = SignChanges(f);
    ASSERT_TRUE(found.has_value());
    ASSERT_EQ(found->size(), 3u);
    EXPECT_NEAR((*found)[1], 0.5, 1e-12);
}

TEST(FreeformRoots, GivesUpOnTooManyRoots) {
    std::vector<double> r;
    for (int i = 1; i < 20; ++i) r.push_back(i / 20.0);
    RootOptions o;
    o.maxRoots = 5;
    EXPECT_FALSE(SignChanges(FromRoots(r), o).has_value());
    EXPECT_TRUE(SignChanges(FromRoots(r)).has_value());
}

TEST(FreeformRoots, BoundsOfTheMaximum) {
    std::mt19937_64 rng(32);
    for (int trial = 0; trial < 50; ++trial) {
        BezierCurve f = BezierCurve::Scalar(testing::RandomVector(rng, 7, -1, 1));
        double sampled = -HUGE_VAL;
        for (int i = 0; i <= 20000; ++i) sampled = std::max(sampled, f.EvaluateScalar(i / 20000.0));
        double bound = MaximumBound(f, 1e-9);
        // An upper bound, within the tolerance plus the sampling gap (derivative O(10) × 5e-5
        // squared curvature term: the sampled maximum is below the true one by < 1e-6).
        EXPECT_GE(bound, sampled - 1e-15);
        EXPECT_LE(bound, sampled + 1e-6);
        EXPECT_TRUE(AtMostEverywhere(f, bound + 1e-9));
        EXPECT_FALSE(AtMostEverywhere(f, sampled - 1e-6));
    }
}

}  // namespace
}  // namespace quadrix::freeform
