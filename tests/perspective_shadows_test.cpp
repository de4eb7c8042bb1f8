// Shadows under perspective (shade/shadows.h, DeviceShadowRay): the device image of the world
// segment toward a light, including where it crosses the eye plane, and the shadows of a ball on a
// floor against their analytic outline and against the same world points in a parallel view.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "quadrix/pipeline/pipeline.h"
#include "quadrix/shade/phong.h"
#include "quadrix/shade/shader.h"
#include "quadrix/shade/shadows.h"

namespace quadrix::testing {
namespace {

constexpr const char* kEye = "3 5 -9";
const Vec3 kEyeV{3, 5, -9}, kBall{0, 1.5, 0};
constexpr double kRadius = 1;

// A ball over a floor slab, lit by ambient .2 and one more light.
std::string Scene(const std::string& light, bool perspective) {
    return "solid box floor =from -6 -1 -6 =to 6 0 6;\n"
           "solid sphere ball =at 0 1.5 0 =r 1;\n"
           "light .2;\n" +
           light + ";\n" +
           (perspective ? std::string("view v vrp 0 0 0 cop ") + kEye + ";\n"
                        : std::string("view v vrp 0 0 0 dop ") + kEye + ";\n");
}

PipelineResult Flatten(const std::string& text) {
    PipelineOptions o;
    o.sceneText = text;
    o.width = 200;
    o.height = 150;
    PipelineResult r;
    Diagnostics d;
    EXPECT_TRUE(RunPipeline(o, r, d)) << text;
    return r;
}

// The lights of the tests: name, language text, homogeneous world position (w = 0: toward).
struct TestLight {
    const char* what;
    std::string text;
    Vec4 h;
};
std::vector<TestLight> Lights() {
    // Eye plane: through the eye, normal n ∝ (-3, -5, 9) (toward vrp).
    return {
        {"point light in front of the eye plane", "light .8 =at -2 6 3", {-2, 6, 3, 1}},
        {"point light behind the eye plane", "light .8 =at 4 9 -13", {4, 9, -13, 1}},
        {"parallel light from behind the viewer", "light .8 .3 1 -.2", {.3, 1, -.2, 0}},
        {"parallel light from beyond the scene", "light .8 -.3 1 .8", {-.3, 1, .8, 0}},
    };
}

// Distance from the ball's centre to the world segment from q toward the light (t > 0).
double AnalyticDistance(const Vec3& q, const Vec4& light) {
    const Vec3 d = light.w == 0 ? light.xyz() : light.xyz() - q;
    double t = Dot(kBall - q, d) / Dot(d, d);
    t = std::fmax(t, 0.0);
    if (light.w != 0) t = std::fmin(t, 1.0);
    return Length(q + d * t - kBall);
}

// Every world point of the segment in front of the eye maps onto the device ray with s in
// [0, sMax], and every device point of the ray maps back onto the world segment in front of the
// eye: for lights on both sides of the eye plane and parallel lights of both senses.
TEST(PerspectiveShadows, TheDeviceRayIsTheImageOfTheWorldSegmentInFrontOfTheEye) {
    const PipelineResult r = Flatten(Scene("light .8 1 1 1", true));
    ASSERT_TRUE(r.flat.projection.perspective);
    const Mat4 m = r.flat.projection.deviceFromWorld.Matrix();
    const Mat4 inv = r.flat.projection.deviceFromWorld.Inverse();
    const Vec3 n = Normalize(Vec3{0, 0, 0} - kEyeV);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int crossing = 0, checks = 0;
    for (int i = 0; i < 400; ++i) {
        const Vec3 pw{3 * u(rng), 2 + 2 * u(rng), 3 * u(rng)};
        Vec4 light{8 * u(rng), 8 + 6 * u(rng), 12 * u(rng), i % 2 ? 1.0 : 0.0};
        if (i % 2 == 0) light = Vec4(Normalize(light.xyz()), 0);
        const Vec3 p = m.MapPoint(pw);
        const DeviceRay ray = DeviceShadowRay(m, light, p, pw);
        ASSERT_GT(Length(ray.d), 0) << i;
        const Vec3 toLight = light.w == 0 ? light.xyz() : light.xyz() - pw;
        // The world segment is pw + t·toLight, t in [0, 1] (point) or [0, ∞) (parallel); the
        // part in front of the eye is where (x − eye)·n > 0.
        const double front0 = Dot(pw - kEyeV, n), slope = Dot(toLight, n);
        double tEnd = light.w == 0 ? HUGE_VAL : 1.0;
        if (slope < 0) tEnd = std::fmin(tEnd, front0 / -slope);
        crossing += slope < 0 && (light.w == 0 || front0 / -slope < 1);
        for (double f : {0.01, 0.1, 0.3, 0.6, 0.9, 0.99}) {
            const double t = std::isinf(tEnd) ? f / (1 - f) * 10 : f * tEnd;
            const Vec3 x = m.MapPoint(pw + toLight * t);
            const double s = Dot(x - p, ray.d) / Dot(ray.d, ray.d);
            EXPECT_LT(Length(p + ray.d * s - x), 1e-7 * (1 + Length(x - p))) << i << " t " << t;
            EXPECT_GE(s, 0) << i;
            EXPECT_LE(s, ray.sMax) << i;
            ++checks;
        }
        // Device points of the ray back in the world: on the line, forward, in front of the eye.
        for (double f : {0.01, 0.2, 0.5, 0.8, 0.99}) {
            const double s = std::isinf(ray.sMax) ? f / (1 - f) : f * ray.sMax;
            const Vec3 xw = inv.MapPoint(p + ray.d * s);
            const double t = Dot(xw - pw, toLight) / Dot(toLight, toLight);
            EXPECT_LT(Length(pw + toLight * t - xw), 1e-6 * (1 + Length(xw - pw))) << i;
            EXPECT_GT(t, 0) << i;
            if (light.w != 0) {
                EXPECT_LT(t, 1 + 1e-9) << i;
            }
            EXPECT_GT(Dot(xw - kEyeV, n), 0) << i;
        }
    }
    EXPECT_GT(crossing, 40);  // both cases are exercised
    EXPECT_LT(crossing, 360);
    EXPECT_EQ(checks, 2400);
}

// The ball's shadow on the floor, per floor pixel: shadowed (darker than without shadows) exactly
// where the world segment toward the light meets the ball, away from the outline; and the same
// world point is shadowed in a parallel view of the scene (its own device space and ray).
TEST(PerspectiveShadows, TheBallsShadowMatchesTheAnalyticOutlineAndAParallelView) {
    for (const TestLight& l : Lights()) {
        const PipelineResult r = Flatten(Scene(l.text, true));
        const PipelineResult par = Flatten(Scene(l.text, false));
        ASSERT_TRUE(r.flat.projection.perspective);
        ASSERT_FALSE(par.flat.projection.perspective);
        ShadeOptions so;
        const Image plain = Shade(r.frame, r.flat, so);
        so.shadows = true;
        const Image shadowed = Shade(r.frame, r.flat, so);
        const ViewerGeometry viewer(r.flat.projection);
        const Mat4 parM = par.flat.projection.deviceFromWorld.Matrix();
        const ShadowTester parTester(par.flat);
        int inShadow = 0, lit = 0, wrong = 0, parWrong = 0;
        for (int y = 0; y < r.frame.height; ++y)
            for (int x = 0; x < r.frame.width; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * r.frame.width + x;
                if (r.frame.surface[i] == Frame::kNone) continue;
                const Vec3 p{x + 0.5, y + 0.5, r.frame.depth[i]};
                const Vec3 q = viewer.WorldPoint(p);
                if (std::fabs(q.y) > 1e-6 || std::fabs(q.x) > 5.9 || std::fabs(q.z) > 5.9)
                    continue;  // the floor's top only
                const double dist = AnalyticDistance(q, l.h);
                if (std::fabs(dist - kRadius) < 0.03) continue;  // near the outline
                const bool want = dist < kRadius;
                const bool got = shadowed.linear[i] < plain.linear[i] - 1e-6;
                wrong += got != want;
                (want ? inShadow : lit) += 1;
                const Vec3 pp = parM.MapPoint(q);
                const DeviceRay ray = DeviceShadowRay(parM, l.h, pp, q);
                parWrong += parTester.Blocked(pp, ray.d, ray.sMax) != got;
            }
        EXPECT_EQ(wrong, 0) << l.what;
        EXPECT_EQ(parWrong, 0) << l.what;
        EXPECT_GT(inShadow, 10) << l.what;
        EXPECT_GT(lit, 1000) << l.what;
    }
}

// Background pixels stay the background under perspective shadows.
TEST(PerspectiveShadows, ShadowsNeverDarkenTheBackground) {
    const PipelineResult r = Flatten(Scene(Lights()[1].text, true));
    ShadeOptions so;
    so.shadows = true;
    const Image img = Shade(r.frame, r.flat, so);
    int background = 0;
    for (std::size_t i = 0; i < r.frame.surface.size(); ++i)
        if (r.frame.surface[i] == Frame::kNone) {
            EXPECT_EQ(img.linear[i], 0.0f);
            ++background;
        }
    EXPECT_GT(background, 1000);
}

}  // namespace
}  // namespace quadrix::testing
