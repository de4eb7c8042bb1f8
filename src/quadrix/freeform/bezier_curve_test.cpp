#include "quadrix/freeform/bezier_curve.h"

#include <gtest/gtest.h>

#include <random>

#include "quadrix/freeform/power_form.h"
#include "quadrix/freeform/test_oracles.h"

namespace quadrix::freeform {
namespace {

using testing::BernsteinOracle;
using testing::MaxAbs;
using testing::MaxAbsDiff;
using testing::RandomVector;
using testing::Uniform;

// Direct Σ P_i B_i^n(s) with the Bernstein polynomials from their definition.
std::vector<double> Oracle(const BezierCurve& c, double t) {
    double s = (t - c.T0()) / (c.T1() - c.T0());
    std::vector<double> r(static_cast<std::size_t>(c.Dim()), 0.0);
    for (int i = 0; i <= c.Degree(); ++i)
        for (int k = 0; k < c.Dim(); ++k)
            r[static_cast<std::size_t>(k)] += c.Point(i)[k] * BernsteinOracle(c.Degree(), i, s);
    return r;
}

BezierCurve RandomCurve(std::mt19937_64& rng, int dim, int degree) {
    double t0 = Uniform(rng, -2, 1);
    double t1 = t0 + Uniform(rng, 0.1, 3);
    return BezierCurve(dim, degree,
                       RandomVector(rng, static_cast<std::size_t>((degree + 1) * dim), -5, 5), t0,
                       t1);
}

// Values of these random curves are O(10): 1e-12 absolute is ~100 ulps of accumulated roundoff
// in a degree-9 de Casteljau triangle.
constexpr double kTol = 1e-12;

TEST(FreeformBezierCurve, BinomialIsExact) {
    EXPECT_EQ(Binomial(0, 0), 1);
    EXPECT_EQ(Binomial(6, 3), 20);
    EXPECT_EQ(Binomial(40, 20), 137846528820.0);
    EXPECT_EQ(Binomial(56, 28), 7648690600760440.0);
    EXPECT_EQ(Binomial(5, -1), 0);
    EXPECT_EQ(Binomial(5, 6), 0);
}

TEST(FreeformBezierCurve, EvaluationMatchesBernsteinSum) {
    std::mt19937_64 rng(1);
    for (int trial = 0; trial < 200; ++trial) {
        int dim = 1 + trial % 4, degree = trial % 10;
        BezierCurve c = RandomCurve(rng, dim, degree);
        for (int k = 0; k < 5; ++k) {
            double t = Uniform(rng, c.T0(), c.T1());
            EXPECT_LT(MaxAbsDiff(c.Evaluate(t), Oracle(c, t)), kTol) << "degree " << degree;
        }
        // Endpoint interpolation.
        EXPECT_LT(MaxAbsDiff(c.Evaluate(c.T0()), std::vector<double>(c.Point(0), c.Point(0) + dim)),
                  kTol);
    }
}

TEST(FreeformBezierCurve, DerivativeMatchesFiniteDifference) {
    std::mt19937_64 rng(2);
    for (int trial = 0; trial < 100; ++trial) {
        BezierCurve c = RandomCurve(rng, 1 + trial % 3, trial % 8);
        BezierCurve d = c.Derivative();
        EXPECT_EQ(d.Degree(), std::max(c.Degree() - 1, 0));
        double t = Uniform(rng, c.T0(), c.T1());
        auto fd = testing::FiniteDifference([&](double x) { return Oracle(c, x); }, t, 1e-3);
        // The 5-point stencil is exact for degree <= 4; for higher degrees its error is
        // h⁴ f⁽⁵⁾/30 ~ 1e-12·|f⁽⁵⁾|, plus roundoff ~ 1e-16·|f| / h ~ 1e-12.
        EXPECT_LT(MaxAbsDiff(d.Evaluate(t), fd), 1e-6 * (1 + MaxAbs(fd)));
    }
}

TEST(FreeformBezierCurve, SplitRestrictAndReparametrizeKeepTheCurve) {
    std::mt19937_64 rng(3);
    for (int trial = 0; trial < 100; ++trial) {
        BezierCurve c = RandomCurve(rng, 3, 1 + trial % 7);
        double m = Uniform(rng, c.T0(), c.T1());
        auto [l, r] = c.Split(m);
        EXPECT_EQ(l.T1(), m);
        EXPECT_EQ(r.T0(), m);
        double a = Uniform(rng, c.T0(), m), b = Uniform(rng, m, c.T1());
        BezierCurve part = c.Restricted(a, b);
        for (int k = 0; k < 5; ++k) {
            double tl = Uniform(rng, c.T0(), m), tr = Uniform(rng, m, c.T1());
            double tp = Uniform(rng, a, b);
            EXPECT_LT(MaxAbsDiff(l.Evaluate(tl), Oracle(c, tl)), 1e-11);
            EXPECT_LT(MaxAbsDiff(r.Evaluate(tr), Oracle(c, tr)), 1e-11);
            EXPECT_LT(MaxAbsDiff(part.Evaluate(tp), Oracle(c, tp)), 1e-10);
        }
    }
}

TEST(FreeformBezierCurve, DegreeElevationKeepsTheCurve) {
    std::mt19937_64 rng(4);
    for (int trial = 0; trial < 50; ++trial) {
        BezierCurve c = RandomCurve(rng, 2, trial % 6);
        BezierCurve e = c.Elevated(1 + trial % 3);
        EXPECT_EQ(e.Degree(), c.Degree() + 1 + trial % 3);
        for (int k = 0; k < 5; ++k) {
            double t = Uniform(rng, c.T0(), c.T1());
            EXPECT_LT(MaxAbsDiff(e.Evaluate(t), c.Evaluate(t)), kTol);
        }
    }
}

TEST(FreeformBezierCurve, SymbolicOperationsMatchPointwise) {
    std::mt19937_64 rng(5);
    for (int trial = 0; trial < 60; ++trial) {
        BezierCurve a = RandomCurve(rng, 3, trial % 5);
        BezierCurve b = RandomCurve(rng, 3, (trial / 5) % 4).Reparametrized(a.T0(), a.T1());
        BezierCurve s = RandomCurve(rng, 1, trial % 3).Reparametrized(a.T0(), a.T1());
        BezierCurve sum = Add(a, b), diff = Subtract(a, b), prod = Multiply(s, a);
        BezierCurve dot = Dot(a, b), cross = Cross(a, b);
        EXPECT_EQ(prod.Degree(), s.Degree() + a.Degree());
        EXPECT_EQ(dot.Degree(), a.Degree() + b.Degree());
        for (int k = 0; k < 5; ++k) {
            double t = Uniform(rng, a.T0(), a.T1());
            Vec3 pa = a.EvaluateVec3(t), pb = b.EvaluateVec3(t);
            double ps = s.EvaluateScalar(t);
            // Products of O(10) values: 1e-10 absolute covers their roundoff.
            EXPECT_LT(Length(sum.EvaluateVec3(t) - (pa + pb)), 1e-11);
            EXPECT_LT(Length(diff.EvaluateVec3(t) - (pa - pb)), 1e-11);
            EXPECT_LT(Length(prod.EvaluateVec3(t) - pa * ps), 1e-10);
            EXPECT_NEAR(dot.EvaluateScalar(t), Dot(pa, pb), 1e-10);
            EXPECT_LT(Length(cross.EvaluateVec3(t) - Cross(pa, pb)), 1e-10);
        }
    }
}

TEST(FreeformBezierCurve, HullBoundsAndConstants) {
    BezierCurve c = BezierCurve::Scalar({1, -2, 3, 0.5});
    EXPECT_EQ(c.MinCoefficient(), -2);
    EXPECT_EQ(c.MaxCoefficient(), 3);
    for (double t = 0; t <= 1; t += 1.0 / 64) {
        double v = c.EvaluateScalar(t);
        EXPECT_GE(v, -2);
        EXPECT_LE(v, 3);
        EXPECT_NEAR(c.PlusConstant(4).EvaluateScalar(t), v + 4, 1e-14);
    }
}

TEST(FreeformBezierCurve, PowerFormMatchesDeCasteljau) {
    std::mt19937_64 rng(6);
    for (int trial = 0; trial < 100; ++trial) {
        BezierCurve c = RandomCurve(rng, 1 + trial % 4, trial % 9);
        PowerForm p(c);
        for (int k = 0; k < 5; ++k) {
            double t = Uniform(rng, c.T0(), c.T1());
            std::vector<double> got(static_cast<std::size_t>(c.Dim()));
            p.Evaluate(t, got.data());
            // Control points O(5), degree <= 8: conversion roundoff <= 3^8 ulps of 5 ≈ 7e-12.
            EXPECT_LT(MaxAbsDiff(got, c.Evaluate(t)), 1e-11);
        }
    }
}

TEST(FreeformBezierCurve, WeightedPointsAreHomogeneous) {
    // A quarter circle as a rational quadratic: weights 1, √½, 1.
    std::vector<Vec3> p = {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    std::vector<double> w = {1, std::sqrt(0.5), 1};
    BezierCurve c = BezierCurve::FromWeightedPoints(p, w);
    for (double t = 0; t <= 1; t += 0.125) {
        Vec3 q = Dehomogenize(c.EvaluateVec4(t));
        EXPECT_NEAR(Length(q), 1, 1e-15);
    }
}

}  // namespace
}  // namespace quadrix::freeform
