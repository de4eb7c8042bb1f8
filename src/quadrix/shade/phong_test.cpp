// The reflection models (phong.h), the lights (lighting.h) and the shader's entry point
// (shader.h) on hand-made Frames.
#include "quadrix/shade/phong.h"

#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/shade/lighting.h"
#include "quadrix/shade/shader.h"

namespace quadrix {
namespace {

// Ambient 0.1 and a headlight of 0.9 toward -z (the viewer), identity device map.
FlatScene TwoLights(int w, int h) {
    FlatScene s;
    s.width = w;
    s.height = h;
    s.projection.towardViewer = {0, 0, -1};
    scene::Light ambient;
    ambient.kind = scene::Light::Kind::kAmbient;
    ambient.intensity = 0.1;
    scene::Light head;
    head.kind = scene::Light::Kind::kParallel;
    head.intensity = 0.9;
    head.direction = {0, 0, -1};
    s.lights = {ambient, head};
    return s;
}

// One body (no geometry needed: the shader reads only the Frame and the body's color/finish).
int AddBody(FlatScene& s, const scene::Color& c, const scene::Finish& f = {}) {
    FlatBody b;
    b.color = c;
    b.finish = f;
    s.bodies.push_back(b);
    return static_cast<int>(s.bodies.size()) - 1;
}

constexpr Reflectance kPhong{0.8, 0.4, 24, false};

TEST(ShadePhong, HeadOnSurfaceGetsFullDiffuseAndHighlight) {
    const FlatScene s = TwoLights(4, 4);
    const PhongTerms t = PhongAt(s.lights, {}, {0, 0, -1}, {0, 0, -1}, kPhong);
    EXPECT_DOUBLE_EQ(t.diffuse.r, 0.1 + 0.9 * kPhong.diffuse);
    EXPECT_DOUBLE_EQ(t.specular.g, 0.9 * kPhong.specular);  // r = v: cos^n = 1
}

TEST(ShadePhong, HighlightFallsOffWithTheMirrorAngle) {
    const FlatScene s = TwoLights(4, 4);
    // Normal tilted 30° from the light: n·l = cos 30°, the mirror direction is 60° from v.
    const double a = 30 * M_PI / 180;
    const Vec3 n{std::sin(a), 0, -std::cos(a)};
    const PhongTerms t = PhongAt(s.lights, {}, n, {0, 0, -1}, kPhong);
    EXPECT_NEAR(t.diffuse.r, 0.1 + 0.9 * kPhong.diffuse * std::cos(a), 1e-12);
    EXPECT_NEAR(t.specular.r, 0.9 * kPhong.specular * std::pow(std::cos(2 * a), 24), 1e-12);
    // Blinn–Phong: the half vector of l = v is the light itself, 30° from n.
    Reflectance blinn = kPhong;
    blinn.blinn = true;
    EXPECT_NEAR(PhongAt(s.lights, {}, n, {0, 0, -1}, blinn).specular.b,
                0.9 * kPhong.specular * std::pow(std::cos(a), 24), 1e-12);
    // Facing away from the light: ambient only.
    const PhongTerms back = PhongAt(s.lights, {}, {0, 0, 1}, {0, 0, -1}, kPhong);
    EXPECT_DOUBLE_EQ(back.diffuse.r, 0.1);
    EXPECT_DOUBLE_EQ(back.specular.r, 0);
}

TEST(ShadePhong, ShadesAFrameWithColorAndBackground) {
    FlatScene s = TwoLights(3, 1);
    const int body = AddBody(s, {1, 0, 0});
    Frame f(3, 1);
    f.Offer(1, 9, Vec3{0, 0, -1}, 0, body);
    ShadeOptions o;
    o.model = ShadingModel::kPhong;
    o.background = scene::Color{0, 0, 1};
    const Image img = Shade(f, s, o);
    ASSERT_EQ(img.channels, 3);
    EXPECT_EQ(img.At(0, 0)[2], 255);  // background
    EXPECT_EQ(img.At(0, 0)[0], 0);
    // Red diffuse 0.82 plus a white highlight 0.36: red saturates, green and blue get the
    // highlight only.
    EXPECT_EQ(img.At(1, 0)[0], 255);
    EXPECT_EQ(img.At(1, 0)[1], std::lround(0.9 * o.phongSpecular * 255));
    EXPECT_NEAR(img.linear[3 * 1 + 1], 0.9 * o.phongSpecular, 1e-6);
}

TEST(ShadePhong, ViewerDirectionForPerspective) {
    Projection p;
    p.perspective = true;
    p.eye = {0, 0, -10};
    const ViewerGeometry g(p);  // identity device-from-world
    const Vec3 v = g.TowardViewer(g.WorldPoint({3, 4, -10}));
    EXPECT_NEAR(v.x, -0.6, 1e-12);
    EXPECT_NEAR(v.y, -0.8, 1e-12);
    EXPECT_NEAR(v.z, 0, 1e-12);
    p.perspective = false;
    p.towardViewer = {0, 0, -1};
    EXPECT_EQ(ViewerGeometry(p).TowardViewer({3, 4, 5}), (Vec3{0, 0, -1}));
}

// The Lambert model with default finishes is the historical shader: min(1, Σ)·color, byte for
// byte (the formula written out here independently).
TEST(ShadeLambert, MatchesTheHistoricalFormulaByteForByte) {
    FlatScene s = TwoLights(64, 1);
    const int body = AddBody(s, {0.3, 0.7, 1});
    Frame f(64, 1);
    for (int x = 0; x < 64; ++x) {
        const double a = x * (M_PI / 2) / 64;
        f.Offer(x, 5, Normalize(Vec3{std::sin(a), 0.1, -std::cos(a)}), 0, body);
    }
    const Image img = Shade(f, s);
    ASSERT_EQ(img.channels, 3);
    for (int x = 0; x < 64; ++x) {
        const Vec3& n = f.normal[f.Index(x, 0)];
        double sum = 0.1;
        const double c = Dot(n, Vec3{0, 0, -1});
        if (c > 0) sum += 0.9 * c;
        const double i = std::min(sum, 1.0);
        const double want[3] = {0.3 * i, 0.7 * i, 1 * i};
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(img.At(x, 0)[k], static_cast<int>(want[k] * 255.0 + 0.5)) << x << " " << k;
        EXPECT_EQ(LambertIntensity(s, n), i);
    }
}

TEST(ShadeLambert, SpecularFinishAddsAHighlightOpacityBlendsWithTheBackground) {
    FlatScene s = TwoLights(3, 1);
    scene::Finish shiny;
    shiny.specular = 0.5;
    shiny.shininess = 10;
    const int a = AddBody(s, {0.5, 0.5, 0.5}, shiny);
    scene::Finish glass;
    glass.opacity = 0.25;
    const int b = AddBody(s, {1, 1, 1}, glass);
    Frame f(3, 1);
    f.Offer(0, 1, Vec3{0, 0, -1}, 0, a);
    f.Offer(1, 1, Vec3{0, 0, -1}, 0, b);
    ShadeOptions o;
    o.background = scene::Color{0.2, 0.2, 0.2};
    const Image img = Shade(f, s, o);
    ASSERT_EQ(img.channels, 3);  // a gray body color is a color (not the default white)
    // 0.5·min(1, 0.1 + 0.9) + 0.9·0.5 (head-on: n·h = 1); saturates at 1 in the image.
    EXPECT_NEAR(img.linear[0], 0.95, 1e-6);
    EXPECT_NEAR(img.linear[3], 0.25 * 1.0 + 0.75 * 0.2, 1e-6);
    EXPECT_NEAR(img.linear[6], 0.2, 1e-6);
}

// 8-bit shading without shadows or world points repeats a pixel's bytes along runs of the same
// (surface, body, normal) and for the background (shader.cpp ShadeRowLocal): the bytes must be
// those of shading every pixel, which the linear (16-bit) output still does.
TEST(ShadeLambert, EightBitRunsGiveTheBytesOfShadingEveryPixel) {
    for (const bool colour : {true, false}) {
        FlatScene s = TwoLights(37, 5);
        s.background = colour ? scene::Color{0.1, 0.2, 0.3} : scene::Color{0.1, 0.1, 0.1};
        s.backgroundBottom = {0.6, 0.6, 0.6};  // a gradient: each row its own background
        scene::Finish shiny;
        shiny.specular = 0.5;
        shiny.shininess = 10;
        scene::Finish glass;
        glass.opacity = 0.4;
        const int a = AddBody(s, colour ? scene::Color{0.9, 0.5, 0.2} : scene::Color{}, shiny);
        const int b = AddBody(s, colour ? scene::Color{0.2, 0.5, 0.9} : scene::Color{}, glass);
        const int c = AddBody(s, {}, {});
        Frame f(37, 5);
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 37; ++x) {
                const std::size_t i = f.Index(x, y);
                if (x % 11 == 10) continue;  // background between the runs
                const int body = x < 12 ? a : x < 20 ? b : c;
                const int surface = x % 7 < 4 ? 0 : 1;  // the same normal on two surfaces
                // Runs of one normal (a plane), then one normal a pixel (a curved surface).
                const double t = x < 25 ? 0.3 * y : 0.05 * x + 0.1 * y;
                const Vec3 n = Normalize({std::sin(t), 0.2, -std::cos(t)});
                f.Offer(i, 1, n, surface, body);
            }
        ShadeOptions o;
        o.linear = false;
        const Image runs = Shade(f, s, o);
        o.linear = true;
        const Image each = Shade(f, s, o);
        ASSERT_EQ(runs.channels, colour ? 3 : 1);
        EXPECT_EQ(runs.pixels, each.pixels) << "colour " << colour;
        // Not all one colour: the runs differ from each other and from the background.
        std::size_t distinct = 0;
        for (std::size_t k = 1; k < runs.pixels.size(); ++k)
            distinct += runs.pixels[k] != runs.pixels[k - 1];
        EXPECT_GT(distinct, runs.pixels.size() / 10);
    }
}

TEST(ShadeLights, PointAndSpotLights) {
    scene::Light point;
    point.kind = scene::Light::Kind::kPoint;
    point.intensity = 0.8;
    point.position = {0, 0, -10};
    const Incident in = IncidentLight(point, {3, 4, -10});
    EXPECT_NEAR(in.toLight.x, -0.6, 1e-15);
    EXPECT_NEAR(in.toLight.y, -0.8, 1e-15);
    EXPECT_DOUBLE_EQ(in.rgb.r, 0.8);  // no fall-off with distance

    scene::Light spot = point;
    spot.kind = scene::Light::Kind::kSpot;
    spot.aim = {0, 0, 0};
    spot.coneDegrees = 20;
    spot.falloffDegrees = 40;
    spot.color = {1, 0.5, 0};
    // On the axis: full; 30° off: between; 45° off: dark.
    EXPECT_DOUBLE_EQ(IncidentLight(spot, {0, 0, 5}).rgb.g, 0.4);
    const double t30 = std::tan(30 * M_PI / 180) * 10;
    const double mid = IncidentLight(spot, {t30, 0, 0}).rgb.r;
    EXPECT_GT(mid, 0.05);
    EXPECT_LT(mid, 0.75);
    EXPECT_EQ(IncidentLight(spot, {10, 0, 0}).rgb.r, 0);
    EXPECT_EQ(IncidentLight(spot, {10, 0, 0}).rgb.b, 0);
    // The smoothstep: continuous at both ends, ½ halfway in cosine.
    const double c20 = std::cos(20 * M_PI / 180), c40 = std::cos(40 * M_PI / 180);
    EXPECT_DOUBLE_EQ(SpotFactor(c20, 20, 40), 1);
    EXPECT_NEAR(SpotFactor(c40 + 1e-12, 20, 40), 0, 1e-9);
    EXPECT_NEAR(SpotFactor((c20 + c40) / 2, 20, 40), 0.5, 1e-12);
}

TEST(ShadeBackground, VerticalGradientInLinearLight) {
    FlatScene s = TwoLights(1, 4);
    s.background = {0, 0, 0};
    s.backgroundBottom = {0.8, 0.8, 0.8};
    Frame f(1, 4);
    const Image img = Shade(f, s);
    for (int y = 0; y < 4; ++y) EXPECT_NEAR(img.linear[y], 0.8 * (y + 0.5) / 4, 1e-6);
}

}  // namespace
}  // namespace quadrix
