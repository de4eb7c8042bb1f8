// The example scenes of examples/ (seed 001 §2.1.2 and §2.1.4) read without diagnostics and have
// the structure the paper describes.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "quadrix/lang/test_util.h"

namespace quadrix::lang {
namespace {

struct Example {
    scene::Scene scene;
    Diagnostics diags;
};

Example ReadExample(const std::string& name) {
    Example e;
    Reader reader(e.scene, e.diags);
    EXPECT_TRUE(reader.ReadFile(std::string(QUADRIX_SOURCE_DIR) + "/examples/" + name));
    EXPECT_EQ(e.diags.Items().size(), 0u) << name;  // not even a warning
    return e;
}

// The tube of §2.1.2: inside radius 1, outside radius 2, length 4 on the y axis.
void ExpectTube(const scene::Scope& scope) {
    ASSERT_EQ(scope.halfSpaces.size(), 4u);
    ASSERT_EQ(scope.bodies.size(), 1u);
    const scene::Body& tube = scope.bodies[0];
    EXPECT_EQ(tube.id, "tube");
    ASSERT_EQ(tube.literals.size(), 4u);
    const bool complemented[4] = {false, true, false, true};
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(tube.literals[i].halfSpace, i);
        EXPECT_EQ(tube.literals[i].complemented, complemented[i]);
    }
    const Quadric& outer = scope.halfSpaces[0].quadric;
    // On the outer wall (radius 2) the outer quadric is zero, inside it negative.
    EXPECT_EQ(outer.Evaluate({2, 0, 0}), 0);
    EXPECT_LT(outer.Evaluate({1.5, 0, 0}), 0);
    EXPECT_EQ(scope.halfSpaces[1].quadric.Evaluate({0, 5, 1}), 0);
    EXPECT_EQ(scope.halfSpaces[2].plane.Evaluate({0, 2, 0}), 0);
    EXPECT_EQ(scope.halfSpaces[3].plane.Evaluate({0, -2, 0}), 0);
}

TEST(LangExamples, Tube) {
    Example e = ReadExample("tube.uq");
    ExpectTube(e.scene.top);
    EXPECT_FALSE(e.scene.Empty());
}

TEST(LangExamples, BundleOfTubes) {
    Example e = ReadExample("bundle_of_tubes.uq");
    ASSERT_EQ(e.scene.definitions.size(), 1u);
    EXPECT_EQ(e.scene.definitions[0].id, "tube");
    ExpectTube(e.scene.definitions[0]);
    ASSERT_EQ(e.scene.top.instances.size(), 1u);
    const scene::Instance& a = e.scene.top.instances[0];
    EXPECT_TRUE(a.isArray);
    EXPECT_EQ(a.count, 6);
    EXPECT_EQ(a.definition, 0);
    // Copy k: the tube axis (origin) moved to 2 along x, then turned k·60° about y.
    Transform place = a.init;
    for (int k = 0; k < 6; ++k) {
        Vec3 axis = place.MapPoint({0, 0, 0});
        double angle = k * 60.0 * M_PI / 180.0;
        // Right-hand rotation about y maps (2,0,0) to (2 cos a, 0, -2 sin a); rounding only.
        EXPECT_NEAR(axis.x, 2 * std::cos(angle), 1e-12) << k;
        EXPECT_NEAR(axis.y, 0, 1e-12) << k;
        EXPECT_NEAR(axis.z, -2 * std::sin(angle), 1e-12) << k;
        place = a.delta * place;
    }
}

TEST(LangExamples, StackOfBundlesHasEighteenTubes) {
    Example e = ReadExample("stack_of_bundles.uq");
    const scene::Scene& s = e.scene;
    ASSERT_EQ(s.definitions.size(), 2u);
    ExpectTube(s.definitions[0]);
    const scene::Scope& bundle = s.definitions[1];
    EXPECT_EQ(bundle.id, "bundle_of_tubes");
    ASSERT_EQ(bundle.instances.size(), 1u);
    const scene::Instance& inner = bundle.instances[0];
    EXPECT_EQ(inner.id, "bundle_of_tubes");
    EXPECT_EQ(inner.definition, 0);
    EXPECT_EQ(inner.count, 6);
    ASSERT_EQ(s.top.instances.size(), 1u);
    const scene::Instance& outer = s.top.instances[0];
    EXPECT_EQ(outer.id, "stack_of_bundles");
    EXPECT_EQ(outer.definition, 1);
    EXPECT_EQ(outer.count, 3);

    // Compose the hierarchy as the Flattener does (seed 001 §3.3: deltas accumulate) and map
    // two points of each tube: its centre and a point on its axis above it.
    std::set<std::tuple<long, long, long>> centres;
    Transform stack = outer.init;
    for (int j = 0; j < outer.count; ++j) {
        Transform copy = inner.init;
        for (int k = 0; k < inner.count; ++k) {
            Transform world = stack * copy;
            Vec3 c = world.MapPoint({0, 0, 0});
            Vec3 up = world.MapPoint({0, 1, 0});
            // Bundle j sits at y = -7 + 5j; the tube axis stays parallel to y (rotations about y).
            EXPECT_NEAR(c.y, -7 + 5 * j, 1e-12);
            EXPECT_NEAR(up.x - c.x, 0, 1e-12);
            EXPECT_NEAR(up.y - c.y, 1, 1e-12);
            EXPECT_NEAR(std::hypot(c.x, c.z), 2, 1e-12);
            // Rounded to 1e-6 to compare placements (they are at least 2 apart).
            centres.insert(
                {std::lround(c.x * 1e6), std::lround(c.y * 1e6), std::lround(c.z * 1e6)});
            copy = inner.delta * copy;
        }
        stack = outer.delta * stack;
    }
    EXPECT_EQ(centres.size(), 18u);
}

}  // namespace
}  // namespace quadrix::lang
