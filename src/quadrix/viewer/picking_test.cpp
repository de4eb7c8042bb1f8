#include "quadrix/viewer/picking.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <optional>

#include "quadrix/pipeline/render_context.h"

namespace quadrix::viewer {
namespace {

// A ball of radius 2 about (1 0 0), cut by the plane y = 1: picks on the sphere and on the cap,
// checked against the analytic surfaces.
TEST(ViewerPicking, PointNormalAndNamesOfThePixel) {
    for (const char* view :
         {"view v vrp 1 0 0 dop 0.2 0.3 -1 whh 3;\n", "view v vrp 1 0 0 cop 3 4 -8 whh 3;\n"}) {
        RenderContext ctx(1);
        InputRequest in;
        in.text = std::string(
                      "quadric ball <1 1 1 0 0 0 -1 0 0 -3>;\n"
                      "plane slab <0 1 0 -1>;\n"
                      "body cut <ball slab>;\n") +
                  view;
        in.textName = "pick.uq";
        Diagnostics diags;
        ASSERT_TRUE(ctx.Read(in, diags));
        ViewRequest req;
        req.width = 120;
        req.height = 100;
        ASSERT_TRUE(ctx.Flatten(req, diags));
        Frame frame;
        RenderReport report;
        ASSERT_TRUE(ctx.Render(EngineRequest{}, frame, report, diags));
        int hits = 0, onSphere = 0, onCap = 0;
        for (int y = 0; y < frame.height; y += 7)
            for (int x = 0; x < frame.width; x += 7) {
                const PickResult p = Pick(frame, ctx.Flat(), &ctx.Scene(), x, y);
                if (!p.hit) {
                    EXPECT_EQ(FormatPick(p), fmt::format("pick {} {}: background", x, y));
                    continue;
                }
                ++hits;
                EXPECT_EQ(p.bodyName, "cut");
                EXPECT_EQ(p.where, "pick.uq:3:1");
                const Vec3 c{1, 0, 0};
                if (p.surfaceName == "ball") {
                    ++onSphere;
                    // |p - c| = 2 and the normal is the radial direction (1e-6: the Frame's
                    // depth is a float, a few 1e-6 pixel here, and the device map scales by ~20
                    // pixels a unit; the normal is packed, frame/packed_normal.h).
                    EXPECT_NEAR(Length(p.point - c), 2, 1e-6);
                    EXPECT_NEAR(Length(p.normal - (p.point - c) / 2), 0,
                                1e-6 + PackedNormal::kMaxError);
                } else {
                    ASSERT_EQ(p.surfaceName, "slab");
                    ++onCap;
                    EXPECT_NEAR(p.point.y, 1, 1e-6);
                    EXPECT_LE(Length(p.point - c), 2 + 1e-6);
                    EXPECT_NEAR(Length(p.normal - Vec3{0, 1, 0}), 0, 1e-9);
                }
            }
        EXPECT_GT(onSphere, 10) << view;
        EXPECT_GT(onCap, 3) << view;
        EXPECT_GT(hits, onSphere);
        EXPECT_FALSE(Pick(frame, ctx.Flat(), nullptr, -1, 5).hit);
        EXPECT_FALSE(Pick(frame, ctx.Flat(), nullptr, 5, frame.height).hit);
    }
}

// A freeform surface has no body: its pick names it and gives its own statement's file:line:col
// (FlatFreeform::loc), in the printed line and in the overlay's lines.
TEST(ViewerPicking, FreeformSurfaceGivesItsStatementsLocation) {
    RenderContext ctx(1);
    InputRequest in;
    in.text =
        "quadric ball <1 1 1 0 0 0 2 0 0 3>;\n"  // a ball of radius 1 about (-2 0 0)
        "body blob <ball>;\n"
        "view v vrp 0 0 0 dop 0 0 -1 whh 4;\n"
        "bezier sq 1 1 < 0 -1 0  2 -1 0  0 1 0  2 1 0 > =c 1 0 0;\n";
    in.textName = "ff.uq";
    Diagnostics diags;
    ASSERT_TRUE(ctx.Read(in, diags));
    ViewRequest req;
    req.width = 80;
    req.height = 80;
    ASSERT_TRUE(ctx.Flatten(req, diags));
    ASSERT_EQ(ctx.Flat().freeforms.size(), 1u);
    Frame frame;
    RenderReport report;
    ASSERT_TRUE(ctx.Render(EngineRequest{}, frame, report, diags));
    // The square covers x in [0, 2], the ball x in [-3, -1]: some pixels of each.
    std::optional<PickResult> patch, ball;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            const PickResult p = Pick(frame, ctx.Flat(), &ctx.Scene(), x, y);
            if (p.hit && p.freeform && !patch) patch = p;
            if (p.hit && !p.freeform && !ball) ball = p;
        }
    ASSERT_TRUE(patch && ball);
    EXPECT_EQ(patch->surfaceName, "sq");
    EXPECT_EQ(patch->where, "ff.uq:4:1");
    EXPECT_NEAR(patch->point.z, 0, 1e-6);
    EXPECT_NE(FormatPick(*patch).find("freeform surface sq (ff.uq:4:1)"), std::string::npos)
        << FormatPick(*patch);
    const std::vector<std::string> lines = PickOverlayLines(*patch);
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0], fmt::format("pick {} {}: freeform surface sq", patch->x, patch->y));
    EXPECT_EQ(lines[1], "  at ff.uq:4:1");
    EXPECT_EQ(lines[2].rfind("  point ", 0), 0u);
    EXPECT_EQ(lines[3].rfind("  normal ", 0), 0u);
    EXPECT_EQ(ball->where, "ff.uq:2:1");
    EXPECT_EQ(ball->surfaceName, "ball");
    EXPECT_NE(PickOverlayLines(*ball)[0].find("body blob  half-space ball"), std::string::npos);
    EXPECT_EQ(PickOverlayLines(Pick(frame, ctx.Flat(), &ctx.Scene(), 1, 1)),
              std::vector<std::string>{"pick 1 1: background"});
}

}  // namespace
}  // namespace quadrix::viewer
