// The float mode of the patch processor on scenes with known answers.
#include "quadrix/engines/patch/float_engine.h"

#include <gtest/gtest.h>

#include <random>

#include "quadrix/engines/patch/patch_test_util.h"

namespace quadrix::patch {
namespace {

using testing::SceneBuilder;
using testing::Sphere;
using testing::SphereBox;

QuadricPatch Convert(const FlatScene& scene, int body) {
    Conversion c = ConvertBody(scene, body, CapPolicy::kSkip);
    EXPECT_TRUE(c.patch.has_value()) << RejectionName(c.why);
    return c.patch.value_or(QuadricPatch{});
}

TEST(PatchFloat, SphereDepthAndNormalAreExact) {
    SceneBuilder b(40, 40);
    const Vec3 c{20, 20, 100};
    const double r = 15;
    const int body = b.AddBody({{b.AddQuadric(Sphere(c, r)), false}}, SphereBox(c, r));
    const QuadricPatch p = Convert(b.scene(), body);
    Frame frame(40, 40);
    FloatStats stats;
    RenderPatchRowsFloat(p, b.scene(), 0, 40, frame, stats);
    EXPECT_EQ(stats.windowPixels, 30 * 30);
    int covered = 0;
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 40; ++x) {
            const double dx = x + 0.5 - c.x, dy = y + 0.5 - c.y;
            const double d2 = r * r - dx * dx - dy * dy;
            const std::size_t i = frame.Index(x, y);
            ASSERT_EQ(frame.Covered(x, y), d2 >= 0) << x << " " << y;
            if (d2 < 0) continue;
            ++covered;
            // Depth: a few ulps of 100 (the stable solver).
            EXPECT_NEAR(frame.depth[i], c.z - std::sqrt(d2),
                        1e-12 + DepthRounding(c.z - std::sqrt(d2)));
            const Vec3 n = Normalize(Vec3{dx, dy, -std::sqrt(d2)});
            EXPECT_NEAR(Dot(frame.normal[i], n), 1, 1e-12 + 1 - std::cos(PackedNormal::kMaxError));
            EXPECT_EQ(frame.surface[i], 0);
            EXPECT_EQ(frame.body[i], body);
        }
    EXPECT_EQ(stats.surfacePixels, covered);
}

TEST(PatchFloat, CutOpenSphereShowsItsInsideFacingTheViewer) {
    // Front cap removed by the front plane z >= 95: inside the cut circle we see the back sheet.
    SceneBuilder b(40, 40);
    const Vec3 c{20, 20, 100};
    const int body =
        b.AddBody({{b.AddQuadric(Sphere(c, 15)), false}, {b.AddPlane({0, 0, -1, 95}), false}},
                  SphereBox(c, 15));
    const QuadricPatch p = Convert(b.scene(), body);
    Frame frame(40, 40);
    FloatStats stats;
    RenderPatchRowsFloat(p, b.scene(), 0, 40, frame, stats);
    const std::size_t centre = frame.Index(20, 20);
    EXPECT_NEAR(frame.depth[centre], 100 + std::sqrt(225 - 0.5),
                1e-12 + DepthRounding(100 + std::sqrt(225 - 0.5)));
    EXPECT_LT(frame.Normal(centre).z, 0);  // world = device here; facing the viewer (-z)
    EXPECT_GT(stats.backSheetPixels, 0);
    // Near the rim the front sheet lies behind z = 95 and is kept (ZF >= 95 for a distance
    // from the axis of at least sqrt(200) = 14.1).
    const std::size_t rim = frame.Index(34, 20);
    const double dx = 34.5 - 20, dy = 0.5;
    EXPECT_NEAR(frame.depth[rim], 100 - std::sqrt(225 - dx * dx - dy * dy),
                1e-12 + DepthRounding(100 - std::sqrt(225 - dx * dx - dy * dy)));
}

TEST(PatchFloat, PatchesAreZBuffered) {
    SceneBuilder b(40, 40);
    const int far =
        b.AddBody({{b.AddQuadric(Sphere({20, 20, 100}, 15)), false}}, SphereBox({20, 20, 100}, 15));
    const int near =
        b.AddBody({{b.AddQuadric(Sphere({25, 20, 60}, 5)), false}}, SphereBox({25, 20, 60}, 5));
    Frame frame(40, 40);
    FloatStats stats;
    // Far patch scanned after the near one: the z-buffer keeps the near one.
    RenderPatchRowsFloat(Convert(b.scene(), near), b.scene(), 0, 40, frame, stats);
    RenderPatchRowsFloat(Convert(b.scene(), far), b.scene(), 0, 40, frame, stats);
    EXPECT_EQ(frame.body[frame.Index(25, 20)], near);
    EXPECT_EQ(frame.body[frame.Index(10, 20)], far);
}

TEST(PatchFloat, NormalsMapToWorldLikeFlatSceneWorldNormal) {
    // A non-trivial affine deviceFromWorld: the patch's pull-back of its device normal equals
    // FlatScene::WorldNormal at the drawn points.
    std::mt19937_64 rng(21);
    SceneBuilder b(48, 48);
    Mat4 m = Mat4::Identity();
    m(0, 0) = 2;
    m(0, 1) = 0.3;
    m(1, 2) = -0.4;
    m(2, 0) = 0.2;
    m(0, 3) = 5;
    b.scene().projection.deviceFromWorld = Transform::FromMatrix(m).value();
    for (int k = 0; k < 10; ++k) {
        const testing::RandomBody rb = testing::AddRandomPatch(b, rng, 2);
        const Conversion conv = ConvertBody(b.scene(), rb.body, CapPolicy::kSkip);
        if (!conv.patch) continue;
        for (int y = 0; y < 48; y += 3)
            for (int x = 0; x < 48; x += 3) {
                const FloatPixel px = EvaluatePixelFloat(*conv.patch, x + 0.5, y + 0.5);
                if (px.sheet == Sheet::kNone || std::fabs(px.gradient.z) < 1e-3) continue;
                const Vec3 p{x + 0.5, y + 0.5, px.zout};
                const Vec3 mine = WorldNormalFromDeviceGradient(b.scene(), p, px.gradient);
                const Vec3 ref = b.scene().WorldNormal(conv.patch->surface, p);
                // Both normalise the same covector up to rounding of g_w (a few ulps of
                // |p|·|g| relative to |g|): 1e-9.
                EXPECT_NEAR(Dot(mine, ref), 1, 1e-9) << x << " " << y;
            }
    }
}

TEST(PatchFloat, RowBandsCoverTheWindowExactlyOnce) {
    SceneBuilder b(40, 40);
    const int body =
        b.AddBody({{b.AddQuadric(Sphere({20, 20, 100}, 15)), false}}, SphereBox({20, 20, 100}, 15));
    const QuadricPatch p = Convert(b.scene(), body);
    Frame whole(40, 40), banded(40, 40);
    FloatStats s1, s2;
    RenderPatchRowsFloat(p, b.scene(), 0, 40, whole, s1);
    for (int y = 0; y < 40; y += 7) RenderPatchRowsFloat(p, b.scene(), y, y + 7, banded, s2);
    EXPECT_EQ(s1.windowPixels, s2.windowPixels);
    EXPECT_EQ(whole.depth, banded.depth);
}

}  // namespace
}  // namespace quadrix::patch
