// Mixed inputs: an imported model drawn with the views and lights of a UniQuadrix file, the
// --az/--el fit, and the render command's import flags (--top, --strict) end to end.
#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/pipeline/pipeline.h"
#include "test_util.h"

namespace quadrix {
namespace {

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
    std::string asc = dir.Write("m.asc",
                                "title {t}\n"
                                "put {s} ell V {0 0 0} A {10 0 0} B {0 10 0} C {0 0 10}\n"
                                "put {t} tor V {0 0 30} H {0 0 1} r_a 10 r_h 2\n"
                                "put {ball.r} comb region yes tree {l s}\n"
                                "put {ring.r} comb region yes tree {l t}\n"
                                "put {all.g} comb region no tree {u {l ball.r} {l ring.r}}\n");
    std::string out = dir.File("o.png");
    auto run = [&](const std::string& flags) {
        return testing::RunShell(testing::QuadrixBinary() + " render " + asc + " -o " + out +
                                 " --size 64x64 " + flags);
    };
    auto ok = run("--top all.g --az 30 --el 20");
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_NE(ok.err.find("tor ×1"), std::string::npos) << ok.err;
    auto strict = run("--top all.g --az 30 --el 20 --strict");
    EXPECT_EQ(strict.exitCode, 1);
    EXPECT_NE(strict.err.find("--strict"), std::string::npos) << strict.err;
    auto ballOnly = run("--top ball.r --strict --az 30 --el 20");
    EXPECT_EQ(ballOnly.exitCode, 0) << ballOnly.err;
    auto missing = run("--top nosuch");
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_NE(missing.err.find("--top nosuch: no object of that name"), std::string::npos)
        << missing.err;
    auto explicitView =
        run("--top ball.r --viewsize 40 --eye-pt 0 0 100 --viewrot 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1");
    EXPECT_EQ(explicitView.exitCode, 0) << explicitView.err;
    auto incomplete = run("--eye-pt 0 0 100");
    EXPECT_EQ(incomplete.exitCode, 2);
}

}  // namespace
}  // namespace quadrix
