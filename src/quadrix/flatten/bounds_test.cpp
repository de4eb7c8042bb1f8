// Tests of the conservative bounds (bounds.h): analytic boxes against exact extents, the
// branch-and-bound against analytic extents of capped/mitered cylinders and cones, rejection
// sampling (every sampled point of a body lies in its box), unbounded and empty sets, and the
// amount of work (counted, so the checks are deterministic; times are printed, not asserted).
#include "quadrix/flatten/bounds.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "quadrix/flatten/bounds_test_bodies.h"

namespace quadrix {
namespace {

using namespace bounds_test;

// The relaxation (b1) and the search (b2) alone: the critical-point stage (a'') would settle the
// capped cylinders and cones first (bounds_critical_test.cpp), and they are its fallback.
BoundsOptions RelaxationOnly() {
    BoundsOptions o;
    o.criticalPoints = false;
    return o;
}

void ExpectConservativeAndTight(const Box3& got, const Box3& exact, double tol, const char* what) {
    for (int i = 0; i < 3; ++i) {
        EXPECT_LE(got.lo[i], exact.lo[i]) << what << " axis " << i;
        EXPECT_GE(got.hi[i], exact.hi[i]) << what << " axis " << i;
        EXPECT_LE(exact.lo[i] - got.lo[i], tol) << what << " axis " << i;
        EXPECT_LE(got.hi[i] - exact.hi[i], tol) << what << " axis " << i;
    }
}

TEST(Bounds, RotatedEllipsoidsAreAnalyticAndExact) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> size(0.1, 5), pos(-20, 20), mag(-8, 8);
    for (int trial = 0; trial < 200; ++trial) {
        // Magnitudes 10^±8 (STYLE.md): the same shape scaled, to check the relative accuracy.
        double s = std::pow(10.0, mag(rng));
        double a = size(rng) * s, b = size(rng) * s, c = size(rng) * s;
        Transform t =
            Transform::Translate({pos(rng) * s, pos(rng) * s, pos(rng) * s}) * RandomRotation(rng);
        FlatHalfSpace hs = QuadricHs(Ellipsoid(a, b, c).Transformed(t));
        BoundLiteral lit{&hs, false};
        BoundsStats stats;
        Box3 got = IntersectionBounds({&lit, 1}, {}, &stats);
        Box3 exact = ExactEllipsoidBox(t, a, b, c);
        // Relative 1e-7 of the size: the analytic formula is exact up to rounding in the
        // transformed coefficients (cond(A) up to 2500 here) plus a 1e-10 relative pad.
        ExpectConservativeAndTight(got, exact, 1e-7 * std::fmax(a, std::fmax(b, c)) * 20,
                                   "ellipsoid");
        EXPECT_EQ(stats.analyticOnly, 1);
        EXPECT_EQ(stats.boxesPopped, 0);
    }
}

TEST(Bounds, ComplementedSphereIsUnboundedAndSphereCanBeEmpty) {
    FlatHalfSpace s = QuadricHs(Ellipsoid(1, 1, 1));
    Box3 outside = LiteralBox(s, true);
    EXPECT_FALSE(outside.Finite());
    // x² + y² + z² + 1 <= 0 is empty.
    FlatHalfSpace none = QuadricHs(Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, 1}));
    EXPECT_TRUE(LiteralBox(none, false).Empty());
    BoundLiteral lit{&none, false};
    EXPECT_TRUE(IntersectionBounds({&lit, 1}).Empty());
}

TEST(Bounds, AxisCylinderCappedByAxisPlanesIsAnalytic) {
    // x² + y² <= 4 capped at 0 <= z <= 3: exact box without search.
    Body b;
    b.hs = {QuadricHs(Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -4})),
            PlaneHs({0, 0, 1, -3}), PlaneHs({0, 0, -1, 0})};
    b.complemented = {false, false, false};
    auto lits = b.Literals();
    BoundsStats stats;
    Box3 got = IntersectionBounds(lits, {}, &stats);
    ExpectConservativeAndTight(got, Box3{{-2, -2, 0}, {2, 2, 3}}, 1e-9, "cylinder");
    EXPECT_EQ(stats.analyticOnly, 1);
}

TEST(Bounds, UncappedCylinderIsUnboundedOnlyAlongItsAxis) {
    // Along z: bounded in x, y (analytically), unbounded in z.
    FlatHalfSpace cyl = QuadricHs(Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 1, 0, 0, 0}));
    BoundLiteral lit{&cyl, false};  // (x+1)² + y² <= 1
    Box3 got = IntersectionBounds({&lit, 1}, {});
    EXPECT_NEAR(got.lo.x, -2, 1e-9);
    EXPECT_NEAR(got.hi.x, 0, 1e-9);
    EXPECT_NEAR(got.lo.y, -1, 1e-9);
    EXPECT_NEAR(got.hi.y, 1, 1e-9);
    EXPECT_EQ(got.lo.z, -HUGE_VAL);
    EXPECT_EQ(got.hi.z, HUGE_VAL);
    // Oblique, in the xy plane: bounded in z only; found by the search.
    std::mt19937_64 rng(3);
    Transform t = Transform::Rotate(2, 30);
    FlatHalfSpace ob = QuadricHs(
        Quadric::FromCoefficients({0, 1, 1, 0, 0, 0, 0, 0, 0, -1}).Transformed(t));  // along x
    BoundLiteral lit2{&ob, false};
    BoundsOptions o;
    o.searchLimit = 1e6;
    Box3 g2 = IntersectionBounds({&lit2, 1}, o);
    EXPECT_EQ(g2.lo.x, -HUGE_VAL);
    EXPECT_EQ(g2.hi.x, HUGE_VAL);
    EXPECT_EQ(g2.lo.y, -HUGE_VAL);
    EXPECT_EQ(g2.hi.y, HUGE_VAL);
    EXPECT_LE(g2.lo.z, -1);
    EXPECT_GE(g2.hi.z, 1);
    // The certificate is rigorous over the whole search region (radius ~1.7e6 here), where a
    // rounding-level uncertainty of the cylinder's zero eigenvalue (~1e-14) costs ~1e-14 R²:
    // a few percent of the radius for a body unbounded along the other axes.
    EXPECT_LE(g2.hi.z, 1.1);
    EXPECT_GE(g2.lo.z, -1.1);
}

TEST(Bounds, MiteredPipesAreConservativeAndTight) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1), r(0.2, 2);
    BoundsStats stats;
    double seconds = 0;
    const int kTrials = 100;
    for (int trial = 0; trial < kTrials; ++trial) {
        Transform t =
            Transform::Translate({5 * u(rng), 5 * u(rng), 5 * u(rng)}) * RandomRotation(rng);
        Box3 exact;
        double radius = r(rng);
        Body b = MiteredPipe(t, radius, 2 + u(rng), 0.8 * u(rng), -2 + u(rng), 0.8 * u(rng), exact);
        auto lits = b.Literals();
        auto t0 = std::chrono::steady_clock::now();
        Box3 got = IntersectionBounds(lits, RelaxationOnly(), &stats);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        // relTolerance 1e-3 of the body's size (about 4-6 here) per side, with slack 2x.
        ExpectConservativeAndTight(got, exact, 2e-2, "mitered pipe");
    }
    std::printf("[ bounds ] mitered pipe: %.1f us/body, %.0f boxes popped/body, %lld budget hits\n",
                1e6 * seconds / kTrials, double(stats.boxesPopped) / kTrials,
                static_cast<long long>(stats.budgetExhausted));
    EXPECT_EQ(stats.budgetExhausted, 0);
}

TEST(Bounds, CappedConesAreConservativeAndTight) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1), slope(0.2, 2), h(0.2, 3);
    BoundsStats stats;
    double seconds = 0;
    const int kTrials = 60;
    for (int trial = 0; trial < kTrials; ++trial) {
        Transform t =
            Transform::Translate({5 * u(rng), 5 * u(rng), 5 * u(rng)}) * RandomRotation(rng);
        double h0 = h(rng), h1 = h0 + h(rng);
        Box3 exact;
        Body b = ConeFrustum(t, slope(rng), h0, h1, exact);
        auto lits = b.Literals();
        auto t0 = std::chrono::steady_clock::now();
        Box3 got = IntersectionBounds(lits, RelaxationOnly(), &stats);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        // The nappe certificate allows for a rounding-level one-sheet neck near the apex
        // (~1e-7 of the size); 1e-4 absolute is far above that and far below a pixel.
        ExpectConservativeAndTight(got, exact, 1e-4, "cone frustum");
    }
    std::printf("[ bounds ] cone frustum: %.1f us/body, %.1f convex solves/body, %lld boxes\n",
                1e6 * seconds / kTrials, double(stats.convexSolves) / kTrials,
                static_cast<long long>(stats.boxesPopped));
    // Convex nappes are settled by the relaxation: no branch-and-bound.
    EXPECT_EQ(stats.boxesPopped, 0);
}

TEST(Bounds, NeckedHyperboloidFallsBackToTheSearch) {
    // x² + y² <= 1 + z² between z = -1 and z = 2 (seed 001 §2.1.1: "necked" cylinders), which is
    // not convex: the branch-and-bound bounds it. Its extremes are on the cap circles (radii √2
    // and √5) since the radius sqrt(1 + z²) is convex in z.
    std::mt19937_64 rng(5);
    Transform t = Transform::Translate({1, 2, 3}) * RandomRotation(rng);
    Body b;
    b.hs.push_back(
        QuadricHs(Quadric::FromCoefficients({1, 1, -1, 0, 0, 0, 0, 0, 0, -1}).Transformed(t)));
    b.hs.push_back(PlaneHs(Plane{0, 0, 1, -2}.Transformed(t)));
    b.hs.push_back(PlaneHs(Plane{0, 0, -1, -1}.Transformed(t)));
    b.complemented = {false, false, false};
    Box3 exact;
    ExtendByEllipse(exact, t.MapPoint({0, 0, -1}), t.MapVector({std::sqrt(2.0), 0, 0}),
                    t.MapVector({0, std::sqrt(2.0), 0}));
    ExtendByEllipse(exact, t.MapPoint({0, 0, 2}), t.MapVector({std::sqrt(5.0), 0, 0}),
                    t.MapVector({0, std::sqrt(5.0), 0}));
    BoundsOptions o;
    o.searchLimit = 1e6;
    BoundsStats stats;
    auto lits = b.Literals();
    Box3 got = IntersectionBounds(lits, o, &stats);
    // relTolerance 1e-3 of the inner box (size ~6): within 1e-2 per side.
    ExpectConservativeAndTight(got, exact, 1e-2, "necked hyperboloid");
    EXPECT_GT(stats.boxesPopped, 0);
    EXPECT_EQ(stats.budgetExhausted, 0);
}

// Every point of a body found by rejection sampling lies in its box: a property test over
// bodies of every kind (convex, nappes, complemented quadrics, two quadrics, non-convex).
TEST(Bounds, RandomPointsOfBodiesLieInTheirBoxes) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    auto quadric = [](std::array<double, 10> k, const Transform& t) {
        return QuadricHs(Quadric::FromCoefficients(k).Transformed(t));
    };
    auto plane = [](Plane p, const Transform& t) { return PlaneHs(p.Transformed(t)); };
    int sampledInside = 0;
    for (int trial = 0; trial < 40; ++trial) {
        Transform t =
            Transform::Translate({2 * u(rng), 2 * u(rng), 2 * u(rng)}) * RandomRotation(rng);
        Body b;
        switch (trial % 8) {
            case 0:  // sphere cut by an oblique plane
                b.hs = {quadric({1, 1, 1, 0, 0, 0, 0, 0, 0, -1}, t),
                        plane({u(rng), u(rng), 1, 0.3 * u(rng)}, t)};
                b.complemented = {false, false};
                break;
            case 1:  // tube with mitered ends
                b.hs = {quadric({1, 1, 0, 0, 0, 0, 0, 0, 0, -1}, t),
                        quadric({1, 1, 0, 0, 0, 0, 0, 0, 0, -0.25}, t),
                        plane({0.4 * u(rng), 0, 1, -1}, t), plane({0, 0.4 * u(rng), -1, -1}, t)};
                b.complemented = {false, true, false, false};
                break;
            case 2: {  // cone frustum
                Box3 unused;
                b = ConeFrustum(t, 0.7, 0.5, 1.5, unused);
                break;
            }
            case 3:  // two crossing cylinders (Steinmetz solid)
                b.hs = {quadric({1, 1, 0, 0, 0, 0, 0, 0, 0, -1}, t),
                        quadric({0, 1, 1, 0, 0, 0, 0, 0, 0, -1}, t)};
                b.complemented = {false, false};
                break;
            case 4:  // ellipsoid minus a sphere reaching out of it
                b.hs = {quadric({1, 0.25, 1, 0, 0, 0, 0, 0, 0, -1}, t),
                        quadric({1, 1, 1, 0, 0, 0, 0, -1.8, 0, 3.24 - 0.81}, t)};
                b.complemented = {false, true};
                break;
            case 5:  // two-sheet hyperboloid, one sheet capped
                b.hs = {quadric({1, 1, -1, 0, 0, 0, 0, 0, 0, 0.25}, t), plane({0, 0, 1, -1.5}, t),
                        plane({0, 0, -1, 0}, t)};
                b.complemented = {false, false, false};
                break;
            case 6:  // paraboloid z >= x² + y², capped
                b.hs = {quadric({1, 1, 0, 0, 0, 0, 0, 0, -0.5, 0}, t), plane({0, 0, 1, -1.2}, t)};
                b.complemented = {false, false};
                break;
            default:  // necked hyperboloid (non-convex), capped obliquely
                b.hs = {quadric({1, 1, -1, 0, 0, 0, 0, 0, 0, -0.5}, t), plane({0.3, 0, 1, -1}, t),
                        plane({0, 0, -1, -1}, t)};
                b.complemented = {false, false, false};
                break;
        }
        auto lits = b.Literals();
        Box3 box = IntersectionBounds(lits, {});
        ASSERT_TRUE(box.Finite()) << "trial " << trial;
        // Sample a region twice the box's size around it: points of the body outside the box
        // would show up there (every body here fits in radius 4 of its centre).
        Vec3 c = box.Center(), half = box.Size() * 1.0;
        for (int i = 0; i < 3; ++i) half[i] = std::fmax(half[i], 1.0);
        for (int k = 0; k < 4000; ++k) {
            Vec3 p{c.x + half.x * u(rng), c.y + half.y * u(rng), c.z + half.z * u(rng)};
            if (!b.Contains(p)) continue;
            ++sampledInside;
            for (int i = 0; i < 3; ++i) {
                ASSERT_GE(p[i], box.lo[i]) << "trial " << trial << " axis " << i;
                ASSERT_LE(p[i], box.hi[i]) << "trial " << trial << " axis " << i;
            }
        }
    }
    EXPECT_GT(sampledInside, 5000);  // the test did sample the bodies (about 6400)
}

TEST(Bounds, ProvablyEmptyBodiesHaveEmptyBoxes) {
    // Two disjoint spheres whose analytic boxes overlap (diagonal neighbours).
    FlatHalfSpace a = QuadricHs(Ellipsoid(1, 1, 1));
    FlatHalfSpace b =
        QuadricHs(Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -1.5, -1.5, 0, 2 * 2.25 - 1}));
    BoundLiteral lits[2] = {{&a, false}, {&b, false}};
    EXPECT_TRUE(IntersectionBounds(lits).Empty());
    // A sphere and a plane missing it.
    FlatHalfSpace p = PlaneHs({1, 1, 1, 3});  // x + y + z <= -3: beyond the unit sphere
    BoundLiteral lits2[2] = {{&a, false}, {&p, false}};
    EXPECT_TRUE(IntersectionBounds(lits2).Empty());
}

TEST(Bounds, TenThousandSpheresTakeTheAnalyticPath) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> pos(-100, 100), rad(0.1, 2);
    std::vector<FlatHalfSpace> spheres;
    for (int i = 0; i < 10000; ++i) {
        Vec3 c{pos(rng), pos(rng), pos(rng)};
        double r = rad(rng);
        spheres.push_back(QuadricHs(
            Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -c.x, -c.y, -c.z, Dot(c, c) - r * r})));
    }
    // With two transparent clip planes each, as the Flattener adds them for perspective.
    FlatHalfSpace nearPlane = PlaneHs({0, 0, -1, -1000}), farPlane = PlaneHs({0, 0, 1, -1000});
    BoundsStats stats;
    auto t0 = std::chrono::steady_clock::now();
    for (const FlatHalfSpace& s : spheres) {
        BoundLiteral lits[3] = {{&s, false}, {&nearPlane, false}, {&farPlane, false}};
        Box3 box = IntersectionBounds(lits, {}, &stats);
        ASSERT_TRUE(box.Finite());
    }
    double ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ bounds ] 10,000 spheres with 2 clip planes: %.1f ms\n", ms);
    EXPECT_EQ(stats.analyticOnly, 10000);  // deterministic proxy for the time
    EXPECT_EQ(stats.convexSolves, 0);
    EXPECT_EQ(stats.boxesPopped, 0);
}

TEST(Bounds, TreeBoundsCombineChildren) {
    FlatScene f;
    f.width = 100;
    f.height = 50;
    f.halfSpaces.push_back(QuadricHs(
        Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -10, -10, 0, 200 - 25})));  // r 5 at (10,10)
    f.halfSpaces.push_back(QuadricHs(
        Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -14, -10, 0, 296 - 25})));  // r 5 at (14,10)
    for (int i = 0; i < 2; ++i) {
        FlatBody b;
        b.literals = {{i, false}};
        f.bodies.push_back(b);
        FlatCsgNode leaf;
        leaf.body = i;
        f.nodes.push_back(leaf);
    }
    for (scene::CsgOp op :
         {scene::CsgOp::kUnion, scene::CsgOp::kIntersection, scene::CsgOp::kDifference}) {
        FlatCsgNode n;
        n.isLeaf = false;
        n.op = op;
        n.children = {0, 1};
        f.nodes.push_back(n);
        FlatSolid s;
        s.root = static_cast<int>(f.nodes.size()) - 1;
        f.solids.push_back(s);
    }
    ComputeSceneBounds(f);
    const double tol = 1e-8;                      // analytic sphere boxes
    EXPECT_NEAR(f.nodes[2].bounds.lo.x, 5, tol);  // union
    EXPECT_NEAR(f.nodes[2].bounds.hi.x, 19, tol);
    EXPECT_NEAR(f.nodes[3].bounds.lo.x, 9, tol);  // intersection
    EXPECT_NEAR(f.nodes[3].bounds.hi.x, 15, tol);
    EXPECT_NEAR(f.nodes[4].bounds.lo.x, 5, tol);  // difference: the minuend's
    EXPECT_NEAR(f.nodes[4].bounds.hi.x, 15, tol);
    // Solids are clipped to the image in x and y (not in depth).
    EXPECT_NEAR(f.solids[0].bounds.lo.y, 5, tol);
    EXPECT_NEAR(f.solids[0].bounds.lo.z, -5, tol);
    FlatSolid off;
    f.halfSpaces.push_back(QuadricHs(Ellipsoid(1, 1, 1)));  // around (0,0): partly in the image
    f.bodies.push_back(FlatBody{{{2, false}}, {}, -1, "", {}, {}});
    FlatCsgNode leaf;
    leaf.body = 2;
    f.nodes.push_back(leaf);
    off.root = static_cast<int>(f.nodes.size()) - 1;
    f.solids.push_back(off);
    ComputeSceneBounds(f);
    EXPECT_EQ(f.solids.back().bounds.lo.x, 0);
    EXPECT_NEAR(f.solids.back().bounds.hi.x, 1, tol);
}

// Stage (a'): bodies of planes only get the box of their vertices. Random polytopes (planes
// tangent to a sphere of radius s at random directions, s = 10^-4 .. 10^4, some open towards +z):
// random points of each lie in its box (conservative); a bounded one's box equals the convex
// relaxation's (the oracle, fast path off, exact for bounded convex bodies) to 1e-7 of its size;
// an unbounded one's box is never looser than the relaxation's.
TEST(Bounds, PolytopesTakeTheVertexPathAndAgreeWithTheRelaxation) {
    std::mt19937_64 rng(17);
    std::normal_distribution<double> g(0, 1);
    int bounded = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const double scale = std::pow(10.0, (trial % 9) - 4);
        const Vec3 centre{g(rng) * scale, g(rng) * scale, g(rng) * scale};
        const int n = 4 + trial % 12;
        std::vector<FlatHalfSpace> hs;
        for (int i = 0; i < n; ++i) {
            Vec3 d = Normalize(Vec3{g(rng), g(rng), g(rng)});
            if (trial % 10 == 0) d.z = -std::fabs(d.z);  // open towards +z: unbounded
            hs.push_back(PlaneHs({d.x, d.y, d.z, -Dot(d, centre) - scale}));
        }
        std::vector<BoundLiteral> lits;
        for (const FlatHalfSpace& h : hs) lits.push_back({&h, false});
        BoundsOptions fast, slow;
        slow.polytopeVertices = false;
        fast.searchLimit = slow.searchLimit = 1e6 * scale;
        const Box3 a = IntersectionBounds(lits, fast);
        const Box3 b = IntersectionBounds(lits, slow);
        ASSERT_FALSE(a.Empty()) << trial;  // the centre is inside
        ASSERT_FALSE(b.Empty()) << trial;
        const bool isBounded = b.Finite();
        bounded += isBounded;
        for (int k = 0; k < 3; ++k) {
            const double size = isBounded ? b.hi[k] - b.lo[k] : 0;
            if (isBounded) {
                EXPECT_NEAR(a.lo[k], b.lo[k], 1e-7 * size) << trial;
                EXPECT_NEAR(a.hi[k], b.hi[k], 1e-7 * size) << trial;
            } else {
                EXPECT_GE(a.lo[k], b.lo[k] - 1e-9 * std::fabs(b.lo[k])) << trial;
                EXPECT_LE(a.hi[k], b.hi[k] + 1e-9 * std::fabs(b.hi[k])) << trial;
            }
        }
        // Random points of the polytope (rejection sampling in a box around the centre).
        std::uniform_real_distribution<double> u(-20 * scale, 20 * scale);
        for (int t = 0; t < 2000; ++t) {
            const Vec3 p = centre + Vec3{u(rng), u(rng), u(rng)};
            bool in = true;
            for (const FlatHalfSpace& h : hs) in = in && h.plane.Evaluate(p) <= 0;
            if (!in) continue;
            for (int k = 0; k < 3; ++k) {
                EXPECT_GE(p[k], a.lo[k]) << trial;
                EXPECT_LE(p[k], a.hi[k]) << trial;
            }
        }
    }
    EXPECT_GT(bounded, 100);
}

}  // namespace
}  // namespace quadrix
