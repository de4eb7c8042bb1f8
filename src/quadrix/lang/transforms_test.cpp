// Transforms of instance and array statements (seed 001 §2.1.4), checked by mapping points.
#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/lang/test_util.h"

namespace quadrix::lang {
namespace {

using testing::Parse;
using testing::Parsed;

// The init transform of `instance x (d <transforms>);`.
Transform InitOf(const std::string& transforms) {
    Parsed r =
        Parse("def d; plane ha <1 0 0 0>; body (ha); end; instance x (d " + transforms + ");");
    EXPECT_TRUE(r.ok) << transforms << "\n" << r.All();
    if (r.scene.top.instances.empty()) return {};
    return r.scene.top.instances[0].init;
}

// Exact comparisons: translations, 90° rotations (exact sines, mat4.h) and scales by powers of
// two are exact in binary floating point.
TEST(LangTransforms, EachTransformMapsAsDocumented) {
    struct Case {
        const char* text;
        Vec3 in, out;
    };
    const Case cases[] = {
        {"=tx 2", {1, 1, 1}, {3, 1, 1}},
        {"=ty -3", {1, 1, 1}, {1, -2, 1}},
        {"=tz .5", {1, 1, 1}, {1, 1, 1.5}},
        {"=ta 1", {1, 2, 3}, {2, 3, 4}},
        {"=sx 2", {1, 1, 1}, {2, 1, 1}},
        {"=sy -1", {1, 1, 1}, {1, -1, 1}},
        {"=sz 4", {1, 1, 1}, {1, 1, 4}},
        {"=sa .5", {2, 4, 8}, {1, 2, 4}},
        // Right-hand rule: about z, x goes to y; about x, y goes to z; about y, z goes to x.
        {"=rz 90", {1, 0, 0}, {0, 1, 0}},
        {"=rx 90", {0, 1, 0}, {0, 0, 1}},
        {"=ry 90", {0, 0, 1}, {1, 0, 0}},
        {"=ry -90", {1, 0, 0}, {0, 0, 1}},
        {"=rz 180", {1, 2, 0}, {-1, -2, 0}},
        // Shear =vAB s: s along B for each unit along A.
        {"=vxy .5", {2, 0, 0}, {2, 1, 0}},
        {"=vxz 1", {2, 0, 0}, {2, 0, 2}},
        {"=vyx 2", {0, 1, 0}, {2, 1, 0}},
        {"=vyz -1", {0, 1, 0}, {0, 1, -1}},
        {"=vzx .25", {0, 0, 4}, {1, 0, 4}},
        {"=vzy 3", {0, 0, 1}, {0, 3, 1}},
    };
    for (const Case& c : cases) {
        Transform t = InitOf(c.text);
        EXPECT_EQ(t.MapPoint(c.in), c.out) << c.text;
        // The stored inverse undoes it.
        EXPECT_EQ(t.Inverse().MapPoint(c.out), c.in) << c.text;
    }
}

TEST(LangTransforms, ConcatenatedLeftToRight) {
    // Translate first, then rotate: (0,0,0) -> (2,0,0) -> rotated 90° about z -> (0,2,0).
    EXPECT_EQ(InitOf("=tx 2 =rz 90").MapPoint({0, 0, 0}), (Vec3{0, 2, 0}));
    // Rotate first, then translate: the origin stays, then moves to (2,0,0).
    EXPECT_EQ(InitOf("=rz 90 =tx 2").MapPoint({0, 0, 0}), (Vec3{2, 0, 0}));
    // Scale then translate vs translate then scale.
    EXPECT_EQ(InitOf("=sx 2 =tx 1").MapPoint({1, 0, 0}), (Vec3{3, 0, 0}));
    EXPECT_EQ(InitOf("=tx 1 =sx 2").MapPoint({1, 0, 0}), (Vec3{4, 0, 0}));
    // Three steps: M = T3 T2 T1.
    Transform m = InitOf("=tx 1 =rz 90 =sy 2");
    Transform expected =
        Transform::Scale({1, 2, 1}) * Transform::Rotate(2, 90) * Transform::Translate({1, 0, 0});
    EXPECT_EQ(m.Matrix(), expected.Matrix());
    EXPECT_EQ(m.Inverse(), expected.Inverse());
}

TEST(LangTransforms, NonRightAngleRotation) {
    Vec3 p = InitOf("=rz 30").MapPoint({1, 0, 0});
    // cos 30° and sin 30° to a few ulps (SinCosDegrees is accurate to rounding).
    EXPECT_NEAR(p.x, std::sqrt(3.0) / 2, 1e-15);
    EXPECT_NEAR(p.y, 0.5, 1e-15);
}

TEST(LangTransforms, ArrayCopiesAccumulateDeltas) {
    Parsed r = Parse("def d; plane ha <1 0 0 0>; body (ha); end; array x (d =tx 2) 4 =rz 90;");
    ASSERT_TRUE(r.ok) << r.All();
    const scene::Instance& a = r.scene.top.instances[0];
    // Copy k is delta^k * init.
    const Vec3 expected[4] = {{2, 0, 0}, {0, 2, 0}, {-2, 0, 0}, {0, -2, 0}};
    Transform place = a.init;
    for (int k = 0; k < a.count; ++k) {
        EXPECT_EQ(place.MapPoint({0, 0, 0}), expected[k]) << k;
        place = a.delta * place;
    }
}

TEST(LangTransforms, ZeroScaleAndOverflowAreErrors) {
    Parsed zero = Parse("def d; plane ha <1 0 0 0>; body (ha); end; instance x (d =sa 0);");
    ASSERT_EQ(zero.Errors().size(), 1u);
    EXPECT_EQ(zero.Errors()[0]->loc.column, 62);
    Parsed huge =
        Parse("def d; plane ha <1 0 0 0>; body (ha); end; instance x (d =sa 1e200 =sa 1e200);");
    ASSERT_EQ(huge.Errors().size(), 1u);
    EXPECT_NE(huge.Errors()[0]->message.find("overflow"), std::string::npos);
}

}  // namespace
}  // namespace quadrix::lang
