#include "quadrix/viewer/picking.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

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
                    // |p - c| = 2 and the normal is the radial direction (1e-9: the depth is
                    // exact to rounding; the device map scales by ~20 pixels a unit).
                    EXPECT_NEAR(Length(p.point - c), 2, 1e-9);
                    EXPECT_NEAR(Length(p.normal - (p.point - c) / 2), 0, 1e-6);
                } else {
                    ASSERT_EQ(p.surfaceName, "slab");
                    ++onCap;
                    EXPECT_NEAR(p.point.y, 1, 1e-9);
                    EXPECT_LE(Length(p.point - c), 2 + 1e-9);
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

}  // namespace
}  // namespace quadrix::viewer
