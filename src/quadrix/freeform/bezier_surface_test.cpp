#include "quadrix/freeform/bezier_surface.h"

#include <gtest/gtest.h>

#include <random>

#include "quadrix/freeform/test_oracles.h"

namespace quadrix::freeform {
namespace {

using testing::BernsteinOracle;
using testing::MaxAbs;
using testing::MaxAbsDiff;
using testing::RandomVector;
using testing::Uniform;

std::vector<double> Oracle(const BezierSurface& s, double u, double v) {
    double a = (u - s.U0()) / (s.U1() - s.U0()), b = (v - s.V0()) / (s.V1() - s.V0());
    std::vector<double> r(static_cast<std::size_t>(s.Dim()), 0.0);
    for (int j = 0; j <= s.DegreeV(); ++j)
        for (int i = 0; i <= s.DegreeU(); ++i) {
            double f = BernsteinOracle(s.DegreeU(), i, a) * BernsteinOracle(s.DegreeV(), j, b);
            for (int k = 0; k < s.Dim(); ++k)
                r[static_cast<std::size_t>(k)] += f * s.Point(i, j)[k];
        }
    return r;
}

BezierSurface RandomSurface(std::mt19937_64& rng, int dim, int m, int n) {
    double u0 = Uniform(rng, -1, 1), v0 = Uniform(rng, -1, 1);
    return BezierSurface(
        dim, m, n, RandomVector(rng, static_cast<std::size_t>((m + 1) * (n + 1) * dim), -3, 3), u0,
        u0 + Uniform(rng, 0.2, 2), v0, v0 + Uniform(rng, 0.2, 2));
}

// A rational surface with weights in [0.5, 2] (positive, so the Euclidean surface is finite).
BezierSurface RandomRational(std::mt19937_64& rng, int m, int n) {
    std::vector<Vec3> p;
    std::vector<double> w;
    for (int k = 0; k < (m + 1) * (n + 1); ++k) {
        p.push_back({Uniform(rng, -3, 3), Uniform(rng, -3, 3), Uniform(rng, -3, 3)});
        w.push_back(Uniform(rng, 0.5, 2));
    }
    return BezierSurface::FromWeightedPoints(m, n, p, w);
}

TEST(FreeformBezierSurface, EvaluationAndIsocurvesMatchTensorSum) {
    std::mt19937_64 rng(11);
    for (int trial = 0; trial < 80; ++trial) {
        BezierSurface s = RandomSurface(rng, 1 + trial % 4, trial % 5, (trial / 5) % 4);
        for (int k = 0; k < 4; ++k) {
            double u = Uniform(rng, s.U0(), s.U1()), v = Uniform(rng, s.V0(), s.V1());
            std::vector<double> o = Oracle(s, u, v);
            // O(3) values, degree <= 4 in each direction: 1e-12 is a few hundred ulps.
            EXPECT_LT(MaxAbsDiff(s.Evaluate(u, v), o), 1e-12);
            EXPECT_LT(MaxAbsDiff(s.IsoCurveAtV(v).Evaluate(u), o), 1e-12);
            EXPECT_LT(MaxAbsDiff(s.IsoCurveAtU(u).Evaluate(v), o), 1e-12);
            EXPECT_LT(MaxAbsDiff(s.Transposed().Evaluate(v, u), o), 1e-12);
        }
    }
}

TEST(FreeformBezierSurface, PartialDerivativesMatchFiniteDifferences) {
    std::mt19937_64 rng(12);
    for (int trial = 0; trial < 60; ++trial) {
        BezierSurface s = RandomSurface(rng, 3, trial % 5, (trial / 5) % 5);
        BezierSurface su = s.DerivativeU(), sv = s.DerivativeV();
        double u = Uniform(rng, s.U0(), s.U1()), v = Uniform(rng, s.V0(), s.V1());
        auto fu = testing::FiniteDifference([&](double x) { return Oracle(s, x, v); }, u, 1e-3);
        auto fv = testing::FiniteDifference([&](double y) { return Oracle(s, u, y); }, v, 1e-3);
        // Exact stencil for degree <= 4 up to roundoff ~1e-16·|S|/h.
        EXPECT_LT(MaxAbsDiff(su.Evaluate(u, v), fu), 1e-8 * (1 + MaxAbs(fu)));
        EXPECT_LT(MaxAbsDiff(sv.Evaluate(u, v), fv), 1e-8 * (1 + MaxAbs(fv)));
    }
}

TEST(FreeformBezierSurface, SubdivisionElevationRestrictionKeepTheSurface) {
    std::mt19937_64 rng(13);
    for (int trial = 0; trial < 40; ++trial) {
        BezierSurface s = RandomSurface(rng, 3, 1 + trial % 4, 1 + (trial / 4) % 3);
        double um = Uniform(rng, s.U0(), s.U1()), vm = Uniform(rng, s.V0(), s.V1());
        auto [ul, ur] = s.SplitU(um);
        auto [vl, vr] = s.SplitV(vm);
        BezierSurface e = s.ElevatedTo(s.DegreeU() + 2, s.DegreeV() + 1);
        BezierSurface part = s.Restricted(s.U0(), um, vm, s.V1());
        for (int k = 0; k < 4; ++k) {
            double u = Uniform(rng, s.U0(), s.U1()), v = Uniform(rng, s.V0(), s.V1());
            std::vector<double> o = Oracle(s, u, v);
            EXPECT_LT(MaxAbsDiff((u < um ? ul : ur).Evaluate(u, v), o), 1e-11);
            EXPECT_LT(MaxAbsDiff((v < vm ? vl : vr).Evaluate(u, v), o), 1e-11);
            EXPECT_LT(MaxAbsDiff(e.Evaluate(u, v), o), 1e-11);
            double pu = Uniform(rng, s.U0(), um), pv = Uniform(rng, vm, s.V1());
            EXPECT_LT(MaxAbsDiff(part.Evaluate(pu, pv), Oracle(s, pu, pv)), 1e-10);
        }
    }
}

TEST(FreeformBezierSurface, SymbolicOperationsMatchPointwise) {
    std::mt19937_64 rng(14);
    for (int trial = 0; trial < 30; ++trial) {
        BezierSurface a = RandomSurface(rng, 3, trial % 4, (trial / 4) % 3);
        BezierSurface b = RandomSurface(rng, 3, (trial / 2) % 3, trial % 3)
                              .Reparametrized(a.U0(), a.U1(), a.V0(), a.V1());
        BezierSurface s =
            RandomSurface(rng, 1, 2, 1).Reparametrized(a.U0(), a.U1(), a.V0(), a.V1());
        BezierSurface sum = Add(a, b), diff = Subtract(a, b), prod = Multiply(s, a);
        BezierSurface dot = Dot(a, b), cross = Cross(a, b);
        for (int k = 0; k < 4; ++k) {
            double u = Uniform(rng, a.U0(), a.U1()), v = Uniform(rng, a.V0(), a.V1());
            Vec3 pa = a.EvaluateVec3(u, v), pb = b.EvaluateVec3(u, v);
            double ps = s.Evaluate(u, v)[0];
            // Products of O(3) values: 1e-11 absolute.
            EXPECT_LT(Length(sum.EvaluateVec3(u, v) - (pa + pb)), 1e-11);
            EXPECT_LT(Length(diff.EvaluateVec3(u, v) - (pa - pb)), 1e-11);
            EXPECT_LT(Length(prod.EvaluateVec3(u, v) - pa * ps), 1e-11);
            EXPECT_NEAR(dot.Evaluate(u, v)[0], Dot(pa, pb), 1e-11);
            EXPECT_LT(Length(cross.EvaluateVec3(u, v) - Cross(pa, pb)), 1e-11);
        }
    }
}

TEST(FreeformBezierSurface, PolynomialNormalFieldIsSuCrossSv) {
    std::mt19937_64 rng(15);
    for (int trial = 0; trial < 30; ++trial) {
        BezierSurface s = RandomSurface(rng, 3, 1 + trial % 4, 1 + (trial / 4) % 4);
        BezierSurface n = NormalField(s);
        EXPECT_EQ(n.DegreeU(), 2 * s.DegreeU() - 1);
        EXPECT_EQ(n.DegreeV(), 2 * s.DegreeV() - 1);
        double u = Uniform(rng, s.U0(), s.U1()), v = Uniform(rng, s.V0(), s.V1());
        auto fu = testing::FiniteDifference([&](double x) { return Oracle(s, x, v); }, u, 1e-3);
        auto fv = testing::FiniteDifference([&](double y) { return Oracle(s, u, y); }, v, 1e-3);
        Vec3 expect = Cross(Vec3{fu[0], fu[1], fu[2]}, Vec3{fv[0], fv[1], fv[2]});
        EXPECT_LT(Length(n.EvaluateVec3(u, v) - expect), 1e-7 * (1 + Length(expect)));
    }
}

TEST(FreeformBezierSurface, RationalNormalFieldIsWCubedSuCrossSv) {
    std::mt19937_64 rng(16);
    for (int trial = 0; trial < 30; ++trial) {
        BezierSurface s = RandomRational(rng, 1 + trial % 3, 1 + (trial / 3) % 3);
        BezierSurface n = NormalField(s);
        EXPECT_EQ(n.DegreeU(), 3 * s.DegreeU() - 1);
        EXPECT_EQ(n.DegreeV(), 3 * s.DegreeV() - 1);
        double u = Uniform(rng, 0.05, 0.95), v = Uniform(rng, 0.05, 0.95);
        auto euclid = [&](double a, double b) {
            Vec3 p = Dehomogenize(s.EvaluateVec4(a, b));
            return std::vector<double>{p.x, p.y, p.z};
        };
        // Finite differences of the Euclidean (rational) surface: not exact for rational
        // functions; with h = 1e-4 the 5-point error is ~h⁴·|S⁽⁵⁾| ≲ 1e-9 relative here.
        auto fu = testing::FiniteDifference([&](double x) { return euclid(x, v); }, u, 1e-4);
        auto fv = testing::FiniteDifference([&](double y) { return euclid(u, y); }, v, 1e-4);
        double w = s.EvaluateVec4(u, v).w;
        Vec3 expect = Cross(Vec3{fu[0], fu[1], fu[2]}, Vec3{fv[0], fv[1], fv[2]}) * (w * w * w);
        EXPECT_LT(Length(n.EvaluateVec3(u, v) - expect), 1e-6 * (1 + Length(expect)));
    }
}

}  // namespace
}  // namespace quadrix::freeform
