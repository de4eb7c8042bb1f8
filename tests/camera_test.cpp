// OpenSCAD-style camera options (pipeline/camera.h) against analytic pictures of a unit sphere:
// where its outline falls and how large it is, orthographic and perspective, with --viewall and
// --autocenter, through RenderContext as `quadrix render` runs them.
#include "quadrix/pipeline/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/pipeline/render_context.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

struct Disc {
    double cx = 0, cy = 0, r = 0;  // centroid and radius from the area, in pixels
};

Disc Measure(const Frame& f) {
    double n = 0, sx = 0, sy = 0;
    for (int j = 0; j < f.height; ++j)
        for (int i = 0; i < f.width; ++i)
            if (f.Covered(i, j)) {
                n += 1;
                sx += i + 0.5;
                sy += j + 0.5;
            }
    if (n == 0) return {};
    return {sx / n, sy / n, std::sqrt(n / M_PI)};
}

// A unit sphere at (5, 1, 2) seen by `camera` in a 200×160 picture.
Disc Render(CameraRequest camera, int w = 200, int h = 160) {
    RenderContext ctx(1);
    Diagnostics d;
    InputRequest in;
    in.text = "solid sphere ball =at 5 1 2 =r 1;";
    EXPECT_TRUE(ctx.Read(in, d));
    ViewRequest view;
    view.width = w;
    view.height = h;
    std::string error;
    auto v = CameraView(camera, *ctx.Scene().ViewToUse(), error);
    EXPECT_TRUE(v) << error;
    if (camera.autoCenter) {
        ViewRequest fit = view;
        fit.view = *v;
        fit.view->whh = fit.view->whw = std::nullopt;
        EXPECT_TRUE(ctx.Flatten(fit, d));
        v = CentreOnScene(*v, ctx.Flat());
    }
    view.view = v;
    EXPECT_TRUE(ctx.Flatten(view, d));
    Frame frame;
    RenderReport report;
    EXPECT_TRUE(ctx.Render({}, frame, report, d));
    return Measure(frame);
}

TEST(Camera, OrthographicLookAtCentresTheTargetAtTheWindowScale) {
    CameraRequest c;
    ASSERT_EQ(ParseCamera("5,1,-8,5,1,2", c), "");
    ASSERT_EQ(ParseProjection("ortho", c), "");
    c.fovDegrees = 30;
    const Disc d = Render(c);
    // whh = 10 tan 15°: 80 pixels for that many units.
    const double pixelsPerUnit = 80 / (10 * std::tan(15 * M_PI / 180));
    // Radius from the count of covered pixel centres: the count differs from the disc's area by
    // the lattice-point error, here up to ~2 r^(2/3) ≈ 20 pixels, i.e. 0.1 on r (0.2 allowed).
    EXPECT_NEAR(d.cx, 100, 0.05);
    EXPECT_NEAR(d.cy, 80, 0.05);
    EXPECT_NEAR(d.r, pixelsPerUnit, 0.2);
}

TEST(Camera, PerspectiveLookAtSeesTheSphereUnderItsAngularRadius) {
    CameraRequest c;
    ASSERT_EQ(ParseCamera("5,1,-8,5,1,2", c), "");  // perspective by default, fov 22.5°
    const Disc d = Render(c);
    // The outline is the cone of half-angle asin(1/10) around the view axis; on the view plane
    // at distance 10 it is a circle of radius 10 tan(asin(0.1)).
    const double whh = 10 * std::tan(22.5 / 2 * M_PI / 180);
    const double r = 10 * std::tan(std::asin(0.1)) * 80 / whh;
    EXPECT_NEAR(d.cx, 100, 0.05);
    EXPECT_NEAR(d.cy, 80, 0.05);
    EXPECT_NEAR(d.r, r, 0.2);
}

TEST(Camera, ViewallFillsThePictureAndAutocenterCentresIt) {
    CameraRequest c;
    ASSERT_EQ(ParseCamera("0,0,-10,0,0,0", c), "");
    ASSERT_EQ(ParseProjection("ortho", c), "");
    // Looking at the origin, the window (half-height 10 tan 11.25° ≈ 2) misses the sphere.
    const Disc off = Render(c);
    EXPECT_EQ(off.r, 0);
    c.autoCenter = true;
    const Disc centred = Render(c);
    EXPECT_NEAR(centred.cx, 100, 0.05);
    EXPECT_NEAR(centred.cy, 80, 0.05);
    EXPECT_NEAR(centred.r, 80 / (10 * std::tan(11.25 * M_PI / 180)), 0.2);  // the camera's scale
    c.autoCenter = false;
    c.viewAll = true;
    const Disc all = Render(c);
    EXPECT_NEAR(all.cx, 100, 0.05);
    EXPECT_NEAR(all.cy, 80, 0.05);
    EXPECT_NEAR(2 * all.r, 160 * (1 - 2 * 0.02), 1.0);  // the auto-fit's 2 % margins
}

TEST(Camera, BadOptionsAreErrors) {
    CameraRequest c;
    EXPECT_NE(ParseCamera("1,2,3", c), "");
    EXPECT_NE(ParseCamera("1,2,3,4,5,x", c), "");
    EXPECT_NE(ParseCamera("1,2,3,1,2,3", c), "");
    EXPECT_NE(ParseProjection("fisheye", c), "");
    CameraRequest fovOnly;
    fovOnly.fovDegrees = 30;
    std::string error;
    EXPECT_FALSE(CameraView(fovOnly, scene::View{}, error));
    EXPECT_NE(error.find("--fov"), std::string::npos);
    const std::string out = ::testing::TempDir() + "/camera_cli.png";
    const CommandResult bad =
        RunShell(QuadrixBinary() + " render " + SourcePath("examples/tube.uq") + " -o " + out +
                 " --camera 1,2,3");
    EXPECT_EQ(bad.exitCode, 2) << bad.err;
    EXPECT_FALSE(FileExists(out));
    const CommandResult good =
        RunShell(QuadrixBinary() + " render " + SourcePath("examples/tube.uq") + " -o " + out +
                 " --size 64x48 --camera 4,6,-8,0,0,0 --projection ortho --viewall");
    EXPECT_EQ(good.exitCode, 0) << good.err;
    EXPECT_TRUE(FileExists(out));
    std::remove(out.c_str());
}

}  // namespace
}  // namespace quadrix::testing
