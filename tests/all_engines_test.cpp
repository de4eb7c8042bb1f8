// Every registered engine × a corpus of scenes, each compared with raycast (the exact reference)
// through the one frame comparison (frame/compare.h). A new engine is covered by being
// registered (engines/registry.h); this file registers a dummy engine in one row to prove it:
// the dummy draws nothing and reports every solid undrawn, so the render context must compose
// the whole picture from raycast.
//
// The corpus holds analytic shapes, CSG with coincident faces (a doorway cut through a wall
// exactly as thick as the door, a hole whose wall is tangent to a face, a coplanar union),
// perspective and clipping. Every engine renders through the render context, as the CLI does, so
// what an engine cannot draw (CSG for patch, everything for isocurve and the dummy) is composed
// from raycast and the picture is still whole.
//
// What must agree: coverage and surface id at every pixel whose 3×3 neighbourhood in the
// reference shows one surface (edge pixels may go either way by one rounding), and the depth of
// same-surface pixels within 1e-6 device units per pixel of image size (the incremental engines
// step depths by forward differences; raycast solves per pixel).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "quadrix/engines/registry.h"
#include "quadrix/eval/ray_evaluator.h"
#include "quadrix/flatten/flatten_test_util.h"
#include "quadrix/frame/compare.h"
#include "quadrix/pipeline/render_context.h"
#include "test_util.h"

namespace quadrix {
namespace {

class DummyEngine final : public Engine {
  public:
    std::string_view Name() const override { return "dummy-test"; }

  protected:
    RenderStats Draw(const FlatScene& scene, const EngineOptions&, Frame& frame) override {
        frame.Reset(scene.width, scene.height);
        RenderStats stats;
        for (std::size_t s = 0; s < scene.solids.size(); ++s)
            stats.undrawn.push_back({static_cast<int>(s), "the dummy draws nothing"});
        return stats;
    }
};

// The one row that registers an engine.
const bool kDummyRegistered =
    RegisterEngine({"dummy-test",
                    "draws nothing (tests composition)",
                    [] { return std::make_unique<DummyEngine>(); },
                    EngineCapabilities{.solids = true, .freeforms = false, .quartics = false},
                    {},
                    true});

struct CorpusScene {
    std::string name;
    std::string text;
};

const std::vector<CorpusScene>& Corpus() {
    static const std::vector<CorpusScene> kScenes{
        {"sphere", "solid sphere ball =at 0 0 0 =r 1; view front dop .3 .4 -1;"},
        {"ellipsoid_turned",
         "solid ellipsoid egg =at 0 0 0 =r 2 1 .7 =rz 30 =rx 20; view front dop .2 .3 -1;"},
        {"cylinder_capped",
         "solid cylinder rod =from 0 -1 0 =to 0 1 0 =r .8; view front dop .5 .6 -1;"},
        {"cone_apex",
         "solid cone tip =from 0 -1 0 =to 0 1 0 =r0 1 =r1 0; view front dop .4 .2 -1;"},
        {"hyperboloid_paraboloid",
         "solid hyperboloid reel =from -2 -1 0 =to -2 1 0 =r 1 =waist .5;\n"
         "solid paraboloid dish =from 1 -1 0 =to 1 1 0 =r 1; view front dop .3 .5 -1;"},
        // A doorway cut through a wall exactly as thick as the door: the door's front and back
        // faces and its sill coincide with the wall's.
        {"doorway_coincident",
         "solid box wall =from -3 0 0 =to 3 3 .5;\n"
         "solid box door =from -.5 0 0 =to .5 2 .5;\n"
         "csg room (wall - door); view front dop .35 .3 -1;"},
        // A hole whose wall is tangent to the block's side face (x = 1).
        {"tangent_hole",
         "solid box block =from -1 -1 -1 =to 1 1 1;\n"
         "solid cylinder drill =from .5 -2 0 =to .5 2 0 =r .5;\n"
         "csg drilled (block - drill); view front dop .4 .5 -1;"},
        // Two boxes sharing a face, and a third overlapping both.
        {"coplanar_union",
         "solid box left =from -2 0 0 =to 0 1 1;\n"
         "solid box right =from 0 0 0 =to 2 1 1;\n"
         "solid box mid =from -1 0 0 =to 1 1.5 .5;\n"
         "csg joined (left | right | mid); view front dop .3 .4 -1;"},
        // Issue 23's coincident cases. A − A: two bodies on one sphere, and two spheres with the
        // same coefficients; nothing is left (the box beside keeps the scene visible).
        {"a_minus_a",
         "quadric unit <1 1 1 0 0 0 0 0 0 -1>; body one (unit); body two (unit);\n"
         "csg none (one - two);\n"
         "solid sphere ball1 =at 0 0 0 =r 1; solid sphere ball2 =at 0 0 0 =r 1;\n"
         "csg gone (ball1 - ball2);\n"
         "solid box side =from 1.5 -1 -1 =to 3 1 1; view front dop .3 .4 -1;"},
        // A body holding p and !p is the plane z = 0 only: empty as a regular set.
        {"body_s_p_not_p",
         "quadric unit <1 1 1 0 0 0 0 0 0 -1>; plane zero <0 0 1 0>;\n"
         "body thin (unit zero !zero);\n"
         "solid box side =from 1.5 -1 -1 =to 3 1 1; view front dop .3 .4 -1;"},
        // Pockets sharing the block's front and back faces (z = 0 and z = 1): the pockets' far
        // (near) faces show through.
        {"pockets_shared_faces",
         "solid box block =from -2 -1 0 =to 2 1 1;\n"
         "solid box front =from -1.5 -.5 0 =to -.2 .5 .5;\n"
         "solid box back =from .2 -.5 .5 =to 1.5 .5 1;\n"
         "csg pocketed (block - front - back); view front dop .3 .4 -1;"},
        // An intersection and a difference of boxes sharing faces (x = .5, y = -.5, z = 0).
        {"shared_faces_intersection",
         "solid box block =from -1 -1 0 =to 1 1 1;\n"
         "solid box slab =from -2 -.5 0 =to .5 .5 .6;\n"
         "solid box notch =from 0 -.5 0 =to .5 0 .6;\n"
         "csg part ((block & slab) - notch); view front dop .3 .4 -1;"},
        // The coplanar union minus a hole, cut by a front clipping plane: rays start inside, so
        // the picture shows exits, whose ties go to a union's right operand (interval_list.h).
        {"coplanar_union_clipped",
         "solid box left =from -2 0 0 =to 0 1 1;\n"
         "solid box right =from 0 0 0 =to 2 1 1;\n"
         "solid box mid =from -1 0 0 =to 1 1.5 .5;\n"
         "solid box hole =from -.5 .2 0 =to .5 .8 1;\n"
         "csg joined ((left | right | mid) - hole); view front dop .3 .4 -1 fbp .25 .75;"},
        // A union of two identical boxes, cut by a front clipping plane: every visible point is
        // an exact tie, of entries (left operand wins) or, behind the cut, of exits (right wins).
        {"identical_union_clipped",
         "solid box one =from -1 -1 -1 =to 1 1 1; solid box two =from -1 -1 -1 =to 1 1 1;\n"
         "csg twice (one | two); view front dop -.35 .25 -1 fbp -.2 .6;"},
        {"intersection_difference",
         "solid sphere ball =at 0 0 0 =r 1.2;\n"
         "solid box cube =from -1 -1 -1 =to 1 1 1;\n"
         "solid cylinder xbore =from -2 0 0 =to 2 0 0 =r .5;\n"
         "solid cylinder ybore =from 0 -2 0 =to 0 2 0 =r .5;\n"
         "csg part ((ball & cube) - xbore - ybore); view front dop .5 .4 -1;"},
        {"perspective",
         "solid box cube =from -1 -1 -1 =to 1 1 1;\n"
         "solid sphere ball =at 0 0 0 =r 1.3;\n"
         "csg part (cube - ball); view eye vrp 0 0 0 cop 3 2.5 -4;"},
        {"clipping_fbp",
         "solid sphere ball =at 0 0 0 =r 1;\n"
         "solid cylinder bore =from 0 -1.5 0 =to 0 1.5 0 =r .4;\n"
         "csg ring (ball - bore); view front dop 0 0 -1 whh 1.2 whw 1.2 fbp -.3 .5;"},
        // Quartics (issue 20): engines other than raycast get them composed from raycast.
        {"torus_csg",
         "solid torus ring =r 1.2 .4 =axis 0 1 1;\n"
         "solid cylinder rod =from -2 0 0 =to 2 0 0 =r .25;\n"
         "solid sphere ball =at 0 0 0 =r .6 =c 1 0 0;\n"
         "csg cut (ring - rod); view front dop .3 .4 -1;"},
        {"machined_part",
         "read \"" + quadrix::testing::SourcePath("examples/machined_part.uq") + "\";"},
    };
    return kScenes;
}

struct Case {
    std::string engine;
    std::string scene;
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.engine << " on " << c.scene; }

std::vector<Case> Cases() {
    std::vector<Case> cases;
    for (const EngineInfo& e : Engines())
        for (const CorpusScene& s : Corpus()) cases.push_back({e.name, s.name});
    return cases;
}

std::string CaseName(const ::testing::TestParamInfo<Case>& info) {
    std::string n = info.param.engine + "_" + info.param.scene;
    for (char& c : n)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return n;
}

EngineRequest Request(const std::string& engine, bool strict = false) {
    EngineRequest r;
    r.engine = engine;
    r.strict = strict;
    return r;
}

ViewRequest Size(int w, int h, const std::string& view = {}) {
    ViewRequest v;
    v.width = w;
    v.height = h;
    v.viewName = view;
    return v;
}

class AllEngines : public ::testing::TestWithParam<Case> {};

TEST_P(AllEngines, MatchesRaycastThroughTheRenderContext) {
    ASSERT_TRUE(kDummyRegistered);
    const Case& c = GetParam();
    const CorpusScene* scene = nullptr;
    for (const CorpusScene& s : Corpus())
        if (s.name == c.scene) scene = &s;
    ASSERT_NE(scene, nullptr);

    RenderContext ctx;
    Diagnostics diags;
    InputRequest in;
    in.text = scene->text;
    in.textName = c.scene + ".uq";
    const ViewRequest view = Size(160, 120);
    ASSERT_TRUE(ctx.Read(in, diags) && ctx.Flatten(view, diags)) << diags.Items().size();

    Frame reference, got;
    RenderReport refReport, report;
    ASSERT_TRUE(ctx.Render(Request("raycast"), reference, refReport, diags));
    ASSERT_TRUE(ctx.Render(Request(c.engine), got, report, diags)) << c.engine;

    const FrameComparison cmp = CompareFrames(got, reference, {});
    EXPECT_GT(reference.CoveredCount(), 200u) << "the scene must be visible";
    EXPECT_EQ(cmp.offEdgeDifferences, 0u)
        << c.engine << " on " << c.scene << ": " << cmp.firstDifference << "\n"
        << cmp.Summary();
    const double tolerance = 1e-6 * 160;
    EXPECT_LE(cmp.maxDepthError, tolerance) << cmp.Summary();
    // Every solid is drawn by the engine or composed from raycast: never silently missing.
    const EngineInfo* info = FindEngine(c.engine);
    ASSERT_NE(info, nullptr);
    if (!info->capabilities.solids) {
        EXPECT_EQ(report.byReference.size(), ctx.Flat().solids.size());
    }
    // Every counter of the report is declared, by the engine's row or by the composition, once.
    std::vector<std::string> seen;
    for (const auto& [name, value] : report.Counters()) {
        EXPECT_TRUE(IsDeclared(info->counters, name) || IsDeclared(kCompositionCounters, name))
            << c.engine << " reports the undeclared counter '" << name << "'";
        EXPECT_EQ(std::count(seen.begin(), seen.end(), name), 0) << c.engine << ": " << name;
        seen.push_back(name);
    }
    if (!info->hidden && info->capabilities.solids) {  // isocurve has no freeform here to draw
        EXPECT_GT(seen.size(), std::size(kCompositionCounters))
            << c.engine << " reports no counter";
    }
}

INSTANTIATE_TEST_SUITE_P(Corpus, AllEngines, ::testing::ValuesIn(Cases()), CaseName);

// raycast's fast paths (tile reduction, body batches, kernels, depth cuts) give, bit for bit, what
// the shared evaluator (eval/ray_evaluator.h) gives pixel by pixel: per solid the first opaque
// endpoint of its tree's set on the pixel's ray, the nearest solid winning and exact ties going to
// the lower index.
TEST(AllEnginesReference, RaycastEqualsTheSharedEvaluatorBitForBit) {
    for (const CorpusScene& scene : Corpus()) {
        RenderContext ctx;
        Diagnostics diags;
        InputRequest in;
        in.text = scene.text;
        in.textName = scene.name + ".uq";
        ASSERT_TRUE(ctx.Read(in, diags) && ctx.Flatten(Size(96, 72), diags)) << scene.name;
        Frame frame;
        RenderReport report;
        ASSERT_TRUE(ctx.Render(Request("raycast"), frame, report, diags));
        const FlatScene& flat = ctx.Flat();
        eval::RayEvaluator evaluator(flat);
        std::uint64_t mismatches = 0, covered = 0;
        std::string first;
        for (int y = 0; y < flat.height; ++y)
            for (int x = 0; x < flat.width; ++x) {
                eval::RayEvaluator::Hit best;
                int bestSolid = Frame::kNone;
                for (std::size_t s = 0; s < flat.solids.size(); ++s) {
                    eval::RayEvaluator::Hit hit;
                    if (evaluator.Node(flat.solids[s].root, x + 0.5, y + 0.5, hit) &&
                        hit.t < best.t) {
                        best = hit;
                        bestSolid = static_cast<int>(s);
                    }
                }
                const std::size_t i = frame.Index(x, y);
                covered += bestSolid != Frame::kNone;
                const bool same = bestSolid == Frame::kNone
                                      ? frame.Solid(i) == Frame::kNone
                                      : frame.depth[i] == static_cast<float>(best.t) &&
                                            frame.surface[i] == best.halfSpace &&
                                            frame.body[i] == best.body &&
                                            frame.Solid(i) == bestSolid;
                if (!same && mismatches++ == 0)
                    first = fmt::format(
                        "({}, {}): evaluator t {} surface {} solid {}, raycast t {} "
                        "surface {} solid {}",
                        x, y, best.t, best.halfSpace, bestSolid, frame.depth[i], frame.surface[i],
                        frame.Solid(i));
            }
        EXPECT_GT(covered, 100u) << scene.name;
        EXPECT_EQ(mismatches, 0u) << scene.name << ": first at " << first;
    }
}

// pixelpowers' paper machine (mode=approx) and its fixed-point depth words (depth-bits=24) on the
// coincident-face rows: depths are approximate or rounded, but a plane's sheet and its inside test
// use one formula, a quadric's strips are the same in the sheet and in the inside test, and roots
// are rounded as ZTEMP is, so coverage and surface ids agree off-edge as in exact mode (depths
// are not compared: they err by up to the tolerance or half a step).
TEST(AllEnginesCoincident, PixelPowersApproxAndDepthWordsExactOnCoincidentFaces) {
    for (const auto& [key, value] :
         std::vector<std::pair<std::string, std::string>>{{"mode", "approx"}, {"depth-bits", "24"}})
        for (const char* name :
             {"doorway_coincident", "a_minus_a", "body_s_p_not_p", "pockets_shared_faces",
              "shared_faces_intersection", "coplanar_union", "coplanar_union_clipped",
              "identical_union_clipped"}) {
            const CorpusScene* scene = nullptr;
            for (const CorpusScene& s : Corpus())
                if (s.name == name) scene = &s;
            ASSERT_NE(scene, nullptr) << name;
            RenderContext ctx;
            Diagnostics diags;
            InputRequest in;
            in.text = scene->text;
            in.textName = std::string(name) + ".uq";
            ASSERT_TRUE(ctx.Read(in, diags) && ctx.Flatten(Size(160, 120), diags)) << name;
            Frame reference, got;
            RenderReport refReport, report;
            ASSERT_TRUE(ctx.Render(Request("raycast"), reference, refReport, diags));
            EngineRequest approx = Request("pixelpowers");
            approx.options[key] = value;
            ASSERT_TRUE(ctx.Render(approx, got, report, diags)) << name;
            const FrameComparison cmp = CompareFrames(got, reference, {});
            EXPECT_EQ(cmp.offEdgeDifferences, 0u)
                << name << " with " << key << "=" << value << ": " << cmp.firstDifference << "\n"
                << cmp.Summary();
        }
}

// With strict, an engine that cannot draw a solid refuses instead of composing.
TEST(RenderContextComposition, StrictRefusesWhatTheEngineCannotDraw) {
    RenderContext ctx;
    Diagnostics diags;
    InputRequest in;
    in.text =
        "solid box cube =from -1 -1 -1 =to 1 1 1; solid sphere ball =at 0 0 0 =r 1.3;"
        "csg part (cube - ball);";
    ASSERT_TRUE(ctx.Read(in, diags) && ctx.Flatten(Size(64, 64), diags));
    Frame frame;
    RenderReport report;
    EXPECT_FALSE(ctx.Render(Request("patch", true), frame, report, diags));
    ASSERT_TRUE(diags.HasErrors());
    EXPECT_NE(diags.Items().back().message.find("cannot draw"), std::string::npos);
    Diagnostics ok;
    EXPECT_TRUE(ctx.Render(Request("patch"), frame, report, ok));
    EXPECT_EQ(report.byReference.size(), 1u);
    ASSERT_EQ(report.notes.size(), 1u);
    EXPECT_NE(report.notes[0].find("drawn by raycast"), std::string::npos);
    EXPECT_GT(frame.CoveredCount(), 100u);
}

// A second Flatten of the same view reuses the kept flat scene; a new view flattens again.
TEST(RenderContextComposition, SameViewIsNotFlattenedTwice) {
    RenderContext ctx;
    Diagnostics diags;
    InputRequest in;
    in.text = "solid sphere ball =at 0 0 0 =r 1; view one dop 0 0 -1; view two dop 1 0 -1;";
    ASSERT_TRUE(ctx.Read(in, diags));
    ViewRequest a = Size(32, 32, "one");
    ASSERT_TRUE(ctx.Flatten(a, diags));
    EXPECT_FALSE(ctx.LastFlattenReused());
    ASSERT_TRUE(ctx.Flatten(a, diags));
    EXPECT_TRUE(ctx.LastFlattenReused());
    ViewRequest b = a;
    b.viewName = "two";
    ASSERT_TRUE(ctx.Flatten(b, diags));
    EXPECT_FALSE(ctx.LastFlattenReused());
    ctx.SceneChanged();
    ASSERT_TRUE(ctx.Flatten(b, diags));
    EXPECT_FALSE(ctx.LastFlattenReused());
}

// What a view change invalidates (issue 16): the first view is flattened in one go; the second
// builds the world stage (the hierarchy walk into world space), which is then kept across views,
// sizes, perspective and a section plane, the view stage alone giving the very same flat scene
// and frame as a freshly built world stage; a scene change walks the hierarchy again.
TEST(RenderContextComposition, WorldStageIsKeptAcrossViews) {
    const std::string text =
        "definition row; quadric ball <1 1 1 0 0 0 0 0 0 -1>; plane cut <0 1 0 -0.5>;"
        "body capped <ball cut>; enddef;"
        "array balls (row =tx -4 =ty 1) 4 =tx 2.5;"
        "solid box slab =from -6 -2 -3 =to 6 -1 3; solid cylinder drill =from -5 -3 0 =to -5 1 0 "
        "=r 0.5; csg plate (slab - drill);"
        "view front dop 0 0 -1; view persp cop 6 -8 -20 vrp 0 0 0;";
    RenderContext ctx;
    Diagnostics diags;
    InputRequest in;
    in.text = text;
    ASSERT_TRUE(ctx.Read(in, diags))
        << (diags.Items().empty() ? std::string() : diags.Items()[0].Format());
    std::vector<ViewRequest> views = {Size(64, 48, "front"), Size(80, 40, "persp"),
                                      Size(64, 48, "front")};
    views[2].section = Plane{0.3, 0, 1, -0.2};
    ViewRequest camera = Size(50, 50);
    camera.view = *ctx.Scene().ViewToUse("persp");
    camera.view->id = "camera";
    camera.view->cop = Vec3{-10, 4, -20};
    views.push_back(camera);
    for (std::size_t i = 0; i < views.size(); ++i) {
        SCOPED_TRACE(i);
        ASSERT_TRUE(ctx.Flatten(views[i], diags))
            << (diags.Items().empty() ? std::string() : diags.Items()[0].Format());
        EXPECT_FALSE(ctx.LastFlattenReused());
        EXPECT_EQ(ctx.LastFlattenReusedWorld(), i > 1);
        EXPECT_EQ(ctx.worldFlattens, i == 0 ? 1 : 2);
        Frame kept;
        RenderReport report;
        ASSERT_TRUE(ctx.Render(Request("raycast"), kept, report, diags));
        EXPECT_GT(kept.CoveredCount(), 100u);

        RenderContext fresh;  // the same stage freshly made: one-shot, or world + view
        ASSERT_TRUE(fresh.Read(in, diags));
        if (i > 0) {
            ASSERT_TRUE(fresh.Flatten(views[0], diags));
        }
        ASSERT_TRUE(fresh.Flatten(views[i], diags));
        EXPECT_EQ(fresh.LastFlattenReusedWorld(), false);
        flatten_test::ExpectSameFlatScenes(ctx.Flat(), fresh.Flat());
        Frame oneShot;
        ASSERT_TRUE(fresh.Render(Request("raycast"), oneShot, report, diags));
        EXPECT_EQ(FirstBitDifference(kept, oneShot), "");
    }
    ctx.SceneChanged();
    ASSERT_TRUE(ctx.Flatten(views[0], diags));
    EXPECT_FALSE(ctx.LastFlattenReusedWorld());
    EXPECT_EQ(ctx.worldFlattens, 3);
}

// A view given directly (the viewer's camera) draws the same frame as the same view written in the
// scene, and a changed camera flattens again.
TEST(RenderContextComposition, DirectViewMatchesTheSceneView) {
    RenderContext ctx;
    Diagnostics diags;
    InputRequest in;
    in.text =
        "solid box cube =from -1 -1 -1 =to 1 1 1; solid sphere ball =at 0 0 0 =r 1.3;"
        "csg part (cube - ball); view side dop 1 -0.5 -1 vup 0 1 0;";
    ASSERT_TRUE(ctx.Read(in, diags));
    Frame written, direct;
    RenderReport report;
    ASSERT_TRUE(ctx.Flatten(Size(48, 40, "side"), diags));
    ASSERT_TRUE(ctx.Render(Request("raycast"), written, report, diags));
    scene::View camera = *ctx.Scene().ViewToUse("side");
    camera.id = "camera";
    ViewRequest v = Size(48, 40);
    v.view = camera;
    ASSERT_TRUE(ctx.Flatten(v, diags));
    EXPECT_FALSE(ctx.LastFlattenReused());
    EXPECT_EQ(ctx.Flat().viewName, "camera");
    ASSERT_TRUE(ctx.Render(Request("raycast"), direct, report, diags));
    EXPECT_GT(written.CoveredCount(), 200u);
    const FrameComparison same = CompareFrames(direct, written);
    EXPECT_EQ(same.onlyA + same.onlyReference + same.surfaceDiffers, 0u);
    EXPECT_EQ(same.maxDepthError, 0.0);
    ASSERT_TRUE(ctx.Flatten(v, diags));
    EXPECT_TRUE(ctx.LastFlattenReused());
    v.view->dop = Vec3{0.2, 0.1, -1};
    ASSERT_TRUE(ctx.Flatten(v, diags));
    EXPECT_FALSE(ctx.LastFlattenReused());
    ASSERT_TRUE(ctx.Render(Request("raycast"), direct, report, diags));
    const FrameComparison moved = CompareFrames(direct, written);
    EXPECT_GT(moved.onlyA + moved.onlyReference, 50u);
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// Whether two Frames hold the same bits in every array.
bool SameBits(const Frame& a, const Frame& b) {
    auto same = [](const auto& x, const auto& y) {
        return x.size() == y.size() &&
               std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0;
    };
    return a.width == b.width && a.height == b.height && same(a.depth, b.depth) &&
           same(a.normal, b.normal) && same(a.surface, b.surface) && same(a.body, b.body) &&
           a.bodySolid == b.bodySolid;
}

// A region (sort-first rendering, frame/pixel_region.h) through every engine: its pixels are the
// whole picture's bit for bit, the rest is background, and three interleaved parts put together
// are the whole picture. 300 pixels wide, so that raycast's second 256-pixel block is skipped by
// a region on the first only, and a rectangle not aligned to any tile.
TEST(RenderContextComposition, RegionsOfEveryEngineAssembleTheWholePictureBitForBit) {
    ASSERT_TRUE(kDummyRegistered);
    const char* scene =
        "solid box block =from -1 -1 -1 =to 1 1 1;\n"
        "solid cylinder drill =from .5 -2 0 =to .5 2 0 =r .5;\n"
        "csg drilled (block - drill); solid sphere ball =at 1.8 .2 0 =r .7;\n"
        "solid sphere far =at 3.6 0 0 =r .6;\n"
        "view front dop .4 .5 -1 whw 5;";
    for (const EngineInfo& e : Engines()) {
        RenderContext ctx;
        Diagnostics diags;
        InputRequest in;
        in.text = scene;
        ASSERT_TRUE(ctx.Read(in, diags) && ctx.Flatten(Size(300, 60), diags));
        Frame whole;
        RenderReport report;
        ASSERT_TRUE(ctx.Render(Request(e.name), whole, report, diags)) << e.name;
        ASSERT_GT(whole.CoveredCount(), 1000u) << e.name;

        Frame assembled(300, 60);
        for (int part = 0; part < 3; ++part) {
            EngineRequest r = Request(e.name);
            r.region = InterleavedBands(300, 60, part, 3, 8);
            Frame got;
            ASSERT_TRUE(ctx.Render(r, got, report, diags)) << e.name;
            CopyRegion(assembled, got, *r.region);
        }
        EXPECT_TRUE(SameBits(assembled, whole)) << e.name << ": interleaved bands";

        // Two rectangles not aligned to any tile, one across the blocks' boundary (x = 256);
        // then one in the second block only (raycast skips the first).
        for (const PixelRegion& region : {PixelRegion{{{131, 5, 171, 50}, {203, 3, 290, 29}}},
                                          PixelRegion{{{262, 0, 300, 60}}}}) {
            EngineRequest r = Request(e.name);
            r.region = region;
            Frame got;
            ASSERT_TRUE(ctx.Render(r, got, report, diags)) << e.name;
            Frame expected = whole;
            CropToRegion(expected, region);
            EXPECT_TRUE(SameBits(got, expected)) << e.name << ": " << region.rects.size();
            EXPECT_GT(got.CoveredCount(), 100u) << e.name << ": " << region.rects.size();
            EXPECT_LT(got.CoveredCount(), whole.CoveredCount()) << e.name;
        }
        EXPECT_TRUE(whole.Covered(125, 30)) << e.name;
        EngineRequest r = Request(e.name);
        r.region = PixelRegion{{{131, 5, 171, 50}}};
        Frame got;
        ASSERT_TRUE(ctx.Render(r, got, report, diags)) << e.name;
        EXPECT_FALSE(got.Covered(125, 30)) << e.name << ": outside the region is background";

        // regionOnly (sort-first): the region's pixels are the same bits; outside it the Frame
        // is left as it was, by raycast (which skips the work there) entirely. The Frame starts
        // as a marker: depth 7, surface 12345.
        r.regionOnly = true;
        r.region = InterleavedBands(300, 60, 1, 3, 8);
        Frame marked(300, 60);
        std::fill(marked.depth.begin(), marked.depth.end(), 7.0);
        std::fill(marked.surface.begin(), marked.surface.end(), 12345);
        ASSERT_TRUE(ctx.Render(r, marked, report, diags)) << e.name;
        Frame inRegion(300, 60), expected(300, 60);
        CopyRegion(inRegion, marked, *r.region);
        CopyRegion(expected, whole, *r.region);
        EXPECT_TRUE(SameBits(inRegion, expected)) << e.name << ": regionOnly";
        if (e.name == "raycast") {
            std::size_t untouched = 0, outside = 0;
            for (int y = 0; y < 60; ++y)
                for (int x = 0; x < 300; ++x) {
                    if (r.region->Contains(x, y)) continue;
                    ++outside;
                    const std::size_t i = marked.Index(x, y);
                    untouched += marked.depth[i] == 7.0 && marked.surface[i] == 12345;
                }
            EXPECT_EQ(untouched, outside) << "raycast wrote outside its region";
            EXPECT_EQ(outside, 300u * 40u);
        }
    }
}

}  // namespace
}  // namespace quadrix
