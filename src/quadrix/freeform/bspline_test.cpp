#include "quadrix/freeform/bspline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "quadrix/freeform/test_oracles.h"

namespace quadrix::freeform {
namespace {

using testing::CoxDeBoor;
using testing::MaxAbs;
using testing::MaxAbsDiff;
using testing::RandomVector;
using testing::Uniform;

// Knots for `count` points of degree p: clamped or not, random interior knots, some repeated.
std::vector<double> RandomKnots(std::mt19937_64& rng, int p, int count, bool clamped) {
    std::vector<double> k;
    int total = count + p + 1;
    if (clamped) {
        k.assign(static_cast<std::size_t>(p + 1), 0.0);
        int interior = total - 2 * (p + 1);
        for (int i = 0; i < interior; ++i) k.push_back(Uniform(rng, 0.05, 0.95));
        // A repeated knot (multiplicity up to p) now and then.
        if (interior >= 2 && p >= 2) k[k.size() - 1] = k[k.size() - 2];
        k.insert(k.end(), static_cast<std::size_t>(p + 1), 1.0);
    } else {
        for (int i = 0; i < total; ++i) k.push_back(Uniform(rng, -1, 2));
    }
    std::sort(k.begin(), k.end());
    return k;
}

std::vector<double> Oracle(const BSplineCurve& c, double t) {
    std::vector<double> r(static_cast<std::size_t>(c.Dim()), 0.0);
    for (int i = 0; i < c.Count(); ++i) {
        double b = CoxDeBoor(c.Knots(), i, c.Degree(), t, c.T1());
        for (int k = 0; k < c.Dim(); ++k) r[static_cast<std::size_t>(k)] += b * c.Point(i)[k];
    }
    return r;
}

BSplineCurve RandomCurve(std::mt19937_64& rng, int dim, int p, int count, bool clamped) {
    return BSplineCurve(dim, p, RandomKnots(rng, p, count, clamped),
                        RandomVector(rng, static_cast<std::size_t>(count * dim), -4, 4));
}

// Sums of O(4) control points with bounded basis functions: 1e-12 absolute.
constexpr double kTol = 1e-12;

TEST(FreeformBSpline, CheckKnotsExplainsProblems) {
    EXPECT_EQ(CheckKnots({0, 0, 0, 1, 1, 1}, 2, 3), "");
    EXPECT_NE(CheckKnots({0, 0, 1, 1}, 2, 3), "");          // too short
    EXPECT_NE(CheckKnots({0, 0, 0, 1, 0.5, 1}, 2, 3), "");  // decreasing
    EXPECT_NE(CheckKnots({0, 0, 0, 0, 0, 0}, 2, 3), "");    // empty domain
    EXPECT_NE(CheckKnots({0, 0, 0, 1, 1, 1}, 2, 2), "");    // too few points
}

TEST(FreeformBSpline, DeBoorMatchesCoxDeBoorSum) {
    std::mt19937_64 rng(21);
    for (int trial = 0; trial < 120; ++trial) {
        int p = trial % 5, count = p + 1 + trial % 6;
        BSplineCurve c = RandomCurve(rng, 1 + trial % 3, p, count, trial % 3 != 0);
        if (!(c.T0() < c.T1())) continue;
        for (int k = 0; k < 6; ++k) {
            double t = Uniform(rng, c.T0(), c.T1());
            EXPECT_LT(MaxAbsDiff(c.Evaluate(t), Oracle(c, t)), kTol);
        }
        EXPECT_LT(MaxAbsDiff(c.Evaluate(c.T1()), Oracle(c, c.T1())), kTol);
    }
}

TEST(FreeformBSpline, DerivativeMatchesFiniteDifference) {
    std::mt19937_64 rng(22);
    for (int trial = 0; trial < 80; ++trial) {
        int p = 1 + trial % 4;
        BSplineCurve c = RandomCurve(rng, 2, p, p + 1 + trial % 5, true);
        BSplineCurve d = c.Derivative();
        // Inside a span (away from knots, where lower-order derivatives may jump).
        std::vector<double> br = c.Breakpoints();
        std::size_t s = static_cast<std::size_t>(trial) % (br.size() - 1);
        if (br[s + 1] - br[s] < 0.02) continue;
        double t = Uniform(rng, br[s] + 0.005, br[s + 1] - 0.005);
        auto fd = testing::FiniteDifference([&](double x) { return Oracle(c, x); }, t, 1e-3);
        EXPECT_LT(MaxAbsDiff(d.Evaluate(t), fd), 1e-7 * (1 + MaxAbs(fd)));
    }
}

TEST(FreeformBSpline, KnotInsertionKeepsTheCurve) {
    std::mt19937_64 rng(23);
    for (int trial = 0; trial < 60; ++trial) {
        int p = 1 + trial % 4;
        BSplineCurve c = RandomCurve(rng, 3, p, p + 2 + trial % 4, trial % 2 == 0);
        double t = Uniform(rng, c.T0(), c.T1());
        int times = 1 + trial % p;
        BSplineCurve r = c.WithKnotInserted(t, times);
        EXPECT_EQ(r.Count(), c.Count() + times);
        for (int k = 0; k < 6; ++k) {
            double x = Uniform(rng, c.T0(), c.T1());
            EXPECT_LT(MaxAbsDiff(r.Evaluate(x), c.Evaluate(x)), 1e-11);
        }
    }
}

TEST(FreeformBSpline, BezierExtractionAndJoinKeepTheCurve) {
    std::mt19937_64 rng(24);
    for (int trial = 0; trial < 60; ++trial) {
        int p = trial % 5;
        BSplineCurve c = RandomCurve(rng, 2, p, p + 1 + trial % 5, trial % 2 == 0);
        std::vector<BezierCurve> segs = c.ToBezier();
        EXPECT_EQ(segs.size() + 1, c.Breakpoints().size());
        for (const BezierCurve& s : segs)
            for (int k = 0; k < 3; ++k) {
                double t = Uniform(rng, s.T0(), s.T1());
                EXPECT_LT(MaxAbsDiff(s.Evaluate(t), Oracle(c, t)), 1e-11);
            }
        BSplineCurve j = BSplineCurve::FromBezierSegments(segs);
        BSplineCurve e = c.Elevated(1);
        EXPECT_EQ(e.Degree(), p + 1);
        for (int k = 0; k < 6; ++k) {
            double t = Uniform(rng, c.T0(), c.T1());
            EXPECT_LT(MaxAbsDiff(j.Evaluate(t), Oracle(c, t)), 1e-11);
            EXPECT_LT(MaxAbsDiff(e.Evaluate(t), Oracle(c, t)), 1e-11);
        }
    }
}

TEST(FreeformBSpline, SymbolicOperationsOnDifferentKnotVectors) {
    std::mt19937_64 rng(25);
    for (int trial = 0; trial < 40; ++trial) {
        BSplineCurve a = RandomCurve(rng, 3, 1 + trial % 3, 5, true);
        BSplineCurve b = RandomCurve(rng, 3, 2 + trial % 2, 6, true);
        BSplineCurve s = RandomCurve(rng, 1, 2, 4, true);
        BSplineCurve sum = Add(a, b), diff = Subtract(a, b), prod = Multiply(s, a);
        BSplineCurve dot = Dot(a, b), cross = Cross(a, b);
        for (int k = 0; k < 6; ++k) {
            double t = Uniform(rng, 0, 1);
            std::vector<double> pa = a.Evaluate(t), pb = b.Evaluate(t);
            double ps = s.Evaluate(t)[0];
            Vec3 va{pa[0], pa[1], pa[2]}, vb{pb[0], pb[1], pb[2]};
            auto v3 = [](const std::vector<double>& x) { return Vec3{x[0], x[1], x[2]}; };
            // Products of O(4) values: 1e-10.
            EXPECT_LT(Length(v3(sum.Evaluate(t)) - (va + vb)), 1e-10);
            EXPECT_LT(Length(v3(diff.Evaluate(t)) - (va - vb)), 1e-10);
            EXPECT_LT(Length(v3(prod.Evaluate(t)) - va * ps), 1e-10);
            EXPECT_NEAR(dot.Evaluate(t)[0], Dot(va, vb), 1e-10);
            EXPECT_LT(Length(v3(cross.Evaluate(t)) - Cross(va, vb)), 1e-10);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Surfaces

std::vector<double> Oracle(const BSplineSurface& s, double u, double v) {
    std::vector<double> r(static_cast<std::size_t>(s.Dim()), 0.0);
    for (int j = 0; j < s.CountV(); ++j) {
        double bv = CoxDeBoor(s.KnotsV(), j, s.DegreeV(), v, s.V1());
        if (bv == 0) continue;
        for (int i = 0; i < s.CountU(); ++i) {
            double b = bv * CoxDeBoor(s.KnotsU(), i, s.DegreeU(), u, s.U1());
            for (int k = 0; k < s.Dim(); ++k)
                r[static_cast<std::size_t>(k)] += b * s.Point(i, j)[k];
        }
    }
    return r;
}

BSplineSurface RandomSurface(std::mt19937_64& rng, int dim, int p, int q, int nu, int nv) {
    return BSplineSurface(dim, p, q, RandomKnots(rng, p, nu, true), RandomKnots(rng, q, nv, true),
                          RandomVector(rng, static_cast<std::size_t>(nu * nv * dim), -3, 3));
}

TEST(FreeformBSplineSurface, EvaluationIsocurvesAndPatchesMatchOracle) {
    std::mt19937_64 rng(26);
    for (int trial = 0; trial < 30; ++trial) {
        int p = 1 + trial % 3, q = 1 + (trial / 3) % 3;
        BSplineSurface s = RandomSurface(rng, 3, p, q, p + 1 + trial % 4, q + 1 + trial % 3);
        PatchGrid g = s.ToPatches();
        std::vector<BSplineSurface> strips = s.SplitIntoUSpans();
        EXPECT_EQ(static_cast<int>(strips.size()), g.SpansU());
        BSplineSurface back = g.ToBSpline();
        for (int k = 0; k < 5; ++k) {
            double u = Uniform(rng, 0, 1), v = Uniform(rng, 0, 1);
            std::vector<double> o = Oracle(s, u, v);
            EXPECT_LT(MaxAbsDiff(s.Evaluate(u, v), o), 1e-12);
            EXPECT_LT(MaxAbsDiff(s.IsoCurveAtV(v).Evaluate(u), o), 1e-12);
            EXPECT_LT(MaxAbsDiff(s.IsoCurveAtU(u).Evaluate(v), o), 1e-12);
            EXPECT_LT(MaxAbsDiff(g.Evaluate(u, v), o), 1e-11);
            EXPECT_LT(MaxAbsDiff(back.Evaluate(u, v), o), 1e-11);
            const BSplineSurface& strip = strips[static_cast<std::size_t>(g.SpanU(u))];
            EXPECT_LT(MaxAbsDiff(strip.Evaluate(u, v), o), 1e-11);
        }
    }
}

TEST(FreeformBSplineSurface, DerivativesKnotInsertionElevation) {
    std::mt19937_64 rng(27);
    for (int trial = 0; trial < 20; ++trial) {
        int p = 2 + trial % 2, q = 1 + trial % 3;
        BSplineSurface s = RandomSurface(rng, 3, p, q, p + 3, q + 2);
        BSplineSurface su = s.DerivativeU(), sv = s.DerivativeV();
        BSplineSurface ins = s.WithKnotInsertedU(0.37, 2).WithKnotInsertedV(0.61);
        BSplineSurface el = s.ElevatedU(1).ElevatedV(2);
        PatchGrid g = s.ToPatches();
        for (int k = 0; k < 5; ++k) {
            double u = Uniform(rng, 0, 1), v = Uniform(rng, 0, 1);
            std::vector<double> o = Oracle(s, u, v);
            EXPECT_LT(MaxAbsDiff(ins.Evaluate(u, v), o), 1e-11);
            EXPECT_LT(MaxAbsDiff(el.Evaluate(u, v), o), 1e-11);
            // Derivatives inside a patch (away from knots).
            int a = g.SpanU(u), b = g.SpanV(v);
            double ua = g.BreaksU()[static_cast<std::size_t>(a)],
                   ub = g.BreaksU()[static_cast<std::size_t>(a + 1)];
            double va = g.BreaksV()[static_cast<std::size_t>(b)],
                   vb = g.BreaksV()[static_cast<std::size_t>(b + 1)];
            if (ub - ua < 0.02 || vb - va < 0.02) continue;
            u = std::clamp(u, ua + 0.005, ub - 0.005);
            v = std::clamp(v, va + 0.005, vb - 0.005);
            auto fu = testing::FiniteDifference([&](double x) { return Oracle(s, x, v); }, u, 1e-3);
            auto fv = testing::FiniteDifference([&](double y) { return Oracle(s, u, y); }, v, 1e-3);
            EXPECT_LT(MaxAbsDiff(su.Evaluate(u, v), fu), 1e-7 * (1 + MaxAbs(fu)));
            EXPECT_LT(MaxAbsDiff(sv.Evaluate(u, v), fv), 1e-7 * (1 + MaxAbs(fv)));
        }
    }
}

TEST(FreeformBSplineSurface, NormalFieldOfPiecewiseSurface) {
    std::mt19937_64 rng(28);
    BSplineSurface s = RandomSurface(rng, 3, 3, 2, 6, 5);
    PatchGrid n = NormalField(s);
    BSplineSurface su = s.DerivativeU(), sv = s.DerivativeV();
    for (int k = 0; k < 50; ++k) {
        double u = Uniform(rng, 0, 1), v = Uniform(rng, 0, 1);
        std::vector<double> a = su.Evaluate(u, v), b = sv.Evaluate(u, v);
        Vec3 expect = Cross(Vec3{a[0], a[1], a[2]}, Vec3{b[0], b[1], b[2]});
        std::vector<double> got = n.Evaluate(u, v);
        EXPECT_LT(Length(Vec3{got[0], got[1], got[2]} - expect), 1e-10 * (1 + Length(expect)));
    }
}

}  // namespace
}  // namespace quadrix::freeform
