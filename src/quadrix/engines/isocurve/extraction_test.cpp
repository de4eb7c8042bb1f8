#include "quadrix/engines/isocurve/extraction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "quadrix/engines/isocurve/coverage.h"
#include "quadrix/freeform/bezier_surface.h"
#include "quadrix/import/freeform/freeform_reader.h"

namespace quadrix::isocurve {
namespace {

using freeform::BezierSurface;
using freeform::Surface;

std::vector<Surface> Model(const std::string& relative) {
    Diagnostics d;
    auto m = import::ReadFreeformFile(
        std::string(QUADRIX_SOURCE_DIR) + "/src/quadrix/import/freeform/testdata/" + relative, d);
    EXPECT_TRUE(m.has_value()) << relative;
    return m ? m->surfaces : std::vector<Surface>{};
}

Surface Bilinear(Vec3 p00, Vec3 p10, Vec3 p01, Vec3 p11) {
    return Surface::FromBezier(BezierSurface::FromPoints(1, 1, {p00, p10, p01, p11}));
}

// True when fixed = f0 + k (f1 - f0) / 2^level with k odd (level >= 1) or an end (level 0).
bool IsDyadic(const Isocurve& c, double f0, double f1) {
    double x = (c.fixed - f0) / (f1 - f0) * std::ldexp(1.0, c.level);
    double k = std::round(x);
    if (std::fabs(x - k) > 1e-12) return false;
    return c.level == 0 ? (k == 0 || k == 1) : std::fmod(k, 2.0) == 1;
}

// Every property of a valid coverage that can be checked on one surface.
void ExpectValidCoverage(const Surface& s, const Extraction& e, int samples, std::uint64_t seed,
                         bool dyadic = true) {
    EXPECT_EQ(e.stats.unresolved, 0);
    // The strips tile the parameter domain: their areas add up to it (sums of products of dyadic
    // rationals and roots: 1e-12 relative roundoff) and no interior point lies in two strips.
    EXPECT_NEAR(StripAreaRatio(s, e), 1.0, 1e-12) << s.Name();
    CoverageReport r = CheckCoverage(s, e, samples, seed);
    EXPECT_EQ(r.outsideStrips, 0) << s.Name();
    EXPECT_EQ(r.inSeveralStrips, 0) << s.Name();
    EXPECT_EQ(r.uncovered, 0) << s.Name() << " max distance " << r.maxDistance << " δ " << e.delta;
    // Adjacent curves are never farther apart than δ: Δ = δ exactly at crossings, found to
    // 1e-12 of the parameter range, so Δ may exceed δ by ~1e-12·|S'|/δ relative.
    EXPECT_LE(MaxAdjacentRatio(s, e, 16), 1 + 1e-8) << s.Name();
    double f0 = e.constant == Constant::kV ? s.V0() : s.U0();
    double f1 = e.constant == Constant::kV ? s.V1() : s.U1();
    if (dyadic) {
        for (const Isocurve& c : e.curves) EXPECT_TRUE(IsDyadic(c, f0, f1)) << c.fixed;
    }
}

TEST(IsocurveExtraction, SymbolicIsoDistanceMatchesPointwise) {
    // Δ²(t) − δ² from the symbolic construction against |C1(t) − C2(t)|² − δ² evaluated pointwise,
    // for polynomial curves and for rational ones (where the symbolic curve is multiplied by
    // (w1 w2)²).
    std::mt19937_64 rng(51);
    std::uniform_real_distribution<double> coord(-2, 2), weight(0.5, 2), unit(0, 1);
    for (int trial = 0; trial < 40; ++trial) {
        int p = 1 + trial % 4;
        bool rational = trial % 2 == 1;
        std::vector<double> a, b;
        for (int i = 0; i <= p; ++i) {
            double wa = rational ? weight(rng) : 1, wb = rational ? weight(rng) : 1;
            for (int k = 0; k < 3; ++k) {
                a.push_back(coord(rng) * wa);
                b.push_back(coord(rng) * wb);
            }
            if (rational) {
                a.push_back(wa);
                b.push_back(wb);
            }
        }
        int dim = rational ? 4 : 3;
        freeform::BezierCurve c1(dim, p, a, 0.25, 0.75), c2(dim, p, b, 0.25, 0.75);
        double delta = 0.3;
        freeform::BezierCurve f = IsoDistanceExcess(c1, c2, delta * delta);
        EXPECT_EQ(f.Degree(), rational ? 4 * p : 2 * p);
        for (int k = 0; k < 10; ++k) {
            double t = 0.25 + 0.5 * unit(rng);
            std::vector<double> x = c1.Evaluate(t), y = c2.Evaluate(t);
            double wx = rational ? x[3] : 1, wy = rational ? y[3] : 1;
            Vec3 d = Vec3{x[0], x[1], x[2]} / wx - Vec3{y[0], y[1], y[2]} / wy;
            double expect = Dot(d, d) - delta * delta;
            double scale = rational ? (wx * wy) * (wx * wy) : 1.0;
            // Values O(10–100) after the weight factor: 1e-11 relative.
            EXPECT_NEAR(f.EvaluateScalar(t) / scale, expect, 1e-11 * (1 + std::fabs(expect)));
        }
    }
}

TEST(IsocurveExtraction, FlatSquareGetsDyadicFullCurves) {
    Surface square = Bilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
    ExtractOptions o;
    o.direction = Direction::kConstV;
    o.keepStrips = true;
    Extraction e = ExtractAdaptive(square, 0.105, o);
    // Spacing 1/16 <= 0.105 < 1/8: curves at k/16, full length.
    ASSERT_EQ(e.curves.size(), 17u);
    for (const Isocurve& c : e.curves) {
        EXPECT_EQ(c.t0, 0);
        EXPECT_EQ(c.t1, 1);
    }
    EXPECT_NEAR(e.stats.length, 17, 1e-9);
    ExpectValidCoverage(square, e, 100000, 1);
    // Uniform spacing may use any n: 1/10 <= 0.105 < 1/9, so 11 curves.
    Extraction u = ExtractUniform(square, 0.105, o);
    EXPECT_EQ(u.curves.size(), 11u);
}

TEST(IsocurveExtraction, AutoBaseStartsFromTheUniformSpacing) {
    Surface square = Bilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
    ExtractOptions o;
    o.direction = Direction::kConstV;
    o.keepStrips = true;
    o.baseCount = 0;
    // Uniform needs n = 10; the base is N = 5 (N 2^L = 10 with N in [4, 8)), refined once.
    Extraction e = ExtractAdaptive(square, 0.105, o);
    EXPECT_EQ(e.baseCount, 5);
    EXPECT_EQ(e.curves.size(), 11u);
    ExpectValidCoverage(square, e, 2000, 7, false);
    auto torus = Model("obj/torus_nurbs.obj");
    Extraction t = ExtractAdaptive(torus[0], 0.1, o);
    ExpectValidCoverage(torus[0], t, 5000, 8, false);
}

TEST(IsocurveExtraction, ConvergingCurvesStopEarly) {
    // A triangle as a bilinear patch with the edge v = 0 collapsed to the apex: curves of constant
    // u all meet there, so adaptive extraction ends middle curves where neighbours come within δ
    // (Figure 2 of the seed) and the total length drops below the uniform one.
    Surface fan = Bilinear({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {1, 1, 0});
    ExtractOptions o;
    o.direction = Direction::kConstU;
    o.keepStrips = true;
    // δ just above 1/64, so that the finest dyadic spacing (1/64) is as wide as the uniform
    // spacing can be (1/61): the comparison measures adaptivity, not dyadic rounding.
    Extraction a = ExtractAdaptive(fan, 0.0165, o);
    Extraction u = ExtractUniform(fan, 0.0165, o);
    ExpectValidCoverage(fan, a, 100000, 2);
    ExpectValidCoverage(fan, u, 5000, 3, false);
    EXPECT_GT(a.stats.crossings, 0);
    bool partial = false;
    for (const Isocurve& c : a.curves) partial = partial || c.t0 > 0;
    EXPECT_TRUE(partial);
    // Δ(v) = v h for curves h apart, so a level-k curve is needed only for v > δ 2^(k-1):
    // Σ_k 2^(k-1) (1 − δ 2^(k-1)) over levels 3..6 plus 5 full curves is ~0.69 of the 62
    // uniform curves.
    EXPECT_EQ(u.curves.size(), 62u);
    EXPECT_LT(a.stats.length, 0.75 * u.stats.length);
}

TEST(IsocurveExtraction, ClosedSurfaceIsRefinedFromMinLevel) {
    auto torus = Model("obj/torus_nurbs.obj");
    ASSERT_EQ(torus.size(), 1u);
    ExtractOptions o;
    o.keepStrips = true;
    for (Direction d : {Direction::kConstU, Direction::kConstV}) {
        o.direction = d;
        Extraction e = ExtractAdaptive(torus[0], 0.1, o);
        ExpectValidCoverage(torus[0], e, 25000, 4);
    }
    // Without the forced levels the coinciding boundary curves (Δ ≡ 0) end the recursion at once.
    o.minLevel = 0;
    Extraction bad = ExtractAdaptive(torus[0], 0.1, o);
    EXPECT_EQ(bad.curves.size(), 2u);
    EXPECT_GT(CheckCoverage(torus[0], bad, 300, 5).uncovered, 0);
}

TEST(IsocurveExtraction, DegenerateInputsStayBounded) {
    // A weight function that vanishes inside the patch (weights of both signs): Δ² is garbage
    // there and must not drive the recursion to maxLevel everywhere.
    std::vector<double> c;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i)
            c.insert(c.end(), {double(i), double(j), 0, i == j ? 1.0 : -1.0});
    Surface bad = Surface::FromBezier(BezierSurface(4, 1, 1, c));
    EXPECT_FALSE(bad.WeightPositive());
    Extraction e = ExtractAdaptive(bad, 1e-3);
    EXPECT_TRUE(e.curves.empty());
    EXPECT_EQ(e.stats.unresolved, 1);
    // A tolerance absurdly small for the surface stops at maxCurves.
    Surface square = Bilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
    ExtractOptions o;
    o.direction = Direction::kConstV;
    o.maxCurves = 1000;
    Extraction tiny = ExtractAdaptive(square, 1e-9, o);
    EXPECT_LE(tiny.curves.size(), 1002u);
    EXPECT_GT(tiny.stats.unresolved, 0);
}

TEST(IsocurveExtraction, RationalSurfaces) {
    ExtractOptions o;
    o.keepStrips = true;
    // 10⁵ points on the NURBS sphere, 2.5·10⁴ on the others (sanitizer builds are slow).
    for (const char* file : {"obj/sphere_nurbs.obj", "geomview/torus.bez", "geomview/octant.bez"}) {
        std::vector<Surface> model = Model(file);
        int points = std::string(file) == "obj/sphere_nurbs.obj" ? 100000 : 25000;
        for (const Surface& s : model) {
            Extraction e = ExtractAdaptive(s, 0.05, o);
            ExpectValidCoverage(s, e, points / static_cast<int>(model.size()), 6);
        }
    }
}

// Acceptance (issue 6): ≥ 10⁵ random points per model within δ of the coverage.
void ExpectModelCovered(const std::string& file, double delta, int points) {
    auto model = Model(file);
    ASSERT_FALSE(model.empty());
    ExtractOptions o;
    o.keepStrips = true;
    int per = (points + static_cast<int>(model.size()) - 1) / static_cast<int>(model.size());
    int total = 0;
    for (std::size_t i = 0; i < model.size(); ++i) {
        Extraction e = ExtractAdaptive(model[i], delta, o);
        ExpectValidCoverage(model[i], e, per, 100 + i);
        total += per;
    }
    EXPECT_GE(total, points);
}

TEST(IsocurveExtraction, TeapotCoverage) { ExpectModelCovered("newell/teapot.txt", 0.05, 100000); }
TEST(IsocurveExtraction, TeacupCoverage) { ExpectModelCovered("newell/teacup.txt", 0.02, 100000); }
TEST(IsocurveExtraction, TeaspoonCoverage) {
    ExpectModelCovered("newell/teaspoon.txt", 0.01, 100000);
}

}  // namespace
}  // namespace quadrix::isocurve
