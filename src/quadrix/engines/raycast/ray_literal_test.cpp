#include "quadrix/engines/raycast/ray_literal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace quadrix::raycast {
namespace {

constexpr double kInf = HUGE_VAL;
constexpr std::int32_t kNo = Interval::kNoId;

FlatHalfSpace PlaneHs(double a, double b, double c, double d) {
    FlatHalfSpace h;
    h.isPlane = true;
    h.plane = {a, b, c, d};
    return h;
}
FlatHalfSpace QuadricHs(const std::array<double, 10>& k) {
    FlatHalfSpace h;
    h.isPlane = false;
    h.quadric = Quadric::FromCoefficients(k);
    return h;
}

IntervalList Set(const FlatHalfSpace& h, bool complemented, double x, double y) {
    IntervalList out;
    LiteralCounters counters;
    LiteralSetOnRay(RayHalfSpace::From(h), complemented, x, y, 7, out, counters);
    EXPECT_TRUE(out.IsCanonical());
    return out;
}

TEST(RaycastLiteral, PlanesGiveHalfLinesOrAllOrNothing) {
    // 2z − 10 <= 0: t <= 5.
    EXPECT_EQ(Set(PlaneHs(0, 0, 2, -10), false, 3, 4), IntervalList::Single(-kInf, kNo, 5, 7));
    EXPECT_EQ(Set(PlaneHs(0, 0, 2, -10), true, 3, 4), IntervalList::Single(5, 7, kInf, kNo));
    // −z + x <= 0 at x = 3: t >= 3.
    EXPECT_EQ(Set(PlaneHs(1, 0, -1, 0), false, 3, 4), IntervalList::Single(3, 7, kInf, kNo));
    // Edge-on plane x − 3 <= 0 (parallel to the rays): all, nothing, or on the plane all for H and
    // nothing for !H (regularised complement).
    EXPECT_EQ(Set(PlaneHs(1, 0, 0, -3), false, 2.5, 0), IntervalList::All());
    EXPECT_TRUE(Set(PlaneHs(1, 0, 0, -3), true, 2.5, 0).empty());
    EXPECT_TRUE(Set(PlaneHs(1, 0, 0, -3), false, 3.5, 0).empty());
    EXPECT_EQ(Set(PlaneHs(1, 0, 0, -3), true, 3.5, 0), IntervalList::All());
    EXPECT_EQ(Set(PlaneHs(1, 0, 0, -3), false, 3, 0), IntervalList::All());
    EXPECT_TRUE(Set(PlaneHs(1, 0, 0, -3), true, 3, 0).empty());
    // NaN coefficients: empty both ways.
    EXPECT_TRUE(Set(PlaneHs(NAN, 0, 1, 0), false, 1, 1).empty());
    EXPECT_TRUE(Set(PlaneHs(NAN, 0, 1, 0), true, 1, 1).empty());
}

TEST(RaycastLiteral, SphereGivesAnIntervalOrNothing) {
    // x² + y² + z² − 25 <= 0 at (3, 0): t in [−4, 4]; at (5, 0) the ray is tangent: nothing.
    auto sphere = QuadricHs({1, 1, 1, 0, 0, 0, 0, 0, 0, -25});
    EXPECT_EQ(Set(sphere, false, 3, 0), IntervalList::Single(-4, 7, 4, 7));
    IntervalList outside = Set(sphere, true, 3, 0);
    ASSERT_EQ(outside.size(), 2u);
    EXPECT_EQ(outside[0], (Interval{-kInf, -4, kNo, 7}));
    EXPECT_EQ(outside[1], (Interval{4, kInf, 7, kNo}));
    EXPECT_TRUE(Set(sphere, false, 5, 0).empty());
    EXPECT_EQ(Set(sphere, true, 5, 0), IntervalList::All());
    EXPECT_TRUE(Set(sphere, false, 6, 0).empty());
}

TEST(RaycastLiteral, ConesCylindersAndParaboloids) {
    // Double cone along z: x² + y² − z² <= 0. At distance 3 from the axis: two half-lines.
    auto cone = QuadricHs({1, 1, -1, 0, 0, 0, 0, 0, 0, 0});
    IntervalList c = Set(cone, false, 3, 0);
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c[0], (Interval{-kInf, -3, kNo, 7}));
    EXPECT_EQ(c[1], (Interval{3, kInf, 7, kNo}));
    // Through the apex (the axis): a double root with a < 0, the whole ray; !H nothing.
    EXPECT_EQ(Set(cone, false, 0, 0), IntervalList::All());
    EXPECT_TRUE(Set(cone, true, 0, 0).empty());
    // Cylinder along z, x² + y² − 4 <= 0: constant along the ray (c = 0, b = 0).
    auto cyl = QuadricHs({1, 1, 0, 0, 0, 0, 0, 0, 0, -4});
    EXPECT_EQ(Set(cyl, false, 1, 1), IntervalList::All());
    EXPECT_TRUE(Set(cyl, false, 3, 0).empty());
    EXPECT_EQ(Set(cyl, false, 2, 0), IntervalList::All());  // on the surface: Q ≡ 0, inside
    EXPECT_TRUE(Set(cyl, true, 2, 0).empty());
    // Cylinder along x, y² + z² − 4 <= 0, seen sideways: an interval, complement two pieces.
    auto side = QuadricHs({0, 1, 1, 0, 0, 0, 0, 0, 0, -4});
    EXPECT_EQ(Set(side, false, 10, 0), IntervalList::Single(-2, 7, 2, 7));
    EXPECT_EQ(Set(side, true, 10, 0).size(), 2u);
    // Paraboloid x² + y² − 2z <= 0 (2J = −2): linear along the ray, t >= (x² + y²)/2.
    auto bowl = QuadricHs({1, 1, 0, 0, 0, 0, 0, 0, -1, 0});
    EXPECT_EQ(Set(bowl, false, 2, 2), IntervalList::Single(4, 7, kInf, kNo));
    EXPECT_EQ(Set(bowl, true, 2, 2), IntervalList::Single(-kInf, kNo, 4, 7));
    // Hyperbolic "no real root" with a < 0: −z² − 1 <= 0 everywhere.
    EXPECT_EQ(Set(QuadricHs({0, 0, -1, 0, 0, 0, 0, 0, 0, -1}), false, 0, 0), IntervalList::All());
    // The empty quadric 0 <= 0 holds everywhere.
    EXPECT_EQ(Set(QuadricHs({}), false, 1, 2), IntervalList::All());
}

TEST(RaycastLiteral, QuadricCentres) {
    // (x − 3)² + 2 (y + 7)² + (z − 1000)² − 4 <= 0.
    auto c = RayHalfSpace::Centre(
        Quadric::FromCoefficients({1, 2, 1, 0, 0, 0, -3, 14, -1000, 9 + 98 + 1e6 - 4}));
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(*c, Vec3(3, -7, 1000));
    // Rounded to integers.
    c = RayHalfSpace::Centre(Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -0.25, 0, -10.75, 0}));
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(*c, Vec3(0, 0, 11));
    // Cylinders and paraboloids have no centre point; a cone's apex is its centre.
    EXPECT_FALSE(RayHalfSpace::Centre(Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -1})));
    EXPECT_FALSE(RayHalfSpace::Centre(Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, -1, 0})));
    EXPECT_EQ(RayHalfSpace::Centre(Quadric::FromCoefficients({1, 1, -1, 0, 0, 0, -5, 0, 6, 0})),
              Vec3(5, 0, 6));
    EXPECT_FALSE(RayHalfSpace::Centre(Quadric::FromCoefficients({NAN, 1, 1, 0, 0, 0, 0, 0, 0, 0})));
}

TEST(RaycastLiteral, RecentringKeepsTheRoots) {
    // Random ellipsoids far from the origin: the set on a ray is the same whether the quadric is
    // evaluated about the origin or about its centre, to the accuracy of the un-centred
    // evaluation (its per-pixel rounding is about u·|centre|²·|A| in Q, i.e. 1e-10 here, which
    // moves a root by that over |dQ/dt| = a·(chord length), i.e. by < 1e-8 for chords over 0.1;
    // shorter chords, near tangency, are skipped).
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0, 1);
    int compared = 0;
    for (int n = 0; n < 2000; ++n) {
        Vec3 c{500 * u(rng), 500 * u(rng), 200 + 800 * u(rng)};
        double r = 5 + 50 * u(rng);
        Transform t = Transform::Translate(c) * Transform::Rotate(0, 360 * u(rng)) *
                      Transform::Rotate(1, 360 * u(rng)) *
                      Transform::Scale({r, r * (0.3 + u(rng)), r * (0.3 + u(rng))});
        FlatHalfSpace h;
        h.isPlane = false;
        h.quadric = Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, -1}).Transformed(t);
        auto centre = RayHalfSpace::Centre(h.quadric);
        ASSERT_TRUE(centre.has_value());
        EXPECT_LE(Length(*centre - c), 1.0);  // rounded to integers: within √3/2
        double x = c.x + r * (2 * u(rng) - 1), y = c.y + r * (2 * u(rng) - 1);
        LiteralCounters counters;
        RaySet a = LiteralOnRay(RayHalfSpace::From(h, {}), false, x, y, 1, counters);
        RaySet b = LiteralOnRay(RayHalfSpace::From(h, *centre), false, x, y, 1, counters);
        if (a.count != b.count) {
            // Only possible for a nearly tangent ray.
            RaySet& hit = a.count ? a : b;
            EXPECT_LT(hit.piece[0].hi - hit.piece[0].lo, 0.1) << n;
            continue;
        }
        if (a.count == 0 || a.piece[0].hi - a.piece[0].lo < 0.1) continue;
        ASSERT_EQ(a.count, 1);
        EXPECT_NEAR(a.piece[0].lo, b.piece[0].lo, 1e-9 * c.z);
        EXPECT_NEAR(a.piece[0].hi, b.piece[0].hi, 1e-9 * c.z);
        ++compared;
    }
    EXPECT_GT(compared, 500);
}

// ClassifyQuadric's claim, tested where it matters: whenever it says no ray of a rectangle meets
// the quadric, the literal's set at every pixel centre of the rectangle is all of the ray
// (kInsideEverywhere) or nothing (kOutsideEverywhere), with and without complement; and it does
// decide most rectangles far from a quadric's silhouette (else culling would be useless).
TEST(RaycastLiteral, ClassifyQuadricOnRectanglesIsNeverWrong) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int decided = 0, farFromSilhouette = 0, rects = 0;
    for (int n = 0; n < 400; ++n) {
        // A random quadric (of any type) placed near the image region, re-centred like the engine.
        std::array<double, 10> k{};
        for (double& v : k) v = u(rng);
        k[9] = 40 * u(rng);
        const Vec3 shift{30 * u(rng), 30 * u(rng), 50 + 20 * u(rng)};
        Quadric q = Quadric::FromCoefficients(k).Transformed(Transform::Translate(shift));
        FlatHalfSpace hs;
        hs.isPlane = false;
        hs.quadric = q;
        const RayHalfSpace r = RayHalfSpace::From(hs, RayHalfSpace::Centre(q).value_or(Vec3{}));
        for (int t = 0; t < 20; ++t) {
            const double x0 = std::floor(60 * u(rng)) + 0.5, y0 = std::floor(60 * u(rng)) + 0.5;
            const int w = 1 + static_cast<int>(16 * (u(rng) + 1) / 2), h = w;
            const QuadricOnRect c = ClassifyQuadric(r, x0, x0 + w - 1, y0, y0 + h - 1);
            ++rects;
            bool anyRoot = false;
            for (int j = 0; j < h; ++j) {
                for (int i = 0; i < w; ++i) {
                    const double x = x0 + i, y = y0 + j;
                    for (bool comp : {false, true}) {
                        LiteralCounters counters;
                        const RaySet set = LiteralOnRay(r, comp, x, y, 3, counters);
                        const bool all = set.count == 1 && std::isinf(set.piece[0].lo) &&
                                         std::isinf(set.piece[0].hi);
                        const bool none = set.count == 0;
                        anyRoot |= !all && !none;
                        if (c == QuadricOnRect::kUnknown) continue;
                        const bool inside = (c == QuadricOnRect::kInsideEverywhere) != comp;
                        ASSERT_TRUE(inside ? all : none)
                            << "quadric " << n << " rect " << t << " pixel " << x << "," << y;
                    }
                }
            }
            decided += c != QuadricOnRect::kUnknown;
            farFromSilhouette += !anyRoot;
        }
    }
    // Rectangles with no root at any pixel: most of them are decided.
    EXPECT_GT(farFromSilhouette, 1000);
    EXPECT_GT(decided, farFromSilhouette / 2) << decided << " of " << farFromSilhouette;
    EXPECT_LT(decided, rects);
}

}  // namespace
}  // namespace quadrix::raycast
