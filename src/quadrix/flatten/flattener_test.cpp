// Tests of the Flattener (flattener.h, view_setup.h): view orientation and defaults, the window
// fit, perspective, clipping planes, culling and user errors. Scenes are built programmatically.
#include "quadrix/flatten/flattener.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstring>
#include <functional>

#include "quadrix/flatten/bounds.h"
#include "quadrix/flatten/flatten_test_util.h"
#include "quadrix/lang/reader.h"
#include "quadrix/util/parallel.h"

namespace quadrix {
namespace {

using namespace flatten_test;

struct Result {
    std::optional<FlatScene> flat;
    Diagnostics diags;
    std::string Messages() const {
        std::string s;
        for (const Diagnostic& d : diags.Items()) s += d.Format(false) + "\n";
        return s;
    }
};

Result RunFlatten(const scene::Scene& s, int w = 400, int h = 400, std::string viewName = {}) {
    Result r;
    FlattenOptions o;
    o.width = w;
    o.height = h;
    o.viewName = std::move(viewName);
    r.flat = Flatten(s, o, r.diags);
    return r;
}

scene::View MakeView(const std::string& id) {
    scene::View v;
    v.id = id;
    v.loc = Loc(9, 1);
    return v;
}

scene::Scene OneSphere(const Vec3& c = {0, 0, 0}, double r = 1) {
    scene::Scene s;
    int q = AddSphere(s.top, "s", c, r);
    AddBody(s.top, "ball", {q}, std::nullopt, 1);
    return s;
}

// The quadric of a body's first literal, normalised so that its x² coefficient is 1: for a
// sphere imaged by a similarity it reads (x-cx)² + (y-cy)² + (z-cz)² - R² in device pixels.
double NormalisedValue(const FlatScene& f, int body, const Vec3& p) {
    const Quadric& q = f.halfSpaces[f.bodies[body].literals[0].halfSpace].quadric;
    return q.Evaluate(p) / q.A();
}

TEST(FlattenView, DefaultViewOrientation) {
    Result r = RunFlatten(OneSphere());
    ASSERT_TRUE(r.flat) << r.Messages();
    const Transform& m = r.flat->projection.deviceFromWorld;
    Vec3 o = m.MapPoint({0, 0, 0}), x = m.MapPoint({1, 0, 0}), y = m.MapPoint({0, 1, 0}),
         z = m.MapPoint({0, 0, 1});
    EXPECT_GT(x.x - o.x, 0);  // world +x to the right
    EXPECT_LT(y.y - o.y, 0);  // world +y up (smaller rows)
    EXPECT_GT(z.z - o.z, 0);  // world +z away: the eye is on the -z side
    EXPECT_FALSE(r.flat->projection.perspective);
    Vec3 toward = r.flat->projection.towardViewer;
    Vec3 expected = Normalize({0.3, 0.3, -1});
    EXPECT_NEAR(Length(toward - expected), 0, 1e-15);
    EXPECT_EQ(r.flat->viewName, "default");
    // A scene without lights gets the default rig (scene/light_rig.h), which follows the view:
    // its headlight points toward the viewer.
    ASSERT_EQ(r.flat->lights.size(), 3u);
    EXPECT_TRUE(r.flat->lights[1].isRig);
    EXPECT_NEAR(Length(r.flat->lights[1].direction - expected), 0, 1e-15);
}

TEST(FlattenView, DopZeroOneOneLooksDownFromAbove) {
    scene::Scene s = OneSphere();
    scene::View v = MakeView("top_down");
    v.dop = Vec3{0, 1, 1};
    s.views.push_back(v);
    Result r = RunFlatten(s);
    ASSERT_TRUE(r.flat) << r.Messages();
    const Transform& m = r.flat->projection.deviceFromWorld;
    // A point above the scene is nearer the viewer than one below.
    EXPECT_LT(m.MapPoint({0, 1, 0}).z, m.MapPoint({0, -1, 0}).z);
    EXPECT_NEAR(Length(r.flat->projection.towardViewer - Normalize({0, 1, 1})), 0, 1e-15);
    // Rays are along +z in device space: world points along -dop keep x and y.
    Vec3 a = m.MapPoint({0.2, 0.3, 0.4}), b = m.MapPoint(Vec3{0.2, 0.3, 0.4} - Vec3{0, 1, 1});
    EXPECT_NEAR(a.x, b.x, 1e-9);
    EXPECT_NEAR(a.y, b.y, 1e-9);
    EXPECT_GT(b.z, a.z);
}

TEST(FlattenView, ObliqueParallelProjectionShearsRaysOntoZ) {
    scene::Scene s = OneSphere();
    scene::View v = MakeView("oblique");
    v.vpn = Vec3{0, 0, 1};
    v.dop = Vec3{0.5, -0.25, -1};  // toward the viewer, not along -vpn
    v.whh = v.whw = 2;
    s.views.push_back(v);
    Result r = RunFlatten(s);
    ASSERT_TRUE(r.flat) << r.Messages();
    const Transform& m = r.flat->projection.deviceFromWorld;
    Vec3 p{0.3, -0.2, 0.1};
    Vec3 a = m.MapPoint(p), b = m.MapPoint(p - Vec3{0.5, -0.25, -1} * 3);
    EXPECT_NEAR(a.x, b.x, 1e-9);
    EXPECT_NEAR(a.y, b.y, 1e-9);
    EXPECT_GT(b.z, a.z);
    // Points of the view plane (z = 0 through vrp) are not sheared: exact window scale.
    Vec3 c = m.MapPoint({2, 0, 0});
    EXPECT_NEAR(c.x, 400, 1e-9);
    EXPECT_NEAR(c.y, 200, 1e-9);
}

TEST(FlattenFit, ParallelAutoFitCentresASphereWithTheMargin) {
    scene::Scene s = OneSphere({3, -2, 5}, 1);
    scene::View v = MakeView("front");
    v.dop = Vec3{0, 0, -1};
    s.views.push_back(v);
    for (auto [w, h] : {std::pair{400, 400}, std::pair{400, 200}}) {
        Result r = RunFlatten(s, w, h);
        ASSERT_TRUE(r.flat) << r.Messages();
        // Default margin 2% per side: the diameter fills 96% of the smaller side.
        double radius = 0.96 * std::min(w, h) / 2;
        const Box3& b = r.flat->solids[0].bounds;
        // Analytic sphere bounds: exact up to a 1e-10 relative pad.
        EXPECT_NEAR(b.lo.x, w / 2.0 - radius, 1e-7);
        EXPECT_NEAR(b.hi.x, w / 2.0 + radius, 1e-7);
        EXPECT_NEAR(b.lo.y, h / 2.0 - radius, 1e-7);
        EXPECT_NEAR(b.hi.y, h / 2.0 + radius, 1e-7);
        // The device quadric is a sphere of that radius around the image centre (the parallel
        // device map is a similarity); its centre's depth is k·5.
        double k = radius, zc = 5 * k;
        EXPECT_NEAR(NormalisedValue(*r.flat, 0, {w / 2.0, h / 2.0, zc}), -radius * radius, 1e-6);
        EXPECT_NEAR(NormalisedValue(*r.flat, 0, {w / 2.0 + radius, h / 2.0, zc}), 0, 1e-6);
        EXPECT_NEAR(NormalisedValue(*r.flat, 0, {w / 2.0, h / 2.0 - radius, zc}), 0, 1e-6);
        EXPECT_GT(r.flat->depthTolerance, 0);
        EXPECT_LT(r.flat->depthTolerance, 1e-5);
    }
}

TEST(FlattenFit, WindowGivesTheExactPixelScale) {
    scene::Scene s = OneSphere();
    scene::View v = MakeView("window");
    v.dop = Vec3{0, 0, -1};
    v.whh = v.whw = 2;
    s.views.push_back(v);
    Result r = RunFlatten(s);
    ASSERT_TRUE(r.flat) << r.Messages();
    // 400 px over 4 units: the unit sphere has radius 100 px.
    EXPECT_NEAR(NormalisedValue(*r.flat, 0, {300, 200, 0}), 0, 1e-9);
    EXPECT_NEAR(NormalisedValue(*r.flat, 0, {200, 100, 0}), 0, 1e-9);
    EXPECT_NEAR(NormalisedValue(*r.flat, 0, {200, 200, 100}), 0, 1e-9);
    EXPECT_NEAR(r.flat->solids[0].bounds.lo.x, 100, 1e-7);
    EXPECT_NEAR(r.flat->solids[0].bounds.hi.y, 300, 1e-7);
    // A window on one axis only: that axis fixes the scale when it is the smaller one.
    s.views.back().whw.reset();
    s.views.back().whh = 4;  // 400 px over 8 units: 50 px per unit (the fit would give 192)
    Result r2 = RunFlatten(s);
    ASSERT_TRUE(r2.flat) << r2.Messages();
    EXPECT_NEAR(NormalisedValue(*r2.flat, 0, {250, 200, 0}), 0, 1e-9);
}

TEST(FlattenPerspective, SpheresShrinkAsOneOverDistanceAndBehindTheEyeIsRemoved) {
    scene::Scene s;
    const double distances[] = {10, 20, 40};
    for (double d : distances) {
        int q = AddSphere(s.top, "s", {0, 0, d}, 1);
        AddBody(s.top, "ball", {q});
    }
    int behind = AddSphere(s.top, "back", {0, 0, -10}, 1);
    AddBody(s.top, "behind", {behind});
    scene::View v = MakeView("persp");
    v.vrp = Vec3{0, 0, 1};
    v.cop = Vec3{0, 0, 0};
    v.whh = v.whw = 0.25;
    s.views.push_back(v);
    Result r = RunFlatten(s);
    ASSERT_TRUE(r.flat) << r.Messages();
    const FlatScene& f = *r.flat;
    EXPECT_TRUE(f.projection.perspective);
    ASSERT_EQ(f.solids.size(), 3u);  // the sphere behind the eye is culled
    // Near and far clip planes, shared by every body.
    int clips = 0;
    for (const FlatHalfSpace& h : f.halfSpaces) clips += h.isClip && h.transparent;
    EXPECT_EQ(clips, 2);
    const double k = 400 / 0.5;  // pixels per unit on the view plane (d = 1)
    double previousDepth = -HUGE_VAL;
    for (int i = 0; i < 3; ++i) {
        double d = distances[i];
        ASSERT_EQ(f.bodies[i].literals.size(), 3u);
        // The silhouette: the tangent cone of half-angle asin(1/d) meets the view plane in a
        // circle of radius 1/sqrt(d²-1). The device quadric is an ellipsoid (positive definite
        // quadratic part) whose box is exact, so the bounds give the radius to rounding.
        const FlatHalfSpace& q = f.halfSpaces[f.bodies[i].literals[0].halfSpace];
        Box3 box = LiteralBox(q, false);
        ASSERT_TRUE(box.Finite());
        double expected = k / std::sqrt(d * d - 1);
        EXPECT_NEAR(0.5 * (box.hi.x - box.lo.x), expected, 1e-6 * expected);
        EXPECT_NEAR(0.5 * (box.hi.y - box.lo.y), expected, 1e-6 * expected);
        EXPECT_NEAR(0.5 * (box.hi.x + box.lo.x), 200, 1e-6);
        // The centre projects to the image centre; depth grows with distance.
        Vec3 c = f.projection.deviceFromWorld.MapPoint({0, 0, d});
        EXPECT_NEAR(c.x, 200, 1e-9);
        EXPECT_GT(c.z, previousDepth);
        previousDepth = c.z;
        EXPECT_LT(q.quadric.Evaluate(c), 0);
    }
    // Radii scale as 1/sqrt(d²-1) ≈ 1/d.
    // A world point projects centrally: x = 200 + k·x/z, y = 200 - k·y/z.
    Vec3 p = f.projection.deviceFromWorld.MapPoint({0.5, 0.3, 10});
    EXPECT_NEAR(p.x, 200 + k * 0.05, 1e-9);
    EXPECT_NEAR(p.y, 200 - k * 0.03, 1e-9);
    // Depth: 0 on the view plane, k·d (= 800) at infinity.
    EXPECT_NEAR(f.projection.deviceFromWorld.MapPoint({0, 0, 1}).z, 0, 1e-9);
    EXPECT_NEAR(f.projection.deviceFromWorld.MapPoint({0, 0, 1e12}).z, k, 1e-6);
}

TEST(FlattenPerspective, AutoFitAndTheFarPlaneExcludesPointsBehindTheEye) {
    scene::Scene s = OneSphere({0, 0, 10}, 1);
    scene::View v = MakeView("persp");
    v.cop = Vec3{0, 0, 0};
    v.vrp = Vec3{0, 0, 5};
    s.views.push_back(v);
    Result r = RunFlatten(s);
    ASSERT_TRUE(r.flat) << r.Messages();
    const FlatScene& f = *r.flat;
    // Auto-fitted: the silhouette fills 96% of the image.
    EXPECT_NEAR(f.solids[0].bounds.lo.x, 8, 1e-5);
    EXPECT_NEAR(f.solids[0].bounds.hi.x, 392, 1e-5);
    // A point behind the eye maps beyond the far plane; one in front inside it.
    auto insideClips = [&](const Vec3& world) {
        Vec3 p = f.projection.deviceFromWorld.MapPoint(world);
        for (const FlatHalfSpace& h : f.halfSpaces)
            if (h.isClip && h.Evaluate(p) > 0) return false;
        return true;
    };
    EXPECT_TRUE(insideClips({0.3, 0.1, 3}));
    EXPECT_TRUE(insideClips({0.3, 0.1, 1e6}));
    EXPECT_FALSE(insideClips({0.3, 0.1, -3}));
    EXPECT_FALSE(insideClips({0.3, 0.1, -1e6}));
    EXPECT_FALSE(insideClips({0.3, 0.1, 1e-5}));  // nearer than 1e-4 d (d = 5)
}

TEST(FlattenClip, FbpAddsTwoTransparentClipPlanesToEveryBody) {
    scene::Scene s = OneSphere();
    int q = AddSphere(s.top, "t", {0.5, 0, 0}, 1);
    AddBody(s.top, "other", {q});
    scene::View v = MakeView("clipped");
    v.dop = Vec3{0, 0, -1};
    v.whh = v.whw = 2;
    v.front = 0.5;  // given in reverse order: front = min, back = max
    v.back = -0.25;
    s.views.push_back(v);
    Result r = RunFlatten(s);
    ASSERT_TRUE(r.flat) << r.Messages();
    const FlatScene& f = *r.flat;
    std::vector<int> clips;
    for (std::size_t i = 0; i < f.halfSpaces.size(); ++i)
        if (f.halfSpaces[i].isClip) clips.push_back(int(i));
    ASSERT_EQ(clips.size(), 2u);
    for (int c : clips) EXPECT_TRUE(f.halfSpaces[c].transparent);
    for (const FlatBody& b : f.bodies) {
        ASSERT_EQ(b.literals.size(), 3u);
        EXPECT_EQ(b.literals[1].halfSpace, clips[0]);
        EXPECT_EQ(b.literals[2].halfSpace, clips[1]);
    }
    auto inside = [&](double worldZ) {
        Vec3 p = f.projection.deviceFromWorld.MapPoint({0, 0, worldZ});
        for (int c : clips)
            if (f.halfSpaces[c].Evaluate(p) > 0) return false;
        return true;
    };
    EXPECT_TRUE(inside(0));
    EXPECT_TRUE(inside(0.49));
    EXPECT_FALSE(inside(0.51));
    EXPECT_FALSE(inside(-0.26));
    // Bodies are bounded by the clip planes in depth: k = 100 px per unit.
    EXPECT_NEAR(f.solids[0].bounds.lo.z, -25, 1e-6);
    EXPECT_NEAR(f.solids[0].bounds.hi.z, 50, 1e-6);
}

TEST(FlattenClip, PerspectiveFbpNearAndBackPlanes) {
    scene::Scene s;
    for (double z : {3.0, 7.0, 20.0}) {
        int q = AddSphere(s.top, "s", {0, 0, z}, 0.5);
        AddBody(s.top, "ball", {q});
    }
    scene::View v = MakeView("persp");
    v.vrp = Vec3{0, 0, 1};
    v.cop = Vec3{0, 0, 0};
    v.whh = v.whw = 1;
    v.front = 4;  // eye distances 5 and 10
    v.back = 9;
    s.views.push_back(v);
    Result r = RunFlatten(s);
    ASSERT_TRUE(r.flat) << r.Messages();
    // The spheres at 3 and 20 lie entirely outside [5, 10]: culled.
    ASSERT_EQ(r.flat->solids.size(), 1u);
    EXPECT_EQ(r.flat->bodies.size(), 1u);
    Vec3 c = r.flat->projection.deviceFromWorld.MapPoint({0, 0, 7});
    EXPECT_LT(r.flat->halfSpaces[r.flat->bodies[0].literals[0].halfSpace].Evaluate(c), 0);
}

TEST(FlattenErrors, UnboundedBodyWithoutWindowNamesTheBody) {
    scene::Scene s;
    int p = AddPlane(s.top, "p", {0, 1, 0, 0});
    AddBody(s.top, "half", {p}, std::nullopt, 2);
    Result r = RunFlatten(s);
    EXPECT_FALSE(r.flat);
    ASSERT_EQ(r.diags.ErrorCount(), 1);
    const Diagnostic& d = r.diags.Items()[0];
    EXPECT_EQ(d.loc.line, 2);
    EXPECT_NE(d.message.find("body 'half' at test.uq:2:1 is unbounded in the view"),
              std::string::npos)
        << d.message;
    // With a window it is fine; its solid covers the whole image in x and y.
    scene::View v = MakeView("window");
    v.whh = v.whw = 3;
    s.views.push_back(v);
    Result ok = RunFlatten(s);
    ASSERT_TRUE(ok.flat) << ok.Messages();
    const Box3& b = ok.flat->solids[0].bounds;
    EXPECT_EQ(b.lo.x, 0);
    EXPECT_EQ(b.hi.x, 400);
}

TEST(FlattenErrors, UnboundedCsgSolidIsNamedAsSuch) {
    // A union of half-spaces is unbounded and nothing else is there to fit: an error naming it.
    scene::Scene s;
    int p = AddPlane(s.top, "p", {0, 1, 0, 0});
    int q = AddPlane(s.top, "q", {1, 0, 0, 0});
    AddBody(s.top, "half", {p});
    AddBody(s.top, "other", {q});
    CsgBuilder b;
    int n = b.Op(scene::CsgOp::kUnion, b.Body(0), b.Body(1));
    AddCsg(s.top, "u", b, n);
    s.top.csgs.back().loc = Loc(4, 2);
    Result r = RunFlatten(s);
    EXPECT_FALSE(r.flat);
    EXPECT_NE(r.Messages().find("csg solid 'u' at test.uq:4:2 is unbounded"), std::string::npos)
        << r.Messages();
}

TEST(FlattenFit, UnionWithAHalfSpaceIsFittedToItsBoundedMember) {
    // window_fit.h: a union's fit box is the hull of its bounded members, so the sphere of
    // sphere ∪ half-space is framed as if alone (384 px wide: 2 % margins of 400) and the
    // half-space is clipped to that window; a difference with a half-space is bounded anyway.
    scene::Scene s = OneSphere();
    int p = AddPlane(s.top, "p", {0, 1, 0, 0});
    AddBody(s.top, "half", {p});
    CsgBuilder b;
    int n = b.Op(scene::CsgOp::kUnion, b.Body(0), b.Body(1));
    AddCsg(s.top, "u", b, n);
    Result r = RunFlatten(s);
    ASSERT_TRUE(r.flat) << r.Messages();
    Result alone = RunFlatten(OneSphere());
    ASSERT_TRUE(alone.flat) << alone.Messages();
    for (const Vec3& w : {Vec3{0, 0, 0}, Vec3{1, -2, 3}})
        EXPECT_NEAR(Length(r.flat->projection.deviceFromWorld.MapPoint(w) -
                           alone.flat->projection.deviceFromWorld.MapPoint(w)),
                    0, 1e-9);
    EXPECT_EQ(r.flat->solids[0].bounds.lo.x, 0);  // the union reaches past the window
    EXPECT_EQ(r.flat->solids[0].bounds.hi.x, 400);
    s.top.csgs.back().nodes.back().op = scene::CsgOp::kDifference;
    Result ok = RunFlatten(s);
    ASSERT_TRUE(ok.flat) << ok.Messages();
    EXPECT_NEAR(ok.flat->solids[0].bounds.hi.x - ok.flat->solids[0].bounds.lo.x, 384, 1e-6);
}

TEST(FlattenErrors, UnboundedOnlyInDepthIsFine) {
    // An uncapped cylinder along the viewing direction: bounded on screen.
    scene::Scene s;
    int q = AddQuadric(s.top, "c", {1, 1, 0, 0, 0, 0, 0, 0, 0, -1});
    AddBody(s.top, "tube", {q});
    scene::View v = MakeView("along");
    v.dop = Vec3{0, 0, -1};
    s.views.push_back(v);
    Result r = RunFlatten(s);
    ASSERT_TRUE(r.flat) << r.Messages();
    const Box3& b = r.flat->solids[0].bounds;
    EXPECT_NEAR(b.lo.x, 8, 1e-6);
    EXPECT_NEAR(b.hi.x, 392, 1e-6);
    EXPECT_EQ(b.lo.z, -HUGE_VAL);
    EXPECT_EQ(b.hi.z, HUGE_VAL);
}

TEST(FlattenErrors, DegenerateViewsAreErrorsAtTheViewsPosition) {
    struct Case {
        const char* what;
        std::function<void(scene::View&)> set;
        const char* expect;
    };
    const Case cases[] = {
        {"vup parallel to vpn",
         [](scene::View& v) {
             v.vpn = Vec3{0, 1, 0};
             v.vup = Vec3{0, 2, 0};
         },
         "parallel"},
        {"zero dop",
         [](scene::View& v) {
             v.dop = Vec3{0, 0, 0};
         },
         "zero vector"},
        {"zero vup",
         [](scene::View& v) {
             v.vup = Vec3{0, 0, 0};
         },
         "zero vector"},
        {"eye behind the view plane",
         [](scene::View& v) {
             v.vrp = Vec3{0, 0, 1};
             v.cop = Vec3{0, 0, 2};
             v.vpn = Vec3{0, 0, 1};
         },
         "in front of the view plane"},
        {"cop on vrp",
         [](scene::View& v) {
             v.cop = Vec3{0, 0, 0};
         },
         "coincides with vrp"},
        {"dop in the view plane",
         [](scene::View& v) {
             v.vpn = Vec3{0, 0, 1};
             v.dop = Vec3{1, 0, 0};
         },
         "parallel"},
        {"dop away from the viewer",
         [](scene::View& v) {
             v.vpn = Vec3{0, 0, 1};
             v.dop = Vec3{0, 0, 1};
         },
         "away from the viewer"},
        {"negative window", [](scene::View& v) { v.whh = -1.0; }, "positive"},
        {"nan vrp",
         [](scene::View& v) {
             v.vrp = Vec3{NAN, 0, 0};
         },
         "not finite"},
        {"fbp behind the eye",
         [](scene::View& v) {
             v.vrp = Vec3{0, 0, 1};
             v.cop = Vec3{0, 0, 0};
             v.front = -5;
             v.back = -2;
         },
         "nothing in front of the eye"},
    };
    for (const Case& c : cases) {
        scene::Scene s = OneSphere({0, 0, 5});
        scene::View v = MakeView("bad");
        c.set(v);
        s.views.push_back(v);
        Result r = RunFlatten(s);
        EXPECT_FALSE(r.flat) << c.what;
        ASSERT_GE(r.diags.ErrorCount(), 1) << c.what;
        EXPECT_EQ(r.diags.Items()[0].loc.line, 9) << c.what;
        EXPECT_NE(r.diags.Items()[0].message.find(c.expect), std::string::npos)
            << c.what << ": " << r.diags.Items()[0].message;
    }
}

TEST(FlattenErrors, EmptySceneUnknownViewAndBadSizes) {
    scene::Scene empty;
    Result r = RunFlatten(empty);
    EXPECT_FALSE(r.flat);
    ASSERT_EQ(r.diags.ErrorCount(), 1);
    EXPECT_NE(r.diags.Items()[0].message.find("nothing to draw"), std::string::npos);
    // Only operands: nothing drawn either.
    scene::Scene ops = OneSphere();
    ops.top.bodies[0].usedAsOperand = true;
    EXPECT_FALSE(RunFlatten(ops).flat);
    Result unknown = RunFlatten(OneSphere(), 100, 100, "nope");
    EXPECT_FALSE(unknown.flat);
    EXPECT_NE(unknown.Messages().find("unknown view 'nope'"), std::string::npos);
    EXPECT_FALSE(RunFlatten(OneSphere(), 0, 100).flat);
}

TEST(FlattenErrors, ExplosionGuardThroughFlatten) {
    scene::Scene s;
    scene::Scope a;
    int q = AddSphere(a, "s", {0, 0, 0}, 1);
    AddBody(a, "b", {q});
    s.definitions.push_back(a);
    scene::Scope b;
    AddInstance(b, "row_array", 0, Transform(), 2000, Transform::Translate({1, 0, 0}));
    s.definitions.push_back(b);
    AddInstance(s.top, "grid_array", 1, Transform(), 2000, Transform::Translate({0, 1, 0}));
    Result r = RunFlatten(s);
    EXPECT_FALSE(r.flat);
    EXPECT_NE(r.Messages().find("4e+06 bodies"), std::string::npos) << r.Messages();
}

TEST(FlattenNormals, WorldNormalOfASphereFacesTheViewer) {
    // Through the shared FlatScene::WorldNormal: the device gradient pulled back to world space
    // is the sphere's outward normal at the visible point, for parallel and perspective views.
    for (bool perspective : {false, true}) {
        scene::Scene s = OneSphere({1, 2, 3}, 1);
        scene::View v = MakeView("v");
        if (perspective) {
            v.cop = Vec3{1, 2, -7};
            v.vrp = Vec3{1, 2, -6};
        } else {
            v.dop = Vec3{0.2, 0.1, -1};
        }
        s.views.push_back(v);
        Result r = RunFlatten(s);
        ASSERT_TRUE(r.flat) << r.Messages();
        const FlatScene& f = *r.flat;
        Vec3 toward = perspective ? Vec3{0, 0, -1} : Normalize({0.2, 0.1, -1});
        Vec3 world = Vec3{1, 2, 3} + toward;  // the point facing the viewer (along the view)
        if (perspective) world = Vec3{1, 2, 2};
        Vec3 dev = f.projection.deviceFromWorld.MapPoint(world);
        int hs = f.bodies[0].literals[0].halfSpace;
        EXPECT_NEAR(f.halfSpaces[hs].Evaluate(dev) / f.halfSpaces[hs].quadric.MaxAbs(), 0, 1e-12);
        Vec3 n = f.WorldNormal(hs, dev);
        Vec3 expected = Normalize(world - Vec3{1, 2, 3});
        EXPECT_NEAR(Length(n - expected), 0, 1e-9) << "perspective " << perspective;
    }
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// ∪(ballᵢ ∩ drill): the drill is one FlatBody per operand over the same half-spaces, and its box
// is computed once and shared (flattener.cpp, FirstWithSameLiterals). The same solid written
// with a separate copy of the drill's half-spaces per operand computes every box on its own: the
// two flat scenes must agree bit for bit, and the drill's boxes must bound it (a cylinder along x
// of radius 1, cut at x = ±3, seen along z).
TEST(FlattenBounds, BodiesSharingLiteralsShareExactlyTheBoxesComputedAlone) {
    auto sceneText = [](bool copies) {
        std::string t;
        for (int i = 0; i < 6; ++i) {
            t += fmt::format("quadric q{} <1 1 1 0 0 0 {} 0 0 {}>;\nbody s{} (q{});\n", i,
                             -(i - 2.5), (i - 2.5) * (i - 2.5) - 0.81, i, i);
            const std::string k = copies ? std::to_string(i) : "";
            if (copies || i == 0)
                t += fmt::format(
                    "quadric cyl{0} <0 1 1 0 0 0 0 0 0 -1>;\nplane cl{0} <-1 0 0 -3>;\n"
                    "plane cr{0} <1 0 0 -3>;\nbody drill{0} (cyl{0} cl{0} cr{0});\n",
                    k);
        }
        t += "csg u (";
        for (int i = 0; i < 6; ++i)
            // (An intersection: differences subtracting the same body are grouped into one,
            // hierarchy.h, and would leave one drill.)
            t += fmt::format("{}(s{} & drill{})", i ? " | " : "", i,
                             copies ? std::to_string(i) : "");
        t += ");\nview v dop 0 0 -1;\n";
        scene::Scene s;
        Diagnostics d;
        lang::Reader reader(s, d);
        EXPECT_TRUE(reader.ReadText(t, "shared.uq"));
        return s;
    };
    Result shared = RunFlatten(sceneText(false), 300, 200);
    Result alone = RunFlatten(sceneText(true), 300, 200);
    ASSERT_TRUE(shared.flat && alone.flat) << shared.Messages() << alone.Messages();
    ASSERT_EQ(shared.flat->bodies.size(), 12u);
    ASSERT_EQ(alone.flat->bodies.size(), 12u);
    for (std::size_t i = 0; i < 12; ++i) {
        const Box3& a = shared.flat->bodies[i].bounds;
        const Box3& b = alone.flat->bodies[i].bounds;
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(a.lo[k], b.lo[k]) << "body " << i;
            EXPECT_EQ(a.hi[k], b.hi[k]) << "body " << i;
        }
    }
    for (std::size_t n = 0; n < shared.flat->nodes.size(); ++n) {
        EXPECT_EQ(shared.flat->nodes[n].bounds.lo[0], alone.flat->nodes[n].bounds.lo[0]);
        EXPECT_EQ(shared.flat->nodes[n].bounds.hi[1], alone.flat->nodes[n].bounds.hi[1]);
    }
    // The auto-fit window too (its second look, RefineFit, bounds each shared drill once).
    for (const Vec3& p : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
        const Vec3 a = shared.flat->projection.deviceFromWorld.MapPoint(p);
        const Vec3 b = alone.flat->projection.deviceFromWorld.MapPoint(p);
        EXPECT_EQ(a.x, b.x);
        EXPECT_EQ(a.y, b.y);
        EXPECT_EQ(a.z, b.z);
    }
    // The drill's box is finite and wider in x than in y: it was bounded, not left unbounded.
    const Box3& drill = shared.flat->bodies[1].bounds;
    EXPECT_GT(drill.hi[0] - drill.lo[0], 2 * (drill.hi[1] - drill.lo[1]));
    EXPECT_TRUE(std::isfinite(drill.lo[0]) && std::isfinite(drill.hi[1]));
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {
using namespace flatten_test;

// Bounds reused by translation (flattener.cpp): 60 oblique capped cylinders, three rotations
// times twenty translations, placed in the top scope with their coefficients transformed (as
// the BRL-CAD importer does), and an array of translated copies of one more. Parallel views,
// auto-fitted and with a window: with reuse the window (deviceFromWorld) is bit for bit the one
// of the direct bounds, the same solids are kept, and every body's box is within 2e-5 × (size
// + |coordinate|) of its direct box and contains the body's points sampled on its surface.
TEST(FlattenBounds, BoxesReusedByTranslationKeepTheWindowAndHoldTheBodies) {
    scene::Scene s;
    const double r = 3, h = 20;
    const Quadric cyl = Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -r * r});
    const Plane top{0, 0, 1, -h}, bottom{0, 0, -1, 0};
    std::vector<Transform> placements;
    for (int rot = 0; rot < 3; ++rot)
        for (int k = 0; k < 20; ++k) {
            const Transform t =
                Transform::Translate({37.5 * k - 300, 11.0 * rot + 0.3 * k, 5.0 * k}) *
                Transform::Rotate(0, 25 + 30 * rot) * Transform::Rotate(2, 10 + 17 * rot);
            placements.push_back(t);
            const int q = AddQuadric(s.top, "c", cyl.Transformed(t).k);
            const int p1 = AddPlane(s.top, "t", top.Transformed(t));
            const int p2 = AddPlane(s.top, "b", bottom.Transformed(t));
            AddBody(s.top, "rod", {q, p1, p2});
        }
    scene::Scope def;
    def.id = "pin";
    {
        const int q = AddQuadric(def, "c", cyl.Transformed(Transform::Rotate(1, 40)).k);
        const int p1 = AddPlane(def, "t", top.Transformed(Transform::Rotate(1, 40)));
        const int p2 = AddPlane(def, "b", bottom.Transformed(Transform::Rotate(1, 40)));
        AddBody(def, "pin", {q, p1, p2});
    }
    s.definitions.push_back(def);
    AddInstance(s.top, "pins", 0, Transform::Translate({0, -80, 0}), 12,
                Transform::Translate({25, 0, 3}));
    scene::View oblique = MakeView("oblique");
    oblique.vpn = Vec3{0.4, -0.5, -1};
    oblique.dop = Vec3{-0.4, 0.5, 1};  // orthographic
    s.views.push_back(oblique);
    scene::View window = oblique;
    window.id = "window";
    window.whw = 150;  // cuts off some rods: culled ones must be the same
    s.views.push_back(window);
    for (const char* view : {"oblique", "window"}) {
        FlattenOptions o;
        o.width = 640;
        o.height = 360;
        o.viewName = view;
        Diagnostics d1, d2;
        std::optional<FlatScene> reused = Flatten(s, o, d1);
        o.reuseBoundsByTranslation = false;
        std::optional<FlatScene> direct = Flatten(s, o, d2);
        ASSERT_TRUE(reused && direct)
            << view << ": " << (d1.Items().empty() ? std::string() : d1.Items()[0].Format(false));
        EXPECT_EQ(reused->projection.deviceFromWorld.Matrix().m,
                  direct->projection.deviceFromWorld.Matrix().m)
            << view;
        ASSERT_EQ(reused->solids.size(), direct->solids.size()) << view;
        ASSERT_EQ(reused->bodies.size(), direct->bodies.size()) << view;
        int differing = 0;
        for (std::size_t b = 0; b < reused->bodies.size(); ++b) {
            const Box3& a = reused->bodies[b].bounds;
            const Box3& e = direct->bodies[b].bounds;
            ASSERT_EQ(reused->bodies[b].name, direct->bodies[b].name);
            for (int axis = 0; axis < 3; ++axis) {
                const double tol = 2e-5 * ((e.hi[axis] - e.lo[axis]) +
                                           std::fmax(std::fabs(e.lo[axis]), std::fabs(e.hi[axis])));
                EXPECT_NEAR(a.lo[axis], e.lo[axis], tol) << view << " body " << b;
                EXPECT_NEAR(a.hi[axis], e.hi[axis], tol) << view << " body " << b;
                differing += a.lo[axis] != e.lo[axis] || a.hi[axis] != e.hi[axis];
            }
        }
        // The reuse happened (boxes from a moved box differ in their last bits).
        EXPECT_GT(differing, 20) << view;
        // Points on the rods' surfaces (in world space) lie in their reused boxes.
        if (std::string(view) == "oblique") {
            ASSERT_EQ(reused->bodies.size(), 72u);
            for (std::size_t b = 0; b < placements.size(); ++b)
                for (int i = 0; i < 64; ++i) {
                    const double phi = 2 * M_PI * i / 64;
                    for (double z : {0.0, h / 2, h}) {
                        const Vec3 p = reused->projection.deviceFromWorld.MapPoint(
                            placements[b].MapPoint({r * std::cos(phi), r * std::sin(phi), z}));
                        const Box3& box = reused->bodies[b].bounds;
                        for (int axis = 0; axis < 3; ++axis) {
                            EXPECT_GE(p[axis], box.lo[axis]) << b;
                            EXPECT_LE(p[axis], box.hi[axis]) << b;
                        }
                    }
                }
        }
    }
}

// FlattenOptions::halfSpaceNames off: the same flat scene bit for bit but for the half-spaces'
// names, which are left empty; bodies and solids keep theirs.
TEST(FlattenNames, HalfSpaceNamesOffChangesNothingButThoseNames) {
    scene::Scene s;
    const Quadric cyl = Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -9});
    for (int k = 0; k < 12; ++k) {
        const Transform t = Transform::Translate({30.0 * k, 2.0 * k, 0}) * Transform::Rotate(0, 20);
        const int q = AddQuadric(s.top, "c", cyl.Transformed(t).k);
        const int p1 = AddPlane(s.top, "t", Plane{0, 0, 1, -20}.Transformed(t));
        const int p2 = AddPlane(s.top, "b", Plane{0, 0, -1, 0}.Transformed(t));
        AddBody(s.top, "rod", {q, p1, p2});
    }
    scene::Scope def;
    def.id = "pin";
    AddBody(def, "pin", {AddSphere(def, "s", {0, 0, 0}, 4)});
    s.definitions.push_back(def);
    AddInstance(s.top, "pins", 0, Transform::Translate({0, -80, 0}), 5,
                Transform::Translate({25, 0, 3}));
    FlattenOptions o;
    o.width = 320;
    o.height = 200;
    Diagnostics d1, d2;
    const std::optional<FlatScene> named = Flatten(s, o, d1);
    o.halfSpaceNames = false;
    const std::optional<FlatScene> plain = Flatten(s, o, d2);
    ASSERT_TRUE(named && plain);
    EXPECT_EQ(named->projection.deviceFromWorld.Matrix().m,
              plain->projection.deviceFromWorld.Matrix().m);
    ASSERT_EQ(named->halfSpaces.size(), plain->halfSpaces.size());
    for (std::size_t i = 0; i < named->halfSpaces.size(); ++i) {
        const FlatHalfSpace &a = named->halfSpaces[i], &b = plain->halfSpaces[i];
        EXPECT_EQ(a.isPlane, b.isPlane);
        EXPECT_EQ(std::memcmp(&a.plane, &b.plane, sizeof a.plane), 0) << i;
        EXPECT_EQ(std::memcmp(&a.quadric, &b.quadric, sizeof a.quadric), 0) << i;
        EXPECT_EQ(a.isClip, b.isClip);
        if (a.isClip) continue;
        EXPECT_FALSE(a.name.empty()) << i;
        EXPECT_TRUE(b.name.empty()) << i;
    }
    ASSERT_EQ(named->bodies.size(), 17u);
    ASSERT_EQ(plain->bodies.size(), 17u);
    for (std::size_t i = 0; i < named->bodies.size(); ++i) {
        const FlatBody &a = named->bodies[i], &b = plain->bodies[i];
        ASSERT_EQ(a.literals.size(), b.literals.size());
        for (std::size_t l = 0; l < a.literals.size(); ++l)
            EXPECT_EQ(a.literals[l].halfSpace, b.literals[l].halfSpace);
        EXPECT_EQ(std::memcmp(&a.bounds, &b.bounds, sizeof a.bounds), 0) << i;
        EXPECT_EQ(a.solid, b.solid);
        EXPECT_EQ(a.name, b.name);
    }
    EXPECT_EQ(named->bodies[12].name, "pins[0]/pin");
    ASSERT_EQ(named->solids.size(), plain->solids.size());
    for (std::size_t i = 0; i < named->solids.size(); ++i) {
        EXPECT_EQ(named->solids[i].name, plain->solids[i].name);
        EXPECT_EQ(std::memcmp(&named->solids[i].bounds, &plain->solids[i].bounds, sizeof(Box3)), 0);
    }
}

// A scene big enough for the literal cache to be made alongside the walk (LiteralCacheBuilder,
// at least kMinHalfSpaces half-spaces: 6,000 ellipsoids and 3,000 capped cylinders) flattens to
// the same bits as inline (a SerialScope: no second thread), boxes, window and device map.
TEST(FlattenBounds, TheCacheMadeAlongsideTheWalkGivesTheInlineScene) {
    if (AvailableProcessors() < 2)
        GTEST_SKIP() << "one processor: the literal cache is not made alongside the walk here";
    scene::Scene s;
    for (int i = 0; i < 6000; ++i) {
        const double x = (i % 80) * 3.0, y = (i / 80) * 3.0;
        const Quadric e = Quadric::FromCoefficients({1, 2, 3, 0.2, 0.1, 0, 0, 0, 0, -1})
                              .Transformed(Transform::Translate({x, y, 0.5 * (i % 7)}) *
                                           Transform::Rotate(2, i % 90));
        AddBody(s.top, "e", {AddQuadric(s.top, "q", e.k)});
    }
    const Quadric cyl = Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -0.25});
    for (int i = 0; i < 3000; ++i) {
        const Transform t = Transform::Translate({(i % 60) * 4.0, -20 - (i / 60) * 4.0, 0}) *
                            Transform::Rotate(0, 10 + i % 50);
        AddBody(s.top, "c",
                {AddQuadric(s.top, "k", cyl.Transformed(t).k),
                 AddPlane(s.top, "t", Plane{0, 0, 1, -2}.Transformed(t)),
                 AddPlane(s.top, "b", Plane{0, 0, -1, 0}.Transformed(t))});
    }
    FlattenOptions o;
    o.width = 640;
    o.height = 480;
    Diagnostics d1, d2;
    const std::optional<FlatScene> alongside = Flatten(s, o, d1);
    std::optional<FlatScene> inlined;
    {
        SerialScope serial;
        inlined = Flatten(s, o, d2);
    }
    ASSERT_TRUE(alongside && inlined);
    EXPECT_EQ(std::memcmp(&alongside->projection.deviceFromWorld.Matrix().m,
                          &inlined->projection.deviceFromWorld.Matrix().m, sizeof(Mat4::m)),
              0);
    ASSERT_EQ(alongside->bodies.size(), 9000u);
    ASSERT_EQ(inlined->bodies.size(), 9000u);
    for (std::size_t b = 0; b < 9000; ++b)
        ASSERT_EQ(
            std::memcmp(&alongside->bodies[b].bounds, &inlined->bodies[b].bounds, sizeof(Box3)), 0)
            << b;
    ASSERT_EQ(alongside->halfSpaces.size(), inlined->halfSpaces.size());
    for (std::size_t h = 0; h < alongside->halfSpaces.size(); ++h)
        ASSERT_EQ(std::memcmp(&alongside->halfSpaces[h].quadric, &inlined->halfSpaces[h].quadric,
                              sizeof(Quadric)),
                  0)
            << h;
    ASSERT_EQ(alongside->solids.size(), inlined->solids.size());
    for (std::size_t i = 0; i < alongside->solids.size(); ++i)
        ASSERT_EQ(
            std::memcmp(&alongside->solids[i].bounds, &inlined->solids[i].bounds, sizeof(Box3)), 0)
            << i;
}

// The same with CSG solids (two rods and a ball in a union, 45 of them by translation): the
// solids that may decide the auto-fitted window are bounded directly and their fit boxes made
// again from their own subtrees (RefitSolids in flattener.cpp); the window is bit for bit the one
// of the direct bounds in three views. Fails when a subtree's nodes are combined out of order
// (a parent before its children) or a solid gets another's fit box.
TEST(FlattenBounds, CsgSolidsSettledForTheWindowKeepIt) {
    scene::Scene s;
    const double r = 3, h = 20;
    const Quadric cyl = Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -r * r});
    const Plane top{0, 0, 1, -h}, bottom{0, 0, -1, 0};
    for (int rot = 0; rot < 3; ++rot)
        for (int k = 0; k < 15; ++k) {
            const Transform t =
                Transform::Translate({41.0 * k - 300, 13.0 * rot + 0.7 * k, 4.0 * k - 20 * rot}) *
                Transform::Rotate(0, 25 + 30 * rot) * Transform::Rotate(2, 10 + 17 * rot);
            const Transform u = t * Transform::Translate({8, 0, 5}) * Transform::Rotate(1, 60);
            const std::string n = std::to_string(rot) + "_" + std::to_string(k);
            CsgBuilder b;
            const int a = b.Body(AddBody(s.top, "a" + n,
                                         {AddQuadric(s.top, "ca" + n, cyl.Transformed(t).k),
                                          AddPlane(s.top, "ta" + n, top.Transformed(t)),
                                          AddPlane(s.top, "ba" + n, bottom.Transformed(t))}));
            const int c = b.Body(AddBody(s.top, "b" + n,
                                         {AddQuadric(s.top, "cb" + n, cyl.Transformed(u).k),
                                          AddPlane(s.top, "tb" + n, top.Transformed(u)),
                                          AddPlane(s.top, "bb" + n, bottom.Transformed(u))}));
            const int ball = b.Body(
                AddBody(s.top, "s" + n, {AddSphere(s.top, "s" + n, t.MapPoint({0, 0, h}), 5)}));
            // The root first: the builder is passed by value, and the order in which a call's
            // arguments are evaluated is unspecified.
            const int root = b.Op(scene::CsgOp::kUnion, b.Op(scene::CsgOp::kUnion, a, c), ball);
            AddCsg(s.top, "part" + n, b, root);
        }
    int settled = 0;
    for (const Vec3& vpn : {Vec3{0.4, -0.5, -1}, Vec3{-1, 0.2, -0.3}, Vec3{0.1, 1, -0.2}}) {
        scene::View v = MakeView("v");
        v.vpn = vpn;
        v.dop = -vpn;
        s.views = {v};
        FlattenOptions o;
        o.width = 640;
        o.height = 360;
        o.viewName = "v";
        Diagnostics d1, d2;
        std::optional<FlatScene> reused = Flatten(s, o, d1);
        o.reuseBoundsByTranslation = false;
        std::optional<FlatScene> direct = Flatten(s, o, d2);
        ASSERT_TRUE(reused && direct)
            << (d1.Items().empty() ? std::string() : d1.Items()[0].Format(false)) << " / "
            << (d2.Items().empty() ? std::string() : d2.Items()[0].Format(false));
        ASSERT_EQ(reused->solids.size(), 45u);
        EXPECT_EQ(reused->projection.deviceFromWorld.Matrix().m,
                  direct->projection.deviceFromWorld.Matrix().m);
        ASSERT_EQ(reused->bodies.size(), direct->bodies.size());
        // The solids at the window's sides were bounded directly (their boxes are the direct
        // ones, bit for bit), and some others were not (boxes moved by translation).
        int same = 0;
        for (std::size_t b = 0; b < reused->bodies.size(); ++b)
            same += reused->bodies[b].bounds.lo == direct->bodies[b].bounds.lo &&
                    reused->bodies[b].bounds.hi == direct->bodies[b].bounds.hi;
        EXPECT_LT(same, static_cast<int>(reused->bodies.size()));
        settled += same > 3 * 3;  // more than the three references' bodies
    }
    EXPECT_EQ(settled, 3);
}

// A generated model in the shape of an imported vehicle (flatten/hierarchy.cpp reserves its lists
// from the guard's counts; SceneScale, TranslationReuse and the bounds run in parallel): rods
// placed in the top scope (translates of each other, so boxes are reused), CSG solids over them
// sharing top-scope half-spaces with drawn bodies, an array of a definition and an instance used
// as a CSG operand.
scene::Scene GeneratedVehicle() {
    scene::Scene s;
    const Quadric cyl = Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -4});
    // z <= 15 and, complemented, z >= 0.
    const Plane top{0, 0, 1, -15}, bottom{0, 0, 1, 0};
    std::vector<int> rods;
    for (int k = 0; k < 120; ++k) {
        const Transform t = Transform::Translate({9.0 * (k % 30), 13.0 * (k / 30), 0.5 * k}) *
                            Transform::Rotate(0, 20 + 15 * (k / 30));
        const int q = AddQuadric(s.top, fmt::format("rod{}.c", k), cyl.Transformed(t).k);
        const int p1 = AddPlane(s.top, fmt::format("rod{}.t", k), top.Transformed(t));
        const int p2 = AddPlane(s.top, fmt::format("rod{}.b", k), bottom.Transformed(t));
        rods.push_back(AddBody(s.top, fmt::format("rod{}", k), {q, p1, ~p2}));
    }
    // A sphere used by a drawn body and by the CSG solids below.
    const int ball = AddSphere(s.top, "hub", {120, 20, 10}, 30);
    AddBody(s.top, "hub", {ball});
    scene::Scope bolt;
    bolt.id = "bolt";
    {
        const int q = AddQuadric(bolt, "c", cyl.Transformed(Transform::Rotate(1, 90)).k);
        const int p1 = AddPlane(bolt, "l", Plane{1, 0, 0, -4});
        const int p2 = AddPlane(bolt, "r", Plane{-1, 0, 0, -4});
        AddBody(bolt, "bolt", {q, p1, p2});
    }
    s.definitions.push_back(bolt);
    AddInstance(s.top, "bolts", 0, Transform::Translate({0, -30, 0}), 25,
                Transform::Translate({11, 0, 1}));
    const int operand = AddInstance(s.top, "pin", 0, Transform::Translate({60, 60, 5}));
    for (int c = 0; c < 6; ++c) {
        // (rod a | rod b | pin) - hub: an instance operand and a shared half-space.
        CsgBuilder b;
        const int rodA = b.Body(rods[static_cast<std::size_t>(c)]);
        const int rodB = b.Body(rods[static_cast<std::size_t>(119 - c)]);
        const int u = b.Op(scene::CsgOp::kUnion, rodA, rodB);
        const int withPin = c == 0 ? b.Op(scene::CsgOp::kUnion, u, b.Inst(operand)) : u;
        const int hub = AddBody(s.top, fmt::format("cut{}", c), {ball});
        // The root first: AddCsg takes the builder, and the order in which a call's arguments
        // are evaluated is unspecified (clang copied the builder before the root was added).
        const int cutRoot = b.Op(scene::CsgOp::kDifference, withPin, b.Body(hub));
        AddCsg(s.top, fmt::format("frame{}", c), b, cutRoot);
    }
    return s;
}

void ExpectSameFlatScene(const FlatScene& a, const FlatScene& b, const std::string& what) {
    auto sameBox = [](const Box3& x, const Box3& y) {
        return std::memcmp(&x, &y, sizeof(Box3)) == 0;
    };
    EXPECT_EQ(a.projection.deviceFromWorld.Matrix().m, b.projection.deviceFromWorld.Matrix().m)
        << what;
    EXPECT_EQ(a.depthTolerance, b.depthTolerance) << what;
    ASSERT_EQ(a.halfSpaces.size(), b.halfSpaces.size()) << what;
    for (std::size_t i = 0; i < a.halfSpaces.size(); ++i) {
        const FlatHalfSpace &x = a.halfSpaces[i], &y = b.halfSpaces[i];
        EXPECT_EQ(x.name, y.name) << what << " half-space " << i;
        EXPECT_EQ(x.isPlane, y.isPlane) << what << " half-space " << i;
        EXPECT_EQ(x.transparent, y.transparent) << what << " half-space " << i;
        EXPECT_EQ(x.isClip, y.isClip) << what << " half-space " << i;
        EXPECT_EQ(std::memcmp(&x.plane, &y.plane, sizeof(Plane)), 0) << what << " " << i;
        EXPECT_EQ(std::memcmp(&x.quadric, &y.quadric, sizeof(Quadric)), 0) << what << " " << i;
    }
    ASSERT_EQ(a.bodies.size(), b.bodies.size()) << what;
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
        const FlatBody &x = a.bodies[i], &y = b.bodies[i];
        EXPECT_EQ(x.name, y.name) << what << " body " << i;
        EXPECT_EQ(x.solid, y.solid) << what << " body " << i;
        ASSERT_EQ(x.literals.size(), y.literals.size()) << what << " body " << i;
        for (std::size_t l = 0; l < x.literals.size(); ++l) {
            EXPECT_EQ(x.literals[l].halfSpace, y.literals[l].halfSpace) << what << " body " << i;
            EXPECT_EQ(x.literals[l].complemented, y.literals[l].complemented) << what;
        }
        EXPECT_TRUE(sameBox(x.bounds, y.bounds)) << what << " body " << i;
    }
    ASSERT_EQ(a.nodes.size(), b.nodes.size()) << what;
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
        const FlatCsgNode &x = a.nodes[i], &y = b.nodes[i];
        EXPECT_EQ(x.isLeaf, y.isLeaf) << what << " node " << i;
        EXPECT_EQ(x.body, y.body) << what << " node " << i;
        EXPECT_EQ(x.op, y.op) << what << " node " << i;
        EXPECT_EQ(x.children, y.children) << what << " node " << i;
        EXPECT_TRUE(sameBox(x.bounds, y.bounds)) << what << " node " << i;
    }
    ASSERT_EQ(a.solids.size(), b.solids.size()) << what;
    for (std::size_t i = 0; i < a.solids.size(); ++i) {
        EXPECT_EQ(a.solids[i].name, b.solids[i].name) << what << " solid " << i;
        EXPECT_EQ(a.solids[i].root, b.solids[i].root) << what << " solid " << i;
        EXPECT_TRUE(sameBox(a.solids[i].bounds, b.solids[i].bounds)) << what << " solid " << i;
    }
}

// The parallel passes of the flattener (the scene scale, the translates' keys, the bounds) give
// the FlatScene of one thread, element for element and bit for bit, in an auto-fitted view (the
// fit's second look) and in a window; the names are the walk's paths.
TEST(FlattenHierarchy, SameSceneOnOneThreadAndOnTwo) {
    scene::Scene s = GeneratedVehicle();
    scene::View oblique = MakeView("oblique");
    oblique.vpn = Vec3{0.3, -0.6, -1};
    oblique.dop = Vec3{-0.3, 0.6, 1};
    s.views.push_back(oblique);
    scene::View window = oblique;
    window.id = "window";
    window.whw = 200;
    s.views.push_back(window);
    for (const char* view : {"oblique", "window"}) {
        FlattenOptions o;
        o.width = 640;
        o.height = 360;
        o.viewName = view;
        std::optional<FlatScene> flat[2];
        for (int threads = 1; threads <= 2; ++threads) {
            Diagnostics d;
            tbb::task_arena arena(threads);
            arena.execute([&] { flat[threads - 1] = Flatten(s, o, d); });
            ASSERT_TRUE(flat[threads - 1]) << view;
        }
        ExpectSameFlatScene(*flat[0], *flat[1], view);
        const FlatScene& f = *flat[1];
        // The walk's order: the top scope's drawn bodies (rod6 to rod113, the hub), the copies
        // of the array, then the CSG solids; half-spaces at their first use. (The window culls.)
        if (std::string(view) != "oblique") continue;
        ASSERT_GT(f.bodies.size(), 109u) << view;
        EXPECT_EQ(f.bodies[0].name, "rod6") << view;
        EXPECT_EQ(f.bodies[108].name, "hub") << view;
        EXPECT_EQ(f.bodies[109].name, "bolts[0]/bolt") << view;
        EXPECT_EQ(f.halfSpaces[5].name, "rod7.b") << view;
        EXPECT_EQ(f.solids.back().name, "frame5");
    }
}

// A view made over a recycled flat scene (the previous view's, as the render context passes it)
// is the one made afresh: bigger and smaller recycled scenes, with and without a section plane
// (one more shared half-space before the world's).
TEST(FlattenView, OverARecycledSceneIsTheSameAsAfresh) {
    scene::Scene small, big;
    for (int i = 0; i < 6; ++i) {
        const int q =
            AddSphere(small.top, fmt::format("s{}", i), {2.0 * i, 0.5 * i, 0}, 1 + 0.1 * i);
        const int p = AddPlane(small.top, fmt::format("p{}", i), {0, 1, 0.2, -0.3 * i});
        AddBody(small.top, fmt::format("b{}", i), {q, i % 2 ? ~p : p});
    }
    for (int i = 0; i < 40; ++i) {
        const int q = AddSphere(big.top, fmt::format("t{}", i), {0.5 * i, 1, 2}, 0.7);
        AddBody(big.top, fmt::format("c{}", i), {q});
    }
    Diagnostics diags;
    const std::optional<WorldScene> world = FlattenWorld(small, diags);
    const std::optional<WorldScene> bigWorld = FlattenWorld(big, diags);
    ASSERT_TRUE(world && bigWorld);
    FlattenOptions views[2];
    views[0].width = 320;
    views[0].height = 200;
    views[1] = views[0];
    views[1].section = Plane{0.2, 0, 1, -0.5};
    for (const FlattenOptions& o : views) {
        const std::optional<FlatScene> fresh = FlattenView(small, *world, o, diags);
        ASSERT_TRUE(fresh);
        for (const std::optional<WorldScene>* other : {&world, &bigWorld}) {
            for (const FlattenOptions& previous : views) {
                std::optional<FlatScene> old =
                    FlattenView(other == &world ? small : big, **other, previous, diags);
                ASSERT_TRUE(old);
                const std::optional<FlatScene> again =
                    FlattenView(small, *world, o, diags, std::move(*old));
                ASSERT_TRUE(again);
                ExpectSameFlatScenes(*fresh, *again);
            }
        }
    }
    EXPECT_FALSE(diags.HasErrors());
}

}  // namespace
}  // namespace quadrix
