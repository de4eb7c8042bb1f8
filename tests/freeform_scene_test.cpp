// The freeform and patch statements of the scene language (docs/language.md), end to end:
// reader → scene model → Flattener (FlatScene::freeforms) → engine → Frame → shader.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/import/freeform/freeform_reader.h"
#include "quadrix/lang/reader.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/shade/shader.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

struct Run {
    bool ok = false;
    PipelineResult r;
    Diagnostics d;
    std::string Messages() const {
        std::string s;
        for (const auto& item : d.Items()) s += item.Format() + "\n";
        return s;
    }
};

std::unique_ptr<Run> Render(const std::string& text, int w, int h,
                            const std::string& engine = "raycast") {
    auto run = std::make_unique<Run>();
    PipelineOptions o;
    o.sceneText = text;
    o.width = w;
    o.height = h;
    o.engine = engine;
    run->ok = RunPipeline(o, run->r, run->d);
    return run;
}

int Covered(const Frame& f) {
    int n = 0;
    for (auto s : f.surface) n += s != Frame::kNone;
    return n;
}

// A window of ±2 world units on a 200×200 image: 50 pixels per unit, looking along +z.
constexpr const char* kFrontView = "view front dop 0 0 -1 whw 2 whh 2;\n";

// A flat bilinear Bézier square [-1, 1]² at z = 0 covers 100×100 pixels. The isocurves are drawn
// about 1.75 px wide (render.h default thickness), so the edges may spill up to one pixel out.
TEST(FreeformScene, BezierSquareCoversItsPixels) {
    auto run = Render(
        std::string(kFrontView) + "bezier sq 1 1 < -1 -1 0  1 -1 0  -1 1 0  1 1 0 > =c 1 0 0;\n",
        200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    ASSERT_EQ(run->r.flat.freeforms.size(), 1u);
    const Frame& f = run->r.frame;
    const int covered = Covered(f);
    EXPECT_GE(covered, 100 * 100);
    EXPECT_LE(covered, 102 * 102);
    // Every pixel whose centre is inside the square by more than a pixel is covered, at depth 0
    // of the window's depth range and with the color of the statement.
    for (int y = 52; y < 148; ++y)
        for (int x = 52; x < 148; ++x) {
            const std::size_t i = f.Index(x, y);
            ASSERT_NE(f.surface[i], Frame::kNone) << x << "," << y;
            EXPECT_EQ(run->r.flat.SurfaceColor(f.surface[i], f.body[i]).g, 0.0);
            EXPECT_NEAR(std::fabs(f.Normal(i).z), 1.0, 1e-9);
        }
    EXPECT_EQ(f.surface[f.Index(10, 10)], Frame::kNone);
}

// Transforms move the control points; the translated square lands 50 px to the right.
TEST(FreeformScene, TransformsMoveTheControlPoints) {
    auto run = Render(std::string(kFrontView) +
                          "bezier sq 1 1 < -.5 -.5 0  .5 -.5 0  -.5 .5 0  .5 .5 0 > =tx 1;\n",
                      200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    const Frame& f = run->r.frame;
    EXPECT_NE(f.surface[f.Index(150, 100)], Frame::kNone);
    EXPECT_EQ(f.surface[f.Index(100, 100)], Frame::kNone);
    EXPECT_EQ(f.surface[f.Index(50, 100)], Frame::kNone);
}

// A surface in front of a sphere hides it, one behind it is hidden: freeform surfaces are
// z-buffered with the quadric solids of any engine.
TEST(FreeformScene, ComposesWithSolidsByDepth) {
    const std::string sphere = "quadric s <1 1 1 0 0 0 0 0 0 -1>; body ball (s);\n";
    for (double z : {-2.0, 2.0}) {
        const std::string sq = fmt::format(
            "bezier sq 1 1 < -.5 -.5 {0} .5 -.5 {0} -.5 .5 {0} "
            ".5 .5 {0} >;\n",
            z);
        for (const char* engine : {"raycast", "isocurve", "patch"}) {
            auto run = Render(std::string(kFrontView) + sphere + sq, 200, 200, engine);
            ASSERT_TRUE(run->ok) << run->Messages();
            const Frame& f = run->r.frame;
            const std::size_t centre = f.Index(100, 100);
            const int freeformId = static_cast<int>(run->r.flat.halfSpaces.size());
            // Rays run along +z: z = -2 is in front of the unit sphere, z = 2 behind it.
            if (z < 0)
                EXPECT_EQ(f.surface[centre], freeformId) << engine;
            else
                EXPECT_NE(f.surface[centre], freeformId) << engine;
            EXPECT_NE(f.surface[centre], Frame::kNone) << engine;
        }
    }
}

TEST(FreeformScene, BsplineAndRationalWeights) {
    // A quarter cylinder as a rational quadratic (weights 1, √2/2, 1) in u, linear in v: every
    // point of the surface lies at distance 1 from the z axis, so its image seen along +z is
    // the quarter circle arc, which covers few pixels; seen along -y it is a square.
    const double w = std::sqrt(0.5);
    const std::string text = fmt::format(
        "view side dop 0 -1 0 vup 0 0 1 whw 2 whh 2;\n"
        "bspline arc 2 1 3 2 < 0 0 0 1 1 1 > < 0 0 1 1 > < 1 0 0  1 1 0  0 1 0   1 0 1  1 1 1  "
        "0 1 1 > =r < 1 {0} 1  1 {0} 1 >;\n",
        w);
    auto run = Render(text, 200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    ASSERT_EQ(run->r.flat.freeforms.size(), 1u);
    const freeform::Surface& s = run->r.flat.freeforms[0].surface;
    EXPECT_TRUE(s.Rational());
    for (double u : {0.0, 0.2, 0.5, 0.9, 1.0}) {
        Vec3 p = s.Point(u, 0.3);
        EXPECT_NEAR(std::hypot(p.x, p.y), 1.0, 1e-12) << u;
        EXPECT_NEAR(p.z, 0.3, 1e-12);
    }
    // Seen from -y looking along +y: the arc spans x in [0, 1], z in [0, 1]: 50×50 pixels.
    const int covered = Covered(run->r.frame);
    EXPECT_GE(covered, 50 * 50);
    EXPECT_LE(covered, 52 * 52);
}

TEST(FreeformScene, PatchesStatementReadsTheTeaSet) {
    TempDir dir;
    const std::string teapot = SourcePath("src/quadrix/import/freeform/testdata/newell/teapot.txt");
    Diagnostics direct;
    auto model = import::ReadFreeformFile(teapot, direct);
    ASSERT_TRUE(model);
    auto run = Render(fmt::format("patches pot \"{}\" newell =rx -90 =c .9 .6 .3;", teapot), 160,
                      120, "isocurve");
    ASSERT_TRUE(run->ok) << run->Messages();
    ASSERT_EQ(run->r.scene.top.freeforms.size(), model->surfaces.size());
    EXPECT_EQ(run->r.scene.top.freeforms[3].id, "pot[3]");
    // The teapot is fitted to the image (the fit includes freeform surfaces) and drawn.
    const int covered = Covered(run->r.frame);
    EXPECT_GT(covered, 160 * 120 / 5);
    EXPECT_LT(covered, 160 * 120);
    Image img = Shade(run->r.frame, run->r.flat, {});
    EXPECT_EQ(img.channels, 3);  // colored
}

TEST(FreeformScene, DefinitionsReplicateFreeformSurfaces) {
    auto run = Render(std::string(kFrontView) +
                          "definition tile;\n"
                          "bezier sq 1 1 < 0 0 0  .4 0 0  0 .4 0  .4 .4 0 >;\n"
                          "enddef;\n"
                          "array row (tile =tx -1.5) 3 =tx 1;\n",
                      200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    ASSERT_EQ(run->r.flat.freeforms.size(), 3u);
    EXPECT_EQ(run->r.flat.freeforms[2].name, "row[2]/sq");
    const Frame& f = run->r.frame;
    // Copy k covers x in [-1.5 + k, -1.1 + k], y in [0, .4] (world; device y grows downward).
    for (int k = 0; k < 3; ++k) {
        const int x = static_cast<int>((-1.3 + k + 2) * 50);
        EXPECT_NE(f.surface[f.Index(x, 90)], Frame::kNone) << k;
    }
    EXPECT_EQ(f.surface[f.Index(static_cast<int>((-0.8 + 2) * 50), 90)], Frame::kNone);
}

// An input with an error: the message expected and where (the column of the first occurrence of
// `at` in the one-line text; nullptr when the error has no position, e.g. a missing file).
// Freeform files given on the command line go through the input dispatcher: the tea-set formats
// are Z-up and get the importers' axis swap, so the teapot's height (model z in [0, 3.15]) is
// Quadrix y and it stands upright in the default view.
TEST(FreeformScene, FreeformFilesAreInputsOfRender) {
    PipelineOptions o;
    o.scenePaths = {SourcePath("src/quadrix/import/freeform/testdata/bpt/teapot.bpt")};
    o.width = 160;
    o.height = 120;
    PipelineResult r;
    Diagnostics d;
    ASSERT_TRUE(RunPipeline(o, r, d));
    ASSERT_EQ(r.flat.freeforms.size(), 32u);
    EXPECT_EQ(r.scene.top.freeforms[0].id, "teapot[0]");
    Box3 box;
    for (const FlatFreeform& f : r.flat.freeforms) box.Extend(f.surface.Bounds());
    EXPECT_NEAR(box.lo.y, 0.0, 1e-9);
    EXPECT_NEAR(box.hi.y, 3.15, 0.01);
    EXPECT_GT(Covered(r.frame), 160 * 120 / 5);
}

struct BadFreeform {
    const char* text;
    const char* message;
    const char* at;
};

TEST(FreeformScene, BadStatementsAreErrorsAtTheirPlace) {
    const BadFreeform cases[] = {
        {"bezier bad 1 1 < 0 0 0  1 0 0  0 1 0 >;", "has 9 numbers; expected 12", ">"},
        {"bezier bad 0 1 < >;", "degree in u must be a whole number from 1 to 12", "0"},
        {"bezier bad 1.5 1 < >;", "degree in u must be a whole number", "1.5"},
        {"bezier bad 1 1 < 0 0 0 1 0 0 0 1 0 1 1 0 > =r < 1 1 -1 1 >;", "weight 3 is -1", "< 1 1"},
        {"bspline bad 1 1 2 2 < 0 1 0 1 > < 0 0 1 1 > < 0 0 0 1 0 0 0 1 0 1 1 0 >;",
         "u knot 3 (0) is smaller than knot 2 (1)", "< 0 1 0 1"},
        {"bspline bad 1 1 2 2 < 0 0 0 0 > < 0 0 1 1 > < 0 0 0 1 0 0 0 1 0 1 1 0 >;",
         "empty parameter range", "< 0 0 0 0"},
        {"bspline bad 2 1 2 2 < >;", "control points in u must be a whole number from 3", "2 2 <"},
        {"patches bad \"no/such/file.txt\";", "cannot", nullptr},
        {"patches bad \"x.txt\" iges;", "unknown freeform format 'iges'", "iges"},
        {"bezier bad 1 1 < 0 0 0 1 0 0 0 1 0 1 1 0 > =q 1;", "unknown option '=q' for a bezier",
         "=q"},
    };
    for (const BadFreeform& c : cases) {
        auto run = Render(c.text, 64, 64);
        EXPECT_FALSE(run->ok) << c.text;
        bool found = false;
        for (const auto& item : run->d.Items()) {
            if (item.Format().find(c.message) == std::string::npos) continue;
            found = true;
            if (c.at) {
                EXPECT_EQ(item.loc.line, 1) << c.text << "\n" << run->Messages();
                EXPECT_EQ(item.loc.column,
                          static_cast<int>(std::string_view(c.text).find(c.at)) + 1)
                    << c.text << "\n"
                    << run->Messages();
            }
        }
        EXPECT_TRUE(found) << c.text << "\n" << run->Messages();
    }
}

// The patch statement: one quadric and up to four planes that bound without being drawn.
TEST(PatchStatement, ExpandsToABodyWithTransparentPlaneCopies) {
    auto run = Render(std::string(kFrontView) +
                          "quadric s <1 1 1 0 0 0 0 0 0 -1>; plane cut <0 0 1 0.5>;\n"
                          "patch cap (s cut) =c 0 1 0;\n",
                      200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    const scene::Scope& top = run->r.scene.top;
    ASSERT_EQ(top.bodies.size(), 1u);
    ASSERT_EQ(top.bodies[0].literals.size(), 2u);
    const scene::HalfSpace& copy = top.halfSpaces[top.bodies[0].literals[1].halfSpace];
    EXPECT_EQ(copy.id, "cap~cut");
    EXPECT_TRUE(copy.transparent);
    EXPECT_FALSE(top.halfSpaces[1].transparent);  // the plane's own statement is untouched
}

// The part of the unit sphere with z <= -0.5 (the cap facing the viewer, rays along +z) is seen
// as a disc of radius √(1 − 0.25) = 0.866; the rest of the sphere is cut away and the plane is
// not drawn, so through the opening one sees nothing else. raycast and patch agree.
TEST(PatchStatement, PatchEngineAndRaycastAgree) {
    const std::string text = std::string(kFrontView) +
                             "quadric s <1 1 1 0 0 0 0 0 0 -1>; plane cut <0 0 1 0.5>;\n"
                             "patch cap (s cut);\n";
    auto ray = Render(text, 200, 200, "raycast");
    auto pat = Render(text, 200, 200, "patch");
    ASSERT_TRUE(ray->ok && pat->ok) << ray->Messages() << pat->Messages();
    const double expected = M_PI * 0.75 * 50 * 50;  // area of the disc in pixels
    EXPECT_NEAR(Covered(ray->r.frame), expected, 2 * M_PI * 0.866 * 50);  // ±1 px of perimeter
    int differ = 0;
    for (std::size_t i = 0; i < ray->r.frame.surface.size(); ++i) {
        const bool a = ray->r.frame.surface[i] != Frame::kNone;
        const bool b = pat->r.frame.surface[i] != Frame::kNone;
        differ += a != b;
        if (a && b) {
            EXPECT_NEAR(ray->r.frame.depth[i], pat->r.frame.depth[i], 1e-6);
        }
    }
    EXPECT_LE(differ, 4);  // silhouette pixels whose centres are within rounding of the edge
}

TEST(PatchStatement, BadPatchesAreErrors) {
    const BadFreeform cases[] = {
        {"plane pa <1 0 0 0>; patch pp (pa);", "needs one quadric", "(pa"},
        {"quadric qq <1 1 1 0 0 0 0 0 0 -1>; quadric rr <1 1 0 0 0 0 0 0 0 -1>; patch pp (qq rr);",
         "'rr' is a second one", "rr)"},
        {"quadric qq <1 1 1 0 0 0 0 0 0 -1>; plane pa <1 0 0 0>; plane pb <0 1 0 0>;"
         "plane pc <0 0 1 0>; plane pd <1 1 0 0>; plane pe <1 0 1 0>; patch pp (qq pa pb pc pd "
         "pe);",
         "at most 4 planes", "pe)"},
        {"quadric qq <1 1 1 0 0 0 0 0 0 -1>; patch pp (qq zz);", "unknown half-space 'zz'", "zz"},
    };
    for (const BadFreeform& c : cases) {
        auto run = Render(c.text, 64, 64);
        EXPECT_FALSE(run->ok) << c.text;
        bool found = false;
        for (const auto& item : run->d.Items())
            if (item.Format().find(c.message) != std::string::npos) {
                found = true;
                EXPECT_EQ(item.loc.line, 1) << c.text;
                EXPECT_EQ(item.loc.column,
                          static_cast<int>(std::string_view(c.text).find(c.at)) + 1)
                    << c.text << "\n"
                    << run->Messages();
            }
        EXPECT_TRUE(found) << c.text << "\n" << run->Messages();
    }
}

}  // namespace
}  // namespace quadrix::testing
