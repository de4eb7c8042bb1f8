// Phong post-shading of a Frame (phong.h).
#include "quadrix/engines/patch/phong.h"

#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/engines/patch/patch_test_util.h"

namespace quadrix::patch {
namespace {

// The builder's lights: ambient 0.1 and a headlight of 0.9 toward -z (the viewer).
TEST(PatchPhong, HeadOnSurfaceGetsFullDiffuseAndHighlight) {
    testing::SceneBuilder b(4, 4);
    PhongOptions o;
    const PhongTerms t = PhongAt(b.scene(), {0, 0, -1}, {0, 0, -1}, o);
    EXPECT_DOUBLE_EQ(t.diffuse, std::min(1.0, 0.1 + 0.9 * o.diffuse));
    EXPECT_DOUBLE_EQ(t.specular, 0.9 * o.specular);  // r = v: cos^n = 1
}

TEST(PatchPhong, HighlightFallsOffWithTheMirrorAngle) {
    testing::SceneBuilder b(4, 4);
    PhongOptions o;
    // Normal tilted 30° from the light: n·l = cos 30°, the mirror direction is 60° from v.
    const double a = 30 * M_PI / 180;
    const Vec3 n{std::sin(a), 0, -std::cos(a)};
    const PhongTerms t = PhongAt(b.scene(), n, {0, 0, -1}, o);
    EXPECT_NEAR(t.diffuse, 0.1 + 0.9 * o.diffuse * std::cos(a), 1e-12);
    EXPECT_NEAR(t.specular, 0.9 * o.specular * std::pow(std::cos(2 * a), o.shininess), 1e-12);
    // Facing away from the light: ambient only.
    const PhongTerms back = PhongAt(b.scene(), {0, 0, 1}, {0, 0, -1}, o);
    EXPECT_DOUBLE_EQ(back.diffuse, 0.1);
    EXPECT_DOUBLE_EQ(back.specular, 0);
}

TEST(PatchPhong, ShadesAFrameWithColorAndBackground) {
    testing::SceneBuilder b(3, 1);
    const int q = b.AddQuadric(testing::Sphere({1.5, 0.5, 10}, 1));
    const int body = b.AddBody({{q, false}}, testing::SphereBox({1.5, 0.5, 10}, 1));
    b.scene().bodies[static_cast<std::size_t>(body)].color = {1, 0, 0};
    Frame f(3, 1);
    f.Offer(1, 9, {0, 0, -1}, q, body, 0);
    PhongOptions o;
    o.background = {0, 0, 1};
    const Image img = PhongShade(f, b.scene(), o);
    ASSERT_EQ(img.channels, 3);
    EXPECT_EQ(img.At(0, 0)[2], 255);  // background
    EXPECT_EQ(img.At(0, 0)[0], 0);
    // Red diffuse 0.82 plus a white highlight 0.36: red saturates, green and blue get the
    // highlight only.
    EXPECT_EQ(img.At(1, 0)[0], 255);
    EXPECT_EQ(img.At(1, 0)[1], std::lround(0.9 * o.specular * 255));
}

TEST(PatchPhong, ViewerDirectionForPerspective) {
    testing::SceneBuilder b(4, 4);
    b.scene().projection.perspective = true;
    b.scene().projection.eye = {0, 0, -10};
    const Vec3 v = TowardViewer(b.scene(), {3, 4, -10});  // identity device-from-world
    EXPECT_NEAR(v.x, -0.6, 1e-12);
    EXPECT_NEAR(v.y, -0.8, 1e-12);
    EXPECT_NEAR(v.z, 0, 1e-12);
    b.scene().projection.perspective = false;
    EXPECT_EQ(TowardViewer(b.scene(), {3, 4, 5}), (Vec3{0, 0, -1}));
}

}  // namespace
}  // namespace quadrix::patch
