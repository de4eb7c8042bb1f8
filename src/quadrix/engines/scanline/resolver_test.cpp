// The Resolver's structures on small bodies: i-line types, i-vertex merging (§4.4, Figure 4.4),
// show-faces and the face pointers of show-edges (the table of §4.4).
#include "quadrix/engines/scanline/resolver.h"

#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/flatten/test_scene_builder.h"

namespace quadrix::scanline {
namespace {

using testing_util::TestSceneBuilder;

struct Resolved {
    ResolvedBody body;
    std::vector<ShowFace> faces;
    std::vector<ShowEdge> edges;
    ResolverCounters counters;
};

Resolved Resolve(TestSceneBuilder& b, int body, bool all = false) {
    Resolved r;
    ResolveBody(b.scene(), body, 0, b.scene().height, all, r.body, r.faces, r.edges, r.counters);
    return r;
}

std::array<double, 10> Sphere(Vec3 c, double rad) {
    return {1, 1, 1, 0, 0, 0, -c.x, -c.y, -c.z, Dot(c, c) - rad * rad};
}

TEST(ScanlineResolver, SphereHasTwoFacesALimbAndFourExtrema) {
    TestSceneBuilder b(100, 100);
    int s = b.AddQuadric(Sphere({50, 50, 50}, 20));
    int body = b.AddBody({{s, false}});
    Resolved r = Resolve(b, body);
    ASSERT_EQ(r.faces.size(), 2u);
    EXPECT_EQ(r.faces[0].sheet, Sheet::kFront);
    EXPECT_EQ(r.faces[1].sheet, Sheet::kBack);
    EXPECT_EQ(r.body.At(0, 0).type, ILineType::kConic);
    EXPECT_TRUE(r.body.At(0, 0).limb);
    EXPECT_EQ(r.counters.verticesByType[static_cast<int>(IVertexType::kVextrm)], 2u);
    EXPECT_EQ(r.counters.verticesByType[static_cast<int>(IVertexType::kHextrm)], 2u);
    // Four quarter arcs, single-valued in x and y, each bounding the front and back faces.
    ASSERT_EQ(r.edges.size(), 4u);
    for (const ShowEdge& e : r.edges) {
        EXPECT_TRUE(e.conic);
        EXPECT_EQ(e.faces[0], 0);
        EXPECT_EQ(e.faces[1], 1);
        EXPECT_NEAR(std::fabs(e.XAt(50) - 50), 20, 1e-9);
        // Monotone in y (split at the HEXTRMs).
        double a = e.XAt(e.yBottom + 1e-3), m = e.XAt(0.5 * (e.yBottom + e.yTop)),
               c = e.XAt(e.yTop - 1e-3);
        EXPECT_TRUE((a <= m && m <= c) || (a >= m && m >= c));
    }
}

TEST(ScanlineResolver, ViewCylinderHasNoFacesAndCapsGetConicEdges) {
    TestSceneBuilder b(100, 100);
    int cyl = b.AddQuadric({1, 1, 0, 0, 0, 0, -50, -50, 0, 5000 - 400});
    int cap = b.AddPlane(0.2, 0, -1, 10);
    int body = b.AddBody({{cyl, false}, {cap, false}});
    Resolved r = Resolve(b, body);
    EXPECT_EQ(r.faces.size(), 1u);  // the cap only (zero test (2): no sheets for the cylinder)
    EXPECT_EQ(r.body.At(0, 0).type, ILineType::kNoExist);
    EXPECT_EQ(r.body.At(1, 0).type, ILineType::kConic);
    for (const ShowEdge& e : r.edges) {
        EXPECT_EQ(e.faces[0], 0);   // the cap's face
        EXPECT_EQ(e.faces[1], -1);  // the cylinder has none
    }
}

TEST(ScanlineResolver, EdgeOnPlaneMakesEdgeAndPointILines) {
    TestSceneBuilder b(100, 100);
    int s = b.AddQuadric(Sphere({50, 50, 50}, 20));
    int cut = b.AddPlane(1, 0, 0, -55);   // edge-on
    int cut2 = b.AddPlane(0, 1, 0, -60);  // edge-on
    int body = b.AddBody({{s, false}, {cut, false}, {cut2, false}});
    Resolved r = Resolve(b, body);
    EXPECT_EQ(r.body.At(1, 0).type, ILineType::kEdge);
    EXPECT_EQ(r.body.At(2, 0).type, ILineType::kEdge);
    // Two edge-on planes: POINT, or not made at all since neither has a face.
    EXPECT_NE(r.body.At(2, 1).type, ILineType::kLinear);
    // LIMB i-vertices where the traces meet the limb circle.
    EXPECT_GT(r.counters.verticesByType[static_cast<int>(IVertexType::kLimb)], 0u);
}

TEST(ScanlineResolver, PyramidApexIsMergedIntoOneIVertexPerLine) {  // Figure 4.4a
    TestSceneBuilder b(80, 80);
    const Vec3 apex{40, 40, 10};
    std::vector<std::pair<int, bool>> lits;
    for (auto [nx, ny] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}}) {
        Plane p{nx, ny, -0.6, 0};
        p.d = -(p.a * apex.x + p.b * apex.y + p.c * apex.z);
        lits.push_back({b.AddPlane(p.a, p.b, p.c, p.d), false});
    }
    lits.push_back({b.AddPlane(0, 0, 1, -60), false});
    int body = b.AddBody(lits);
    Resolved r = Resolve(b, body);
    // The side planes 0/2 are adjacent: their line holds the apex once (merged from the triples
    // (0, 2, 1) and (0, 2, 3)) and a base corner.
    const ILine& side = r.body.At(2, 0);
    ASSERT_EQ(side.type, ILineType::kLinear);
    int apexCount = 0;
    for (const IVertex& v : side.lists[0])
        apexCount += std::hypot(v.x - apex.x, v.y - apex.y) < 1e-6;
    EXPECT_EQ(apexCount, 1);
    // Opposite planes 0/1 meet only at the apex (a line outside the body elsewhere).
    // Every show-edge points at two plane faces.
    for (const ShowEdge& e : r.edges) {
        EXPECT_FALSE(e.conic);
        EXPECT_GE(e.faces[0], 0);
        EXPECT_GE(e.faces[1], 0);
    }
    // 4 lateral edges + the 2 base edges that are not horizontal; the 2 horizontal base edges (a
    // horizontal line is crossed by no row centre) are horizontal show-edges, which only link
    // their vertices for the renderer's pass one (§5.4).
    EXPECT_EQ(r.counters.edgesLinear, 6u);
    EXPECT_EQ(r.counters.edgesHorizontal, 2u);
    for (const ShowEdge& e : r.edges) {
        if (!e.horizontal) continue;
        EXPECT_NEAR(e.yBottom, e.yTop, 1e-9);
        EXPECT_GT(std::fabs(e.xTop - e.xBottom), 1);
    }
}

TEST(ScanlineResolver, TangentPlaneCreatesNoIVertex) {  // Figure 4.4b: tangency → none
    TestSceneBuilder b(100, 100);
    int s = b.AddQuadric(Sphere({50, 50, 50}, 20));
    int p = b.AddPlane(0.5, 0, -1, 0);  // some cut, not tangent
    int t = b.AddPlane(1, 0, 0, -70);   // x <= 70: the edge-on plane tangent to the limb
    int body = b.AddBody({{s, false}, {p, false}, {t, false}});
    Resolved r = Resolve(b, body);
    for (const ILine& l : r.body.table)
        for (const auto& list : l.lists)
            for (const IVertex& v : list) {
                // The limb's HEXTRM lies at the tangent point legitimately; no ISECT/LIMB may.
                if (v.type == IVertexType::kHextrm || v.type == IVertexType::kVextrm) continue;
                EXPECT_GT(std::hypot(v.x - 70, v.y - 50), 1e-3) << ToString(v.type);
            }
}

TEST(ScanlineResolver, ConicEdgeFacePointerFollowsTheTableOfSection44) {
    TestSceneBuilder b(100, 100);
    // Sphere cut by a plane z <= 45 in front of its centre (z = 50): the cut circle lies on the
    // front sheet, n_z < 0 there, C > 0 (limb exists) → "front".
    int s = b.AddQuadric(Sphere({50, 50, 50}, 20));
    int front = b.AddPlane(0, 0, 1, -45);
    int body = b.AddBody({{s, false}, {front, false}});
    Resolved r = Resolve(b, body);
    bool sawConic = false;
    for (const ShowEdge& e : r.edges) {
        if (r.body.At(1, 0).type != ILineType::kConic || e.iline != 1 * 2 + 0) continue;
        sawConic = true;
        EXPECT_EQ(e.faces[0], r.body.hsbs[1].face[0]);
        EXPECT_EQ(e.faces[1], r.body.hsbs[0].face[0]);  // front sheet
    }
    EXPECT_TRUE(sawConic);
    // Behind the centre (z >= 55): the circle is on the back sheet → "back".
    TestSceneBuilder b2(100, 100);
    int s2 = b2.AddQuadric(Sphere({50, 50, 50}, 20));
    int back = b2.AddPlane(0, 0, -1, 55);
    int body2 = b2.AddBody({{s2, false}, {back, false}});
    Resolved r2 = Resolve(b2, body2);
    for (const ShowEdge& e : r2.edges)
        if (e.iline == 2) {
            EXPECT_EQ(e.faces[1], r2.body.hsbs[0].face[1]);
        }
}

TEST(ScanlineResolver, CrossingQuadricsAreRefusedDisjointOnesAccepted) {
    TestSceneBuilder b(100, 100);
    int a = b.AddQuadric(Sphere({50, 50, 50}, 20));
    int c = b.AddQuadric(Sphere({60, 50, 50}, 20));
    int d = b.AddQuadric(Sphere({50, 50, 50}, 10));
    Resolved crossing = Resolve(b, b.AddBody({{a, false}, {c, true}}));
    EXPECT_TRUE(crossing.body.perPixel);
    EXPECT_EQ(crossing.body.At(1, 0).type, ILineType::kQuartic);
    Resolved shell = Resolve(b, b.AddBody({{a, false}, {d, true}}));
    EXPECT_FALSE(shell.body.perPixel);
    EXPECT_EQ(shell.body.At(1, 0).type, ILineType::kNoExist);
}

TEST(ScanlineResolver, CsgOperandsGetOutlinesOfViewDirectionSurfaces) {
    TestSceneBuilder b(100, 100);
    int cyl = b.AddQuadric({1, 1, 0, 0, 0, 0, -50, -50, 0, 5000 - 400});
    int body = b.AddBody({{cyl, false}});
    EXPECT_TRUE(Resolve(b, body).edges.empty());        // drawn alone: nothing to bound
    Resolved operand = Resolve(b, body, /*all=*/true);  // as a CSG operand: its outline
    EXPECT_EQ(operand.edges.size(), 4u);
}

}  // namespace
}  // namespace quadrix::scanline
