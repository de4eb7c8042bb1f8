// Engine `patch` end to end on hand-built FlatScenes: options, what is skipped, the --stats
// report, fixed against float, and float against the raycast oracle on random patches.
#include "quadrix/engines/patch/patch_engine.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "quadrix/engines/engine_test_util.h"
#include "quadrix/engines/patch/host_setup.h"
#include "quadrix/engines/patch/patch_test_util.h"
#include "quadrix/engines/raycast/raycast.h"
#include "quadrix/pipeline/stats_report.h"

namespace quadrix {
namespace {

using testing_util::CounterOrFail;

using patch::testing::SceneBuilder;
using patch::testing::Sphere;
using patch::testing::SphereBox;

RenderOptions Options(std::map<std::string, std::string> kv) {
    RenderOptions o;
    o.engineOptions = std::move(kv);
    return o;
}

TEST(PatchEngine, ValidatesItsOptions) {
    auto e = MakePatchEngine();
    EXPECT_EQ(e->Name(), "patch");
    EXPECT_EQ(e->ValidateOptions(Options({})), "");
    EXPECT_EQ(e->ValidateOptions(Options({{"mode", "fixed"},
                                          {"depth-bits", "20"},
                                          {"normal-bits", "12"},
                                          {"caps", "open"},
                                          {"clock-mhz", "100"},
                                          {"compare", "off"},
                                          {"verify", "on"}})),
              "");
    EXPECT_NE(e->ValidateOptions(Options({{"mod", "fixed"}})).find("no option 'mod'"),
              std::string::npos);
    EXPECT_NE(e->ValidateOptions(Options({{"mode", "double"}})), "");
    EXPECT_NE(e->ValidateOptions(Options({{"depth-bits", "64"}})), "");
    EXPECT_NE(e->ValidateOptions(Options({{"depth-bits", "2x"}})), "");
    EXPECT_NE(e->ValidateOptions(Options({{"normal-bits", "30"}})), "");  // > depth-bits
    EXPECT_NE(e->ValidateOptions(Options({{"clock-mhz", "-5"}})), "");
    EXPECT_NE(e->ValidateOptions(Options({{"caps", "maybe"}})), "");
    // Render with bad options draws nothing and says why, never throws.
    SceneBuilder b(8, 8);
    Frame f;
    const RenderStats s = e->Render(b.scene(), Options({{"mode", "x"}}), f);
    EXPECT_EQ(f.CoveredCount(), 0u);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("option 'mode' must be float or fixed"), std::string::npos)
        << s.warnings[0];
}

TEST(PatchEngine, SkipsCsgAndUndrawableBodiesAndReportsThem) {
    SceneBuilder b(32, 32);
    const Vec3 c{16, 16, 50};
    const int q = b.AddQuadric(Sphere(c, 8));
    const int q2 = b.AddQuadric(Sphere(c + Vec3{4, 0, 0}, 8));
    b.AddBody({{q, false}}, SphereBox(c, 8));                                              // drawn
    b.AddBody({{q, false}, {b.AddPlane({1, 0, 0, -16}, false), false}}, SphereBox(c, 8));  // cap
    b.AddBody({{q, false}, {q2, false}}, SphereBox(c, 8));  // two quadrics
    b.AddCsg(scene::CsgOp::kDifference, {{{q, false}}, {{q2, false}}}, SphereBox(c, 8));
    auto e = MakePatchEngine();
    Frame frame;
    const RenderStats s = e->Render(b.scene(), Options({}), frame);
    EXPECT_EQ(CounterOrFail(s, "patches"), 1);
    EXPECT_EQ(CounterOrFail(s, "csg solids skipped"), 1);
    EXPECT_EQ(CounterOrFail(s, "bodies skipped: opaque plane face (caps=skip)"), 1);
    EXPECT_EQ(CounterOrFail(s, "bodies skipped: more than one quadric"), 1);
    EXPECT_NE(s.report.find("cannot do CSG"), std::string::npos) << s.report;
    EXPECT_GT(frame.CoveredCount(), 150u);  // the sphere of radius 8: about 201 pixels
    // caps=open draws the capped body too.
    const RenderStats open = e->Render(b.scene(), Options({{"caps", "open"}}), frame);
    EXPECT_EQ(CounterOrFail(open, "patches"), 2);
    EXPECT_EQ(CounterOrFail(open, "bodies drawn open"), 1);
}

TEST(PatchEngine, StatsReportCyclesTimeAndTheCostTable) {
    SceneBuilder b(40, 40);
    const Vec3 c{20, 20, 100};
    b.AddBody({{b.AddQuadric(Sphere(c, 15)), false}}, SphereBox(c, 15));
    auto e = MakePatchEngine();
    Frame frame;
    const RenderStats s = e->Render(b.scene(), Options({}), frame);
    // One patch with a 30 × 30 window: 900 pixels + the 58-cycle pipeline.
    EXPECT_EQ(CounterOrFail(s, "window pixels"), 900);
    EXPECT_EQ(CounterOrFail(s, "cycles"), 958);
    EXPECT_DOUBLE_EQ(CounterOrFail(s, "estimated seconds"), 958 / 50e6);
    EXPECT_EQ(CounterOrFail(s, "transistors"), 225732);
    // The timing in the report, the paper's tables formatted by the stats report.
    std::string all = s.report;
    for (const StatsTable& t : s.tables) all += FormatStatsTable(t);
    for (const char* text :
         {"50 MHz", "start-up 58 cycles", "Table 1.6", "Table 1.7", "TOTAL", "225732  225732"})
        EXPECT_NE(all.find(text), std::string::npos) << text << "\n" << all;
}

TEST(PatchEngine, FixedModeMatchesFloatAndItsIntegerReference) {
    std::mt19937_64 rng(77);
    SceneBuilder b(40, 40);
    for (int k = 0; k < 5; ++k) patch::testing::AddRandomPatch(b, rng, 3);
    auto e = MakePatchEngine();
    Frame flt, fix;
    e->Render(b.scene(), Options({}), flt);
    const RenderStats s = e->Render(b.scene(), Options({{"mode", "fixed"}, {"verify", "on"}}), fix);
    EXPECT_EQ(CounterOrFail(s, "reference mismatches"), 0);
    EXPECT_NE(s.report.find("depth error histogram"), std::string::npos) << s.report;
    EXPECT_NE(s.report.find("integer reference: 0 of"), std::string::npos) << s.report;
    // Same coverage on all but a few silhouette pixels; depths within the fixed format's
    // error (max error reported in LSB, checked against its a-priori bound in
    // patch_processor_test.cpp); normals within the 16-bit words' resolution.
    std::size_t differ = 0, both = 0;
    double maxDepth = 0, minDot = 1;
    for (std::size_t i = 0; i < flt.depth.size(); ++i) {
        if ((flt.surface[i] == Frame::kNone) != (fix.surface[i] == Frame::kNone) ||
            flt.body[i] != fix.body[i]) {
            ++differ;
            continue;
        }
        if (flt.surface[i] == Frame::kNone) continue;
        ++both;
        maxDepth = std::max<double>(maxDepth, std::fabs(flt.depth[i] - fix.depth[i]));
        minDot = std::min(minDot, Dot(flt.normal[i], fix.normal[i]));
    }
    std::printf(
        "[patch] fixed vs float: %zu pixels agree, %zu differ, max |dz| %.3g, min n.n %.9f\n", both,
        differ, maxDepth, minDot);
    EXPECT_GT(both, 300u);
    EXPECT_LT(differ, both / 50);
    // A priori bound for a 40 × 40 window (host_setup.h), in device units.
    const double bound = patch::DepthErrorBoundLsb({0, 0, 40, 40}) * CounterOrFail(s, "depth ulp");
    EXPECT_LE(CounterOrFail(s, "max depth error lsb"), patch::DepthErrorBoundLsb({0, 0, 40, 40}));
    EXPECT_LE(maxDepth, bound);
    EXPECT_GT(minDot, 1 - 1e-3);  // 16-bit normal words: well within a degree
}

TEST(PatchEngine, DegenerateInputNeverCrashes) {
    // Extreme magnitudes, a zero quadric, a plane seen edge-on, unbounded and NaN bounds, an
    // empty body and a literal naming no half-space; both modes, several widths.
    SceneBuilder b(24, 24);
    Quadric huge = Sphere({12, 12, 50}, 8);
    for (double& k : huge.k) k *= 1e300;
    Quadric tiny = Sphere({12, 12, 50}, 8);
    for (double& k : tiny.k) k *= 1e-300;
    Quadric far = Sphere({12, 12, 1e12}, 1e11);
    b.AddBody({{b.AddQuadric(huge), false}}, Box3::Everything());
    b.AddBody({{b.AddQuadric(tiny), false}}, SphereBox({12, 12, 50}, 8));
    b.AddBody({{b.AddQuadric(far), false}}, Box3::Everything());
    b.AddBody({{b.AddQuadric(Quadric{}), false}}, Box3::Everything());
    b.AddBody({{b.AddQuadric(Sphere({12, 12, 50}, 8)), false},
               {b.AddPlane({1, 0, 1e-18, -12}), false}},  // nearly edge-on
              Box3::Everything());
    const double nan = std::nan("");
    b.AddBody({{b.AddQuadric(Sphere({12, 12, 50}, 8)), false}}, {{nan, nan, nan}, {nan, nan, nan}});
    b.AddBody({}, Box3::Everything());
    b.AddBody({{1234, false}}, Box3::Everything());
    auto e = MakePatchEngine();
    for (const auto& opts : std::vector<std::map<std::string, std::string>>{
             {},
             {{"mode", "fixed"}, {"verify", "on"}},
             {{"mode", "fixed"}, {"depth-bits", "12"}, {"normal-bits", "8"}, {"verify", "on"}},
             {{"mode", "fixed"}, {"depth-bits", "30"}, {"verify", "on"}}}) {
        Frame f;
        const RenderStats s = e->Render(b.scene(), Options(opts), f);
        EXPECT_EQ(f.width, 24);
        for (std::size_t i = 0; i < f.depth.size(); ++i)
            if (f.surface[i] != Frame::kNone) {
                EXPECT_TRUE(std::isfinite(f.depth[i]));
                EXPECT_TRUE(IsFinite(f.normal[i]));
            }
        if (opts.count("verify")) {
            EXPECT_EQ(CounterOrFail(s, "reference mismatches"), 0);
        }
    }
}

// True when a pixel of `f` has an 8-neighbour showing something else (another body, surface or
// background): a silhouette or intersection pixel.
bool OnEdge(const Frame& f, int x, int y) {
    const std::size_t i = f.Index(x, y);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= f.width || yy >= f.height) continue;
            const std::size_t j = f.Index(xx, yy);
            if (f.body[j] != f.body[i] || f.surface[j] != f.surface[i]) return true;
        }
    return false;
}

TEST(PatchVsRaycast, FloatPatchAgreesWithRaycastOnRandomPatches) {
    // 12 scenes × 3 random patches (36 patches, every shape, 0-4 transparent planes incl.
    // perpendicular and complemented ones), z-buffered together.
    auto patchEngine = MakePatchEngine();
    auto raycast = MakeRaycastEngine();
    std::size_t patches = 0, agree = 0, coverageEdge = 0;
    double worstRelative = 0;
    for (int scene = 0; scene < 12; ++scene) {
        std::mt19937_64 rng(1000 + scene);
        SceneBuilder b(40, 40);
        for (int k = 0; k < 3; ++k) patch::testing::AddRandomPatch(b, rng);
        Frame pf, rf;
        const RenderStats ps = patchEngine->Render(b.scene(), Options({}), pf);
        raycast->Render(b.scene(), RenderOptions{}, rf);
        patches += static_cast<std::size_t>(CounterOrFail(ps, "patches"));
        if (rf.CoveredCount() == 0) {
            // Nothing to compare: the patch engine must draw nothing as well (this also fails if
            // raycast were to draw nothing while the patches are visible).
            EXPECT_EQ(pf.CoveredCount(), 0u);
            continue;
        }
        double zlo = HUGE_VAL, zhi = -HUGE_VAL;
        for (std::size_t i = 0; i < rf.depth.size(); ++i)
            if (rf.surface[i] != Frame::kNone) {
                zlo = std::min<double>(zlo, rf.depth[i]);
                zhi = std::max<double>(zhi, rf.depth[i]);
            }
        const double range = std::max(zhi - zlo, 1.0);
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 40; ++x) {
                const std::size_t i = rf.Index(x, y);
                const bool same = pf.surface[i] == rf.surface[i] && pf.body[i] == rf.body[i];
                if (!same) {
                    // Coverage may differ only on silhouette (and intersection) pixels.
                    EXPECT_TRUE(OnEdge(rf, x, y) || OnEdge(pf, x, y))
                        << "scene " << scene << " pixel " << x << "," << y << " patch body "
                        << pf.body[i] << " raycast body " << rf.body[i];
                    ++coverageEdge;
                    continue;
                }
                if (rf.surface[i] == Frame::kNone) continue;
                ++agree;
                const double rel = std::fabs(pf.depth[i] - rf.depth[i]) / range;
                worstRelative = std::max(worstRelative, rel);
                EXPECT_LE(rel, 1e-6) << "scene " << scene << " pixel " << x << "," << y;
                // Normals: both from the gradient at the same point; 1e-6 allows the last bits.
                EXPECT_GT(Dot(pf.normal[i], rf.normal[i]), 1 - 1e-6) << x << "," << y;
            }
    }
    std::printf(
        "[patch] vs raycast: %zu patches, %zu pixels agree, %zu edge pixels differ, "
        "worst depth error %.3g of range\n",
        patches, agree, coverageEdge, worstRelative);
    EXPECT_GE(patches, 30u);
    EXPECT_GT(agree, 5000u);
    EXPECT_LT(coverageEdge, agree / 50);
}

}  // namespace
}  // namespace quadrix
