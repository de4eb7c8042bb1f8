// Scene-level shading tests (issue 17): lighting never hides geometry, and the picture is
// written in sRGB.
//
// "No example or documented snippet renders with a covered pixel equal to the background": every
// examples/*.uq and gallery scene, and every code block of docs/language.md that is a complete
// scene (and each of its single statements that is one), is rendered through RunPipeline + Shade;
// no pixel the Frame covers may have the background's value.
#include <gtest/gtest.h>
#include <png.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "quadrix/io/writers.h"
#include "quadrix/math/srgb.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/scene/css_colors.h"
#include "quadrix/shade/antialias.h"
#include "quadrix/shade/shader.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

struct Hidden {
    long covered = 0, hidden = 0;
};

// Pixels the Frame covers whose shaded value equals the background's (8-bit linear).
Hidden CountHidden(const PipelineResult& r) {
    const Image img = Shade(r.frame, r.flat);
    Hidden h;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            if (!r.frame.Covered(x, y)) continue;
            ++h.covered;
            const std::uint8_t* p = img.At(x, y);
            bool same = true;
            const scene::Color& bg = r.flat.background;
            const double want[3] = {bg.r, bg.g, bg.b};
            for (int k = 0; k < img.channels; ++k)
                same &= p[k] == static_cast<std::uint8_t>(std::lround(want[k] * 255));
            h.hidden += same;
        }
    return h;
}

std::vector<std::string> SceneFiles() {
    std::vector<std::string> files;
    for (const char* dir : {"examples", "examples/gallery"})
        for (const auto& e : std::filesystem::directory_iterator(SourcePath(dir)))
            if (e.path().extension() == ".uq") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

TEST(Shading, NoExampleRendersACoveredPixelEqualToTheBackground) {
    const std::vector<std::string> files = SceneFiles();
    ASSERT_GE(files.size(), 10u);
    int rendered = 0;
    for (const std::string& path : files) {
        PipelineOptions o;
        o.scenePaths = {path};
        o.width = 96;
        o.height = 72;
        PipelineResult r;
        Diagnostics d;
        // Gallery tube files are definitions read by their scenes; they draw nothing alone.
        if (!RunPipeline(o, r, d)) {
            EXPECT_NE(path.find("_tubes.uq"), std::string::npos) << path << " does not render";
            continue;
        }
        ++rendered;
        const Hidden h = CountHidden(r);
        EXPECT_GT(h.covered, 0) << path;
        EXPECT_EQ(h.hidden, 0) << path << ": " << h.hidden << " of " << h.covered
                               << " covered pixels have the background's value";
    }
    EXPECT_GE(rendered, 10);
}

// The picture defaults of quadrix render (shadows and --aa 4) never touch the background: every
// pixel whose 3 × 3 neighbourhood the Frame does not cover is exactly the background (its row's
// value of a gradient), byte and linear value, and with anti-aliasing off every uncovered pixel
// is; and shadows never make a covered pixel the background's value.
TEST(Shading, ShadowsAndAntialiasingNeverDarkenTheBackground) {
    int scenes = 0;
    for (const std::string& path : SceneFiles()) {
        PipelineOptions o;
        o.scenePaths = {path};
        o.width = 96;
        o.height = 72;
        PipelineResult r;
        Diagnostics d;
        if (!RunPipeline(o, r, d)) continue;
        ++scenes;
        for (int aa : {0, 4}) {
            ShadeOptions so;
            so.shadows = true;
            so.aaSamples = aa;
            so.forceColor = true;
            Image img = Shade(r.frame, r.flat, so);
            Antialias(r.frame, r.flat, so, img);
            const PixelShader shader(r.frame, r.flat, so);
            long background = 0, wrong = 0, hidden = 0;
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x) {
                    const std::uint8_t* p = img.At(x, y);
                    const float* f = &img.linear[static_cast<std::size_t>(p - img.pixels.data())];
                    const scene::Color bg = shader.Background(y, img.height);
                    const double want[3] = {bg.r, bg.g, bg.b};
                    bool same = true;
                    for (int k = 0; k < 3; ++k) same &= f[k] == static_cast<float>(want[k]);
                    if (r.frame.Covered(x, y)) {
                        bool sameByte = true;
                        for (int k = 0; k < 3; ++k)
                            sameByte &=
                                p[k] == static_cast<std::uint8_t>(std::lround(want[k] * 255));
                        hidden += sameByte;
                        continue;
                    }
                    bool near = false;
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const int u = x + dx, v = y + dy;
                            if (u >= 0 && v >= 0 && u < img.width && v < img.height)
                                near |= r.frame.Covered(u, v);
                        }
                    if (aa && near) continue;
                    ++background;
                    wrong += !same;
                }
            EXPECT_GT(background, 0) << path;
            EXPECT_EQ(wrong, 0) << path << " --aa " << aa;
            EXPECT_EQ(hidden, 0) << path << " --aa " << aa;
        }
    }
    EXPECT_GE(scenes, 10);
}

// The code blocks of docs/language.md.
std::vector<std::string> DocBlocks() {
    std::ifstream in(SourcePath("docs/language.md"));
    std::vector<std::string> blocks;
    std::string line, block;
    bool inside = false;
    while (std::getline(in, line)) {
        if (line.rfind("```", 0) == 0) {
            if (inside) blocks.push_back(block);
            block.clear();
            inside = !inside;
            continue;
        }
        if (inside) block += line + "\n";
    }
    return blocks;
}

// A snippet renders when it is a complete scene: it reads without errors and draws something.
std::optional<Hidden> RenderSnippet(const std::string& text) {
    PipelineOptions o;
    o.sceneText = text;
    o.width = 80;
    o.height = 60;
    PipelineResult r;
    Diagnostics d;
    if (!RunPipeline(o, r, d) || d.HasErrors()) return std::nullopt;
    return CountHidden(r);
}

TEST(Shading, NoDocumentedSnippetRendersACoveredPixelEqualToTheBackground) {
    int scenes = 0;
    bool sawOpenRod = false;
    for (const std::string& block : DocBlocks()) {
        std::vector<std::string> candidates = {block};
        std::istringstream lines(block);
        for (std::string l; std::getline(lines, l);) candidates.push_back(l);
        for (const std::string& text : candidates) {
            auto h = RenderSnippet(text);
            if (!h || h->covered == 0) continue;
            ++scenes;
            sawOpenRod |= text.find("solid cylinder rod") == 0;
            EXPECT_EQ(h->hidden, 0) << h->hidden << " of " << h->covered
                                    << " covered pixels have the background's value:\n"
                                    << text;
        }
    }
    RecordProperty("scenes", scenes);
    EXPECT_GE(scenes, 10);
    EXPECT_TRUE(sawOpenRod) << "the documented open cylinder was not found or did not render";
}

// The tube's top annulus (issue 17: it was 0 under `light default 1 0 0 -1`) is lit by the rig.
TEST(Shading, TheDefaultRigLightsFacesParallelToZ) {
    PipelineOptions o;
    o.scenePaths = {SourcePath("examples/tube.uq")};
    o.width = 160;
    o.height = 120;
    PipelineResult r;
    Diagnostics d;
    ASSERT_TRUE(RunPipeline(o, r, d));
    ASSERT_EQ(r.flat.lights.size(), 3u);
    EXPECT_TRUE(r.flat.lights[0].isRig);
    const Image img = Shade(r.frame, r.flat);
    long top = 0, dark = 0;
    for (int y = 0; y < r.frame.height; ++y)
        for (int x = 0; x < r.frame.width; ++x) {
            const std::size_t i = r.frame.Index(x, y);
            if (!r.frame.Covered(x, y)) continue;
            // The top plane's world normal is +y.
            if (std::fabs(r.frame.Normal(i).y - 1) > 1e-9) continue;
            ++top;
            dark += img.At(x, y)[0] < 40;
        }
    EXPECT_GT(top, 100);
    EXPECT_EQ(dark, 0);
}

// A scene that declares a light keeps UniQuadrix's semantics: only ambient lights declared →
// `light default 1 0 0 -1` is added, and no rig.
TEST(Shading, DeclaredLightsKeepTheDefaultLightSemantics) {
    PipelineOptions o;
    o.sceneText = "solid sphere s =r 1; light amb .25;";
    o.width = 20;
    o.height = 20;
    PipelineResult r;
    Diagnostics d;
    ASSERT_TRUE(RunPipeline(o, r, d));
    ASSERT_EQ(r.flat.lights.size(), 2u);
    EXPECT_EQ(r.flat.lights[0].id, "amb");
    EXPECT_TRUE(r.flat.lights[1].isDefault);
    EXPECT_EQ(r.flat.lights[1].direction, (Vec3{0, 0, -1}));
}

TEST(Shading, MaterialsAndBackgroundFromTheLanguage) {
    PipelineOptions o;
    o.sceneText =
        "solid sphere left =at -1.5 0 0 =r 1 =c steelblue =finish .7 .5 30;\n"
        "solid sphere right =at 1.5 0 0 =r 1 =c 1 0 0 =alpha .5;\n"
        "background 0 0 .2 .6 .6 .6;\n"
        "light key .8 =at 0 5 -10 =c white; light .2;\n";
    o.width = 120;
    o.height = 60;
    PipelineResult r;
    Diagnostics d;
    ASSERT_TRUE(RunPipeline(o, r, d)) << (d.Items().empty() ? "" : d.Items()[0].Format());
    ASSERT_EQ(r.flat.bodies.size(), 2u);
    const auto steel = scene::CssColor("SteelBlue");
    ASSERT_TRUE(steel);
    EXPECT_EQ(r.flat.bodies[0].color, *steel);
    EXPECT_NEAR(steel->b, LinearFromSrgb(0xb4 / 255.0), 1e-15);
    EXPECT_EQ(*r.flat.bodies[0].finish.specular, 0.5);
    EXPECT_EQ(*r.flat.bodies[1].finish.opacity, 0.5);
    EXPECT_EQ(r.flat.backgroundBottom, (scene::Color{.6, .6, .6}));
    ASSERT_EQ(r.flat.lights[0].kind, scene::Light::Kind::kPoint);
    const Image img = Shade(r.frame, r.flat);
    ASSERT_EQ(img.channels, 3);
    // Background gradient: dark blue at the top, gray at the bottom.
    EXPECT_LT(img.At(0, 0)[0], img.At(0, 59)[0]);
    // The half-transparent red ball shows the background's blue through it.
    const std::uint8_t* mid = img.At(90, 30);
    ASSERT_TRUE(r.frame.Covered(90, 30));
    EXPECT_GT(mid[2], 10);
    EXPECT_GT(mid[0], mid[1]);
    EXPECT_EQ(scene::CssColorCount(), 148);
}

TEST(Shading, PngIsSrgbEncodedWithItsChunks) {
    Image img(4, 1, 3);
    img.linear = {0, 0, 0, 0.5f, 0.5f, 0.5f, 0.0031308f, 0.0031308f, 0.0031308f, 1, 1, 1};
    img.pixels = {0, 0, 0, 128, 128, 128, 1, 1, 1, 255, 255, 255};
    TempDir dir;
    for (int depth : {8, 16}) {
        PngOptions o;
        o.bitDepth = depth;
        const std::string path = dir.File("t" + std::to_string(depth) + ".png");
        ASSERT_EQ(WritePng(path, img, o), "");
        std::FILE* f = std::fopen(path.c_str(), "rb");
        ASSERT_TRUE(f);
        png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
        png_infop info = png_create_info_struct(png);
        png_init_io(png, f);
        png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
        EXPECT_EQ(png_get_bit_depth(png, info), depth);
        int intent = -1;
        EXPECT_TRUE(png_get_sRGB(png, info, &intent));
        double gamma = 0;
        EXPECT_TRUE(png_get_gAMA(png, info, &gamma));
        EXPECT_NEAR(gamma, 1 / 2.2, 1e-4);
        EXPECT_TRUE(png_get_valid(png, info, PNG_INFO_cHRM));
        png_textp text = nullptr;
        int nText = 0;
        png_get_text(png, info, &text, &nText);
        ASSERT_EQ(nText, 1);
        EXPECT_STREQ(text[0].key, "Software");
        EXPECT_EQ(std::string(text[0].text).rfind("Quadrix ", 0), 0u);
        png_bytepp rows = png_get_rows(png, info);
        auto sample = [&](int x) {
            return depth == 8 ? rows[0][3 * x] / 255.0
                              : (rows[0][6 * x] * 256 + rows[0][6 * x + 1]) / 65535.0;
        };
        const double tol = depth == 8 ? 0.5 / 255 : 0.5 / 65535;
        EXPECT_EQ(sample(0), 0);
        EXPECT_EQ(sample(3), 1);
        if (depth == 16) {                                     // from the unquantised values
            EXPECT_NEAR(sample(1), SrgbFromLinear(0.5), tol);  // 0.7354
            EXPECT_NEAR(sample(2), 0.0031308 * 12.92, tol + 1e-6);
        } else {  // from the 8-bit linear pixels 128 and 1
            EXPECT_NEAR(sample(1), SrgbFromLinear(128 / 255.0), tol);
            EXPECT_NEAR(sample(2), SrgbFromLinear(1 / 255.0), tol);
        }
        png_destroy_read_struct(&png, &info, nullptr);
        std::fclose(f);
    }
}

}  // namespace
}  // namespace quadrix::testing
