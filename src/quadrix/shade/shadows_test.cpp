// Shadow rays through the CSG (shadows.h) against analytic answers: a ray misses a sphere
// exactly when its distance from the centre exceeds the radius; CSG differences let light
// through their holes.
#include "quadrix/shade/shadows.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace quadrix {
namespace {

Quadric SphereQ(const Vec3& c, double r) {
    return Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -c.x, -c.y, -c.z, Dot(c, c) - r * r});
}

// Solid 0 = sphere A minus sphere B (B may be far away: then it is just A).
FlatScene Spheres(const Vec3& a, double ra, const Vec3& b, double rb) {
    FlatScene s;
    for (const Quadric& q : {SphereQ(a, ra), SphereQ(b, rb)}) {
        FlatHalfSpace h;
        h.isPlane = false;
        h.quadric = q;
        s.halfSpaces.push_back(h);
    }
    for (int k = 0; k < 2; ++k) {
        FlatBody body;
        body.literals = {{k, false}};
        s.bodies.push_back(body);
        FlatCsgNode leaf;
        leaf.body = k;
        leaf.bounds = {{-1e9, -1e9, -1e9}, {1e9, 1e9, 1e9}};
        s.nodes.push_back(leaf);
    }
    FlatCsgNode diff;
    diff.isLeaf = false;
    diff.op = scene::CsgOp::kDifference;
    diff.children = {0, 1};
    diff.bounds = {a - Vec3{ra, ra, ra}, a + Vec3{ra, ra, ra}};
    s.nodes.push_back(diff);
    FlatSolid solid;
    solid.root = 2;
    s.solids.push_back(solid);
    return s;
}

TEST(ShadeShadows, RaysAreBlockedExactlyWhenTheyMeetTheSphere) {
    const Vec3 c{10, -3, 7};
    const double r = 2.5;
    const FlatScene s = Spheres(c, r, {1e6, 0, 0}, 1);
    const ShadowTester t(s);
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    int blocked = 0, checked = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 p = c + Vec3{u(rng), u(rng), u(rng)} * 12;
        if (Length(p - c) < r + 0.01) continue;
        // Half the rays aimed near the sphere, so that both answers are common.
        const Vec3 aim =
            i % 2 ? c - p + Vec3{u(rng), u(rng), u(rng)} * 3 : Vec3{u(rng), u(rng), u(rng)};
        const Vec3 d = Normalize(aim) * (1 + 3 * std::fabs(u(rng)));
        // Distance from c to the half-line p + s d, s > 0.
        const double s0 = std::max(0.0, Dot(c - p, d) / Dot(d, d));
        const double dist = Length(p + d * s0 - c);
        if (std::fabs(dist - r) < 1e-6) continue;  // grazing: either answer is right
        const bool want = dist < r && s0 > 0;
        EXPECT_EQ(t.Blocked(p, d, HUGE_VAL), want) << i;
        // A segment that ends before the sphere is never blocked.
        const double near = Length(p - c) - r;  // the sphere is at least this far along the ray
        EXPECT_FALSE(t.Blocked(p, d, 0.99 * near / Length(d))) << i;
        blocked += want;
        ++checked;
    }
    EXPECT_GT(blocked, 800);
    EXPECT_LT(blocked, checked - 800);
    EXPECT_GT(checked, 3000);
}

TEST(ShadeShadows, AHoleLetsTheLightThroughAndASurfaceDoesNotShadowItself) {
    // A ball with a ball-shaped bite taken out of its top (y < 0 is up in device space).
    const FlatScene s = Spheres({0, 0, 0}, 2, {0, -2, 0}, 1.2);
    const ShadowTester t(s);
    const Vec3 up{0, -1, 0};
    EXPECT_TRUE(t.Blocked({0, 5, 0}, up, HUGE_VAL));    // below: the ball is in the way
    EXPECT_TRUE(t.Blocked({1.5, 5, 0}, up, HUGE_VAL));  // beside the bite: still the ball
    // On the floor of the bite, looking up through it: free (the bite's floor is at y = −0.8).
    EXPECT_FALSE(t.Blocked({0, -0.8, 0}, up, HUGE_VAL));
    // A point on the ball's outside looking away from it: not shadowed by its own surface.
    const Vec3 side = Normalize(Vec3{1, 0.3, -0.2}) * 2;
    EXPECT_FALSE(t.Blocked(side, Normalize(side), HUGE_VAL));
    // Planes: a half-space literal on a line is a half-line.
    FlatHalfSpace floor;
    floor.plane = {0, 1, 0, -3};  // y <= 3
    const IntervalList set = ShadowTester::LiteralOnLine(floor, false, {0, 0, 0}, {0, 1, 0});
    ASSERT_EQ(set.size(), 1u);
    EXPECT_EQ(set[0].hi, 3);
    EXPECT_TRUE(std::isinf(set[0].lo));
    const IntervalList out = ShadowTester::LiteralOnLine(floor, true, {0, 0, 0}, {0, 1, 0});
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].lo, 3);
}

}  // namespace
}  // namespace quadrix
