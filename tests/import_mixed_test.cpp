// Mixed inputs: an imported model drawn with the views and lights of a UniQuadrix file, the
// --az/--el fit, and the render command's import flags (--top, --strict) end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "quadrix/import/rt_view.h"
#include "quadrix/pipeline/inputs.h"
#include "quadrix/pipeline/pipeline.h"
#include "test_util.h"

namespace quadrix {
namespace {

std::string FileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// A sphere of radius 10 centred at model (5, 5, 5).
const char* kSphereCsg = "translate([5, 5, 5]) sphere(r = 10);\n";

TEST(ImportMixed, ImportedModelUsesViewsAndLightsOfUqFile) {
    testing::TempDir dir;
    std::string csg = dir.Write("ball.csg", kSphereCsg);
    // Quadrix coordinates: the model's z is Quadrix y, so this looks straight down on it.
    std::string uq = dir.Write("look.uq",
                               "view down vrp 5 5 5 dop 0 1 0 vup 0 0 1 whh 20 whw 20;\n"
                               "light sun 0.8 0 1 0;\nlight 0.2;\n");
    PipelineOptions po;
    po.scenePaths = {csg, uq};
    po.viewName = "down";
    po.width = po.height = 100;
    PipelineResult res;
    Diagnostics diags;
    ASSERT_TRUE(RunPipeline(po, res, diags));
    EXPECT_EQ(res.flat.viewName, "down");
    EXPECT_EQ(res.flat.lights.size(), 2u);
    // The window is 40 mm across 100 px: the sphere (20 mm across) covers a disc of radius 25 px
    // centred in the image; its area π·25² ≈ 1963 px, within the perimeter (≈157 px) of pixels
    // that quantisation can flip.
    double covered = static_cast<double>(res.frame.CoveredCount());
    EXPECT_NEAR(covered, M_PI * 25 * 25, 157);
    EXPECT_TRUE(res.frame.Covered(50, 50));
    EXPECT_FALSE(res.frame.Covered(5, 5));
}

TEST(ImportMixed, AzElFitsTheBoundingBoxLikeRt) {
    testing::TempDir dir;
    std::string csg = dir.Write("ball.csg", kSphereCsg);
    for (double az : {0.0, 35.0, 200.0}) {
        PipelineOptions po;
        po.scenePaths = {csg};
        po.azimuth = az;
        po.elevation = 25;
        po.width = po.height = 300;
        PipelineResult res;
        Diagnostics diags;
        ASSERT_TRUE(RunPipeline(po, res, diags));
        // rt's fit: viewsize = the box diagonal, 20·√3 mm, so the sphere's outline spans
        // 300/√3 ≈ 173.2 px whatever the direction; columns are counted to ±1 px.
        int c0 = 300, c1 = -1;
        for (int r = 0; r < 300; ++r)
            for (int c = 0; c < 300; ++c)
                if (res.frame.Covered(c, r)) c0 = std::min(c0, c), c1 = std::max(c1, c);
        EXPECT_NEAR(c1 - c0 + 1, 300 / std::sqrt(3.0), 1.5) << az;
        EXPECT_NEAR(0.5 * (c0 + c1 + 1), 150, 1.5) << az;  // centred
    }
}

TEST(ImportMixed, RenderCommandFlags) {
    testing::TempDir dir;
    std::string asc =
        dir.Write("m.asc",
                  "title {t}\n"
                  "put {s} ell V {0 0 0} A {10 0 0} B {0 10 0} C {0 0 10}\n"
                  "put {t} superell V {0 0 30} A {10 0 0} B {0 10 0} C {0 0 2} n 1 e 1\n"
                  "put {ball.r} comb region yes tree {l s}\n"
                  "put {ring.r} comb region yes tree {l t}\n"
                  "put {all.g} comb region no tree {u {l ball.r} {l ring.r}}\n");
    std::string out = dir.File("o.png");
    auto run = [&](const std::string& flags) {
        return testing::RunShell(testing::QuadrixBinary() + " render " + asc + " -o " + out +
                                 " --size 64x64 " + flags);
    };
    auto ok = run("--top all.g --az 30 --el 20 --allow-missing --stats");
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_NE(ok.err.find("superell ×1"), std::string::npos) << ok.err;
    EXPECT_NE(ok.err.find("left out: superell ×1"), std::string::npos) << ok.err;  // --stats
    std::filesystem::remove(out);
    auto missing = run("--top all.g --az 30 --el 20");
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_NE(missing.err.find("m.asc:3:1: error: primitive 't' (superell) cannot be drawn"),
              std::string::npos)
        << missing.err;
    EXPECT_FALSE(testing::FileExists(out));
    auto strict = run("--top all.g --az 30 --el 20 --strict --allow-missing");
    EXPECT_EQ(strict.exitCode, 1);
    auto ballOnly = run("--top ball.r --strict --az 30 --el 20");
    EXPECT_EQ(ballOnly.exitCode, 0) << ballOnly.err;
    auto noSuch = run("--top nosuch");
    EXPECT_EQ(noSuch.exitCode, 1);
    EXPECT_NE(noSuch.err.find("--top nosuch: no object of that name"), std::string::npos)
        << noSuch.err;
    auto explicitView = run(
        "--top ball.r --viewsize 40 --eye-pt 0 0 100 --viewrot 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1");
    EXPECT_EQ(explicitView.exitCode, 0) << explicitView.err;
    auto incomplete = run("--eye-pt 0 0 100");
    EXPECT_EQ(incomplete.exitCode, 2);
}

// rt's `ae AZ EL` in a view script (--rt-view, --views) is the --az/--el view: fitted to the
// model, byte for byte the same picture; with `viewsize` in the script, that viewsize.
TEST(ImportMixed, RtScriptAeIsTheAzElView) {
    testing::TempDir dir;
    std::string asc = dir.Write("m.asc",
                                "title {t}\n"
                                "put {s} ell V {0 0 0} A {10 0 0} B {0 4 0} C {0 0 6}\n"
                                "put {b} arb8 V1 {8 -2 -2} V2 {16 -2 -2} V3 {16 2 -2} V4 {8 2 -2} "
                                "V5 {8 -2 2} V6 {16 -2 2} V7 {16 2 2} V8 {8 2 2}\n"
                                "put {all.g} comb region yes tree {u {l s} {l b}}\n");
    std::string ae = dir.Write("ae.rt", "ae 30 20;\n");
    std::string aeSized = dir.Write("aes.rt", "viewsize 60;\nae 120 -35;\n");
    auto png = [&](const std::string& name, const std::string& flags) {
        const std::string out = dir.File(name);
        auto r = testing::RunShell(testing::QuadrixBinary() + " render " + asc + " -o " + out +
                                   " --size 96x80 " + flags);
        EXPECT_EQ(r.exitCode, 0) << flags << "\n" << r.err;
        return FileBytes(out);
    };
    const std::string azel = png("azel.png", "--az 30 --el 20");
    ASSERT_FALSE(azel.empty());
    EXPECT_EQ(png("ae.png", "--rt-view " + ae), azel);
    EXPECT_NE(png("other.png", "--az 31 --el 20"), azel);  // the comparison can tell views apart
    EXPECT_EQ(png("aes.png", "--rt-view " + aeSized),
              png("azels.png", "--az 120 --el -35 --viewsize 60"));
    // One frame per `start`/`end` of a view list, the --az/--el view. (Only the first frame is
    // compared byte for byte: the render context keeps the rt eye light of the first rt view for
    // the later frames of a list, whatever their kind; their coverage is compared.)
    std::string list =
        dir.Write("list.rt", "start 0;\nae 30 20;\nend;\nstart 1;\nae 120 -35;\nend;\n");
    png("f.png", "--views " + list + " --format ppm");
    png("azel2.ppm", "--az 120 --el -35");
    EXPECT_EQ(FileBytes(dir.File("f_0000.png")), png("azel.ppm", "--az 30 --el 20"));
    Image second, want;
    ASSERT_TRUE(testing::ReadPnm(dir.File("f_0001.png"), second));
    ASSERT_TRUE(testing::ReadPnm(dir.File("azel2.ppm"), want));
    ASSERT_EQ(second.width, want.width);
    int differ = 0, covered = 0;
    for (int y = 0; y < want.height; ++y)
        for (int x = 0; x < want.width; ++x) {
            const bool a = second.At(x, y)[0] + second.At(x, y)[1] + second.At(x, y)[2] > 0;
            const bool b = want.At(x, y)[0] + want.At(x, y)[1] + want.At(x, y)[2] > 0;
            covered += b;
            differ += a != b;
        }
    EXPECT_GT(covered, 500);
    EXPECT_EQ(differ, 0);
    // MGED's twist is not rt's: a positioned error, exit 2.
    std::string twist = dir.Write("tw.rt", "ae 30 20 10;\n");
    auto r = testing::RunShell(testing::QuadrixBinary() + " render " + asc + " -o " +
                               dir.File("t.png") + " --rt-view " + twist);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("tw.rt:1:10: error: rt's 'ae' takes the azimuth and the elevation only"),
              std::string::npos)
        << r.err;
}

}  // namespace
}  // namespace quadrix

namespace quadrix::import {
namespace {

TEST(ImportRtView, ScriptCommandsAndErrors) {
    Diagnostics d;
    auto rt = ParseRtViewScript(
        "viewsize 1.572026215e+02;\neye_pt 2.0 3.0 4.0;\n"
        "viewrot 0 1 0 0  -1 0 0 0  0 0 1 0  0 0 0 1;\nstart 0; clean; end;\n",
        "v.rt", d);
    ASSERT_TRUE(rt.has_value());
    EXPECT_DOUBLE_EQ(rt->viewsize, 157.2026215);
    EXPECT_EQ(rt->eye, (Vec3{2, 3, 4}));
    EXPECT_EQ(rt->viewrot.m[1][0], -1);
    // The view rows in Quadrix space: X = (0 1 0) → (0 0 1), Y = (-1 0 0), Z = (0 0 1) → (0 1 0).
    scene::View v = MakeRtView(*rt, 512, 512);
    EXPECT_EQ(*v.vup, (Vec3{-1, 0, 0}));
    EXPECT_EQ(*v.dop, (Vec3{0, 1, 0}));
    EXPECT_DOUBLE_EQ(*v.whw, 0.5 * 157.2026215);
    // The identity quaternion is the identity rotation.
    auto q = ParseRtViewScript("viewsize 10; eye_pt 0 0 0; orientation 0 0 0 1;", "q.rt", d);
    ASSERT_TRUE(q.has_value());
    EXPECT_EQ(q->viewrot, Mat4::Identity());
    Diagnostics bad;
    EXPECT_FALSE(ParseRtViewScript("viewsize 10;\neye_pt 0 0 x;", "b.rt", bad).has_value());
    ASSERT_FALSE(bad.Items().empty());
    EXPECT_EQ(bad.Items()[0].Format(false), "b.rt:2:12: error: 'x' is not a finite number");
    Diagnostics missing;
    EXPECT_FALSE(ParseRtViewScript("viewsize 10;", "m.rt", missing).has_value());
    // ae: alone it is fitted to the model later; an eye_pt after it keeps ae's rotation, which is
    // the --az/--el one; a viewrot after it replaces it.
    auto fitted = ParseRtViewScript("ae 30 20;", "a.rt", d);
    ASSERT_TRUE(fitted.has_value());
    EXPECT_TRUE(fitted->Fitted());
    EXPECT_EQ(*fitted->aeAzimuth, 30);
    EXPECT_EQ(*fitted->aeElevation, 20);
    EXPECT_EQ(fitted->viewsize, 0);
    auto placed = ParseRtViewScript("ae 30 20; eye_pt 1 2 3; viewsize 9;", "p.rt", d);
    ASSERT_TRUE(placed.has_value());
    EXPECT_FALSE(placed->Fitted());
    EXPECT_EQ(placed->viewrot, AzElRtView(30, 20, Box3{}, std::nullopt).viewrot);
    EXPECT_EQ(placed->eye, (Vec3{1, 2, 3}));
    auto replaced = ParseRtViewScript(
        "ae 30 20; viewrot 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1; "
        "eye_pt 0 0 0; viewsize 5;",
        "r.rt", d);
    ASSERT_TRUE(replaced.has_value());
    EXPECT_EQ(replaced->viewrot, Mat4::Identity());
    Diagnostics noEye;
    EXPECT_FALSE(ParseRtViewScript("ae 30 20; eye_pt 1 2 3;", "n.rt", noEye).has_value());
}

}  // namespace
}  // namespace quadrix::import

namespace quadrix {
namespace {

// rt's orientation, not its mirror image: from az 0 el 0 (viewer on +X) model +Y is screen right
// and +Z screen up; from az 270 el 90 (above) +X is right and +Y up.
TEST(ImportMixed, AzElIsNotMirrored) {
    testing::TempDir dir;
    std::string csg = dir.Write("marks.csg",
                                "sphere(1);\ntranslate([0, 10, 0]) sphere(2);\n"
                                "translate([0, 0, 10]) sphere(3);\n"
                                "translate([10, 0, 0]) sphere(4);\n"
                                // small counterweights that make the box symmetric about 0
                                "translate([0, -11.5, 0]) sphere(0.5);\n"
                                "translate([0, 0, -12.5]) sphere(0.5);\n"
                                "translate([-13.5, 0, 0]) sphere(0.5);\n");
    struct Case {
        double az, el;
        int rightRadius, upRadius;  // which sphere should lie right of / above the centre
    };
    for (const Case& c : {Case{0, 0, 2, 3}, Case{270, 90, 4, 2}}) {
        PipelineOptions po;
        po.scenePaths = {csg};
        po.azimuth = c.az;
        po.elevation = c.el;
        po.width = po.height = 101;
        PipelineResult res;
        Diagnostics diags;
        ASSERT_TRUE(RunPipeline(po, res, diags));
        // Sum of covered columns right of the image centre vs left, rows above vs below.
        int right = 0, left = 0, up = 0, down = 0;
        for (int r = 0; r < 101; ++r)
            for (int col = 0; col < 101; ++col) {
                if (!res.frame.Covered(col, r)) continue;
                if (col > 50) ++right;
                if (col < 50) ++left;
                if (r < 50) ++up;
                if (r > 50) ++down;
            }
        // The box is centred on the origin, so the image centre is the origin; the spheres on
        // the +side are much larger than their counterweights.
        EXPECT_GT(right, left) << c.az << " " << c.el;
        EXPECT_GT(up, down) << c.az << " " << c.el;
    }
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// rt's rays start at the eye: a solid behind the eye plane is not drawn.
TEST(ImportMixed, RtViewClipsBehindTheEye) {
    testing::TempDir dir;
    std::string csg =
        dir.Write("two.csg", "sphere(5);\ntranslate([0, 0, 50]) sphere(20);\n");  // 2nd above eye
    PipelineOptions po;
    po.scenePaths = {csg};
    po.width = po.height = 64;
    import::RtView rt;
    rt.viewsize = 64;
    rt.eye = {0, 0, 20};  // looking down -z from z = 20: the big sphere (z 30..70) is behind
    po.rtView = rt;
    PipelineResult res;
    Diagnostics diags;
    ASSERT_TRUE(RunPipeline(po, res, diags));
    // Only the small sphere: radius 5 mm = 5 px, area ≈ 78.5 px (± its 31 px perimeter).
    EXPECT_NEAR(static_cast<double>(res.frame.CoveredCount()), M_PI * 25, 31);
}

}  // namespace
}  // namespace quadrix
