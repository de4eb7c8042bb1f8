// `quadrix draw` (src/quadrix/draw/, docs/drawings.md): exact arcs read back from the SVG,
// hidden-line break points against analytic values, drawn curves against the edges of raycast's
// Frame, degenerate views, and the command line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "quadrix/draw/drawing.h"
#include "quadrix/draw/page.h"
#include "quadrix/draw/svg_writer.h"
#include "quadrix/draw/undrawable.h"
#include "quadrix/pipeline/pipeline.h"
#include "test_util.h"

namespace quadrix {
namespace {

using draw::CurveRole;
using draw::Drawing;
using draw::Stroke;
using draw::StrokeKind;

bool Flat(const std::string& text, int w, int h, FlatScene& out) {
    PipelineOptions o;
    o.sceneText = text;
    o.width = w;
    o.height = h;
    PipelineResult r;
    Diagnostics d;
    if (!ReadAndFlatten(o, r, d)) {
        d.Print(stderr);
        return false;
    }
    out = std::move(r.flat);
    return true;
}

double PixelsPerUnit(const FlatScene& f) {
    const Mat4& m = f.projection.deviceFromWorld.Matrix();
    return std::sqrt(m(0, 0) * m(0, 0) + m(1, 0) * m(1, 0) + m(2, 0) * m(2, 0));
}

Vec3 Dev(const FlatScene& f, const Vec3& world) {
    return f.projection.deviceFromWorld.MapPoint(world);
}

struct SvgEllipse {
    std::string cls;
    double rx = 0, ry = 0;
};

std::vector<SvgEllipse> Ellipses(const std::string& svg) {
    std::vector<SvgEllipse> out;
    const std::regex re(
        R"re(<ellipse class="(\w+)" cx="[^"]*" cy="[^"]*" rx="([^"]*)" ry="([^"]*)")re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator();
         ++it)
        out.push_back({(*it)[1], std::stod((*it)[2]), std::stod((*it)[3])});
    return out;
}

const char* kCylinderZ =
    "quadric cyl <1 1 0 0 0 0 0 0 0 -4>;  plane near <0 0 -1 -5>;  plane far <0 0 1 -5>;\n"
    "body c <cyl near far>;\n";

// A cylinder seen along its axis: the near cap is one visible <ellipse> (a circle) of the exact
// radius, the far cap the same circle hidden; the cylinder itself has no silhouette.
TEST(Draw, CylinderCapSeenAlongTheAxisIsOneExactCircle) {
    FlatScene f;
    ASSERT_TRUE(Flat(std::string(kCylinderZ) + "view front dop 0 0 -1;", 400, 400, f));
    const Drawing d = draw::MakeDrawing(f);
    const std::string svg = draw::SvgDocument(draw::SingleViewPage(d, "cyl"));
    const auto el = Ellipses(svg);
    const double r = 2 * PixelsPerUnit(f);
    int visible = 0, hidden = 0;
    for (const SvgEllipse& e : el) {
        EXPECT_NEAR(e.rx / r, 1, 1e-9);
        EXPECT_NEAR(e.ry / r, 1, 1e-9);
        (e.cls == "hidden" ? hidden : visible) += 1;
    }
    EXPECT_EQ(visible, 1);
    EXPECT_EQ(hidden, 1);
    EXPECT_EQ(d.strokes.size(), 2u);  // nothing else: no silhouette, no rulings
}

// Seen obliquely, the cap is an ellipse whose major semi-axis is the radius exactly and whose
// minor one is r·cos(tilt); read back from the SVG to 1e-9 relative.
TEST(Draw, CylinderCapSeenObliquelyIsOneExactEllipse) {
    FlatScene f;
    ASSERT_TRUE(Flat(std::string(kCylinderZ) + "view tilted dop 0 1 -1;", 400, 400, f));
    const Drawing d = draw::MakeDrawing(f);
    const auto el = Ellipses(draw::SvgDocument(draw::SingleViewPage(d, "cyl")));
    const double r = 2 * PixelsPerUnit(f);
    ASSERT_GE(el.size(), 1u);  // the near cap, whole and visible
    int whole = 0;
    for (const SvgEllipse& e : el) {
        EXPECT_NEAR(e.rx / r, 1, 1e-9);
        EXPECT_NEAR(e.ry / (r * std::sqrt(0.5)), 1, 1e-9);
        whole += e.cls == "edge";
    }
    EXPECT_EQ(whole, 1);
    int silhouettes = 0;
    for (const Stroke& s : d.strokes) silhouettes += s.role == CurveRole::kSilhouette && s.visible;
    EXPECT_EQ(silhouettes, 2);  // the two outline rulings
}

// Pieces of strokes that are segments at device x ≈ `x`, as (y0, y1, visible) sorted by y.
struct Span {
    double y0, y1;
    bool visible;
};
std::vector<Span> SpansAtX(const Drawing& d, double x, double tol) {
    std::vector<Span> out;
    for (const Stroke& s : d.strokes) {
        if (s.kind != StrokeKind::kSegment) continue;
        if (std::fabs(s.points[0].x - x) > tol || std::fabs(s.points[1].x - x) > tol) continue;
        out.push_back({std::min(s.points[0].y, s.points[1].y),
                       std::max(s.points[0].y, s.points[1].y), s.visible});
    }
    std::sort(out.begin(), out.end(), [](const Span& a, const Span& b) { return a.y0 < b.y0; });
    return out;
}

// A block with a drilled hole along y (radius 2), a window cut into its front down to z = 1
// (|x| < 5, |y| < 4) that opens the hole, and a separate bar in front covering |y| < 2. Seen
// from the front:
//  - the hole's outline rulings x = ±2 (z = 0) exist only outside the window, |y| in [4, 10],
//    and are hidden there (behind the block's front face): dashed exactly from 4 to 10;
//  - where the window floor z = 1 cuts the hole, x = ±√3: visible for 2 < |y| < 4 and hidden
//    behind the bar for |y| < 2, with breaks exactly at y = ±2 and ends at ±4.
TEST(Draw, ThroughHoleIsDashedExactlyWhereItPassesBehindMaterial) {
    const std::string scene = R"(
plane bx0 <-1 0 0 -10>; plane bx1 <1 0 0 -10>; plane by0 <0 -1 0 -10>; plane by1 <0 1 0 -10>;
plane bz0 <0 0 -1 -10>; plane bz1 <0 0 1 -10>;
body block <bx0 bx1 by0 by1 bz0 bz1>;
quadric hole <1 0 1 0 0 0 0 0 0 -4>;
plane hy0 <0 -1 0 -11>; plane hy1 <0 1 0 -11>;
body drill <hole hy0 hy1>;
plane wx0 <-1 0 0 -5>; plane wx1 <1 0 0 -5>; plane wy0 <0 -1 0 -4>; plane wy1 <0 1 0 -4>;
plane wz0 <0 0 -1 -11>; plane wz1 <0 0 1 -1>;
body window <wx0 wx1 wy0 wy1 wz0 wz1>;
csg part (block - drill - window);
plane cx0 <-1 0 0 -20>; plane cx1 <1 0 0 -20>; plane cy0 <0 -1 0 -2>; plane cy1 <0 1 0 -2>;
plane cz0 <0 0 -1 -30>; plane cz1 <0 0 1 20>;
body bar <cx0 cx1 cy0 cy1 cz0 cz1>;
view front dop 0 0 -1;
)";
    FlatScene f;
    ASSERT_TRUE(Flat(scene, 600, 600, f));
    const Drawing d = draw::MakeDrawing(f);
    auto y = [&](double wy) { return Dev(f, {0, wy, 0}).y; };
    const double tol = 1e-6;  // device px; the breaks are bisected to ~1e-13
    for (double sx : {-1.0, 1.0}) {
        // Hole rulings.
        auto rul = SpansAtX(d, Dev(f, {2 * sx, 0, 0}).x, 1e-9);
        ASSERT_EQ(rul.size(), 2u) << "x = " << 2 * sx;
        for (const Span& s : rul) EXPECT_FALSE(s.visible);
        EXPECT_NEAR(rul[0].y0, y(10), tol);
        EXPECT_NEAR(rul[0].y1, y(4), tol);
        EXPECT_NEAR(rul[1].y0, y(-4), tol);
        EXPECT_NEAR(rul[1].y1, y(-10), tol);
        // The window floor's lines.
        auto fl = SpansAtX(d, Dev(f, {std::sqrt(3.0) * sx, 0, 1}).x, 1e-9);
        ASSERT_EQ(fl.size(), 3u) << "x = " << std::sqrt(3.0) * sx;
        EXPECT_TRUE(fl[0].visible);
        EXPECT_FALSE(fl[1].visible);
        EXPECT_TRUE(fl[2].visible);
        EXPECT_NEAR(fl[0].y0, y(4), tol);
        EXPECT_NEAR(fl[0].y1, y(2), tol);
        EXPECT_NEAR(fl[1].y0, y(2), tol);
        EXPECT_NEAR(fl[1].y1, y(-2), tol);
        EXPECT_NEAR(fl[2].y0, y(-2), tol);
        EXPECT_NEAR(fl[2].y1, y(-4), tol);
    }
}

// ---- Drawn curves against the edges of raycast's Frame. ----

// A pair of neighbouring pixels is a Frame edge when exactly one is background, or their surface
// ids differ and either their normals differ by more than `creaseDegrees` or their depths by more
// than 2 px, unless each pixel's point lies on the other's surface (coincident faces of different
// bodies). Two thresholds are used: drawn curves must lie near a WEAK edge (0.25°: a mitre crease
// whose dihedral angle falls to zero along the ellipse is still an edge, and the Frame's ids
// alternate along it), and STRONG edges (3°) must be drawn (a tangent join — the slot's flat side
// meeting its round bottom — changes ids with a normal jump of about a degree per pixel of
// curvature). Tangent edges (thin strokes, Stroke::tangent) are where a surface id changes with no
// normal jump: no Frame edge by definition, so they are not sampled here; their own tests are in
// tests/draw_tangent_edges_test.cpp.
struct FrameEdges {
    int w = 0, h = 0;
    std::vector<unsigned char> horiz, vert;  // pair (i, j)–(i+1, j) and (i, j)–(i, j+1)
};

FrameEdges EdgesOf(const Frame& fr, const FlatScene& flat, double creaseDegrees) {
    FrameEdges e;
    e.w = fr.width;
    e.h = fr.height;
    e.horiz.assign(static_cast<std::size_t>(e.w * e.h), 0);
    e.vert.assign(static_cast<std::size_t>(e.w * e.h), 0);
    auto edge = [&](std::size_t a, std::size_t b) {
        const bool ba = fr.surface[a] == Frame::kNone, bb = fr.surface[b] == Frame::kNone;
        if (ba || bb) return ba != bb;
        if (fr.surface[a] == fr.surface[b]) return false;
        // Different half-spaces with one surface (coincident faces of different bodies): the
        // point seen at b lies on a's surface (within 0.01 px), so no edge separates them.
        auto onSurface = [&](std::size_t from, std::size_t to) {
            const FlatHalfSpace& h = flat.halfSpaces[static_cast<std::size_t>(fr.surface[from])];
            const Vec3 q{static_cast<double>(to % static_cast<std::size_t>(fr.width)) + 0.5,
                         static_cast<double>(to / static_cast<std::size_t>(fr.width)) + 0.5,
                         fr.depth[to]};
            const double g = Length(h.isPlane ? h.plane.Normal() : h.quadric.Gradient(q));
            return g > 0 && std::fabs(h.Evaluate(q)) <= 0.01 * g;
        };
        if (onSurface(a, b) && onSurface(b, a)) return false;
        return Dot(fr.normal[a], fr.normal[b]) < std::cos(creaseDegrees * M_PI / 180) ||
               std::fabs(fr.depth[a] - fr.depth[b]) > 2;
    };
    for (int j = 0; j < e.h; ++j)
        for (int i = 0; i < e.w; ++i) {
            const std::size_t p = static_cast<std::size_t>(j * e.w + i);
            if (i + 1 < e.w) e.horiz[p] = edge(p, p + 1);
            if (j + 1 < e.h) e.vert[p] = edge(p, p + static_cast<std::size_t>(e.w));
        }
    return e;
}

double SegDist(double px, double py, double ax, double ay, double bx, double by) {
    const double dx = bx - ax, dy = by - ay;
    const double t = std::clamp(((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
    return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

// Distance from (x, y) to the nearest centre-to-centre segment of an edge pair.
double DistanceToFrameEdge(const FrameEdges& e, double x, double y) {
    double best = HUGE_VAL;
    const int ci = static_cast<int>(std::floor(x)), cj = static_cast<int>(std::floor(y));
    for (int j = cj - 2; j <= cj + 2; ++j)
        for (int i = ci - 2; i <= ci + 2; ++i) {
            if (i < 0 || j < 0 || i >= e.w || j >= e.h) continue;
            const std::size_t p = static_cast<std::size_t>(j * e.w + i);
            if (e.horiz[p]) best = std::fmin(best, SegDist(x, y, i + .5, j + .5, i + 1.5, j + .5));
            if (e.vert[p]) best = std::fmin(best, SegDist(x, y, i + .5, j + .5, i + .5, j + 1.5));
        }
    return best;
}

struct Sample : draw::Point2 {
    const Stroke* stroke = nullptr;
};

std::vector<Sample> VisibleSamples(const Drawing& d, double spacing) {
    std::vector<Sample> out;
    for (const Stroke& s : d.strokes) {
        if (!s.visible || s.tangent) continue;
        std::vector<draw::Point2> pts;
        if (s.kind == StrokeKind::kEllipseArc) {
            for (int i = 0; i <= 4096; ++i)
                pts.push_back(s.ArcPoint(s.a0 + (s.a1 - s.a0) * i / 4096));
        } else {
            pts = s.points;
        }
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
            const double len = std::hypot(pts[i + 1].x - pts[i].x, pts[i + 1].y - pts[i].y);
            const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
            for (int k = 0; k < n; ++k) {
                Sample q;
                q.x = pts[i].x + (pts[i + 1].x - pts[i].x) * k / n;
                q.y = pts[i].y + (pts[i + 1].y - pts[i].y) * k / n;
                q.stroke = &s;
                out.push_back(q);
            }
        }
        if (!pts.empty()) {
            Sample q;
            q.x = pts.back().x;
            q.y = pts.back().y;
            q.stroke = &s;
            out.push_back(q);
        }
    }
    return out;
}

struct EdgeAgreement {
    double curveNearEdge = 0;  // share of visible curve samples within 0.5 px of a Frame edge
    double edgeCovered = 0;  // share of Frame edge pairs (in runs > 3 px) within 0.75 px of a curve
    int samples = 0, edgePairs = 0;
    double farthest = 0;  // px, largest distance of a visible curve sample from a Frame edge
};

EdgeAgreement Compare(const Frame& fr, const FlatScene& flat, const Drawing& d) {
    const FrameEdges weak = EdgesOf(fr, flat, 0.25);
    const FrameEdges e = EdgesOf(fr, flat, 3);
    EdgeAgreement a;
    const auto samples = VisibleSamples(d, 0.25);
    // Curve samples → Frame edges (away from the image border, where the Frame ends).
    int near = 0, counted = 0;
    std::vector<std::vector<draw::Point2>> grid(static_cast<std::size_t>(e.w * e.h));
    for (const Sample& p : samples) {
        if (p.x < 1.5 || p.y < 1.5 || p.x > e.w - 1.5 || p.y > e.h - 1.5) continue;
        grid[static_cast<std::size_t>(static_cast<int>(p.y) * e.w + static_cast<int>(p.x))]
            .push_back(p);
        ++counted;
        const double dist = DistanceToFrameEdge(weak, p.x, p.y);
        near += dist <= 0.5 + 1e-9;
        a.farthest = std::fmax(a.farthest, dist);
        if (dist > 0.5 + 1e-9 && std::getenv("QUADRIX_DRAW_DEBUG"))
            std::printf("  far sample (%.3f, %.3f): %.3f px, stroke %s %s surfaces %d %d\n", p.x,
                        p.y, dist, draw::ToString(p.stroke->source),
                        p.stroke->role == CurveRole::kSilhouette ? "silhouette" : "edge",
                        p.stroke->surfaceA, p.stroke->surfaceB);
    }
    a.samples = counted;
    a.curveNearEdge = counted ? static_cast<double>(near) / counted : 1;
    // Frame edges in runs longer than 3 px: components of edge pixels (8-connected) of > 3.
    std::vector<int> comp(static_cast<std::size_t>(e.w * e.h), -1);
    std::vector<int> size;
    auto isEdgePixel = [&](int i, int j) {
        const std::size_t p = static_cast<std::size_t>(j * e.w + i);
        return e.horiz[p] || e.vert[p];
    };
    for (int j = 0; j < e.h; ++j)
        for (int i = 0; i < e.w; ++i) {
            if (!isEdgePixel(i, j) || comp[static_cast<std::size_t>(j * e.w + i)] >= 0) continue;
            const int id = static_cast<int>(size.size());
            size.push_back(0);
            std::vector<std::pair<int, int>> stack{{i, j}};
            comp[static_cast<std::size_t>(j * e.w + i)] = id;
            while (!stack.empty()) {
                auto [x, y] = stack.back();
                stack.pop_back();
                ++size.back();
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int u = x + dx, v = y + dy;
                        if (u < 0 || v < 0 || u >= e.w || v >= e.h || !isEdgePixel(u, v)) continue;
                        int& c = comp[static_cast<std::size_t>(v * e.w + u)];
                        if (c < 0) {
                            c = id;
                            stack.push_back({u, v});
                        }
                    }
            }
        }
    auto nearCurve = [&](double x, double y) {
        for (int j = static_cast<int>(y) - 1; j <= static_cast<int>(y) + 1; ++j)
            for (int i = static_cast<int>(x) - 1; i <= static_cast<int>(x) + 1; ++i) {
                if (i < 0 || j < 0 || i >= e.w || j >= e.h) continue;
                for (const draw::Point2& p : grid[static_cast<std::size_t>(j * e.w + i)])
                    if (std::hypot(p.x - x, p.y - y) <= 0.75) return true;
            }
        return false;
    };
    int pairs = 0, covered = 0;
    for (int j = 2; j < e.h - 2; ++j)
        for (int i = 2; i < e.w - 2; ++i) {
            const std::size_t p = static_cast<std::size_t>(j * e.w + i);
            if (comp[p] < 0 || size[static_cast<std::size_t>(comp[p])] <= 3) continue;
            for (int k = 0; k < 2; ++k) {
                if (!(k == 0 ? e.horiz[p] : e.vert[p])) continue;
                const double x = i + (k == 0 ? 1.0 : 0.5), y = j + (k == 0 ? 0.5 : 1.0);
                ++pairs;
                const bool ok = nearCurve(x, y);
                covered += ok;
                if (!ok && std::getenv("QUADRIX_DRAW_DEBUG"))
                    std::printf("  uncovered Frame edge at (%.1f, %.1f)\n", x, y);
            }
        }
    a.edgePairs = pairs;
    a.edgeCovered = pairs ? static_cast<double>(covered) / pairs : 1;
    return a;
}

std::string ReadText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

struct EdgeCase {
    std::string name, scene, view;
    // Share of visible curve samples required near a Frame edge, and the largest distance
    // allowed (see the test).
    double nearShare = 0.99;
    double farthest = 1.0;
    std::string path = {};  // read this file instead of `scene` (scenes that include others)
};

class DrawAgainstFrame : public ::testing::TestWithParam<EdgeCase> {};

TEST_P(DrawAgainstFrame, VisibleCurvesAreFrameEdgesAndFrameEdgesAreDrawn) {
    const EdgeCase& c = GetParam();
    PipelineOptions o;
    if (c.path.empty()) {
        o.sceneText = c.scene + "\n" + c.view;
    } else {
        o.scenePaths = {c.path};
    }
    o.width = 480;
    o.height = 360;
    PipelineResult r;
    Diagnostics diags;
    ASSERT_TRUE(RunPipeline(o, r, diags)) << (diags.Print(stderr), "");
    const Drawing d = draw::MakeDrawing(r.flat);
    const EdgeAgreement a = Compare(r.frame, r.flat, d);
    std::printf(
        "[ %s ] %d samples, %.4f near a Frame edge (farthest %.3f px); %d edge pairs, %.4f "
        "covered\n",
        c.name.c_str(), a.samples, a.curveNearEdge, a.farthest, a.edgePairs, a.edgeCovered);
    EXPECT_GT(a.samples, 100);
    // Measured: 0.998–1.000 of the samples, the far ones within a quarter pixel of a vertex
    // (QUADRIX_DRAW_DEBUG=1 lists them): at a convex corner the nearest pair of differing pixel
    // centres can be up to ~0.8 px away although the drawn corner is exact. 1 % is left for that;
    // nothing may be farther than one pixel (except the sub-pixel cases below).
    EXPECT_GE(a.curveNearEdge, c.nearShare);
    EXPECT_LE(a.farthest, c.farthest);
    // Measured: 1.000 everywhere.
    EXPECT_GE(a.edgeCovered, 0.99);
}

std::vector<EdgeCase> EdgeCases() {
    const std::string part = ReadText(testing::SourcePath("examples/machined_part.uq"));
    const std::string boxSphere =
        "plane sa <1 0 0 -3>; plane sb <-1 0 0 -3>; plane sc <0 1 0 -1>; plane sd <0 -1 0 -1>;\n"
        "plane se <0 0 1 -2>; plane sf <0 0 -1 -2>; body slab <sa sb sc sd se sf>;\n"
        "quadric ball <1 1 1 0 0 0 0 -1 0 0>; body sphere <ball>;\n"  // centre (0,1,0), r 1
        "quadric pin <1 0 1 0 0 0 -2 0 0 3.75>; plane pt <0 1 0 -3>; plane pb <0 -1 0 -1>;\n"
        "body post <pin pt pb>;\n"  // radius .5 at x = 2, y in [−1, 3]
        "csg s (slab | sphere | post);\n";
    const std::string sphereCylinder =
        "quadric ball <1 1 1 0 0 0 0 0 0 -4>; body sphere <ball>;\n"  // r 2 at the origin
        "quadric rod <1 0 1 0 0 0 -0.8 0 0 -0.2>; plane rt <0 1 0 -4>; plane rb <0 -1 0 -4>;\n"
        "body bar <rod rt rb>;\n"  // (x − .8)² + z² <= .84, y in [−4, 4]
        "csg s (sphere | bar);\n";
    const std::string coneCylinder =
        "quadric k <1 -0.25 1 0 0 0 0 0 0 0>; plane kt <0 1 0 -6>; plane kb <0 -1 0 0>;\n"
        "body cone <k kt kb>;\n"  // x² + z² <= (y/2)², y in [0, 6]
        "quadric cy <0 1 1 0 0 0 0 -4 0 15>; plane cr <1 0 0 -4>; plane cl <-1 0 0 -4>;\n"
        "body tube <cy cr cl>;\n"  // (y − 4)² + z² <= 1 along x
        "csg s (cone | tube);\n";
    std::vector<EdgeCase> cases;
    for (const char* f : {"bundle_of_tubes", "cylinder_minus_cylinder", "stack_of_bundles", "tube",
                          "gallery/gear", "gallery/solids", "gallery/clover_knot",
                          "gallery/hilbert3", "gallery/triangles", "gallery/name"}) {
        std::string name = f;
        std::replace(name.begin(), name.end(), '/', '_');
        // Scenes of tubes as separate overlapping bodies: where the bore of one tube is
        // partly filled by its neighbours, the visible crescent of the bore ends in tips
        // thinner than a pixel, which the drawing shows and the Frame cannot (samples there
        // lie up to ~2 px from the nearest Frame edge; 0.8–1.7 % of the samples). clover_knot:
        // 0.75 % of the samples up to 1.4 px, not yet explained (docs/drawings.md). Held to
        // 98 % and 2.5 px; every Frame edge must still be drawn.
        const std::string n = f;
        const bool subPixel =
            n == "bundle_of_tubes" || n == "stack_of_bundles" || n == "gallery/clover_knot";
        cases.push_back({name, "", "", subPixel ? 0.98 : 0.99, subPixel ? 2.5 : 1.0,
                         testing::SourcePath(std::string("examples/") + f + ".uq")});
    }
    std::vector<EdgeCase> fixed = {
        {"part_own_view", part, ""},
        {"part_front", part, "view vw_front dop 0 0 -1;"},
        {"part_top", part, "view vw_top dop 0 1 0 vup 0 0 1;"},
        {"part_right", part, "view vw_right dop 1 0 0;"},
        {"part_iso", part, "view vw_iso dop 1 1 -1;"},
        {"box_sphere_post", boxSphere, "view v dop .4 .7 -1;"},
        {"cylinder_tilted", kCylinderZ, "view v dop .3 1 -1;"},
        // Quadric–quadric curves (traced): a cylinder through a sphere, off-centre, and a cone
        // meeting a cylinder at right angles.
        {"sphere_cylinder", sphereCylinder, "view v dop .5 .6 -1;"},
        {"cone_cylinder", coneCylinder, "view v dop .8 .5 -1;"},
    };
    cases.insert(cases.begin(), fixed.begin(), fixed.end());
    return cases;
}

INSTANTIATE_TEST_SUITE_P(Scenes, DrawAgainstFrame, ::testing::ValuesIn(EdgeCases()),
                         [](const auto& info) { return info.param.name; });

// ---- Degenerate cases: no crash, sensible output. ----

// A box seen exactly from the front: its side faces are edge-on and their depth edges are seen
// end-on (points): the drawing is the four visible edges of the front face (the back face's,
// coincident with them, are hidden).
TEST(DrawDegenerate, BoxSeenFaceOnHasFourVisibleEdges) {
    FlatScene f;
    ASSERT_TRUE(
        Flat("plane sa <1 0 0 -3>; plane sb <-1 0 0 -3>; plane sc <0 1 0 -1>;\n"
             "plane sd <0 -1 0 -1>; plane se <0 0 1 -2>; plane sf <0 0 -1 -2>;\n"
             "body slab <sa sb sc sd se sf>; view front dop 0 0 -1;",
             400, 300, f));
    const Drawing d = draw::MakeDrawing(f);
    int visible = 0, hidden = 0;
    for (const Stroke& s : d.strokes) (s.visible ? visible : hidden) += 1;
    EXPECT_EQ(visible, 4);
    EXPECT_EQ(hidden, 4);
}

// Two boxes sharing a face, united: the shared face is inside the union, and the line where it
// meets the front face is no edge (the front faces are one plane: coincident faces).
TEST(DrawDegenerate, CoincidentFacesOfAUnionDrawNoEdge) {
    FlatScene f;
    ASSERT_TRUE(Flat(
        "plane ql <-1 0 0 -2>; plane qm <1 0 0 0>; plane qr <1 0 0 -2>; plane mi <-1 0 0 0>;\n"
        "plane qt <0 1 0 -1>; plane qb <0 -1 0 -1>; plane qn <0 0 -1 -1>; plane fa <0 0 1 -1>;\n"
        "body left <ql qm qt qb qn fa>; body right <mi qr qt qb qn fa>;\n"
        "csg u (left | right); view v dop .3 .4 -1;",
        400, 300, f));
    const Drawing d = draw::MakeDrawing(f);
    const double xm = Dev(f, {0, 0, -1}).x;
    const double xm2 = Dev(f, {0, 1, 1}).x;
    for (const Stroke& s : d.strokes) {
        if (s.kind != StrokeKind::kSegment) continue;
        const bool onSeam =
            (std::fabs(s.points[0].x - xm) < 1e-6 && std::fabs(s.points[1].x - xm) < 1e-6) ||
            (std::fabs(s.points[0].x - xm2) < 1e-6 && std::fabs(s.points[1].x - xm2) < 1e-6);
        EXPECT_FALSE(onSeam) << s.points[0].x << "," << s.points[0].y;
    }
    int visible = 0;
    for (const Stroke& s : d.strokes) visible += s.visible;
    EXPECT_EQ(visible, 9);  // a box seen from a corner shows 9 edges
}

// A cone: seen from the side its two outline rulings meet at the apex; seen along its axis (apex
// toward the viewer) its limb is the apex alone and the base circle is its outline.
TEST(DrawDegenerate, ConeApexSideOnAndEndOn) {
    const std::string cone = "quadric k <1 0 1 0 0 0 0 0 0 0>;\n";  // placeholder replaced below
    (void)cone;
    // x² + z² − (y/2)² <= 0 (half-angle atan(1/2)), apex at the origin, y in [0, 4].
    const std::string scene =
        "quadric k <1 -0.25 1 0 0 0 0 0 0 0>; plane top <0 1 0 -4>; plane bot <0 -1 0 0>;\n"
        "body cone <k top bot>;\n";
    FlatScene side;
    ASSERT_TRUE(Flat(scene + "view s dop 0 0 -1;", 400, 400, side));
    const Drawing ds = draw::MakeDrawing(side);
    const Vec3 apex = Dev(side, {0, 0, 0});
    int rulings = 0;
    for (const Stroke& s : ds.strokes) {
        if (s.role != CurveRole::kSilhouette || !s.visible) continue;
        ASSERT_EQ(s.kind, StrokeKind::kSegment);
        const double d0 = std::hypot(s.points[0].x - apex.x, s.points[0].y - apex.y);
        const double d1 = std::hypot(s.points[1].x - apex.x, s.points[1].y - apex.y);
        EXPECT_LT(std::fmin(d0, d1), 1e-6);
        ++rulings;
    }
    EXPECT_EQ(rulings, 2);
    FlatScene end;
    ASSERT_TRUE(Flat(scene + "view e dop 0 -1 0 vup 0 0 1;", 400, 400, end));
    const Drawing de = draw::MakeDrawing(end);
    int arcs = 0;
    for (const Stroke& s : de.strokes) arcs += s.kind == StrokeKind::kEllipseArc && s.visible;
    EXPECT_EQ(arcs, 1);  // the base circle
}

// Edges seen edge-on: a cylinder seen from the side, so the circles of its caps lie in planes that
// contain the rays. Each cap's image is a segment across the outline's full width (its ends the
// images of the circle's extreme points), not a flattened ellipse or nothing: once visible (the
// near half of the circle) and once hidden (the far half, behind the cylinder), both whole.
TEST(DrawDegenerate, CircleSeenEdgeOnIsOneSegment) {
    FlatScene f;
    ASSERT_TRUE(Flat(std::string(kCylinderZ) + "view side dop 1 0 0;", 400, 300, f));
    const Drawing d = draw::MakeDrawing(f);
    for (double z : {-5.0, 5.0}) {
        const Vec3 a = Dev(f, {0, 2, z}), b = Dev(f, {0, -2, z});
        int visible = 0, hidden = 0;
        for (const Stroke& s : d.strokes) {
            if (s.source != draw::CurveKind::kEllipse) continue;
            EXPECT_EQ(s.kind, StrokeKind::kSegment);
            const auto& p = s.points;
            const bool ab = std::hypot(p[0].x - a.x, p[0].y - a.y) < 1e-6 &&
                            std::hypot(p[1].x - b.x, p[1].y - b.y) < 1e-6;
            const bool ba = std::hypot(p[0].x - b.x, p[0].y - b.y) < 1e-6 &&
                            std::hypot(p[1].x - a.x, p[1].y - a.y) < 1e-6;
            if (ab || ba) (s.visible ? visible : hidden) += 1;
        }
        EXPECT_EQ(visible, 1) << "cap at z = " << z;
        EXPECT_EQ(hidden, 1) << "cap at z = " << z;
    }
}

// Tangent surfaces: a sphere resting on a plate and a second sphere touching the first. Touching
// points make no edges; each sphere's outline is one whole visible circle where nothing hides it.
TEST(DrawDegenerate, TangentSpheresAndPlate) {
    FlatScene f;
    ASSERT_TRUE(Flat(
        "plane pa <1 0 0 -4>; plane pb <-1 0 0 -4>; plane pc <0 1 0 0>; plane pd <0 -1 0 -1>;\n"
        "plane pe <0 0 1 -4>; plane pg <0 0 -1 -4>; body plate <pa pb pc pd pe pg>;\n"
        "quadric s1 <1 1 1 0 0 0 0 -1 0 0>; body ball1 <s1>;\n"   // centre (0,1,0) r 1
        "quadric s2 <1 1 1 0 0 0 -2 -1 0 4>; body ball2 <s2>;\n"  // centre (2,1,0) r 1
        "csg all (plate | ball1 | ball2); view v dop 0 0 -1;",
        400, 300, f));
    const Drawing d = draw::MakeDrawing(f);
    int circles = 0;
    for (const Stroke& s : d.strokes)
        if (s.kind == StrokeKind::kEllipseArc && s.role == CurveRole::kSilhouette && s.visible)
            circles += s.a1 - s.a0 > 2 * M_PI - 1e-9;
    EXPECT_EQ(circles, 2);
}

// ---- The command line. ----

TEST(DrawCommand, WritesSvgPdfEpsAndRefusesUnknownFormats) {
    testing::TempDir dir;
    const std::string scene = testing::SourcePath("examples/machined_part.uq");
    for (const char* ext : {"svg", "pdf", "eps"}) {
        const std::string out = dir.File(std::string("part.") + ext);
        auto r = testing::RunShell(testing::QuadrixBinary() + " draw '" + scene + "' -o '" + out +
                                   "' --views front,top,right,iso");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const std::string head = ReadText(out).substr(0, 40);
        const std::string e = ext;
        const std::string want =
            e == "svg" ? "<?xml" : (e == "pdf" ? "%PDF-" : "%!PS-Adobe-3.0 EPSF");
        EXPECT_EQ(head.rfind(want, 0), 0u) << e;
    }
    auto bad = testing::RunShell(testing::QuadrixBinary() + " draw '" + scene + "' -o '" +
                                 dir.File("part.txt") + "'");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_FALSE(testing::FileExists(dir.File("part.txt")));
    const std::string broken = dir.Write("broken.uq", "plane p <1 0 0>;\n");
    auto err = testing::RunShell(testing::QuadrixBinary() + " draw '" + broken + "' -o '" +
                                 dir.File("b.svg") + "'");
    EXPECT_EQ(err.exitCode, 1);
    EXPECT_NE(err.err.find("broken.uq:1:"), std::string::npos) << err.err;
    EXPECT_FALSE(testing::FileExists(dir.File("b.svg")));
    auto view = testing::RunShell(testing::QuadrixBinary() + " draw '" + scene + "' -o '" +
                                  dir.File("v.svg") + "' --views front,sideways");
    EXPECT_EQ(view.exitCode, 2);
    EXPECT_FALSE(testing::FileExists(dir.File("v.svg")));
}

// Freeform surfaces are not drawn (docs/drawings.md): `quadrix draw` stops with an error at the
// surface's definition, for a single view and a sheet, and writes nothing; --allow-missing draws
// the quadric solids with a warning naming what was left out.
TEST(DrawCommand, FreeformSurfaceIsAnErrorUnlessAllowMissing) {
    testing::TempDir dir;
    const std::string scene = dir.Write("mixed.uq",
                                        "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n"
                                        "  bezier sq 1 1 < -1 -1 3  1 -1 3  -1 1 3  1 1 3 >;\n"
                                        "bezier sq2 1 1 < -1 -1 4  1 -1 4  -1 1 4  1 1 4 >;\n");
    for (const char* views : {"", " --views front,iso"}) {
        const std::string out = dir.File("m.svg");
        const std::string cmd =
            testing::QuadrixBinary() + " draw '" + scene + "' -o '" + out + "'" + views;
        auto r = testing::RunShell(cmd);
        EXPECT_EQ(r.exitCode, 1) << views;
        EXPECT_NE(r.err.find("mixed.uq:3:3: error: freeform surface 'sq' (and 1 more freeform "
                             "surface) cannot be drawn"),
                  std::string::npos)
            << r.err;
        EXPECT_NE(r.err.find("--allow-missing"), std::string::npos) << r.err;
        EXPECT_FALSE(testing::FileExists(out)) << views;
        auto ok = testing::RunShell(cmd + " --allow-missing");
        EXPECT_EQ(ok.exitCode, 0) << ok.err;
        EXPECT_NE(ok.err.find("mixed.uq:3:3: warning: freeform surface 'sq' (and 1 more freeform "
                              "surface) left out of the drawing"),
                  std::string::npos)
            << ok.err;
        // The sphere is still drawn: its outline circle.
        EXPECT_FALSE(Ellipses(ReadText(out)).empty()) << views;
        std::remove(out.c_str());
    }
}

// The check itself (draw/undrawable.h), as every drawing front end calls it.
TEST(DrawUndrawable, FreeformsNeedAllowMissingAndQuadricScenesPass) {
    FlatScene plain, mixed;
    ASSERT_TRUE(Flat("quadric s <1 1 1 0 0 0 0 0 0 -1>; body ball (s);", 100, 100, plain));
    ASSERT_TRUE(
        Flat("quadric s <1 1 1 0 0 0 0 0 0 -1>; body ball (s);\n"
             "bezier sq 1 1 < -1 -1 3  1 -1 3  -1 1 3  1 1 3 >;",
             100, 100, mixed));
    Diagnostics d1, d2, d3;
    EXPECT_TRUE(draw::CheckDrawable(plain, false, d1));
    EXPECT_EQ(d1.ErrorCount() + d1.WarningCount(), 0);
    EXPECT_FALSE(draw::CheckDrawable(mixed, false, d2));
    EXPECT_EQ(d2.ErrorCount(), 1);
    EXPECT_TRUE(draw::CheckDrawable(mixed, true, d3));
    EXPECT_EQ(d3.ErrorCount(), 0);
    EXPECT_EQ(d3.WarningCount(), 1);
}

}  // namespace
}  // namespace quadrix
