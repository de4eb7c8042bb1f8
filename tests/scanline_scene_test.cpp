// Engine `scanline` against the oracle `raycast`, pixel by pixel, on unit scenes (the degenerate
// cases of seed 001 §4.4 and §5.5.1), on every example scene and on generated scenes with random
// views (parallel and perspective).
//
// Agreement criteria and why:
//  - Coverage and surface id: `scanline` evaluates a pixel exactly (with raycast's own interval
//    code) whenever its centre lies within 1e-6 px of a traced show-edge, and otherwise takes the
//    face found by exact evaluation at one pixel of the same span. A difference is therefore only
//    possible where a crossing traced by finite differences is off by more than 1e-6 px, or where
//    the Resolver missed a boundary; the first can only happen next to a silhouette. So we allow
//    mismatches only on "edge pixels" (a 4-neighbour in the raycast frame has a different surface
//    or coverage), and at most 0.5 % of covered pixels in all (issue 3: >= 99.5 %).
//  - Depth: within 1e-6 of the scene's depth range on pixels with the same surface (the span
//    shader's difference-updated conic agrees with the per-pixel solve to ~1e-12 relative).
//  - Normals: within 1e-6 (unit vectors from the same gradient formula).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <tuple>

#include "quadrix/engines/engine.h"
#include "quadrix/engines/engine_test_util.h"
#include "quadrix/engines/scanline/renderer.h"
#include "quadrix/flatten/test_scene_builder.h"
#include "quadrix/frame/compare.h"
#include "quadrix/pipeline/pipeline.h"
#include "test_util.h"

namespace quadrix {
namespace {

using testing_util::Counter;
using testing_util::RenderWith;
using testing_util::TestSceneBuilder;

// scanline against raycast through the one comparison (frame/compare.h), plus the depth range of
// the reference, which scales the depth tolerance.
struct Agreement {
    FrameComparison cmp;
    std::size_t covered = 0, mismatches = 0, interiorMismatches = 0;
    double maxDepthError = 0, depthRange = 0, maxNormalErrorDegrees = 0;
    std::string firstInterior;
};

Agreement Compare(const Frame& ref, const Frame& got) {
    Agreement a;
    a.cmp = CompareFrames(got, ref);
    double zlo = HUGE_VAL, zhi = -HUGE_VAL;
    for (double z : ref.depth)
        if (std::isfinite(z)) zlo = std::min(zlo, z), zhi = std::max(zhi, z);
    a.depthRange = zhi > zlo ? zhi - zlo : 1;
    a.covered = a.cmp.coveredBoth + a.cmp.onlyReference;
    a.mismatches = a.cmp.onlyA + a.cmp.onlyReference + a.cmp.surfaceDiffers;
    a.interiorMismatches = a.cmp.offEdgeDifferences;
    a.firstInterior = a.cmp.firstDifference;
    a.maxDepthError = a.cmp.maxDepthError;
    a.maxNormalErrorDegrees = a.cmp.maxNormalErrorDegrees;
    return a;
}

void ExpectAgree(const Frame& ref, const Frame& got, const std::string& what) {
    Agreement a = Compare(ref, got);
    if (std::getenv("SCANLINE_DUMP"))
        std::fprintf(stderr,
                     "%s: covered %zu mismatches %zu (interior %zu) depth err %.3g of %.3g\n",
                     what.substr(0, what.find('\n')).c_str(), a.covered, a.mismatches,
                     a.interiorMismatches, a.maxDepthError, a.depthRange);
    SCOPED_TRACE(what);
    EXPECT_EQ(a.interiorMismatches, 0u) << "first interior mismatch " << a.firstInterior;
    EXPECT_LE(static_cast<double>(a.mismatches), 0.005 * std::max<double>(a.covered, 1))
        << a.mismatches << " of " << a.covered;
    EXPECT_LE(a.maxDepthError, 1e-6 * a.depthRange);
    EXPECT_LE(a.maxNormalErrorDegrees, 1e-6 * 180 / M_PI);  // 1e-6 radians
}

void CheckScene(FlatScene& scene, const std::string& what, std::size_t minCovered = 1) {
    Frame ref = RenderWith("raycast", scene);
    RenderStats stats;
    Frame got = RenderWith("scanline", scene, &stats);
    EXPECT_GE(ref.CoveredCount(), minCovered) << what << ": scene draws too little to test";
    EXPECT_LE(Counter(stats, "root_fallback_pixels"),
              5 + 0.002 * static_cast<double>(ref.CoveredCount()))
        << what;
    ExpectAgree(ref, got, what);
}

std::array<double, 10> Sphere(Vec3 c, double r) {
    return {1, 1, 1, 0, 0, 0, -c.x, -c.y, -c.z, Dot(c, c) - r * r};
}

TEST(ScanlineScene, Sphere) {
    TestSceneBuilder b(96, 80);
    int s = b.AddQuadric(Sphere({40.3, 37.7, 50}, 25.3));
    b.AddSolidOfBody(b.AddBody({{s, false}}));
    RenderStats stats;
    Frame got = RenderWith("scanline", b.scene(), &stats);
    ExpectAgree(RenderWith("raycast", b.scene()), got, "sphere");
    EXPECT_GT(Counter(stats, "show_edges_conic"), 0);
    EXPECT_GT(Counter(stats, "ivertices_VEXTRM"), 0);
    EXPECT_GT(Counter(stats, "ivertices_HEXTRM"), 0);
    // Work grows with spans, not pixels × surfaces: few exact evaluations.
    EXPECT_LT(Counter(stats, "span_sample_evaluations"), 3 * 80);
    EXPECT_LE(Counter(stats, "root_fallback_pixels"), 2);
}

TEST(ScanlineScene, CylinderAlongTheViewAxisWithTiltedCaps) {
    TestSceneBuilder b(80, 80);
    int cyl = b.AddQuadric({1, 1, 0, 0, 0, 0, -40, -41, 0, 40 * 40 + 41 * 41 - 27.5 * 27.5});
    int front = b.AddPlane(0.2, 0.1, -1, 10);  // z >= 0.2x + 0.1y + 10
    int back = b.AddPlane(0, 0, 1, -90);
    b.AddSolidOfBody(b.AddBody({{cyl, false}, {front, false}, {back, false}}));
    CheckScene(b.scene(), "view-axis cylinder", 2000);
}

TEST(ScanlineScene, TubeOfTwoCoaxialCylindersSeenEndOn) {
    TestSceneBuilder b(80, 80);
    int outer = b.AddQuadric({1, 1, 0, 0, 0, 0, -40, -40, 0, 3200 - 900});
    int inner = b.AddQuadric({1, 1, 0, 0, 0, 0, -40, -40, 0, 3200 - 225});
    int front = b.AddPlane(0.1, 0.3, -1, 5);
    int back = b.AddPlane(0, 0, 1, -90);
    b.AddSolidOfBody(b.AddBody({{outer, false}, {inner, true}, {front, false}, {back, false}}));
    RenderStats stats;
    Frame got = RenderWith("scanline", b.scene(), &stats);
    ExpectAgree(RenderWith("raycast", b.scene()), got, "tube end-on");
    EXPECT_EQ(Counter(stats, "per_pixel_bodies"), 0);  // the pencil test proved them disjoint
}

TEST(ScanlineScene, ConeApexAtAPixelCentre) {
    TestSceneBuilder b(80, 80);
    // (x−40.5)² + (y−40.5)² − 0.36 (z−20)² <= 0, nappe z >= 20, cut at z <= 80: apex toward us.
    const double cx = 40.5, cy = 40.5, cz = 20, k = 0.36;
    int cone = b.AddQuadric({1, 1, -k, 0, 0, 0, -cx, -cy, k * cz, cx * cx + cy * cy - k * cz * cz});
    int nappe = b.AddPlane(0, 0, -1, cz);
    int cut = b.AddPlane(0.3, 0, 1, -80 - 0.3 * 40);
    b.AddSolidOfBody(b.AddBody({{cone, false}, {nappe, false}, {cut, false}}));
    CheckScene(b.scene(), "cone apex", 1000);
}

TEST(ScanlineScene, ConeSeenFromTheSide) {
    TestSceneBuilder b(96, 64);
    // Axis along x: (y−32)² + (z−50)² − 0.25 (x−20)² <= 0, 20 <= x <= 80.
    int cone = b.AddQuadric({-0.25, 1, 1, 0, 0, 0, 5, -32, -50, 1024 + 2500 - 100});
    int l = b.AddPlane(-1, 0, 0, 20), r = b.AddPlane(1, 0, 0.2, -80 - 10);
    b.AddSolidOfBody(b.AddBody({{cone, false}, {l, false}, {r, false}}));
    CheckScene(b.scene(), "cone from the side", 500);
}

TEST(ScanlineScene, PlanesEdgeOnAndAHemisphere) {
    TestSceneBuilder b(90, 70);
    // A box whose left and right faces are edge-on, the front tilted.
    int x0 = b.AddPlane(-1, 0, 0, 10), x1 = b.AddPlane(1, 0, 0, -40);
    int y0 = b.AddPlane(0, -1, 0, 10.25), y1 = b.AddPlane(0, 1, 0, -50.5);
    int f = b.AddPlane(0.3, 0.1, -1, 10), bk = b.AddPlane(0, 0, 1, -80);
    b.AddSolidOfBody(
        b.AddBody({{x0, false}, {x1, false}, {y0, false}, {y1, false}, {f, false}, {bk, false}}));
    // A sphere halved by an edge-on plane x <= 65.
    int s = b.AddQuadric(Sphere({65, 35, 50}, 20));
    int cut = b.AddPlane(1, 0, 0, -65);
    b.AddSolidOfBody(b.AddBody({{s, false}, {cut, false}}));
    CheckScene(b.scene(), "edge-on planes", 1500);
}

TEST(ScanlineScene, HemisphereCutAtItsLimbPlane) {  // tangent plane/quadric degenerate case
    TestSceneBuilder b(80, 80);
    int s = b.AddQuadric(Sphere({40, 40, 50}, 30));
    int limbPlane = b.AddPlane(0, 0, 1, -50);  // z <= 50: exactly the limb plane
    b.AddSolidOfBody(b.AddBody({{s, false}, {limbPlane, false}}));
    int s2 = b.AddQuadric(Sphere({40, 40, 150}, 30));
    int lp2 = b.AddPlane(0, 0, -1, 150);  // z >= 150: the front half cut away, inside visible
    b.AddSolidOfBody(b.AddBody({{s2, false}, {lp2, false}}));
    CheckScene(b.scene(), "hemispheres at the limb plane", 2000);
}

TEST(ScanlineScene, TangentSpheres) {
    TestSceneBuilder b(100, 60);
    int a = b.AddQuadric(Sphere({30, 30, 50}, 20));
    int c = b.AddQuadric(Sphere({70, 30, 50}, 20));  // touching at (50, 30, 50)
    int d = b.AddQuadric(Sphere({50, 30, 90}, 20));  // behind, touching neither
    b.AddSolidOfBody(b.AddBody({{a, false}}));
    b.AddSolidOfBody(b.AddBody({{c, false}}));
    b.AddSolidOfBody(b.AddBody({{d, false}}));
    CheckScene(b.scene(), "tangent spheres", 2000);
}

TEST(ScanlineScene, PyramidApexWhereFourPlanesMeet) {
    TestSceneBuilder b(80, 80);
    // Apex (40, 40, 10) toward the viewer; four sides through it; base z <= 60.
    const Vec3 apex{40, 40, 10};
    std::vector<std::pair<int, bool>> lits;
    for (auto [nx, ny] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}}) {
        Plane p{nx, ny, -0.6, 0};
        p.d = -(p.a * apex.x + p.b * apex.y + p.c * apex.z);
        lits.push_back({b.AddPlane(p.a, p.b, p.c, p.d), false});
    }
    lits.push_back({b.AddPlane(0, 0, 1, -60), false});
    b.AddSolidOfBody(b.AddBody(lits));
    RenderStats stats;
    Frame got = RenderWith("scanline", b.scene(), &stats);
    ExpectAgree(RenderWith("raycast", b.scene()), got, "pyramid");
    // The apex is one merged i-vertex on each of the four side lines (zero test (5)).
    EXPECT_GT(Counter(stats, "ivertices_ISECT"), 0);
}

TEST(ScanlineScene, HorizontalEdgesAndEqualDepthsAlongAnEdge) {
    TestSceneBuilder b(80, 80);
    // Two boxes sharing the edge y = 40 (a horizontal edge) at equal depth there (Figure 5.1 a/b).
    int top0 = b.AddPlane(0, -1, 0, 10), mid = b.AddPlane(0, 1, 0, -40);
    int l = b.AddPlane(-1, 0, 0, 10), r = b.AddPlane(1, 0, 0, -70);
    int f1 = b.AddPlane(0, 0.5, -1, 10), bk = b.AddPlane(0, 0, 1, -100);
    b.AddSolidOfBody(
        b.AddBody({{top0, false}, {mid, false}, {l, false}, {r, false}, {f1, false}, {bk, false}}));
    int mid2 = b.AddPlane(0, -1, 0, 40), bot = b.AddPlane(0, 1, 0, -70);
    int f2 = b.AddPlane(0, -0.5, -1, 50);  // z = 50 − 0.5 y: equals f1's z = 10 + 0.5 y at y = 40
    b.AddSolidOfBody(
        b.AddBody({{mid2, false}, {bot, false}, {l, false}, {r, false}, {f2, false}, {bk, false}}));
    CheckScene(b.scene(), "horizontal shared edge", 3000);
}

TEST(ScanlineScene, IntersectingQuadricsInOneBodyFallBackPerPixel) {
    TestSceneBuilder b(80, 80);
    int s = b.AddQuadric(Sphere({40, 40, 50}, 30));
    int hole = b.AddQuadric(Sphere({55, 35, 30}, 15));
    b.AddSolidOfBody(b.AddBody({{s, false}, {hole, true}}));
    RenderStats stats;
    Frame got = RenderWith("scanline", b.scene(), &stats);
    ExpectAgree(RenderWith("raycast", b.scene()), got, "sphere with a bite");
    EXPECT_EQ(Counter(stats, "per_pixel_bodies"), 1);
}

TEST(ScanlineScene, UnboundedBodiesWithoutShowEdges) {
    // Bodies whose regions reach the image sides: a half-space, the outside of a sphere, a
    // paraboloid opening along the view (C = 0: no limb), a two-sheet hyperboloid across the view.
    struct Case {
        const char* name;
        std::function<void(TestSceneBuilder&)> build;
    };
    std::vector<Case> cases = {
        {"half-space",
         [](TestSceneBuilder& b) {
             b.AddSolidOfBody(b.AddBody({{b.AddPlane(0.1, 0.2, -1, 20), false}}));
         }},
        {"outside of a sphere",
         [](TestSceneBuilder& b) {
             b.AddSolidOfBody(b.AddBody({{b.AddQuadric(Sphere({40, 30, 50}, 20)), true}}));
         }},
        {"paraboloid along the view",
         [](TestSceneBuilder& b) {
             // (x−40)² + (y−30)² − 4 (z − 10) <= 0
             b.AddSolidOfBody(b.AddBody(
                 {{b.AddQuadric({1, 1, 0, 0, 0, 0, -40, -30, -2, 1600 + 900 + 40}), false}}));
         }},
        {"two-sheet hyperboloid",
         [](TestSceneBuilder& b) {
             // (x−40)²/4 − (y−30)² − (z−50)² − 25 >= 0 … i.e. −(…) <= 0: two sheets along x.
             b.AddSolidOfBody(b.AddBody(
                 {{b.AddQuadric({-0.25, 1, 1, 0, 0, 0, 10, -30, -50, -400 + 900 + 2500 + 25}),
                   false}}));
         }},
    };
    for (const Case& c : cases) {
        TestSceneBuilder b(80, 60);
        c.build(b);
        CheckScene(b.scene(), c.name, 500);
    }
}

TEST(ScanlineScene, CsgDifferenceIsEvaluatedPerPixel) {
    TestSceneBuilder b(80, 80);
    int s = b.AddQuadric(Sphere({40, 40, 50}, 30));
    int cyl = b.AddQuadric({1, 1, 0, 0, 0, 0, -45, -40, 0, 45 * 45 + 1600 - 100});
    int body = b.AddBody({{s, false}});
    int drill = b.AddBody({{cyl, false}});
    int root = b.AddNode(scene::CsgOp::kDifference, {b.AddLeaf(body), b.AddLeaf(drill)});
    b.AddSolid(root);
    CheckScene(b.scene(), "csg difference", 1000);
}

TEST(ScanlineScene, DepthTieBreaksOfFigure51) {
    TestSceneBuilder b(10, 10);
    // (a)/(b): two planes through the same line, different slopes.
    int p1 = b.AddPlane(0.5, 0, -1, 10);   // z = 0.5 x + 10
    int p2 = b.AddPlane(-0.5, 0, -1, 10);  // z = −0.5 x + 10 (meets p1 at x = 0)
    // (c): a plane tangent to a sphere at (0, 0, 10): z = 10 and the sphere centred at z = 20.
    int t = b.AddPlane(0, 0, -1, 10);
    int s = b.AddQuadric(Sphere({0, 0, 20}, 10));
    const FlatScene& sc = b.scene();
    using scanline::CompareFaces;
    using scanline::FaceRef;
    // At x = 0 the depths tie; one step on, p2 is nearer (its z decreases).
    EXPECT_EQ(CompareFaces(sc, {p1, 0}, {p2, 0}, 0, 0, 1e-9), 1);
    EXPECT_EQ(CompareFaces(sc, {p2, 0}, {p1, 0}, 0, 0, 1e-9), -1);
    // Tangent plane and sphere front sheet: equal depth and slope; the plane has the smaller rate
    // of change (0 against the sphere's positive d²z/dx²) and is in front.
    EXPECT_EQ(CompareFaces(sc, {t, 0}, {s, 0}, 0, 0, 1e-9), -1);
    EXPECT_EQ(CompareFaces(sc, {s, 0}, {t, 0}, 0, 0, 1e-9), 1);
    // The same face against itself is coincident.
    EXPECT_EQ(CompareFaces(sc, {s, 0}, {s, 0}, 3, 2, 1e-9), 0);
    // FaceDerivatives: the full chain rule against finite differences on the sphere.
    double z, dz, d2z, zp, zm, tmp1, tmp2;
    ASSERT_TRUE(scanline::FaceDerivatives(sc, {s, 0}, 3, 2, z, dz, d2z));
    ASSERT_TRUE(scanline::FaceDerivatives(sc, {s, 0}, 3 + 1e-4, 2, zp, tmp1, tmp2));
    ASSERT_TRUE(scanline::FaceDerivatives(sc, {s, 0}, 3 - 1e-4, 2, zm, tmp1, tmp2));
    EXPECT_NEAR(dz, (zp - zm) / 2e-4, 1e-7);
    EXPECT_NEAR(d2z, (zp - 2 * z + zm) / 1e-8, 1e-4);
}

TEST(ScanlineScene, ShadingIntervalAndFastShading) {
    TestSceneBuilder b(96, 96);
    int s = b.AddQuadric(Sphere({48, 48, 60}, 40));
    b.AddSolidOfBody(b.AddBody({{s, false}}));
    Frame ref = RenderWith("raycast", b.scene());
    RenderStats exact, coarse, fast;
    Frame f1 = RenderWith("scanline", b.scene(), &exact);
    Frame f4 = RenderWith("scanline", b.scene(), &coarse, {{"sd", "4"}});
    Frame ff = RenderWith("scanline", b.scene(), &fast, {{"shade", "fast"}});
    // Depth and coverage never depend on the shading options.
    for (const Frame* f : {&f1, &f4, &ff}) {
        Agreement a = Compare(ref, *f);
        EXPECT_EQ(a.interiorMismatches, 0u);
        EXPECT_LE(a.maxDepthError, 1e-6 * a.depthRange);
    }
    // Fewer normals; interpolated normals stay close (a chord of 4 px on radius 40: < 0.01 rad).
    EXPECT_LT(Counter(coarse, "intensity_calculations"),
              0.6 * Counter(exact, "intensity_calculations"));
    EXPECT_LT(Counter(fast, "intensity_calculations"),
              0.2 * Counter(exact, "intensity_calculations"));
    // Away from the silhouette (|n_z| > 0.5, where the normal turns by at most ~0.05 rad a
    // pixel on this radius) a chord of Δ = 4 pixels leaves an error below 0.01.
    double worst = 0;
    for (std::size_t i = 0; i < f1.normal.size(); ++i)
        if (f1.surface[i] >= 0 && std::fabs(f1.Normal(i).z) > 0.5)
            worst = std::max(worst, Length(f1.Normal(i) - f4.Normal(i)));
    EXPECT_GT(worst, 0);
    EXPECT_LT(worst, 0.01);
    // Unknown options are rejected.
    RenderOptions o;
    o.engineOptions["sd"] = "0";
    EXPECT_NE(MakeEngine("scanline")->ValidateOptions(o), "");
    o.engineOptions = {{"speed", "1"}};
    EXPECT_NE(MakeEngine("scanline")->ValidateOptions(o), "");
}

// ---- whole scenes through the pipeline ----

void CheckPipeline(const PipelineOptions& base, const std::string& what) {
    PipelineOptions o = base;
    o.engine = "raycast";
    PipelineResult ref, got;
    Diagnostics d1, d2;
    if (!RunPipeline(o, ref, d1)) {
        d1.Print(stderr);
        FAIL() << what;
    }
    o.engine = "scanline";
    ASSERT_TRUE(RunPipeline(o, got, d2)) << what;
    ExpectAgree(ref.frame, got.frame, what);
    // The show-edges, not the exact fallbacks, must do the work: a stack face without a root
    // means a missed boundary (a few pixels at tangencies and apexes are legitimate).
    EXPECT_LE(Counter(got.stats, "root_fallback_pixels"),
              5 + 0.002 * static_cast<double>(ref.frame.CoveredCount()))
        << what;
}

TEST(ScanlineScene, ExamplesAgreeWithRaycast) {
    for (const char* name : {"tube", "bundle_of_tubes", "stack_of_bundles",
                             "cylinder_minus_cylinder", "machined_part"}) {
        PipelineOptions o;
        o.scenePaths = {testing::SourcePath(std::string("examples/") + name + ".uq")};
        o.width = 160;
        o.height = 120;
        CheckPipeline(o, name);
    }
}

// Random bodies: a quadric of a random kind, placed and turned at random, bounded by a box of
// six planes in its own frame and cut by one or two random planes; random parallel or perspective
// views.
std::string RandomScene(std::mt19937& rng, bool perspective, bool csg = false) {
    const double spread = csg ? 3 : 6;  // CSG operands closer together, so that they overlap
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> kind(0, 5), count(2, 4);
    std::string text;
    char buf[512];
    int bodies = count(rng);
    for (int b = 0; b < bodies; ++b) {
        std::array<double, 10> k{};
        const double r = 2 + 2 * (u(rng) + 1);
        switch (kind(rng)) {
            case 0:
                k = {1, 1, 1, 0, 0, 0, 0, 0, 0, -r * r};
                break;  // sphere
            case 1:
                k = {1 / (r * r), 4 / (r * r), 2 / (r * r), 0, 0, 0, 0, 0, 0, -1};
                break;  // ellipsoid
            case 2:
                k = {1, 1, 0, 0, 0, 0, 0, 0, 0, -r * r};
                break;  // cylinder
            case 3:
                k = {1, 1, -0.3, 0, 0, 0, 0, 0, 0, 0};
                break;  // cone
            case 4:
                k = {1, 1, 0, 0, 0, 0, 0, 0, -1.5, 0};
                break;  // paraboloid
            default:
                k = {1, 1, -0.5, 0, 0, 0, 0, 0, 0, -r};
                break;  // hyperboloid
        }
        Transform m = Transform::Translate({spread * u(rng), spread * u(rng), spread * u(rng)}) *
                      Transform::Rotate(0, 180 * u(rng)) * Transform::Rotate(1, 180 * u(rng)) *
                      Transform::Rotate(2, 180 * u(rng));
        Quadric q = Quadric::FromCoefficients(k).Transformed(m);
        std::snprintf(buf, sizeof buf, "quadric q%d <", b);
        text += buf;
        for (double v : q.k) {
            std::snprintf(buf, sizeof buf, " %.17g", v);
            text += buf;
        }
        text += ">;\n";
        std::string lits = "q" + std::to_string(b);
        const double half = r + 1.5;
        std::vector<Plane> planes = {{1, 0, 0, -half},  {-1, 0, 0, -half}, {0, 1, 0, -half},
                                     {0, -1, 0, -half}, {0, 0, 1, -half},  {0, 0, -1, -half}};
        int cuts = 1 + (u(rng) > 0);
        for (int c = 0; c < cuts; ++c) planes.push_back({u(rng), u(rng), u(rng), -0.4 * r});
        for (std::size_t p = 0; p < planes.size(); ++p) {
            Plane w = planes[p].Transformed(m);
            std::snprintf(buf, sizeof buf, "plane p%d_%zu <%.17g %.17g %.17g %.17g>;\n", b, p, w.a,
                          w.b, w.c, w.d);
            text += buf;
            lits += " p" + std::to_string(b) + "_" + std::to_string(p);
        }
        text += "body b" + std::to_string(b) + " (" + lits + ");\n";
    }
    if (csg) {  // one CSG statement over all the bodies, random operators, left to right
        const char* ops[3] = {" - ", " & ", " | "};
        std::uniform_int_distribution<int> op(0, 2);
        text += "csg s (b0";
        for (int b = 1; b < bodies; ++b)
            text += std::string(ops[op(rng)]) + "b" + std::to_string(b);
        text += ");\n";
    }
    if (perspective) {
        std::snprintf(buf, sizeof buf, "view v cop %.6g %.6g %.6g;\n", 15 * u(rng), 15 * u(rng),
                      -45 - 10 * std::fabs(u(rng)));
    } else {
        std::snprintf(buf, sizeof buf, "view v dop %.6g %.6g %.6g;\n", u(rng), u(rng),
                      -1 - std::fabs(u(rng)));
    }
    text += buf;
    return text;
}

TEST(ScanlineScene, GeneratedScenesAgreeWithRaycast) {
    std::mt19937 rng(20261130);
    for (int n = 0; n < 32; ++n) {
        PipelineOptions o;
        o.sceneText = RandomScene(rng, n % 3 == 2);
        o.viewName = "v";
        o.width = 120;
        o.height = 90;
        CheckPipeline(o, "generated scene " + std::to_string(n) + ":\n" + o.sceneText);
    }
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// CSG solids by per-span body templates (renderer.h) against raycast, and against the per-pixel
// evaluation of the same engine (csg=pixels), which must give the same frame bit for bit where
// the templates hold: the same interval code runs on the same endpoint depths.
TEST(ScanlineScene, GeneratedCsgScenesAgreeWithRaycast) {
    std::mt19937 rng(7);
    int drawn = 0;
    for (int n = 0; n < 24; ++n) {
        PipelineOptions o;
        o.sceneText = RandomScene(rng, n % 3 == 1, true);
        o.viewName = "v";
        o.width = 120;
        o.height = 90;
        PipelineResult spans, pixels;
        Diagnostics d1, d2;
        o.engine = "scanline";
        if (!RunPipeline(o, spans, d1)) continue;  // an empty CSG result ("nothing to draw")
        CheckPipeline(o, "generated CSG scene " + std::to_string(n) + ":\n" + o.sceneText);
        o.engineOptions = {{"csg", "pixels"}};
        ASSERT_TRUE(RunPipeline(o, pixels, d2));
        Agreement a = Compare(pixels.frame, spans.frame);
        EXPECT_EQ(a.mismatches, 0u) << "scene " << n;
        EXPECT_LE(a.maxDepthError, 1e-9 * a.depthRange) << "scene " << n;
        drawn += pixels.frame.CoveredCount() > 100;
    }
    EXPECT_GE(drawn, 12);  // most random CSG expressions draw something
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// Rows are rendered in fixed bands of 32 in parallel: the frame must not depend on the threads.
TEST(ScanlineScene, FrameDoesNotDependOnThreads) {
    PipelineOptions o;
    o.scenePaths = {testing::SourcePath("examples/machined_part.uq")};
    o.width = 150;
    o.height = 130;  // not a multiple of the band height
    o.engine = "scanline";
    PipelineResult one, many;
    Diagnostics d1, d2;
    o.threads = 1;
    ASSERT_TRUE(RunPipeline(o, one, d1));
    o.threads = 0;
    ASSERT_TRUE(RunPipeline(o, many, d2));
    EXPECT_EQ(FirstBitDifference(one.frame, many.frame), "");
    EXPECT_EQ(Counter(one.stats, "spans"), Counter(many.stats, "spans"));
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// ---- face stacks (seed 001 §5.2–5.5), the default Renderer path for bodies ----

// Runs `scanline` with verify=on and checks the face-stack machinery itself: for every span and
// every stack body present there, the body's first face on the stack must be the face that the
// exact evaluation finds at the span's sample pixel (verify_body_face_mismatches == 0: the
// stacks are exact, not approximately right). The stack HEAD may legitimately differ from the
// nearest exact hit only where bodies of different solids interpenetrate (no show-edge marks
// where their order flips; the paper's scenes had none), so head mismatches are bounded by the
// spans that have interpenetration pixels — checked by the caller where the scene has none.
PipelineResult CheckFaceStacks(PipelineOptions o, const std::string& what) {
    o.engine = "scanline";
    o.engineOptions = {{"verify", "on"}};
    PipelineResult got;
    Diagnostics d;
    EXPECT_TRUE(RunPipeline(o, got, d)) << what;
    EXPECT_EQ(Counter(got.stats, "verify_body_face_mismatches"), 0) << what;
    if (Counter(got.stats, "face_stack_bodies") > 0) {
        EXPECT_GT(Counter(got.stats, "verify_body_faces"), 0) << what;
    }
    EXPECT_EQ(Counter(got.stats, "face_stack_inserts"), Counter(got.stats, "face_stack_deletes"))
        << what << ": every face that enters a row's stack leaves it (bounded bodies)";
    // The same frame as the face-stack path without verification (verify only counts).
    o.engineOptions = {};
    PipelineResult plain;
    EXPECT_TRUE(RunPipeline(o, plain, d)) << what;
    EXPECT_EQ(FirstBitDifference(plain.frame, got.frame), "") << what;
    return got;
}

TEST(ScanlineFaceStacks, OptionsAreValidated) {
    RenderOptions o;
    for (auto [k, v, ok] : {std::tuple{"render", "stacks", true},
                            {"render", "exact", true},
                            {"render", "stack", false},
                            {"verify", "on", true},
                            {"verify", "off", true},
                            {"verify", "1", true},  // one boolean vocabulary for all engines
                            {"verify", "2", false}}) {
        o.engineOptions = {{k, v}};
        EXPECT_EQ(MakeEngine("scanline")->ValidateOptions(o).empty(), ok) << k << "=" << v;
    }
}

// A sphere: on each of its rows the front and back sheets enter at the left limb crossing (equal
// depth there: a §5.5.1 tie, resolved at Q) and leave at the right one, so the counts are exact.
TEST(ScanlineFaceStacks, SphereStackCountsAreExact) {
    TestSceneBuilder b(96, 80);
    int s = b.AddQuadric(Sphere({40.3, 37.7, 50}, 25.3));
    b.AddSolidOfBody(b.AddBody({{s, false}}));
    RenderStats stats;
    Frame got = RenderWith("scanline", b.scene(), &stats, {{"verify", "on"}});
    ExpectAgree(RenderWith("raycast", b.scene()), got, "sphere, face stacks");
    // Rows whose centre y = j + ½ lies strictly inside (37.7 − 25.3, 37.7 + 25.3) = (12.4, 63).
    const double rows = 63 - 12;  // j = 12 … 62
    EXPECT_EQ(Counter(stats, "face_stack_inserts"), 2 * rows);
    EXPECT_EQ(Counter(stats, "face_stack_deletes"), 2 * rows);
    EXPECT_EQ(Counter(stats, "face_stack_max_depth"), 2);
    EXPECT_GE(Counter(stats, "face_stack_tie_breaks"), rows);  // front vs back at each limb
    EXPECT_EQ(Counter(stats, "verify_mismatch_spans"), 0);
    EXPECT_EQ(Counter(stats, "verify_body_face_mismatches"), 0);
    EXPECT_EQ(Counter(stats, "span_sample_evaluations"), 0);  // no per-span exact evaluation
    EXPECT_EQ(Counter(stats, "face_stack_corrections"), 0);   // plain parity toggling sufficed
    // render=exact: the colleague's per-span evaluation, kept as an option: same frame.
    RenderStats exactStats;
    Frame exact = RenderWith("scanline", b.scene(), &exactStats, {{"render", "exact"}});
    EXPECT_EQ(FirstBitDifference(exact, got), "");
    EXPECT_EQ(Counter(exactStats, "face_stack_inserts"), 0);
    EXPECT_GT(Counter(exactStats, "span_sample_evaluations"), 0);
}

// Figure 5.1 (a)/(b): two boxes sharing the horizontal edge y = 40 at equal depth there, and the
// pyramid apex where four planes meet on a row centre: the stack head must be exact everywhere.
TEST(ScanlineFaceStacks, DegenerateCasesHaveExactStackHeads) {
    {
        TestSceneBuilder b(80, 80);
        const Vec3 apex{40.5, 40.5, 10};  // on a pixel centre and a row centre
        std::vector<std::pair<int, bool>> lits;
        for (auto [nx, ny] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}}) {
            Plane p{nx, ny, -0.6, 0};
            p.d = -(p.a * apex.x + p.b * apex.y + p.c * apex.z);
            lits.push_back({b.AddPlane(p.a, p.b, p.c, p.d), false});
        }
        lits.push_back({b.AddPlane(0, 0, 1, -60), false});
        b.AddSolidOfBody(b.AddBody(lits));
        RenderStats stats;
        Frame got = RenderWith("scanline", b.scene(), &stats, {{"verify", "on"}});
        ExpectAgree(RenderWith("raycast", b.scene()), got, "pyramid apex on a row centre");
        ExpectAgree(RenderWith("raycast", b.scene()),
                    RenderWith("scanline", b.scene(), nullptr, {{"render", "exact"}}),
                    "pyramid apex on a row centre, render=exact");
        EXPECT_EQ(Counter(stats, "verify_mismatch_spans"), 0);
        EXPECT_GT(Counter(stats, "verify_spans"), 0);
    }
    {
        TestSceneBuilder b(80, 80);
        int top0 = b.AddPlane(0, -1, 0, 10), mid = b.AddPlane(0, 1, 0, -40.5);
        int l = b.AddPlane(-1, 0, 0, 10), r = b.AddPlane(1, 0, 0, -70);
        int f1 = b.AddPlane(0, 0.5, -1, 10), bk = b.AddPlane(0, 0, 1, -100);
        b.AddSolidOfBody(b.AddBody(
            {{top0, false}, {mid, false}, {l, false}, {r, false}, {f1, false}, {bk, false}}));
        int mid2 = b.AddPlane(0, -1, 0, 40.5), bot = b.AddPlane(0, 1, 0, -70);
        int f2 = b.AddPlane(0, -0.5, -1, 50.5);  // equal to f1 on the shared edge y = 40.5
        b.AddSolidOfBody(b.AddBody(
            {{mid2, false}, {bot, false}, {l, false}, {r, false}, {f2, false}, {bk, false}}));
        RenderStats stats;
        Frame got = RenderWith("scanline", b.scene(), &stats, {{"verify", "on"}});
        ExpectAgree(RenderWith("raycast", b.scene()), got, "shared edge on a row centre");
        EXPECT_EQ(Counter(stats, "verify_body_face_mismatches"), 0);
    }
}

// Every example scene and the gallery's gear and clover knot: agreement with raycast (the
// issue's acceptance, ExpectAgree) on the default face-stack path, and exact stacks.
TEST(ScanlineFaceStacks, ExamplesAndGalleryAgreeWithRaycast) {
    for (const char* name :
         {"tube", "bundle_of_tubes", "stack_of_bundles", "teapot_on_table",
          "cylinder_minus_cylinder", "machined_part", "gallery/gear", "gallery/clover_knot"}) {
        PipelineOptions o;
        o.scenePaths = {testing::SourcePath(std::string("examples/") + name + ".uq")};
        o.width = 160;
        o.height = 120;
        CheckPipeline(o, name);
        PipelineResult got = CheckFaceStacks(o, name);
        const bool hasStackBodies = Counter(got.stats, "face_stack_bodies") > 0;
        if (hasStackBodies) {
            EXPECT_GT(Counter(got.stats, "face_stack_inserts"), 0) << name;
        }
        // The clover knot's tubes meet only at shared mitre planes: no interpenetration, so the
        // stack head itself is exact in every span.
        if (std::string(name) == "gallery/clover_knot") {
            EXPECT_EQ(Counter(got.stats, "interpenetration_pixels"), 0);
            EXPECT_EQ(Counter(got.stats, "verify_mismatch_spans"), 0);
            EXPECT_EQ(Counter(got.stats, "face_stack_bodies"), 24);
        }
    }
}

// The 32 generated scenes of GeneratedScenesAgreeWithRaycast (same seed, same scenes): exact
// stacks per body, and the stack head exact wherever no other body interpenetrates.
TEST(ScanlineFaceStacks, GeneratedScenesHaveExactStacks) {
    std::mt19937 rng(20261130);
    double bodies = 0, heads = 0;
    for (int n = 0; n < 32; ++n) {
        PipelineOptions o;
        o.sceneText = RandomScene(rng, n % 3 == 2);
        o.viewName = "v";
        o.width = 120;
        o.height = 90;
        PipelineResult got = CheckFaceStacks(o, "generated scene " + std::to_string(n));
        bodies += Counter(got.stats, "verify_body_faces");
        if (Counter(got.stats, "interpenetration_pixels") == 0) {
            EXPECT_EQ(Counter(got.stats, "verify_mismatch_spans"), 0) << "scene " << n;
            heads += Counter(got.stats, "verify_spans");
        }
    }
    EXPECT_GT(bodies, 10000);  // the check had something to check
    EXPECT_GT(heads, 1000);
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// Face stacks are rebuilt per scan line, so bands of rows stay independent: the frame of a scene
// drawn entirely from face stacks must not depend on the threads either.
TEST(ScanlineFaceStacks, FrameDoesNotDependOnThreads) {
    PipelineOptions o;
    o.scenePaths = {testing::SourcePath("examples/gallery/clover_knot.uq")};
    o.width = 150;
    o.height = 130;
    o.engine = "scanline";
    PipelineResult one, many;
    Diagnostics d1, d2;
    o.threads = 1;
    ASSERT_TRUE(RunPipeline(o, one, d1));
    o.threads = 0;
    ASSERT_TRUE(RunPipeline(o, many, d2));
    EXPECT_EQ(FirstBitDifference(one.frame, many.frame), "");
    EXPECT_EQ(Counter(one.stats, "face_stack_inserts"), Counter(many.stats, "face_stack_inserts"));
    EXPECT_GT(Counter(one.stats, "face_stack_inserts"), 0);
}

}  // namespace
}  // namespace quadrix
