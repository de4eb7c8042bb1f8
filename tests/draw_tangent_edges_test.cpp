// Tangent edges of hidden-line drawings (src/quadrix/draw/trim.h, docs/drawings.md): where two
// faces meet without a crease — a box face tangent to a cylinder, a cylinder ending in a
// hemisphere of its radius — the join is a TANGENT edge, drawn thin by default, left out with
// --tangent-edges off and drawn as an ordinary edge with on; a face that cuts the cylinder at an
// angle gives an ordinary edge and no tangent one.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "quadrix/draw/drawing.h"
#include "quadrix/pipeline/pipeline.h"
#include "test_util.h"

namespace quadrix {
namespace {

using draw::CurveRole;
using draw::Drawing;
using draw::Stroke;
using draw::StrokeKind;
using draw::TangentEdges;

FlatScene Flatten(const std::string& text, int w = 480, int h = 360) {
    PipelineOptions o;
    o.sceneText = text;
    o.width = w;
    o.height = h;
    PipelineResult r;
    Diagnostics d;
    EXPECT_TRUE(ReadAndFlatten(o, r, d)) << (d.Print(stderr), "");
    return std::move(r.flat);
}

Drawing DrawWith(const FlatScene& f, TangentEdges mode) {
    draw::DrawOptions o;
    o.tangentEdges = mode;
    return draw::MakeDrawing(f, o);
}

Vec3 Dev(const FlatScene& f, const Vec3& world) {
    return f.projection.deviceFromWorld.MapPoint(world);
}

// Distance from the 2-D point p to the segment's line through a, b (device px).
double OffLine(const draw::Point2& p, const Vec3& a, const Vec3& b) {
    const double dx = b.x - a.x, dy = b.y - a.y;
    return std::fabs((p.x - a.x) * dy - (p.y - a.y) * dx) / std::hypot(dx, dy);
}

// A segment stroke lying on the world line a–b (both ends within 1e-6 px of its image).
int SegmentsOn(const Drawing& d, const FlatScene& f, const Vec3& a, const Vec3& b, bool tangent) {
    const Vec3 da = Dev(f, a), db = Dev(f, b);
    int n = 0;
    for (const Stroke& s : d.strokes)
        if (s.kind == StrokeKind::kSegment && s.tangent == tangent &&
            OffLine(s.points[0], da, db) < 1e-6 && OffLine(s.points[1], da, db) < 1e-6)
            ++n;
    return n;
}

int TangentStrokes(const Drawing& d) {
    int n = 0;
    for (const Stroke& s : d.strokes) n += s.tangent;
    return n;
}

// A D-shaped block: the box x in [-1, 1], y in [0, 2] united with the cylinder x² + y² <= 1
// (along z, z in [-1, 1]). The box's sides x = ±1 are tangent to the cylinder along the lines
// (±1, 0, z): the flat sides run into the round bottom without a crease.
const char* kTangentBlock =
    "plane bl <-1 0 0 -1>; plane br <1 0 0 -1>; plane bb <0 -1 0 0>; plane bt <0 1 0 -2>;\n"
    "plane zn <0 0 -1 -1>; plane zf <0 0 1 -1>; body box <bl br bb bt zn zf>;\n"
    "quadric round <1 1 0 0 0 0 0 0 0 -1>; body bottom <round zn zf>;\n"
    "csg d (box | bottom);\n"
    "view v dop .5 .3 -1;\n";

TEST(DrawTangentEdges, BoxFaceTangentToACylinderIsAThinEdgeOffOrOn) {
    const FlatScene f = Flatten(kTangentBlock);
    const Drawing thin = DrawWith(f, TangentEdges::kThin);
    const Drawing off = DrawWith(f, TangentEdges::kOff);
    const Drawing on = DrawWith(f, TangentEdges::kOn);
    // The two tangent lines, whole: the near one (x = 1, its normal toward the viewer) visible,
    // the far one hidden. Exactly along the lines, from cap to cap.
    const Vec3 nearA{1, 0, -1}, nearB{1, 0, 1}, farA{-1, 0, -1}, farB{-1, 0, 1};
    EXPECT_EQ(thin.stats.tangentPairs, 2);
    EXPECT_EQ(thin.stats.tangentPieces, 2);
    ASSERT_EQ(TangentStrokes(thin), 2);
    EXPECT_EQ(SegmentsOn(thin, f, nearA, nearB, true), 1);
    EXPECT_EQ(SegmentsOn(thin, f, farA, farB, true), 1);
    for (const Stroke& s : thin.strokes) {
        if (!s.tangent) continue;
        EXPECT_EQ(s.role, CurveRole::kEdge);
        const Vec3 a = Dev(f, s.visible ? nearA : farA), b = Dev(f, s.visible ? nearB : farB);
        const double len = std::hypot(s.points[1].x - s.points[0].x, s.points[1].y - s.points[0].y);
        EXPECT_NEAR(len, std::hypot(b.x - a.x, b.y - a.y), 1e-6);
    }
    // off: the same drawing without them; on: the same lines as ordinary edges.
    EXPECT_EQ(TangentStrokes(off), 0);
    EXPECT_EQ(off.strokes.size() + 2, thin.strokes.size());
    EXPECT_EQ(SegmentsOn(off, f, nearA, nearB, false), 0);
    EXPECT_EQ(TangentStrokes(on), 0);
    EXPECT_EQ(on.strokes.size(), thin.strokes.size());
    EXPECT_EQ(SegmentsOn(on, f, nearA, nearB, false), 1);
    EXPECT_EQ(SegmentsOn(on, f, farA, farB, false), 1);
}

// The same block with the box narrowed to x in [-0.8, 0.8]: its sides cut the cylinder at
// y = 0.6 at an angle, a crease, so ordinary edges and no tangent edge.
TEST(DrawTangentEdges, BoxFaceCuttingACylinderIsAnOrdinaryEdge) {
    std::string scene = kTangentBlock;
    scene.replace(scene.find("<-1 0 0 -1>"), 11, "<-1 0 0 -.8>");
    scene.replace(scene.find("<1 0 0 -1>"), 10, "<1 0 0 -.8>");
    const FlatScene f = Flatten(scene);
    const Drawing d = DrawWith(f, TangentEdges::kThin);
    EXPECT_EQ(d.stats.tangentPairs, 0);
    EXPECT_EQ(d.stats.tangentPieces, 0);
    EXPECT_EQ(TangentStrokes(d), 0);
    EXPECT_EQ(SegmentsOn(d, f, {.8, .6, -1}, {.8, .6, 1}, false), 1);
    EXPECT_EQ(DrawWith(f, TangentEdges::kOff).strokes.size(), d.strokes.size());
}

// A rod ending in a hemisphere of its radius: x² + z² <= 1 for y in [0, 2], united with the unit
// sphere. The circle y = 0 where they join lies on three surfaces (the rod's end plane, the
// sphere, the cylinder) and two candidate curves carry it (plane ∩ sphere, plane ∩ cylinder):
// it is drawn once, a whole tangent circle, front half visible and back half hidden.
TEST(DrawTangentEdges, HemisphereEndOfARodIsOneTangentCircle) {
    const FlatScene f = Flatten(
        "quadric rod <1 0 1 0 0 0 0 0 0 -1>; plane base <0 -1 0 0>; plane cap <0 1 0 -2>;\n"
        "body shaft <rod base cap>; quadric ball <1 1 1 0 0 0 0 0 0 -1>; body tip <ball>;\n"
        "csg pin (shaft | tip); view v dop 0 .4 -1;\n");
    const Drawing d = DrawWith(f, TangentEdges::kThin);
    double visible = 0, hidden = 0;
    for (const Stroke& s : d.strokes) {
        if (!s.tangent) continue;
        ASSERT_EQ(s.kind, StrokeKind::kEllipseArc);
        (s.visible ? visible : hidden) += s.a1 - s.a0;
    }
    // Seen from above the join's plane (dop y > 0), the front half of the circle is in view:
    // π each (the arcs end where the outline touches it, to the bisection's precision).
    EXPECT_NEAR(visible, M_PI, 1e-6);
    EXPECT_NEAR(hidden, M_PI, 1e-6);
    EXPECT_EQ(TangentStrokes(DrawWith(f, TangentEdges::kOff)), 0);
}

std::string ReadText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The command line: the machined part's slot (flat sides running into a round bottom) has one
// visible tangent edge in its own view, written with class "tangent"; off leaves it out.
TEST(DrawTangentEdges, CommandLineOption) {
    testing::TempDir dir;
    const std::string scene = testing::SourcePath("examples/machined_part.uq");
    auto count = [](const std::string& svg, const std::string& what) {
        int n = 0;
        for (auto at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
        return n;
    };
    const std::string cmd = testing::QuadrixBinary() + " draw '" + scene + "' --size 400x300";
    auto thin = testing::RunShell(cmd + " -o '" + dir.File("thin.svg") + "'");
    ASSERT_EQ(thin.exitCode, 0) << thin.err;
    auto off = testing::RunShell(cmd + " --tangent-edges off -o '" + dir.File("off.svg") + "'");
    ASSERT_EQ(off.exitCode, 0) << off.err;
    const std::string a = ReadText(dir.File("thin.svg")), b = ReadText(dir.File("off.svg"));
    EXPECT_EQ(count(a, "<path class=\"tangent\""), 1);
    EXPECT_EQ(count(b, "class=\"tangent\""), 0);
    EXPECT_EQ(count(a, "<path class=\"edge\""), count(b, "<path class=\"edge\""));
    auto bad = testing::RunShell(cmd + " --tangent-edges dotted -o '" + dir.File("x.svg") + "'");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_FALSE(testing::FileExists(dir.File("x.svg")));
}

}  // namespace
}  // namespace quadrix
