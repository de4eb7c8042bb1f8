// Numerical checks of every §4.5 formula (seed 001) and of the zero tests of §4.5.13.
//
// Each shape is checked against points built independently of the formula (points lying on both
// surfaces, on the limb, extreme points of a sampled conic). Tolerances are relative to the size
// of the terms of the tested expression: a few hundred ulps of the largest term, since every
// coefficient is a sum of two- and three-factor products of the inputs.
#include "quadrix/engines/scanline/coefficients.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "quadrix/engines/scanline/resolver.h"

namespace quadrix::scanline {
namespace {

constexpr double kRel = 1e-12;  // relative tolerance for identities checked in double

// A random plane through point p.
Plane PlaneThrough(std::mt19937& rng, const Vec3& p) {
    std::uniform_real_distribution<double> u(-1, 1);
    Plane pl{u(rng), u(rng), u(rng), 0};
    pl.d = -(pl.a * p.x + pl.b * p.y + pl.c * p.z);
    return pl;
}

// A random quadric through point p (K adjusted).
Quadric QuadricThrough(std::mt19937& rng, const Vec3& p) {
    std::uniform_real_distribution<double> u(-1, 1);
    std::array<double, 10> k{};
    for (double& v : k) v = u(rng);
    Quadric q = Quadric::FromCoefficients(k);
    q.k[9] -= q.Evaluate(p);
    return q;
}

double Scale(const Quadric& q, const Vec3& p) {
    double s = 1 + std::fabs(p.x) + std::fabs(p.y) + std::fabs(p.z);
    return q.MaxAbs() * s * s;
}

TEST(ScanlineCoefficients, LineOfPlanesVanishesOnTheirCommonLine) {  // (4.7)
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-50, 50);
    for (int n = 0; n < 100; ++n) {
        Vec3 p{u(rng), u(rng), u(rng)};
        Plane a = PlaneThrough(rng, p), b = PlaneThrough(rng, p);
        Line2 l = LineOfPlanes(a, b);
        Vec3 dir = Cross(a.Normal(), b.Normal());
        for (double t : {0.0, 3.0, -7.5}) {
            Vec3 q = p + dir * t;
            EXPECT_NEAR(l.Evaluate(q.x, q.y), 0, kRel * 1e3 * (1 + l.TermScale(q.x, q.y)));
        }
        // And it does not vanish off the line (a point on plane a only).
        Vec3 off = p + Cross(a.Normal(), dir) * 1.0;
        EXPECT_GT(std::fabs(l.Evaluate(off.x, off.y)), 1e-6);
    }
}

TEST(ScanlineCoefficients, ConicOfPlaneQuadricIsHalfCp2TimesQOnThePlane) {  // (4.8)
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-20, 20);
    for (int n = 0; n < 100; ++n) {
        Vec3 p{u(rng), u(rng), u(rng)};
        Plane pl = PlaneThrough(rng, p);
        Quadric q = QuadricThrough(rng, p);
        Conic2 c = ConicOfPlaneQuadric(pl, q);
        // Vanishes at the common point.
        EXPECT_NEAR(c.Evaluate(p.x, p.y), 0, kRel * 1e2 * Scale(q, p));
        // Equals C_p²/2 · Q(x, y, z_plane(x, y)) anywhere.
        double x = u(rng), y = u(rng), z = -(pl.a * x + pl.b * y + pl.d) / pl.c;
        double expect = 0.5 * pl.c * pl.c * q.Evaluate({x, y, z});
        EXPECT_NEAR(c.Evaluate(x, y), expect,
                    kRel * 1e3 * (1 + std::fabs(expect)) * Scale(q, {x, y, z}));
    }
}

TEST(ScanlineCoefficients, LimbPlaneAndConicGiveDoubleRootsInZ) {  // (4.11), (4.12)
    // The sphere of radius 5 at (3, -2, 7): limb plane z = 7, limb conic the circle.
    Quadric s = Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -3, 2, -7, 9 + 4 + 49 - 25});
    Plane lp = LimbPlane(s);
    EXPECT_NEAR(lp.Evaluate({0, 0, 7}), 0, 1e-12);
    Conic2 c = LimbConic(s);
    EXPECT_NEAR(c.Evaluate(8, -2), 0, 1e-12);  // (3 + 5, −2)
    EXPECT_NEAR(c.Evaluate(3, 3), 0, 1e-12);
    EXPECT_LT(c.Evaluate(3, -2), 0);  // inside the silhouette (C > 0: same sign as Q)

    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-10, 10);
    for (int n = 0; n < 100; ++n) {
        Quadric q = QuadricThrough(rng, {u(rng), u(rng), u(rng)});
        if (std::fabs(q.C()) < 0.1) continue;
        Conic2 lc = LimbConic(q);
        // Limb conic value = C/2 · Q on the limb plane, and = −(discriminant of Q in z)/2 ...
        double x = u(rng), y = u(rng);
        double z = -(q.F() * x + q.E() * y + q.J()) / q.C();
        double onPlane = q.Evaluate({x, y, z});
        EXPECT_NEAR(lc.Evaluate(x, y), 0.5 * q.C() * onPlane,
                    kRel * 1e3 * (1 + std::fabs(onPlane)) * Scale(q, {x, y, z}));
        // ... so where it vanishes, Q(x, y, ·) has a double root (h² − a c = 0).
        double h = q.F() * x + q.E() * y + q.J();
        double a = q.Evaluate({x, y, 0});
        EXPECT_NEAR(-2 * lc.Evaluate(x, y) / q.C(), h * h / q.C() - a,
                    kRel * 1e4 * Scale(q, {x, y, z}) * (1 + 1 / std::fabs(q.C())));
    }
}

TEST(ScanlineCoefficients, LimbExistsFollowsTheSignOfC) {  // (4.14)
    Quadric sphere = Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, -1});
    Quadric hole = Quadric::FromCoefficients({-1, -1, -1, 0, 0, 0, 0, 0, 0, 1});
    Quadric zCylinder = Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -1});
    EXPECT_TRUE(LimbExists(sphere));
    EXPECT_FALSE(LimbExists(hole));
    EXPECT_FALSE(LimbExists(zCylinder));
}

TEST(ScanlineCoefficients, ThreePlanesMeetAtTheirCommonPoint) {  // §4.5.8
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-100, 100);
    for (int n = 0; n < 100; ++n) {
        Vec3 p{u(rng), u(rng), u(rng)};
        auto v =
            IntersectThreePlanes(PlaneThrough(rng, p), PlaneThrough(rng, p), PlaneThrough(rng, p));
        ASSERT_TRUE(v.has_value());
        EXPECT_LT(Length(*v - p), 1e-6 * (1 + Length(p)));
    }
    // Two parallel planes: no point (zero test on the pivot).
    EXPECT_FALSE(IntersectThreePlanes({1, 0, 0, 1}, {2, 0, 0, 5}, {0, 1, 0, 0}).has_value());
}

TEST(ScanlineCoefficients, LineConicQuadraticsFindTheCommonPoints) {  // (4.15), (4.16)
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-10, 10);
    for (int n = 0; n < 200; ++n) {
        Vec3 p{u(rng), u(rng), 0};
        Conic2 c{u(rng), u(rng), u(rng), u(rng), u(rng), 0};
        c.f = -c.Evaluate(p.x, p.y);  // through p
        Line2 l{u(rng), u(rng), 0};
        l.c = -(l.a * p.x + l.b * p.y);
        // Both eliminations are zero at p's free coordinate.
        if (l.b != 0) {
            EXPECT_NEAR(LineConicInX(l, c).Evaluate(p.x), 0,
                        1e-9 * (1 + std::fabs(l.b * l.b)) * 1e2);
        }
        if (l.a != 0) {
            EXPECT_NEAR(LineConicInY(l, c).Evaluate(p.y), 0,
                        1e-9 * (1 + std::fabs(l.a * l.a)) * 1e2);
        }
        auto pts = LineConicIntersections(l, c);
        if (pts.empty()) continue;  // tangent within the zero test (rare with random data)
        double best = HUGE_VAL;
        for (const Vec3& q : pts) {
            best = std::min(best, std::hypot(q.x - p.x, q.y - p.y));
            EXPECT_NEAR(l.Evaluate(q.x, q.y), 0, 1e-9);
            EXPECT_NEAR(c.Evaluate(q.x, q.y), 0, 1e-7);
        }
        EXPECT_LT(best, 1e-6);
    }
}

TEST(ScanlineCoefficients, RowAndColumnQuadraticsAreTheConic) {  // (4.17), (4.18)
    Conic2 c{1.5, -2, 0.7, 3, -1, 4};
    for (double x : {-3.0, 0.5, 7.0})
        for (double y : {-2.0, 1.25, 9.0}) {
            EXPECT_NEAR(ConicAtY(c, y).Evaluate(x), c.Evaluate(x, y), 1e-12 * 200);
            EXPECT_NEAR(ConicAtX(c, x).Evaluate(y), c.Evaluate(x, y), 1e-12 * 200);
        }
}

TEST(ScanlineCoefficients, ExtremaOfARotatedEllipseMatchSampling) {  // (4.20)–(4.23)
    // Ellipse with semi-axes 7 and 3, turned by 30°, centred at (11, −4), sampled densely.
    const double th = M_PI / 6, cs = std::cos(th), sn = std::sin(th), cx = 11, cy = -4;
    // x'²/49 + y'²/9 = 1 with x' = cs(x−cx) + sn(y−cy), y' = −sn(x−cx) + cs(y−cy).
    const double p = cs * cs / 49 + sn * sn / 9, q = sn * sn / 49 + cs * cs / 9,
                 r = 2 * cs * sn * (1.0 / 49 - 1.0 / 9);
    Conic2 c{p,
             q,
             r,
             -2 * p * cx - r * cy,
             -2 * q * cy - r * cx,
             p * cx * cx + q * cy * cy + r * cx * cy - 1};
    double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
    for (int i = 0; i < 200000; ++i) {
        double t = 2 * M_PI * i / 200000;
        double xe = 7 * std::cos(t), ye = 3 * std::sin(t);
        double x = cx + cs * xe - sn * ye, y = cy + sn * xe + cs * ye;
        EXPECT_NEAR(c.Evaluate(x, y), 0, 1e-12);
        xmin = std::min(xmin, x), xmax = std::max(xmax, x);
        ymin = std::min(ymin, y), ymax = std::max(ymax, y);
    }
    Roots1 v = SolveQuadratic1(VextrmQuadratic(c), 1e-12);
    ASSERT_EQ(v.kind, Roots1::kTwo);
    EXPECT_NEAR(v.r0, ymin, 1e-6);
    EXPECT_NEAR(v.r1, ymax, 1e-6);
    Roots1 h = SolveQuadratic1(HextrmQuadratic(c), 1e-12);
    ASSERT_EQ(h.kind, Roots1::kTwo);
    EXPECT_NEAR(h.r0, xmin, 1e-6);
    EXPECT_NEAR(h.r1, xmax, 1e-6);
    // (4.22) passes through the VEXTRMs, (4.23) through the HEXTRMs, both on the ellipse.
    for (double y : {v.r0, v.r1}) {
        Line2 il = InsertLine(c);
        double x = -(il.b * y + il.c) / il.a;
        EXPECT_NEAR(c.Evaluate(x, y), 0, 1e-9);
    }
    for (double x : {h.r0, h.r1}) {
        Line2 hl = HextrmLine(c);
        double y = -(hl.a * x + hl.c) / hl.b;
        EXPECT_NEAR(c.Evaluate(x, y), 0, 1e-9);
    }
}

// ---- zero tests (§4.5.13) ----

TEST(ScanlineZeroTests, EdgeOnPlaneToleratesRoundingButNotTilt) {  // (1)
    // A vertical world plane after a rotation about x by 90° leaves ~1e-17 in C.
    Plane rotated{0.6, 0.8, 6.123233995736766e-17 * 0.8, -5};
    EXPECT_TRUE(PlaneIsEdgeOn(rotated));
    EXPECT_TRUE(PlaneIsEdgeOn({1, 0, 0, -3}));
    EXPECT_FALSE(PlaneIsEdgeOn({1, 0, 1e-9, -3}));  // 1e-9 is a real tilt, 1e7 ulps
}

TEST(ScanlineZeroTests, ViewCylinderAfterRoundingIsDetected) {  // (2)
    Quadric c = Quadric::FromCoefficients({1, 1, 1e-17, 0, 2e-17, -1e-17, -30, -30, 1e-15, 1700});
    EXPECT_TRUE(QuadricIsViewCylinder(c, 100));
    Quadric tilted = Quadric::FromCoefficients({1, 1, 1e-6, 0, 0, 0, -30, -30, 0, 1700});
    EXPECT_FALSE(QuadricIsViewCylinder(tilted, 100));
    Quadric sphere = Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, -1});
    EXPECT_FALSE(QuadricIsViewCylinder(sphere, 100));
}

TEST(ScanlineZeroTests, DoubleRootsWithinTheirErrorEstimate) {  // (3)
    // (x − 1/3)² with rounded coefficients: exact discriminant zero, computed one not.
    Quadratic1 q{1, -2.0 / 3, 1.0 / 9};
    EXPECT_EQ(SolveQuadratic1(q, 0).kind, Roots1::kDouble);
    Quadratic1 two{1, -2.0 / 3, 1.0 / 9 - 1e-9};
    EXPECT_EQ(SolveQuadratic1(two, 1e-12).kind, Roots1::kTwo);
    Quadratic1 none{1, -2.0 / 3, 1.0 / 9 + 1e-9};
    EXPECT_EQ(SolveQuadratic1(none, 1e-12).kind, Roots1::kNone);
    // With a declared coefficient error of 1e-6 the 1e-9 perturbation is a double root.
    EXPECT_EQ(SolveQuadratic1(two, 1e-6).kind, Roots1::kDouble);
}

TEST(ScanlineZeroTests, PointOnHsiBoundaryWithinItsErrorEstimate) {  // (4)
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> u(-1000, 1000);
    for (int n = 0; n < 200; ++n) {
        Vec3 p{u(rng), u(rng), u(rng)};
        Plane a = PlaneThrough(rng, p);
        // p is on the plane up to the rounding of d: the estimate must cover it ...
        EXPECT_TRUE(SatisfiesPlane(a, p, 0));
        Plane neg{-a.a, -a.b, -a.c, -a.d};
        EXPECT_TRUE(SatisfiesPlane(neg, p, 0));
        // ... and must not swallow a displacement of 1e-3 outward.
        Vec3 out = p + a.Normal() * (1e-3 / Length(a.Normal()));
        EXPECT_FALSE(SatisfiesPlane(a, out, 1e-7));
        Quadric q = QuadricThrough(rng, p);
        EXPECT_TRUE(SatisfiesQuadric(q, p, 0));
        Quadric nq = q;
        for (double& v : nq.k) v = -v;
        EXPECT_TRUE(SatisfiesQuadric(nq, p, 0));
    }
}

TEST(ScanlineZeroTests, CoincidentVertices) {  // (5)
    EXPECT_TRUE(VerticesCoincide(100, 200, 100 + 1e-8, 200));
    EXPECT_FALSE(VerticesCoincide(100, 200, 100.001, 200));
}

TEST(ScanlinePencil, DisjointAndMeetingQuadricSurfaces) {
    auto q = [](std::array<double, 10> k) { return Quadric::FromCoefficients(k); };
    // Coaxial cylinders (the tube): disjoint.
    EXPECT_TRUE(QuadricSurfacesDisjoint(q({1, 0, 1, 0, 0, 0, 0, 0, 0, -4}),
                                        q({1, 0, 1, 0, 0, 0, 0, 0, 0, -1})));
    // A small sphere off-centre inside a big one: disjoint.
    EXPECT_TRUE(QuadricSurfacesDisjoint(q({1, 1, 1, 0, 0, 0, 0, 0, 0, -100}),
                                        q({1, 1, 1, 0, 0, 0, -3, 0, 0, 9 - 4})));
    // Two overlapping spheres: they meet.
    EXPECT_FALSE(QuadricSurfacesDisjoint(q({1, 1, 1, 0, 0, 0, 0, 0, 0, -4}),
                                         q({1, 1, 1, 0, 0, 0, -1, 0, 0, 1 - 4})));
    // Crossing cylinders: they meet.
    EXPECT_FALSE(QuadricSurfacesDisjoint(q({1, 0, 1, 0, 0, 0, 0, 0, 0, -4}),
                                         q({0, 1, 1, 0, 0, 0, 0, 0, 0, -1})));
}

}  // namespace
}  // namespace quadrix::scanline
