// Face stacks carried from scan line to scan line (seed 001 §5.2–5.4) and CSG trees pruned per
// span: the frames must be raycast's, the verifier must find nothing to correct on scenes whose
// show-edges are exact (the mitred joints of the gallery included) and the carried stacks alone
// (check=off) must draw the same frame, the stacks must really be carried (derived far less
// often than faces cross), and pruning many-operand CSG trees must not change a surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "quadrix/engines/engine.h"
#include "quadrix/engines/engine_test_util.h"
#include "quadrix/engines/scanline/resolver.h"
#include "quadrix/flatten/test_scene_builder.h"
#include "quadrix/frame/compare.h"
#include "quadrix/pipeline/pipeline.h"

namespace quadrix {
namespace {

using testing_util::Counter;
using testing_util::RenderWith;
using testing_util::TestSceneBuilder;

// The quadric of an ellipsoid centred at c with radii (rx, ry, rz), turned by t about z:
// ((x', y') rotated) / radii, expanded into UniQuadrix coefficients.
std::array<double, 10> TurnedEllipsoid(const Vec3& c, double rx, double ry, double rz, double t) {
    const double ct = std::cos(t), st = std::sin(t);
    const double a = ct * ct / (rx * rx) + st * st / (ry * ry);
    const double bb = st * st / (rx * rx) + ct * ct / (ry * ry);
    const double d = ct * st * (1 / (rx * rx) - 1 / (ry * ry));
    const double cc = 1 / (rz * rz);
    std::array<double, 10> q{a, bb, cc, d, 0, 0, 0, 0, 0, 0};
    q[6] = -(a * c.x + d * c.y);
    q[7] = -(d * c.x + bb * c.y);
    q[8] = -cc * c.z;
    q[9] = a * c.x * c.x + bb * c.y * c.y + 2 * d * c.x * c.y + cc * c.z * c.z - 1;
    return q;
}

// The scale of the depth tolerances: the reference's depth range (1 for a flat or empty frame).
double DepthScale(const FrameComparison& c) {
    return c.referenceDepthRange > 0 ? c.referenceDepthRange : 1;
}

// scanline (default: carried face stacks) against raycast through the one comparison
// (frame/compare.h): at most `allowed` pixels with another surface, coverage included
// (silhouette pixels where a traced crossing and the per-pixel solve round differently), and
// depths within 1e-6 of the range where the surfaces agree.
void ExpectRaycastFrame(const Frame& ref, const Frame& got, std::size_t allowed,
                        const std::string& what) {
    const FrameComparison d = CompareFrames(got, ref);
    const std::uint64_t covered = d.coveredBoth + d.onlyReference;
    EXPECT_GT(covered, 0u) << what;
    EXPECT_LE(d.SurfaceMismatches(), allowed)
        << what << ": " << d.SurfaceMismatches() << " of " << covered;
    EXPECT_LE(d.maxDepthError / DepthScale(d), 1e-6) << what;
}

PipelineResult RunScene(const std::string& path, int w, int h, const char* engine,
                        std::map<std::string, std::string> opts = {}) {
    PipelineOptions o;
    o.scenePaths = {std::string(QUADRIX_SOURCE_DIR) + "/" + path};
    o.width = w;
    o.height = h;
    o.engine = engine;
    o.engineOptions = std::move(opts);
    PipelineResult r;
    Diagnostics d;
    EXPECT_TRUE(RunPipeline(o, r, d)) << path;
    return r;
}

// Every example and gallery scene drawn from faces stacks, at two sizes (one of them odd, so
// that vertices fall on other rows): raycast's frame, and a verifier with nothing to do. Before
// the Resolver's wedge test the gallery's triangles needed 4388 corrections at 512×512 (spurious
// show-edges along the joint lines of four mitred tubes), and a row-by-row sweep rebuilt every
// stack on every row.
TEST(ScanlineCarriedStacks, ExamplesAndGalleryNeedNoCorrections) {
    double swaps = 0, derivations = 0, inserts = 0, deriveInserts = 0;
    double vertices = 0, recursions = 0, deletionSwaps = 0;
    for (const char* name :
         {"examples/tube.uq", "examples/bundle_of_tubes.uq", "examples/stack_of_bundles.uq",
          "examples/teapot_on_table.uq", "examples/gallery/clover_knot.uq",
          "examples/gallery/gear.uq", "examples/gallery/hilbert3.uq", "examples/gallery/name.uq",
          "examples/gallery/solids.uq", "examples/gallery/triangles.uq"}) {
        for (auto [w, h] : {std::pair{160, 120}, std::pair{333, 257}}) {
            const std::string what = std::string(name) + " " + std::to_string(w);
            PipelineResult ref = RunScene(name, w, h, "raycast");
            PipelineResult got = RunScene(name, w, h, "scanline", {{"verify", "on"}});
            ExpectRaycastFrame(ref.frame, got.frame, 0, what);
            const RenderStats& s = got.stats;
            ASSERT_GT(Counter(s, "face_stack_bodies"), 0) << what;
            EXPECT_EQ(Counter(s, "face_stack_corrections"), 0) << what;
            EXPECT_EQ(Counter(s, "face_stack_repairs"), 0) << what;
            EXPECT_EQ(Counter(s, "face_stack_order_corrections"), 0) << what;
            EXPECT_EQ(Counter(s, "verify_body_face_mismatches"), 0) << what;
            EXPECT_GT(Counter(s, "face_stack_derivations"), 0) << what;
            // Pass one's vertex processing (§5.4) closed every vertex: no fallback derivation.
            EXPECT_EQ(Counter(s, "face_stack_vertex_fallbacks"), 0) << what;
            EXPECT_EQ(Counter(s, "face_stack_rebuilds"), 0) << what;
            // The carried stacks alone (no verifier) draw the same frame.
            PipelineResult unchecked = RunScene(name, w, h, "scanline", {{"check", "off"}});
            EXPECT_EQ(FirstBitDifference(unchecked.frame, got.frame), "") << what;
            swaps += Counter(s, "face_stack_swap_updates");
            deriveInserts += Counter(s, "face_stack_derive_inserts");
            vertices += Counter(s, "face_stack_vertices");
            recursions += Counter(s, "face_stack_vertex_recursions");
            deletionSwaps += Counter(s, "face_stack_deletion_swaps");
            derivations += Counter(s, "face_stack_derivations");
            inserts += Counter(s, "face_stack_inserts");
        }
    }
    EXPECT_GT(swaps, 0);  // pass two handed stacks over somewhere
    // Pass one processed vertices, moved finishing edges next to CE past other edges, and
    // recursed through edges lying within one scan line (the gallery's tubes have many short
    // pieces between nearly coincident vertices).
    EXPECT_GT(vertices, 1000);
    EXPECT_GT(deletionSwaps, 100);
    EXPECT_GT(recursions, 100);
    // Carried, not rebuilt: stacks are derived (from a left neighbour) for starting edges and
    // at the end of a swap only, far less often than faces cross the scan lines (a row-by-row
    // rebuild derives one stack per crossing: more derivations than face inserts), and the
    // faces put in depth order while carrying are fewer than the faces crossing.
    EXPECT_LT(derivations, 0.4 * inserts);
    EXPECT_LT(deriveInserts, 0.5 * inserts);
}

TEST(ScanlineCarriedStacks, CheckOptionIsValidated) {
    RenderOptions o;
    for (auto [v, ok] : {std::pair{"on", true}, {"off", true}, {"no", true}, {"maybe", false}}) {
        o.engineOptions = {{"check", v}};
        EXPECT_EQ(MakeEngine("scanline")->ValidateOptions(o).empty(), ok) << v;
    }
}

// A mitred joint built directly: a tube along x cut at x = 40 by two planes through the joint
// line {x = 40, z = 50} (parallel to y, so it projects to the column x = 40) and by a third
// plane through the same line that contains their wedge (it bounds nothing). The zero test
// alone accepts the joint line for the pairs with the third plane (the line lies ON it); the
// wedge test must reject them. A second tube meets the first on the shared mitre plane.
TEST(ScanlineCarriedStacks, MitredJointMakesNoSpuriousShowEdges) {
    TestSceneBuilder b(96, 80);
    const double cy = 40.3, cz = 50, r = 14.7;
    // (y − cy)² + (z − cz)² − r² <= 0: a cylinder along x.
    const int cyl = b.AddQuadric({0, 1, 1, 0, 0, 0, 0, -cy, -cz, cy * cy + cz * cz - r * r});
    auto plane = [&](double a, double c) {  // a (x − 40) + c (z − 50) <= 0
        return b.AddPlane(a, 0, c, -(a * 40 + c * cz));
    };
    const int p1 = plane(1, 0.3), p2 = plane(1, -0.3), p3 = plane(1, 0.1);
    const int capL = b.AddPlane(-1, 0, 0.2, 8 - 0.2 * cz);  // x >= 8 + 0.2 (z − 50)
    const int bodyA =
        b.AddBody({{cyl, false}, {p1, false}, {p2, false}, {p3, false}, {capL, false}});
    b.AddSolidOfBody(bodyA);
    const int capR = b.AddPlane(1, 0, 0.1, -(86 + 0.1 * cz));
    const int bodyB = b.AddBody({{cyl, false}, {p1, true}, {capR, false}});
    b.AddSolidOfBody(bodyB);
    FlatScene& scene = b.scene();

    // Resolver: no show-edge of body A bounds a face of the third plane.
    scanline::ResolverCounters rc;
    scanline::ResolvedBody resolved;
    std::vector<scanline::ShowFace> faces;
    std::vector<scanline::ShowEdge> edges;
    scanline::ResolveBody(scene, bodyA, 0, 80, false, resolved, faces, edges, rc);
    ASSERT_FALSE(resolved.perPixel);
    int p3Face = -1, p1Face = -1, p2Face = -1;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        if (faces[f].halfSpace == p3) p3Face = static_cast<int>(f);
        if (faces[f].halfSpace == p1) p1Face = static_cast<int>(f);
        if (faces[f].halfSpace == p2) p2Face = static_cast<int>(f);
    }
    ASSERT_GE(p3Face, 0);
    int jointEdges = 0;
    for (const scanline::ShowEdge& e : edges) {
        // Pieces holding no row centre never reach the renderer (BuildEsl drops them); the two
        // between the nearly coincident vertices where the joint line meets the cylinder (the
        // ellipse of the third plane touches it there, 4e-13 px long) are of that kind.
        if (std::ceil(e.yBottom - 0.5) > std::floor(e.yTop - 0.5)) continue;
        EXPECT_TRUE(e.faces[0] != p3Face && e.faces[1] != p3Face)
            << "show-edge on i-line " << e.iline << " bounds the redundant plane's face, y "
            << e.yBottom << " .. " << e.yTop;
        const bool joint = (e.faces[0] == p1Face && e.faces[1] == p2Face) ||
                           (e.faces[0] == p2Face && e.faces[1] == p1Face);
        jointEdges += joint;
    }
    EXPECT_EQ(jointEdges, 1);  // the true edge of the wedge is kept

    // Renderer: nothing for the verifier to correct, and raycast's frame.
    RenderStats stats;
    Frame got = RenderWith("scanline", scene, &stats, {{"verify", "on"}});
    ExpectRaycastFrame(RenderWith("raycast", scene), got, 0, "mitred joint");
    EXPECT_EQ(Counter(stats, "face_stack_corrections"), 0);
    EXPECT_EQ(Counter(stats, "face_stack_repairs"), 0);
    EXPECT_EQ(Counter(stats, "verify_body_face_mismatches"), 0);
    EXPECT_EQ(Counter(stats, "face_stack_bodies"), 2);
}

// Random ellipsoids, spheres and boxed cylinders in device space whose outlines cross from row
// to row: pass two's swaps hand stacks over, vertices derive new ones. Every frame must be
// raycast's (and render=exact's), with nothing for the verifier to correct.
TEST(ScanlineCarriedStacks, CrossingOutlinesSwapStacksExactly) {
    std::mt19937 rng(3003);
    std::uniform_real_distribution<double> u(0, 1);
    double swaps = 0, derivations = 0, inserts = 0;
    for (int scene = 0; scene < 12; ++scene) {
        TestSceneBuilder b(120, 90);
        const int n = 3 + scene % 4;
        for (int k = 0; k < n; ++k) {
            const Vec3 c{15 + 90 * u(rng), 12 + 66 * u(rng), 40 + 40 * u(rng)};
            const double rx = 6 + 14 * u(rng), ry = 6 + 14 * u(rng), rz = 6 + 14 * u(rng);
            const std::array<double, 10> q = TurnedEllipsoid(c, rx, ry, rz, 3.14159 * u(rng));
            std::vector<std::pair<int, bool>> lits{{b.AddQuadric(q), false}};
            if (k % 2 == 1) {  // cut by a slanted plane through the centre
                const double px = u(rng) - 0.5, py = u(rng) - 0.5, pz = -0.6 - u(rng);
                lits.push_back(
                    {b.AddPlane(px, py, pz, -(px * c.x + py * c.y + pz * c.z) - 2), false});
            }
            b.AddSolidOfBody(b.AddBody(lits));
        }
        RenderStats stats;
        Frame got = RenderWith("scanline", b.scene(), &stats, {{"verify", "on"}});
        const std::string what = "random scene " + std::to_string(scene);
        ExpectRaycastFrame(RenderWith("raycast", b.scene()), got, 2, what);
        EXPECT_EQ(FirstBitDifference(
                      RenderWith("scanline", b.scene(), nullptr, {{"render", "exact"}}), got),
                  "")
            << what;
        EXPECT_EQ(Counter(stats, "face_stack_corrections"), 0) << what;
        EXPECT_EQ(Counter(stats, "face_stack_repairs"), 0) << what;
        EXPECT_EQ(Counter(stats, "verify_body_face_mismatches"), 0) << what;
        EXPECT_EQ(Counter(stats, "face_stack_vertex_fallbacks"), 0) << what;
        EXPECT_EQ(Counter(stats, "face_stack_rebuilds"), 0) << what;
        EXPECT_EQ(Counter(stats, "face_stack_inserts"), Counter(stats, "face_stack_deletes"))
            << what;
        EXPECT_EQ(
            FirstBitDifference(RenderWith("scanline", b.scene(), nullptr, {{"check", "off"}}), got),
            "")
            << what;
        swaps += Counter(stats, "face_stack_swap_updates");
        derivations += Counter(stats, "face_stack_derivations");
        inserts += Counter(stats, "face_stack_inserts");
    }
    EXPECT_GT(swaps, 20);
    EXPECT_LT(derivations, 0.5 * inserts);
}

// Figure 5.1's shared horizontal edge exactly on a row centre: the upper box's edges end on the
// row (half-open: they no longer toggle in the carried stacks), but raycast's closed
// half-spaces still draw the upper box there. The face test keeps its faces for that row only.
TEST(ScanlineCarriedStacks, EdgesEndingOnARowCentreKeepTheirFacesForThatRow) {
    TestSceneBuilder b(80, 80);
    int top0 = b.AddPlane(0, -1, 0, 10), mid = b.AddPlane(0, 1, 0, -40.5);
    int l = b.AddPlane(-1, 0, 0, 10), r = b.AddPlane(1, 0, 0, -70);
    int f1 = b.AddPlane(0, 0.5, -1, 10), bk = b.AddPlane(0, 0, 1, -100);
    b.AddSolidOfBody(
        b.AddBody({{top0, false}, {mid, false}, {l, false}, {r, false}, {f1, false}, {bk, false}}));
    int mid2 = b.AddPlane(0, -1, 0, 40.5), bot = b.AddPlane(0, 1, 0, -70);
    int f2 = b.AddPlane(0, -0.5, -1, 50.5);
    b.AddSolidOfBody(
        b.AddBody({{mid2, false}, {bot, false}, {l, false}, {r, false}, {f2, false}, {bk, false}}));
    RenderStats stats;
    Frame got = RenderWith("scanline", b.scene(), &stats);
    ExpectRaycastFrame(RenderWith("raycast", b.scene()), got, 0, "shared edge on a row centre");
    EXPECT_GT(Counter(stats, "face_stack_closed_row_faces"), 0);
    EXPECT_EQ(Counter(stats, "face_stack_repairs"), 0);
}

// Boxes whose top and bottom edges are horizontal (lines along a row: no row centre crosses
// them, so they never enter the AEL) behind and in front of spheres and turned ellipsoids.
// Without the horizontal show-edges, a box's two top corners are separate vertices whose
// toggles do not cancel; pass one links them by recursion through the horizontal edge (§5.4:
// "each incident starting edge that lies completely within the scan line ... its opposite
// vertex is processed recursively"), and a sphere outline passing between the corners makes
// the second corner's finishing edge move next to CE by swaps. `box` is (x0, x1, yTop, yBottom,
// zFront, zBack, slant): the top and bottom faces are slanted toward the viewer so that they
// are seen, and meet the front face on the rows yTop and yBottom.
struct SlantedBox {
    double x0, x1, yTop, yBottom, zFront, zBack, slant;
};
void AddSlantedBox(TestSceneBuilder& b, const SlantedBox& x) {
    const int l = b.AddPlane(-1, 0, 0, x.x0), r = b.AddPlane(1, 0, 0, -x.x1);
    const int front = b.AddPlane(0, 0, -1, x.zFront), back = b.AddPlane(0, 0, 1, -x.zBack);
    // y >= yTop − slant (z − zFront) and y <= yBottom + slant (z − zFront).
    const int top = b.AddPlane(0, -1, -x.slant, x.yTop + x.slant * x.zFront);
    const int bottom = b.AddPlane(0, 1, -x.slant, -x.yBottom + x.slant * x.zFront);
    b.AddSolidOfBody(b.AddBody(
        {{l, false}, {r, false}, {front, false}, {back, false}, {top, false}, {bottom, false}}));
}

// The carried stacks of one scene: raycast's frame with and without the verifier, nothing for
// the verifier to do, no fallback at any vertex. Returns the stats.
RenderStats ExpectVerticesClosed(const FlatScene& scene, std::size_t allowed,
                                 const std::string& what) {
    RenderStats stats;
    Frame got = RenderWith("scanline", scene, &stats, {{"verify", "on"}});
    const Frame ref = RenderWith("raycast", scene);
    ExpectRaycastFrame(ref, got, allowed, what);
    // The carried stacks alone: the same frame (a vertex processed wrongly would leave wrong
    // stacks to the right of it, which only the verifier corrects).
    const Frame unchecked = RenderWith("scanline", scene, nullptr, {{"check", "off"}});
    EXPECT_EQ(FirstBitDifference(unchecked, got), "") << what;
    EXPECT_EQ(Counter(stats, "face_stack_corrections"), 0) << what;
    EXPECT_EQ(Counter(stats, "face_stack_repairs"), 0) << what;
    EXPECT_EQ(Counter(stats, "face_stack_order_corrections"), 0) << what;
    EXPECT_EQ(Counter(stats, "verify_body_face_mismatches"), 0) << what;
    EXPECT_EQ(Counter(stats, "face_stack_vertex_fallbacks"), 0) << what;
    EXPECT_EQ(Counter(stats, "face_stack_rebuilds"), 0) << what;
    return stats;
}

TEST(ScanlineVertexProcessing, HorizontalEdgesLinkTheirVerticesByRecursion) {
    TestSceneBuilder b(120, 96);
    AddSlantedBox(b, {20, 100, 20.3, 70.6, 50, 80, 0.5});
    // A sphere in front whose outline passes between the top corners (and the bottom ones).
    b.AddSolidOfBody(b.AddBody({{b.AddSphere({58, 20, 30}, 12.2), false}}));
    b.AddSolidOfBody(b.AddBody({{b.AddSphere({45, 72, 40}, 9.7), false}}));
    const RenderStats stats = ExpectVerticesClosed(b.scene(), 0, "box and spheres");
    EXPECT_GE(Counter(stats, "show_edges_horizontal"), 4);
    EXPECT_GT(Counter(stats, "face_stack_vertex_recursions"), 0);
    EXPECT_GT(Counter(stats, "face_stack_deletion_swaps"), 0);
    EXPECT_GT(Counter(stats, "face_stack_vertices"), 0);
}

// The same box with its horizontal edges exactly on row centres (20.5 and 70.5). The rows on
// the edges are ties: the front face and the top (bottom) face have the same depth along the
// whole row, and raycast's closed half-spaces pick the slanted face where the stacks keep the
// front one. The verifier's face test must not take the front face away there (it lies on the
// slanted plane, but the box goes on behind it along the ray): the frame with and without the
// verifier is the same, and raycast's depth everywhere.
TEST(ScanlineVertexProcessing, RowsExactlyOnHorizontalEdges) {
    TestSceneBuilder b(120, 96);
    AddSlantedBox(b, {20, 100, 20.5, 70.5, 50, 81, 0.5});  // back edges at y 5 and 86
    b.AddSolidOfBody(b.AddBody({{b.AddSphere({58, 20, 30}, 12.2), false}}));
    RenderStats stats;
    const Frame got = RenderWith("scanline", b.scene(), &stats);
    const Frame unchecked = RenderWith("scanline", b.scene(), nullptr, {{"check", "off"}});
    EXPECT_EQ(FirstBitDifference(unchecked, got), "");
    EXPECT_EQ(Counter(stats, "face_stack_corrections"), 0);
    EXPECT_EQ(Counter(stats, "face_stack_repairs"), 0);
    EXPECT_EQ(Counter(stats, "face_stack_vertex_fallbacks"), 0);
    EXPECT_GT(Counter(stats, "face_stack_vertex_recursions"), 0);
    const Frame ref = RenderWith("raycast", b.scene());
    std::size_t covered = 0, tieRows = 0;
    for (int y = 0; y < ref.height; ++y) {
        for (int x = 0; x < ref.width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * ref.width + x;
            ASSERT_EQ(ref.surface[i] == Frame::kNone, got.surface[i] == Frame::kNone)
                << x << " " << y;
            if (ref.surface[i] == Frame::kNone) continue;
            ++covered;
            EXPECT_NEAR(got.depth[i], ref.depth[i], 1e-9) << x << " " << y;
            if (ref.surface[i] != got.surface[i]) {
                EXPECT_TRUE(y == 20 || y == 70) << x << " " << y;
                ++tieRows;
            }
        }
    }
    EXPECT_GT(covered, 1000u);
    EXPECT_LE(tieRows, 2u * 80u);
}

// Random slanted boxes, spheres and turned ellipsoids (some cut by a plane), at two sizes: every
// vertex closes, the carried stacks alone give raycast's frame, and pass one's recursion and
// deletion swaps are exercised.
TEST(ScanlineVertexProcessing, RandomBoxesAndEllipsoidsCloseEveryVertex) {
    std::mt19937 rng(5405);
    std::uniform_real_distribution<double> u(0, 1);
    double recursions = 0, deletionSwaps = 0, vertices = 0;
    for (int scene = 0; scene < 16; ++scene) {
        const int w = scene % 2 ? 131 : 96, h = scene % 2 ? 101 : 80;
        TestSceneBuilder b(w, h);
        const int boxes = 1 + scene % 3;
        for (int k = 0; k < boxes; ++k) {
            const double x0 = w * (0.05 + 0.5 * u(rng)), y0 = h * (0.05 + 0.4 * u(rng));
            AddSlantedBox(b, {x0, x0 + w * (0.2 + 0.3 * u(rng)), y0, y0 + h * (0.2 + 0.3 * u(rng)),
                              30 + 30 * u(rng), 95, 0.2 + 0.6 * u(rng)});
        }
        const int n = 2 + scene % 3;
        for (int k = 0; k < n; ++k) {
            const Vec3 c{w * (0.1 + 0.8 * u(rng)), h * (0.1 + 0.8 * u(rng)), 20 + 50 * u(rng)};
            const double rx = 5 + 12 * u(rng), ry = 5 + 12 * u(rng), rz = 5 + 12 * u(rng);
            const std::array<double, 10> q = TurnedEllipsoid(c, rx, ry, rz, 3.14159 * u(rng));
            std::vector<std::pair<int, bool>> lits{{b.AddQuadric(q), false}};
            if (k % 2 == 1) {
                const double px = u(rng) - 0.5, py = u(rng) - 0.5, pz = -0.6 - u(rng);
                lits.push_back(
                    {b.AddPlane(px, py, pz, -(px * c.x + py * c.y + pz * c.z) - 2), false});
            }
            b.AddSolidOfBody(b.AddBody(lits));
        }
        const RenderStats stats =
            ExpectVerticesClosed(b.scene(), 3, "random scene " + std::to_string(scene));
        recursions += Counter(stats, "face_stack_vertex_recursions");
        deletionSwaps += Counter(stats, "face_stack_deletion_swaps");
        vertices += Counter(stats, "face_stack_vertices");
    }
    EXPECT_GT(vertices, 100);
    EXPECT_GT(recursions, 16);
    EXPECT_GT(deletionSwaps, 10);
}

// Many operands in one CSG tree: n spheres unioned, intersected with a box, minus a cylinder and
// minus a union of small spheres (the bench's spheres-minus-cylinder, with every operator). The
// per-span trees are pruned to the operands whose x range meets the span; the frame must be the
// one of the full tree per pixel (csg=pixels) and raycast's.
std::string ManySpheresScene(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-10, 10);
    const double r = std::cbrt(0.6 * 8000.0 / (n * 4.18879));
    std::string text, big = "(", small = "(";
    char buf[256];
    for (int i = 0; i < n; ++i) {
        const double x = u(rng), y = u(rng), z = u(rng);
        std::snprintf(buf, sizeof buf, "quadric q%d <1 1 1 0 0 0 %.9g %.9g %.9g %.9g>;\n", i, -x,
                      -y, -z, x * x + y * y + z * z - r * r);
        text += buf;
        text += "body s" + std::to_string(i) + " (q" + std::to_string(i) + ");\n";
        std::string& group = i % 5 == 4 ? small : big;
        if (group.size() > 1) group += " | ";
        group += "s" + std::to_string(i);
    }
    big += ")";
    small += ")";
    text +=
        "quadric cyl <0.9615384615 0.03846153846 1 -0.1923076923 0 0 0 0 0 -9>;\n"
        "plane cl <-1 0 0 -13>;\nplane cr <1 0 0 -13>;\nbody drill (cyl cl cr);\n"
        "plane bx0 <1 0 0 -8>;\nplane bx1 <-1 0 0 -8>;\nplane by0 <0 1 0 -8>;\n"
        "plane by1 <0 -1 0 -8>;\nplane bz0 <0 0 1 -8>;\nplane bz1 <0 0 -1 -8>;\n"
        "body box (bx0 bx1 by0 by1 bz0 bz1);\n";
    text += "csg balls (((" + big + " & box) - drill) - " + small + ");\n";
    text += "light fill .25;\nview v dop .4 .5 -1;\n";
    return text;
}

TEST(ScanlineCsgPruning, ManySpheresAgreeWithTheFullTreeAndRaycast) {
    for (int n : {60, 400}) {
        PipelineOptions o;
        o.sceneText = ManySpheresScene(n, 12345u + static_cast<unsigned>(n));
        o.viewName = "v";
        o.width = 96;
        o.height = 72;
        PipelineResult ray, spans, pixels;
        Diagnostics d;
        o.engine = "raycast";
        ASSERT_TRUE(RunPipeline(o, ray, d));
        o.engine = "scanline";
        ASSERT_TRUE(RunPipeline(o, spans, d));
        o.engineOptions = {{"csg", "pixels"}};
        ASSERT_TRUE(RunPipeline(o, pixels, d));
        const std::string what = std::to_string(n) + " spheres";
        // The same surfaces as the full tree per pixel; depths differ only by the rounding of the
        // span shader's incremental conics.
        const FrameComparison full = CompareFrames(spans.frame, pixels.frame);
        EXPECT_EQ(full.SurfaceMismatches(), 0u) << what;
        EXPECT_LE(full.maxDepthError / DepthScale(full), 1e-9) << what;
        ExpectRaycastFrame(ray.frame, spans.frame, 0, what);
        EXPECT_GT(ray.frame.CoveredCount(), 1000u) << what;
        EXPECT_EQ(Counter(spans.stats, "csg_exact_fallback_pixels"), 0) << what;
        // Pruned: the templates built per span are the operands there, not the whole tree.
        const double spansDrawn = Counter(spans.stats, "spans");
        EXPECT_LT(Counter(spans.stats, "csg_template_bodies"), 0.1 * spansDrawn * (n + 2)) << what;
        EXPECT_EQ(Counter(spans.stats, "csg_solids"), 1);
    }
}

}  // namespace
}  // namespace quadrix
