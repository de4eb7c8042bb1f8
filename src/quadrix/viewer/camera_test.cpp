#include "quadrix/viewer/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/flatten/view_setup.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix::viewer {
namespace {

constexpr int kW = 320, kH = 240;

const char* kScene =
    "quadric ball <1 1 1 0 0 0 -1 0 0 -3>;\n"
    "plane slab <0 1 0 -1>;\n"
    "body cut <ball slab>;\n";

RenderContext& Context() {
    static RenderContext* ctx = [] {
        auto* c = new RenderContext(1);
        InputRequest in;
        in.text = kScene;
        Diagnostics diags;
        EXPECT_TRUE(c->Read(in, diags));
        return c;
    }();
    return *ctx;
}

// The projection a camera's view gives through the real Flattener.
Projection Flatten(const Camera& cam) {
    ViewRequest req;
    req.width = kW;
    req.height = kH;
    req.view = cam.ToView();
    Diagnostics diags;
    EXPECT_TRUE(Context().Flatten(req, diags));
    return Context().Flat().projection;
}

Camera SomeCamera() {
    Camera c;
    c.target = {1, 0.5, 0};
    c.halfHeight = 3;
    c.toward = Normalize({0.3, 0.4, -1});
    c.up = Normalize(Vec3{0, 1, 0} - c.toward * c.toward.y);
    return c;
}

TEST(ViewerCamera, PrintedViewReadsBackAsTheSameDoubles) {
    for (bool perspective : {false, true}) {
        Camera c = SomeCamera();
        c.Orbit(37, -11, kH);
        c.Zoom(1.7, 100, 50, kW, kH);
        c.Pan(3, 9, kH);
        c.SetPerspective(perspective);
        const std::string text = std::string(kScene) + FormatViewStatement(c, kW, kH);
        RenderContext ctx(1);
        InputRequest in;
        in.text = text;
        Diagnostics diags;
        ASSERT_TRUE(ctx.Read(in, diags)) << text;
        const scene::View read = ctx.Scene().views.back();
        const scene::View want = c.ToView();
        EXPECT_EQ(read.id, "camera");
        EXPECT_EQ(*read.vrp, *want.vrp);
        EXPECT_EQ(*read.vpn, *want.vpn);
        EXPECT_EQ(*read.vup, *want.vup);
        EXPECT_EQ(*read.whh, *want.whh);
        EXPECT_EQ(read.dop.has_value(), !perspective);
        EXPECT_EQ(read.cop.has_value(), perspective);
        if (perspective)
            EXPECT_EQ(*read.cop, *want.cop);
        else
            EXPECT_EQ(*read.dop, *want.dop);
    }
}

TEST(ViewerCamera, OrbitCarriesTheNearSideWithTheDrag) {
    Camera c;  // toward -z, up +y, right +x
    const Vec3 near = c.target + c.toward;
    c.Orbit(40, 0, kH);
    EXPECT_GT(Dot(near - c.target, c.Right()), 0.1);  // dragged right: moved right
    EXPECT_NEAR(Dot(near - c.target, c.up), 0, 1e-12);
    Camera d;
    d.Orbit(0, 40, kH);
    EXPECT_LT(Dot(near - d.target, d.up), -0.1);  // dragged down: moved down
    // A drag over twice the window's height is a full turn; the frame stays orthonormal.
    Camera e = SomeCamera();
    const Camera before = e;
    for (int i = 0; i < 48; ++i) e.Orbit(2.0 * kH / 48, 0, kH);
    EXPECT_NEAR(Length(e.toward - before.toward), 0, 1e-12);
    EXPECT_NEAR(Length(e.up - before.up), 0, 1e-12);
    EXPECT_NEAR(Dot(e.toward, e.up), 0, 1e-15);
    EXPECT_EQ(e.target, before.target);
    // A half turn about worldUp (a drag over the window's height) looks from the other side.
    Camera f;
    f.Orbit(kH, 0, kH);
    EXPECT_NEAR(Length(f.toward - Vec3{0, 0, 1}), 0, 1e-12);
}

TEST(ViewerCamera, OrbitAboutAPivotKeepsItOnTheScreen) {
    for (bool perspective : {false, true}) {
        Camera c = SomeCamera();
        c.SetPerspective(perspective, 10);
        const Vec3 pivot{2, 0.5, -1};
        c.pivot = pivot;
        const Vec3 before = Flatten(c).deviceFromWorld.MapPoint(pivot);
        c.Orbit(55, -20, kH);
        const Vec3 after = Flatten(c).deviceFromWorld.MapPoint(pivot);
        EXPECT_NEAR(after.x, before.x, 1e-9);
        EXPECT_NEAR(after.y, before.y, 1e-9);
        EXPECT_NE(c.target, SomeCamera().target);
    }
}

// The device point (x, y) on the view plane (device z = 0 there, view_setup.h) in world space.
Vec3 WorldAt(const Projection& p, double x, double y) {
    return p.deviceFromWorld.Inverse().MapPoint({x, y, 0});
}

TEST(ViewerCamera, ZoomKeepsThePointUnderTheCursor) {
    for (bool perspective : {false, true}) {
        Camera c = SomeCamera();
        c.SetPerspective(perspective);
        const double x = 250, y = 60;
        const Vec3 q = WorldAt(Flatten(c), x, y);
        c.Zoom(2.5, x, y, kW, kH);
        const Vec3 back = Flatten(c).deviceFromWorld.MapPoint(q);
        EXPECT_NEAR(back.x, x, 1e-9) << perspective;
        EXPECT_NEAR(back.y, y, 1e-9) << perspective;
        // And the window's scale changed by 0.8^2.5 (a point one pixel away is 1/f pixels away).
        const Vec3 q1 = WorldAt(Flatten(c), x + 1, y);
        c.Zoom(-2.5, x, y, kW, kH);
        const Vec3 back1 = Flatten(c).deviceFromWorld.MapPoint(q1);
        EXPECT_NEAR(back1.x - x, std::pow(0.8, 2.5), 1e-9);
    }
}

TEST(ViewerCamera, PanMovesTheModelWithTheCursor) {
    for (bool perspective : {false, true}) {
        Camera c = SomeCamera();
        c.SetPerspective(perspective);
        const Vec3 q = WorldAt(Flatten(c), 100, 100);
        c.Pan(17, -5, kH);
        const Vec3 back = Flatten(c).deviceFromWorld.MapPoint(q);
        EXPECT_NEAR(back.x, 117, 1e-9);
        EXPECT_NEAR(back.y, 95, 1e-9);
    }
}

TEST(ViewerCamera, StartsFromTheScenesViewExactly) {
    // The default view (dop .3 .3 -1, auto-fit) and a perspective view with a window.
    for (const char* viewText : {"", "view persp vrp 1 0 0 cop 2 3 -9 whh 3;\n"}) {
        RenderContext ctx(1);
        InputRequest in;
        in.text = std::string(kScene) + viewText;
        Diagnostics diags;
        ASSERT_TRUE(ctx.Read(in, diags));
        ViewRequest req;
        req.width = kW;
        req.height = kH;
        ASSERT_TRUE(ctx.Flatten(req, diags));
        const Mat4 want = ctx.Flat().projection.deviceFromWorld.Matrix();
        auto cam = CameraFromView(*ctx.Scene().ViewToUse(), ctx.Flat());
        ASSERT_TRUE(cam);
        req.view = cam->ToView();
        ASSERT_TRUE(ctx.Flatten(req, diags));
        const Mat4 got = ctx.Flat().projection.deviceFromWorld.Matrix();
        // Both maps agree on the scene's points to 1e-9 pixels.
        for (Vec3 p : {Vec3{1, 0, 0}, Vec3{3, 1, 0}, Vec3{-1, -1, 2}, Vec3{1, 2, -1}}) {
            const Vec3 a = want.MapPoint(p), b = got.MapPoint(p);
            EXPECT_NEAR(a.x, b.x, 1e-9) << viewText;
            EXPECT_NEAR(a.y, b.y, 1e-9) << viewText;
        }
    }
}

TEST(ViewerCamera, MovingTheTargetInDepthKeepsTheParallelPicture) {
    Camera c = SomeCamera();
    const Projection before = Flatten(c);
    c.MoveTargetToDepthOf({5, -3, 8});
    EXPECT_NEAR(Dot(Vec3{5, -3, 8} - c.target, c.Right()),
                Dot(Vec3{5, -3, 8} - SomeCamera().target, c.Right()), 1e-12);
    EXPECT_NEAR(Dot(Vec3{5, -3, 8} - c.target, c.toward), 0, 1e-12);
    const Projection after = Flatten(c);
    for (Vec3 p : {Vec3{1, 0, 0}, Vec3{3, 1, 0}, Vec3{-1, -1, 2}}) {
        const Vec3 a = before.deviceFromWorld.MapPoint(p), b = after.deviceFromWorld.MapPoint(p);
        EXPECT_NEAR(a.x, b.x, 1e-9);
        EXPECT_NEAR(a.y, b.y, 1e-9);
    }
}

TEST(ViewerCamera, StandardViewsLookAlongTheAxes) {
    const SceneSphere s{{1, 2, 3}, 2};
    struct Case {
        StandardView view;
        Vec3 vpn, right, up;
    };
    const Case cases[] = {
        {StandardView::kFront, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}},
        {StandardView::kBack, {0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
        {StandardView::kLeft, {1, 0, 0}, {0, 0, -1}, {0, 1, 0}},
        {StandardView::kRight, {-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {StandardView::kTop, {0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {StandardView::kBottom, {0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
    };
    for (const Case& k : cases) {
        Camera c;
        c.SetStandardView(k.view, s);
        Diagnostics diags;
        auto vs = ResolveView(c.ToView(), diags);
        ASSERT_TRUE(vs);
        EXPECT_NEAR(Length(vs->n - k.vpn), 0, 1e-15) << int(k.view);
        EXPECT_NEAR(Length(vs->u - k.right), 0, 1e-15) << int(k.view);
        EXPECT_NEAR(Length(vs->v - k.up), 0, 1e-15) << int(k.view);
        EXPECT_EQ(c.target, s.centre);
    }
}

TEST(ViewerCamera, FitAllContainsTheSphere) {
    Camera c = SomeCamera();
    const SceneSphere s{{1, 0, 0}, 2};
    for (bool perspective : {false, true}) {
        c.SetPerspective(perspective);
        c.FitAll(s, kW, kH);
        const Projection p = Flatten(c);
        // Points of the sphere in every direction land inside the image.
        for (int i = 0; i < 200; ++i) {
            const double a = i * 2.399963, z = 1 - 2 * (i + 0.5) / 200, r = std::sqrt(1 - z * z);
            const Vec3 q = s.centre + Vec3{r * std::cos(a), r * std::sin(a), z} * s.radius;
            const Vec3 d = p.deviceFromWorld.MapPoint(q);
            EXPECT_GT(d.x, 0);
            EXPECT_LT(d.x, kW);
            EXPECT_GT(d.y, 0);
            EXPECT_LT(d.y, kH);
        }
    }
}

TEST(ViewerCamera, BoundingSphereContainsTheBoundedSolids) {
    RenderContext ctx(1);
    InputRequest in;
    in.text = kScene;
    Diagnostics diags;
    ASSERT_TRUE(ctx.Read(in, diags));
    scene::View along;
    along.dop = Vec3{0, 0, -1};
    along.vpn = Vec3{0, 0, 1};
    ViewRequest req;
    req.width = kW;
    req.height = kH;
    req.view = along;
    ASSERT_TRUE(ctx.Flatten(req, diags));
    auto s = BoundingSphere(ctx.Flat());
    ASSERT_TRUE(s);
    // The half-ball of radius 2 about (1 0 0) below y = 1: its box is [-1 3]×[-2 1]×[-2 2].
    for (Vec3 corner : {Vec3{-1, -2, -2}, Vec3{3, 1, 2}, Vec3{3, -2, -2}})
        EXPECT_LE(Length(corner - s->centre), s->radius * (1 + 1e-9));
    EXPECT_LT(s->radius, 4);  // conservative, but not wildly
}

}  // namespace
}  // namespace quadrix::viewer
