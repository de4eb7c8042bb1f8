// Scene-level tests through the whole pipeline (reader → Flattener → raycast → Frame), written in
// the scene language: the trunk's acceptance criteria that need every stage.
#include "quadrix/pipeline/pipeline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "quadrix/io/writers.h"
#include "quadrix/shade/shader.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

PipelineResult Render(const std::string& text, int w, int h, std::string view = {}) {
    PipelineOptions o;
    o.sceneText = text;
    o.width = w;
    o.height = h;
    o.viewName = std::move(view);
    PipelineResult r;
    Diagnostics d;
    bool ok = RunPipeline(o, r, d);
    std::string msgs;
    for (const auto& item : d.Items()) msgs += item.Format() + "\n";
    EXPECT_TRUE(ok) << msgs;
    return r;
}

PipelineResult RenderFile(const std::string& path, int w, int h) {
    PipelineOptions o;
    o.scenePaths = {path};
    o.width = w;
    o.height = h;
    PipelineResult r;
    Diagnostics d;
    bool ok = RunPipeline(o, r, d);
    std::string msgs;
    for (const auto& item : d.Items()) msgs += item.Format() + "\n";
    EXPECT_TRUE(ok) << msgs;
    return r;
}

void ExpectNoNan(const Frame& f) {
    for (std::size_t i = 0; i < f.depth.size(); ++i) {
        ASSERT_FALSE(std::isnan(f.depth[i])) << i;
        ASSERT_TRUE(IsFinite(f.normal[i])) << i;
        if (f.surface[i] != Frame::kNone) {
            ASSERT_TRUE(std::isfinite(f.depth[i]));
            ASSERT_NEAR(Length(f.normal[i]), 1.0, 1e-9);
        }
    }
}

TEST(Pipeline, StackOfBundlesYields18Tubes) {
    PipelineResult r = RenderFile(SourcePath("examples/stack_of_bundles.uq"), 200, 200);
    EXPECT_EQ(r.flat.bodies.size(), 18u);
    EXPECT_EQ(r.flat.solids.size(), 18u);
    std::set<int> seen(r.frame.body.begin(), r.frame.body.end());
    seen.erase(Frame::kNone);
    // From the default view the front tubes hide some of the others, but most are visible.
    EXPECT_GE(seen.size(), 12u);
    ExpectNoNan(r.frame);
}

// Sphere of radius 1 with a window of half-size 1.28 at 256×256: radius 100 px exactly.
TEST(Pipeline, SphereAreaThroughTheLanguage) {
    PipelineResult r = Render(
        "quadric s <1 1 1 0 0 0 0 0 0 -1>; body ball (s);\n"
        "view v dop 0 0 -1 whh 1.28 whw 1.28;\n",
        256, 256);
    double area = static_cast<double>(r.frame.CoveredCount());
    EXPECT_NEAR(area / (M_PI * 100.0 * 100.0), 1.0, 0.005);
    ExpectNoNan(r.frame);
}

// An array whose delta is 360°/n repeated n times, all copies coincident (a sphere on the axis):
// the same image as its first copy alone.
TEST(Pipeline, CoincidentArrayCopiesGiveTheFirstCopysImage) {
    const std::string def =
        "definition ball; quadric s <1 1 1 0 0 0 0 0 -.5 -.75>; plane cut <1 0 0 -.5>;\n"
        "body ball (s cut); enddef;\n";  // a sphere cut by a plane: the cut is not axis-symmetric
    const std::string view =
        "light amb .2; light key .8 .3 .5 -1; view v dop .2 .4 -1 whh 1.5 whw 1.5;\n";
    PipelineResult many = Render(def + "array (ball =rx 0) 7 =rz 360;\n" + view, 160, 160);
    PipelineResult one = Render(def + "instance (ball =rx 0);\n" + view, 160, 160);
    ASSERT_EQ(many.flat.bodies.size(), 7u);
    Image a = Shade(many.frame, many.flat), b = Shade(one.frame, one.flat);
    EXPECT_EQ(a.pixels, b.pixels);
}

TEST(Pipeline, ArrayOfSixRotationsAboutTheAxisIsSymmetric) {
    // A rotation by 60° six times maps the bundle onto itself: the 6th delta is 360°.
    PipelineResult r = RenderFile(SourcePath("examples/bundle_of_tubes.uq"), 120, 120);
    EXPECT_EQ(r.flat.bodies.size(), 6u);
}

// Perspective: equal spheres along the view axis; the measured radius of each shrinks as
// 1/distance from the eye (to within a pixel's worth of silhouette error).
TEST(Pipeline, PerspectiveSpheresShrinkAsOneOverDistance) {
    // Eye at the origin looking along +z (vpn from cop to vrp); spheres of radius 1 at
    // x = -4, 0, 4 … would overlap, so put them side by side at increasing depth instead:
    // centres (3k-4.5, 0, 10+10k)... Here: three spheres, each seen alone in its own render.
    const double distances[] = {10, 20, 40};
    double radiusAt10 = 0;
    for (double d : distances) {
        std::string s = "quadric s <1 1 1 0 0 0 0 0 " + std::to_string(-d) + " " +
                        std::to_string(d * d - 1) + ">; body ball (s);\n" +
                        "view v vrp 0 0 1 cop 0 0 0 whh .25 whw .25;\n";
        PipelineResult r = Render(s, 400, 400);
        ExpectNoNan(r.frame);
        double area = static_cast<double>(r.frame.CoveredCount());
        double radius = std::sqrt(area / M_PI);
        // Exact apparent radius on the view plane at distance 1: tan(asin(1/d)) = 1/sqrt(d²-1);
        // the window is 0.5 wide over 400 px.
        double expected = 400.0 / 0.5 / std::sqrt(d * d - 1);
        EXPECT_NEAR(radius / expected, 1.0, 0.01) << "d=" << d;
        if (d == 10)
            radiusAt10 = radius;
        else
            EXPECT_NEAR(radius * d / (radiusAt10 * 10), 1.0, 0.02) << "d=" << d;
    }
}

TEST(Pipeline, ExamplesRenderWithoutNan) {
    for (const char* ex : {"examples/tube.uq", "examples/bundle_of_tubes.uq",
                           "examples/cylinder_minus_cylinder.uq", "examples/machined_part.uq"}) {
        SCOPED_TRACE(ex);
        PipelineResult r = RenderFile(SourcePath(ex), 160, 120);
        ExpectNoNan(r.frame);
        // Auto-fitted: something substantial is drawn and nothing touches the border rows.
        EXPECT_GT(r.frame.CoveredCount(), 160u * 120u / 10u);
        for (int x = 0; x < r.frame.width; ++x) {
            EXPECT_FALSE(r.frame.Covered(x, 0));
            EXPECT_FALSE(r.frame.Covered(x, r.frame.height - 1));
        }
    }
}

}  // namespace
}  // namespace quadrix::testing
