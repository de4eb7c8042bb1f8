// The public C++ API (include/quadrix/quadrix.h), tested as a consumer uses it: this binary links
// only the shared library quadrix::quadrix and includes only the public header.
//
// Geometry is checked against analytic answers: a unit sphere seen along +z through a 4×4 window
// (halfHeight = halfWidth = 2) on a 64×64 image, so a pixel is 1/16 unit, pixel (i, j) samples
// world (x, y) = (-2 + (i + ½)/16, 2 - (j + ½)/16) (rows top to bottom), the visible point is
// z = -√(1 - x² - y²), its normal (x, y, z), and the device depth of a parallel view is
// 16·(z - vrp_z) (the window fit is a similarity: docs/architecture.md, flatten/view_setup.h).
#include <gtest/gtest.h>
#include <quadrix/quadrix.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

namespace {

// Half a float ulp at z: how far the renderer's Frame (depth kept as a float, Rendering's
// comment) may move a depth.
double DepthRounding(double z) {
    const float f = std::fabs(static_cast<float>(z));
    return 0.5 * (static_cast<double>(std::nextafter(f, HUGE_VALF)) - static_cast<double>(f));
}

constexpr int kSize = 64;
constexpr double kPixel = 4.0 / kSize;

quadrix::Renderer::Options SphereOptions() {
    quadrix::Renderer::Options o;
    o.width = o.height = kSize;
    quadrix::View camera = quadrix::View::Parallel({0, 0, -1});
    camera.halfHeight = 2;
    camera.halfWidth = 2;
    o.camera = camera;
    return o;
}

double WorldX(int i) { return -2 + (i + 0.5) * kPixel; }
double WorldY(int j) { return 2 - (j + 0.5) * kPixel; }

TEST(Api, UnitSphereMatchesTheAnalyticAnswer) {
    quadrix::Scene scene;
    scene.AddSphere("ball", {0, 0, 0}, 1);
    quadrix::Renderer renderer(2);
    const quadrix::Rendering r = renderer.Render(scene, SphereOptions());
    ASSERT_EQ(r.width, kSize);
    ASSERT_EQ(r.height, kSize);
    ASSERT_EQ(r.depth.size(), static_cast<std::size_t>(kSize * kSize));
    ASSERT_EQ(r.normal.size(), 3 * r.depth.size());
    ASSERT_EQ(r.image.rgb.size(), 3 * r.depth.size());
    int checked = 0;
    for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i) {
            const double x = WorldX(i), y = WorldY(j), rr = x * x + y * y;
            const std::size_t k = r.Index(i, j);
            // Pixels whose centre is within 1e-9 of the silhouette are left out (either answer
            // is right there).
            if (std::abs(rr - 1) < 1e-9) continue;
            ASSERT_EQ(r.Covered(i, j), rr < 1) << i << "," << j;
            if (rr >= 1) {
                EXPECT_TRUE(std::isinf(r.depth[k]));
                EXPECT_EQ(r.solid[k], quadrix::Rendering::kNone);
                continue;
            }
            const double z = -std::sqrt(1 - rr);
            // The exact engine's root is a stable quadratic solution: 1e-9 covers its rounding
            // at these magnitudes (grazing pixels near the rim lose digits to the square root).
            // The normal as the Frame packs it: within 7e-5 (Rendering's comment).
            EXPECT_NEAR(r.normal[3 * k], x, 1e-7 + 7e-5);
            EXPECT_NEAR(r.normal[3 * k + 1], y, 1e-7 + 7e-5);
            EXPECT_NEAR(r.normal[3 * k + 2], z, 1e-7 + 7e-5);
            EXPECT_NEAR(r.depth[k], z / kPixel, 1e-6 + DepthRounding(z / kPixel));
            EXPECT_EQ(r.solidNames.at(r.solid[k]), "ball");
            EXPECT_EQ(r.surfaceNames.at(r.surface[k]), "ball");
            ++checked;
        }
    // π r² / pixel area = π·256 ≈ 804 covered pixels.
    EXPECT_NEAR(checked, M_PI * 256, 20);
    EXPECT_EQ(r.CoveredCount(), static_cast<std::size_t>(checked));
    // Lit by the default rig, the sphere is not black and the background is.
    const std::uint8_t* centre = r.image.At(kSize / 2, kSize / 2);
    EXPECT_GT(centre[0], 30);
    EXPECT_EQ(centre[0], centre[1]);  // white sphere, white rig: gray in RGB
    EXPECT_EQ(r.image.At(0, 0)[0], 0);
}

// Anti-aliasing resamples only pixels at the silhouette: interior pixels are the plain ones, bit
// for bit, and every pixel that changes lies within a pixel and a half of the analytic rim.
TEST(Api, AntialiasingChangesOnlyTheRimPixels) {
    quadrix::Scene scene;
    scene.AddSphere("ball", {0, 0, 0}, 1);
    quadrix::Renderer renderer(2);
    quadrix::Renderer::Options o = SphereOptions();
    const quadrix::Rendering plain = renderer.Render(scene, o);
    o.antialias = 16;
    const quadrix::Rendering smooth = renderer.Render(scene, o);
    int changed = 0;
    for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i) {
            const double x = WorldX(i), y = WorldY(j);
            const double fromRim = std::abs(std::sqrt(x * x + y * y) - 1) / kPixel;  // pixels
            bool same = true;
            for (int c = 0; c < 3; ++c) same &= plain.image.At(i, j)[c] == smooth.image.At(i, j)[c];
            if (!same) {
                ++changed;
                EXPECT_LT(fromRim, 1.5) << i << "," << j;
            }
        }
    // The rim is about 2π·16 ≈ 100 pixels long.
    EXPECT_GT(changed, 50);
    o.antialias = 5;
    EXPECT_THROW(renderer.Render(scene, o), quadrix::Error);
}

TEST(Api, CsgThroughHoleShowsTheBackgroundAndNamesTheFace) {
    quadrix::Scene scene;
    scene.AddBox("block", {-1, -1, -1}, {1, 1, 1}, quadrix::Color{0.8, 0.2, 0.2})
        .AddCylinder("drill", {0, 0, -2}, {0, 0, 2}, 0.5)
        .AddCsg("part", quadrix::CsgOperation::kDifference, "block", "drill");
    EXPECT_EQ(scene.CsgCount(), 1u);
    quadrix::Renderer renderer;
    const quadrix::Rendering r = renderer.Render(scene, SphereOptions());
    // Centre: inside the hole, through to the background.
    EXPECT_FALSE(r.Covered(kSize / 2, kSize / 2));
    // x = 0.75: the block's near face z = -1 (its low z face, "block#z0"), normal (0, 0, -1).
    const int i = static_cast<int>((0.75 + 2) / kPixel);
    const std::size_t k = r.Index(i, kSize / 2);
    ASSERT_TRUE(r.Covered(i, kSize / 2));
    EXPECT_EQ(r.surfaceNames.at(r.surface[k]), "block#z0");
    EXPECT_EQ(r.solidNames.at(r.solid[k]), "part");
    EXPECT_DOUBLE_EQ(r.normal[3 * k + 2], -1);
    EXPECT_NEAR(r.depth[k], -1 / kPixel, 1e-9 + DepthRounding(-1 / kPixel));
    // Red body in RGB.
    EXPECT_GT(r.image.At(i, kSize / 2)[0], r.image.At(i, kSize / 2)[1]);
    // Outside the block: background.
    EXPECT_FALSE(r.Covered(2, 2));
}

TEST(Api, EveryEngineDrawsTheSphereLikeRaycast) {
    quadrix::Scene scene;
    scene.AddSphere("ball", {0, 0, 0}, 1);
    quadrix::Renderer renderer;
    const auto reference = renderer.Render(scene, SphereOptions());
    const auto engines = quadrix::Renderer::Engines();
    ASSERT_FALSE(engines.empty());
    EXPECT_EQ(engines.front(), "raycast");
    for (const std::string& engine : engines) {
        auto o = SphereOptions();
        o.engine = engine;
        const auto r = renderer.Render(scene, o);
        std::size_t differ = 0;
        for (std::size_t k = 0; k < r.surface.size(); ++k)
            differ += (r.surface[k] == quadrix::Rendering::kNone) !=
                      (reference.surface[k] == quadrix::Rendering::kNone);
        // Engines differ at most on rim pixels (a few of the ~100 on the silhouette).
        EXPECT_LE(differ, 12u) << engine;
    }
}

TEST(Api, TextDiagnosticsCarryFileLineAndColumn) {
    try {
        quadrix::Scene::FromText("plane top <0 1 0 0>;\nbody blob <top hole>;\n", "bad.uq");
        FAIL() << "no error";
    } catch (const quadrix::Error& e) {
        EXPECT_EQ(e.File(), "bad.uq");
        EXPECT_EQ(e.Line(), 2);
        EXPECT_EQ(e.Column(), 16);
        EXPECT_NE(std::string(e.what()).find("bad.uq:2:16: error:"), std::string::npos) << e.what();
        ASSERT_FALSE(e.Messages().empty());
        EXPECT_EQ(e.Messages()[0].sourceLine, "body blob <top hole>;");
        EXPECT_NE(e.Messages()[0].Format(true).find("^"), std::string::npos);
    }
}

TEST(Api, FileDiagnosticsNameTheFile) {
    const std::string path = ::testing::TempDir() + "/api_bad_scene.uq";
    {
        std::ofstream f(path);
        f << "{ a comment }\nquadric q <0 0 0 0 0 0 0 0 0 0>;\n";
    }
    try {
        quadrix::Scene::FromFile(path);
        FAIL() << "no error";
    } catch (const quadrix::Error& e) {
        EXPECT_EQ(e.File(), path);
        EXPECT_EQ(e.Line(), 2);
        EXPECT_GT(e.Column(), 0);
    }
    std::remove(path.c_str());
    EXPECT_THROW(quadrix::Scene::FromFile(::testing::TempDir() + "/does_not_exist.uq"),
                 quadrix::Error);
}

TEST(Api, FailedEditLeavesTheSceneAsItWas) {
    quadrix::Scene scene;
    scene.AddPlane("floor", {0, 1, 0, 0});
    EXPECT_THROW(scene.AddBody("slab", {"floor", "!missing"}), quadrix::Error);
    EXPECT_EQ(scene.BodyCount(), 0u);
    EXPECT_EQ(scene.HalfSpaceCount(), 1u);
    // A failing multi-statement text adds nothing, not even its valid first statement.
    EXPECT_THROW(scene.Append("plane top <0 1 0 -1>; body x <nothing>;"), quadrix::Error);
    EXPECT_EQ(scene.HalfSpaceCount(), 1u);
    EXPECT_THROW(scene.AddSphere("s", {0, 0, 0}, -1), quadrix::Error);
    EXPECT_THROW(scene.AddSphere("s", {0, 0, NAN}, 1), quadrix::Error);
    EXPECT_THROW(scene.AddBody("two words", {"floor"}), quadrix::Error);
    EXPECT_THROW(scene.AddCsg("c", "a; plane evil <1 0 0 0>"), quadrix::Error);
    EXPECT_EQ(scene.HalfSpaceCount(), 1u);
    scene.AddBody("slab", {"!floor"});
    EXPECT_EQ(scene.BodyCount(), 1u);
    EXPECT_THROW(scene.AddBody("slab", {"floor"}), quadrix::Error);  // duplicate id
    EXPECT_EQ(scene.BodyCount(), 1u);
}

TEST(Api, BadOptionsAreErrors) {
    quadrix::Scene scene;
    scene.AddSphere("ball", {0, 0, 0}, 1);
    quadrix::Renderer renderer;
    auto o = SphereOptions();
    o.engine = "no_such_engine";
    EXPECT_THROW(renderer.Render(scene, o), quadrix::Error);
    o = SphereOptions();
    o.width = 0;
    EXPECT_THROW(renderer.Render(scene, o), quadrix::Error);
    o = SphereOptions();
    o.camera.reset();
    o.view = "no_such_view";
    EXPECT_THROW(renderer.Render(scene, o), quadrix::Error);
    o = SphereOptions();
    o.camera->dop = quadrix::Vector3{0, 0, 0};
    EXPECT_THROW(renderer.Render(scene, o), quadrix::Error);
    // The renderer still works after the errors.
    EXPECT_GT(renderer.Render(scene, SphereOptions()).CoveredCount(), 700u);
}

TEST(Api, NamedViewsAndLightsFromCode) {
    quadrix::Scene scene;
    scene.AddSphere("ball", {0, 0, 0}, 1, quadrix::Color{0, 0, 1});
    quadrix::View side;
    side.id = "side";
    side.dop = quadrix::Vector3{1, 0, 0};
    side.halfHeight = 2;
    scene.AddView(side);
    scene.AddAmbientLight("amb", 0.2).AddParallelLight("sun", 0.8, {-1, 0, 0});
    EXPECT_EQ(scene.LightCount(), 2u);
    ASSERT_EQ(scene.ViewNames().size(), 1u);
    EXPECT_EQ(scene.ViewNames()[0], "side");
    quadrix::Renderer::Options o;
    o.width = o.height = kSize;
    o.view = "side";
    quadrix::Renderer renderer;
    const auto r = renderer.Render(scene, o);
    // Seen from +x: the centre normal points to +x; the sun shines from -x, so only ambient
    // light: blue at 0.2 (sRGB of linear 0.2 is about 124).
    const std::size_t k = r.Index(kSize / 2, kSize / 2);
    ASSERT_TRUE(r.Covered(kSize / 2, kSize / 2));
    EXPECT_NEAR(r.normal[3 * k], 1, 1e-3);
    const std::uint8_t* p = r.image.At(kSize / 2, kSize / 2);
    EXPECT_EQ(p[0], 0);
    EXPECT_NEAR(p[2], 124, 3);
}

TEST(Api, ComposeEqualsRenderingBothTogether) {
    quadrix::Scene a, b, both;
    a.AddSphere("ball", {0.5, 0, 0}, 1);
    b.AddBox("box", {-1.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
    both.AddSphere("ball", {0.5, 0, 0}, 1).AddBox("box", {-1.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
    quadrix::Renderer renderer;
    auto o = SphereOptions();
    o.image = false;
    const auto ra = renderer.Render(a, o), rb = renderer.Render(b, o);
    const auto rboth = renderer.Render(both, o);
    const auto composed = quadrix::Compose(ra, rb);
    ASSERT_EQ(composed.depth.size(), rboth.depth.size());
    for (std::size_t k = 0; k < composed.depth.size(); ++k) {
        ASSERT_EQ(composed.surface[k] == quadrix::Rendering::kNone,
                  rboth.surface[k] == quadrix::Rendering::kNone);
        if (composed.surface[k] == quadrix::Rendering::kNone) continue;
        EXPECT_DOUBLE_EQ(composed.depth[k], rboth.depth[k]);
        EXPECT_EQ(composed.surfaceNames[composed.surface[k]], rboth.surfaceNames[rboth.surface[k]]);
    }
    quadrix::Rendering small;
    EXPECT_THROW(quadrix::Compose(ra, small), quadrix::Error);
}

TEST(Api, WritesPngAndPpmAndRefusesOtherNames) {
    quadrix::Scene scene = quadrix::Scene::FromText("solid sphere s =r 1 =c 1 .5 0;");
    quadrix::Renderer renderer;
    const auto r = renderer.Render(scene, SphereOptions());
    const std::string dir = ::testing::TempDir();
    r.image.Write(dir + "/api_out.png");
    r.image.Write(dir + "/api_out16.png", true);
    r.image.Write(dir + "/api_out.ppm");
    std::ifstream ppm(dir + "/api_out.ppm", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(ppm)), {});
    const std::string header = "P6\n64 64\n255\n";
    ASSERT_EQ(bytes.substr(0, header.size()), header);
    ASSERT_EQ(bytes.size(), header.size() + r.image.rgb.size());
    // The file holds exactly the image's sRGB bytes.
    EXPECT_EQ(bytes.substr(header.size()), std::string(r.image.rgb.begin(), r.image.rgb.end()));
    std::ifstream png(dir + "/api_out.png", std::ios::binary);
    char magic[8] = {};
    png.read(magic, 8);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG");
    EXPECT_THROW(r.image.Write(dir + "/api_out.jpg"), quadrix::Error);
    EXPECT_THROW(r.image.Write(dir + "/api_out.pgm"), quadrix::Error);
    EXPECT_THROW(r.image.Write(dir + "/no_such_dir/x.png"), quadrix::Error);
    for (const char* f : {"/api_out.png", "/api_out16.png", "/api_out.ppm"})
        std::remove((dir + f).c_str());
}

TEST(Api, ScenesAreValues) {
    quadrix::Scene a;
    a.AddSphere("ball", {0, 0, 0}, 1);
    quadrix::Scene b = a;
    b.AddSphere("other", {3, 0, 0}, 1);
    EXPECT_EQ(a.BodyCount(), 1u);
    EXPECT_EQ(b.BodyCount(), 2u);
    quadrix::Renderer renderer;
    auto o = SphereOptions();
    o.camera->halfWidth = 5;
    o.camera->halfHeight = 5;
    // Rendering a, then b, then a again: each render sees its own scene.
    const auto n1 = renderer.Render(a, o).CoveredCount();
    const auto n2 = renderer.Render(b, o).CoveredCount();
    const auto n3 = renderer.Render(a, o).CoveredCount();
    EXPECT_EQ(n1, n3);
    EXPECT_GT(n2, n1 + n1 / 2);
    EXPECT_STREQ(quadrix::VersionString(), QUADRIX_TEST_VERSION);
}

}  // namespace
