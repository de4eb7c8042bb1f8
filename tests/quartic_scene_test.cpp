// Quartic solids (torus, elliptical torus, general cone; math/quartic_surface.h) through the whole
// pipeline: analytic areas and per-pixel classification against the closed-form shapes, CSG with
// quadrics and planes, exact normals, composition for the engines that cannot draw them, strict
// refusal, the drawer's refusal and the language's errors.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "quadrix/frame/compare.h"
#include "quadrix/pipeline/pipeline.h"
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
                            const std::string& engine = "raycast", bool strict = false) {
    auto run = std::make_unique<Run>();
    PipelineOptions o;
    o.sceneText = text;
    o.width = w;
    o.height = h;
    o.engine = engine;
    o.strict = strict;
    run->ok = RunPipeline(o, run->r, run->d);
    return run;
}

int Covered(const Frame& f) {
    int n = 0;
    for (auto s : f.surface) n += s != Frame::kNone;
    return n;
}

// 200 × 200 pixels over [−2, 2]²: 50 px per unit, world (x, y) at pixel centre (i + ½, j + ½) is
// x = (i + ½ − 100) / 50, y = (100 − j − ½) / 50; rays along +z.
constexpr const char* kFrontView = "view front dop 0 0 -1 whw 2 whh 2;\n";
constexpr double kPx = 50;

// Pixels whose centre is classified wrongly by `inside`, leaving out those within `margin` px
// of a boundary (`distance` gives the distance, in world units, to the nearest boundary).
int Misclassified(const Frame& f, const std::function<bool(double, double)>& inside,
                  const std::function<double(double, double)>& distance, double margin = 1.0) {
    int bad = 0;
    for (int j = 0; j < f.height; ++j)
        for (int i = 0; i < f.width; ++i) {
            const double x = (i + 0.5 - 100) / kPx, y = (100 - j - 0.5) / kPx;
            if (distance(x, y) * kPx < margin) continue;
            bad += (f.surface[f.Index(i, j)] != Frame::kNone) != inside(x, y);
        }
    return bad;
}

TEST(QuarticScene, TorusSeenAlongItsAxisIsAnAnnulus) {
    auto run = Render(std::string(kFrontView) + "solid torus ring =r 1.2 .5;\n", 200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    const Frame& f = run->r.frame;
    const double area = M_PI * (1.7 * 1.7 - 0.7 * 0.7) * kPx * kPx;
    EXPECT_NEAR(Covered(f), area, M_PI * (1.7 + 0.7) * kPx);  // ±½ px of both circles
    auto rho = [](double x, double y) { return std::hypot(x, y); };
    EXPECT_EQ(Misclassified(
                  f, [&](double x, double y) { return rho(x, y) > 0.7 && rho(x, y) < 1.7; },
                  [&](double x, double y) {
                      return std::fmin(std::fabs(rho(x, y) - 0.7), std::fabs(rho(x, y) - 1.7));
                  }),
              0);
    // Exact normals: at a tube point seen from −z, (d x/ρ, d y/ρ, −√(r² − d²)) / r with d = ρ − R.
    for (int i : {140, 160, 180}) {
        const double x = (i + 0.5 - 100) / kPx, y = (100 - 100 - 0.5) / kPx, rh = rho(x, y);
        const double d = rh - 1.2, dz = std::sqrt(0.25 - d * d);
        const std::size_t k = f.Index(i, 100);
        ASSERT_NE(f.surface[k], Frame::kNone);
        const double tol = 1e-9 + PackedNormal::kMaxError;  // the Frame's packed normal
        EXPECT_NEAR(f.Normal(k).x, d * x / rh / 0.5, tol) << i;
        EXPECT_NEAR(f.Normal(k).y, d * y / rh / 0.5, tol) << i;
        EXPECT_NEAR(f.Normal(k).z, -dz / 0.5, tol) << i;
    }
}

TEST(QuarticScene, TorusSeenSidewaysIsAStadium) {
    // Axis y, seen along z: every point within r of the segment |x| <= R (area 4Rr + πr²).
    auto run =
        Render(std::string(kFrontView) + "solid torus ring =r 1.2 .5 =axis 0 1 0;\n", 200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    auto dist = [](double x, double y) { return std::hypot(std::fmax(std::fabs(x) - 1.2, 0), y); };
    EXPECT_EQ(Misclassified(
                  run->r.frame, [&](double x, double y) { return dist(x, y) < 0.5; },
                  [&](double x, double y) { return std::fabs(dist(x, y) - 0.5); }),
              0);
    EXPECT_NEAR(Covered(run->r.frame), (4 * 1.2 * 0.5 + M_PI * 0.25) * kPx * kPx,
                (4 * 1.2 + M_PI * 0.5) * kPx);
}

TEST(QuarticScene, TorusMinusCylinderAndTorusCutByAPlane) {
    // A cylinder along the view drills the tube at (1.2, 0); the half-space y <= 0 keeps half.
    auto run = Render(std::string(kFrontView) +
                          "solid torus ring =r 1.2 .5;\n"
                          "solid cylinder drill =from 1.2 0 -2 =to 1.2 0 2 =r .3;\n"
                          "csg drilled (ring - drill);\n"
                          "solid halfspace cut =n 0 1 0 =at 0 0 0;\n"
                          "solid torus ring2 =r 1.2 .5 =at 0 0 5 =hsb;\n",
                      200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    auto rho = [](double x, double y) { return std::hypot(x, y); };
    auto inside = [&](double x, double y) {
        return rho(x, y) > 0.7 && rho(x, y) < 1.7 && std::hypot(x - 1.2, y) > 0.3;
    };
    auto dist = [&](double x, double y) {
        return std::fmin(std::fmin(std::fabs(rho(x, y) - 0.7), std::fabs(rho(x, y) - 1.7)),
                         std::fabs(std::hypot(x - 1.2, y) - 0.3));
    };
    EXPECT_EQ(Misclassified(run->r.frame, inside, dist), 0);
    // Inside the drilled hole one sees through: nothing behind.
    EXPECT_EQ(run->r.frame.surface[run->r.frame.Index(160, 100)], Frame::kNone);

    auto half = Render(std::string(kFrontView) +
                           "solid torus ring =r 1.2 .5 =hsb;\n"
                           "solid halfspace cut =n 0 1 0 =at 0 0 0;\n"
                           "body half (ring cut);\n",
                       200, 200);
    ASSERT_TRUE(half->ok) << half->Messages();
    EXPECT_EQ(Misclassified(
                  half->r.frame,
                  [&](double x, double y) { return rho(x, y) > 0.7 && rho(x, y) < 1.7 && y < 0; },
                  [&](double x, double y) {
                      return std::fmin(
                          std::fmin(std::fabs(rho(x, y) - 0.7), std::fabs(rho(x, y) - 1.7)),
                          std::fabs(y));
                  }),
              0);
}

TEST(QuarticScene, ComplementedTorusInABody) {
    // A slab with a torus cut out of it (! literal: three pieces on rays through both tubes).
    auto run = Render(std::string(kFrontView) +
                          "solid torus ring =r 1.2 .5 =axis 0 1 0 =hsb;\n"
                          "solid box slab =from -1.9 -.2 -1 =to 1.9 .2 1 =hsb;\n"
                          "body slabbed (slab#x0 slab#x1 slab#y0 slab#y1 slab#z0 slab#z1 !ring);\n",
                      200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    // Along z through (x, y) the slab keeps z ∈ [−1, 1], where ρ = √(x² + z²) runs over
    // [|x|, √(x² + 1)]; the ray sees the body unless that whole range lies in the tube,
    // |ρ − 1.2| <= w = √(.25 − y²).
    auto slack = [](double x, double y, int which) {
        const double w = std::sqrt(0.25 - y * y);
        return which == 0 ? std::fabs(x) - (1.2 - w) : (1.2 + w) - std::sqrt(x * x + 1);
    };
    auto inside = [&](double x, double y) {
        if (!(std::fabs(x) < 1.9 && std::fabs(y) < 0.2)) return false;
        return !(slack(x, y, 0) >= 0 && slack(x, y, 1) >= 0);
    };
    auto dist = [&](double x, double y) {
        double d = std::fmin(std::fabs(std::fabs(x) - 1.9), std::fabs(std::fabs(y) - 0.2));
        if (std::fabs(y) < 0.2)  // the slacks change by at most ~1 per unit (|∂/∂x|, |∂/∂y| <= 1)
            d = std::fmin(d, std::fmin(std::fabs(slack(x, y, 0)), std::fabs(slack(x, y, 1))));
        return d;
    };
    EXPECT_EQ(Misclassified(run->r.frame, inside, dist), 0);
    // At x = 0 the tube takes z ∈ [−1.7, −0.7] out of the slab's front: the visible surface is
    // the torus itself (its complement bounds the body), at z = −0.7.
    const Frame& f = run->r.frame;
    const int s = f.surface[f.Index(100, 100)];
    ASSERT_NE(s, Frame::kNone);
    EXPECT_TRUE(run->r.flat.halfSpaces[static_cast<std::size_t>(s)].IsQuartic());
}

TEST(QuarticScene, GeneralConeSectionsAndCaps) {
    // Seen along its axis the tgc's outline is the larger of its ends in each direction: base
    // 1.6 × 0.4, top 0.4 × 1.2 (the union of the sections' ellipses, bounded by both ends'
    // ellipses' hull). At the centre one sees the top cap.
    auto run = Render(std::string(kFrontView) +
                          "solid tgc leg =v 0 0 1 =h 0 0 -2 =a 1.6 0 0 =b 0 .4 0 =top .4 1.2;\n",
                      200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    const Frame& f = run->r.frame;
    const auto& hs = run->r.flat.halfSpaces;
    const int centre = f.surface[f.Index(100, 100)];
    ASSERT_NE(centre, Frame::kNone);
    EXPECT_FALSE(hs[static_cast<std::size_t>(centre)].IsQuartic());  // a cap plane (nearest: top)
    EXPECT_NEAR(f.Normal(f.Index(100, 100)).z, -1, 1e-12);
    // On the x axis beyond the top ellipse (|x| > .4) the side is seen, out to the base's 1.6.
    const int side = f.surface[f.Index(100 + 50, 100)];
    ASSERT_NE(side, Frame::kNone);
    EXPECT_TRUE(hs[static_cast<std::size_t>(side)].IsQuartic());
    EXPECT_NE(f.surface[f.Index(100 + 78, 100)], Frame::kNone);
    EXPECT_EQ(f.surface[f.Index(100 + 82, 100)], Frame::kNone);
    EXPECT_NE(f.surface[f.Index(100, 100 - 58)], Frame::kNone);
    EXPECT_EQ(f.surface[f.Index(100, 100 - 62)], Frame::kNone);
    // The side at x ≈ 1 lies behind the top cap (farther along the rays).
    EXPECT_GT(f.depth[f.Index(150, 100)], f.depth[f.Index(100, 100)]);
}

TEST(QuarticScene, EllipticalTorusMatchesItsMeridianEllipse) {
    // Seen along its axis, an eto whose ellipse (semi-axes 0.6 along the radius, 0.3 along the
    // axis) has no tilt is the annulus 1.2 ± 0.6.
    auto run =
        Render(std::string(kFrontView) + "solid etorus e =r 1.2 =e .6 0 0 =d .3;\n", 200, 200);
    ASSERT_TRUE(run->ok) << run->Messages();
    auto rho = [](double x, double y) { return std::hypot(x, y); };
    EXPECT_EQ(
        Misclassified(
            run->r.frame, [&](double x, double y) { return std::fabs(rho(x, y) - 1.2) < 0.6; },
            [&](double x, double y) { return std::fabs(std::fabs(rho(x, y) - 1.2) - 0.6); }),
        0);
}

TEST(QuarticScene, OtherEnginesComposeQuarticsFromRaycast) {
    const std::string text =
        "solid torus ring =r 1.2 .4 =axis 0 1 1;\n"
        "solid sphere ball =at 0 0 0 =r .7 =c 1 0 0;\n"
        "solid cylinder rod =from -2 0 0 =to 2 0 0 =r .2;\n"
        "csg cut (ring - rod);\n"
        "view v dop .3 .4 -1 whw 2 whh 2;\n";
    auto ref = Render(text, 120, 120);
    ASSERT_TRUE(ref->ok) << ref->Messages();
    for (const char* engine : {"scanline", "pixelpowers", "patch", "isocurve"}) {
        auto got = Render(text, 120, 120, engine);
        ASSERT_TRUE(got->ok) << engine << ": " << got->Messages();
        const FrameComparison cmp = CompareFrames(got->r.frame, ref->r.frame, {});
        EXPECT_EQ(cmp.offEdgeDifferences, 0u) << engine << ": " << cmp.Summary();
        bool noted = false;
        for (const std::string& n : got->r.report.notes)
            noted |= n.find("quartic") != std::string::npos;
        EXPECT_TRUE(noted || std::string(engine) == "isocurve") << engine;
        // --strict refuses, naming the primitive.
        auto strict = Render(text, 60, 60, engine, true);
        EXPECT_FALSE(strict->ok) << engine;
        if (std::string(engine) != "isocurve") {  // (isocurve draws no solid at all)
            EXPECT_NE(strict->Messages().find("torus"), std::string::npos) << strict->Messages();
        }
    }
}

TEST(QuarticScene, BadParametersAreErrorsAtTheirPositions) {
    struct Case {
        const char* text;
        const char* where;
        const char* what;
    };
    const Case cases[] = {
        {"solid torus t =r 1 2;", "1:15", "smaller than its major radius"},
        {"solid torus t =r 2 1 =axis 0 0 0;", "1:22", "non-zero vector"},
        {"solid torus t =r 2 0;", "1:15", "must be > 0"},
        {"solid etorus e =r 1 =e 2 0 0 =d .5;", "1:16", "reaches the axis"},
        {"solid tgc g =v 0 0 0 =h 1 0 0 =a 1 0 0 =b 0 1 0 =top 1 2;", "1:22", "plane of A and B"},
        {"solid tgc g =v 0 0 0 =h 0 0 1 =a 1 0 0 =b 1 1 0 =top 1 2;", "1:22", "perpendicular"},
        {"solid tgc g =v 0 0 0 =h 0 0 1 =a 1 0 0 =b 0 1 0 =top -1 2;", "1:49", ">= 0"},
    };
    for (const Case& c : cases) {
        auto run = Render(c.text, 40, 40);
        EXPECT_FALSE(run->ok) << c.text;
        const std::string m = run->Messages();
        EXPECT_NE(m.find(c.where), std::string::npos) << c.text << "\n" << m;
        EXPECT_NE(m.find(c.what), std::string::npos) << c.text << "\n" << m;
    }
}

TEST(QuarticScene, DrawRefusesQuarticsByName) {
    TempDir dir;
    const std::string scene = dir.Write("t.uq", "solid torus ring =r 2 .5;\n");
    CommandResult r =
        RunShell(QuadrixBinary() + " draw '" + scene + "' -o '" + dir.File("t.svg") + "'");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("torus"), std::string::npos) << r.err;
    EXPECT_FALSE(FileExists(dir.File("t.svg")));
}

}  // namespace
}  // namespace quadrix::testing

namespace quadrix::testing {
namespace {

// The example scene renders, and the composition for an engine without quartics gives the
// reference picture away from edges.
TEST(QuarticScene, ExampleSceneRendersAndComposes) {
    PipelineOptions o;
    o.scenePaths = {SourcePath("examples/quartics.uq")};
    o.width = 120;
    o.height = 80;
    PipelineResult ref, scan;
    Diagnostics d;
    ASSERT_TRUE(RunPipeline(o, ref, d));
    o.engine = "scanline";
    ASSERT_TRUE(RunPipeline(o, scan, d));
    EXPECT_GT(ref.frame.CoveredCount(), 2000u);
    EXPECT_EQ(CompareFrames(scan.frame, ref.frame, {}).offEdgeDifferences, 0u);
}

}  // namespace
}  // namespace quadrix::testing
