// BRL-CAD tor, eto, general tgc and pipe → exact quartic and quadric half-spaces (issue 20):
// membership against each primitive's own definition, exact boxes, the pipe's layout (bend
// geometry, joints that leave no crack), its volume and projected area against the analytic
// values, the readers (v4, v5, .g round trip), the ars as the closed mesh it bounds, and the
// shared samples drawn whole: the truck's 11 tyres are in the picture where they should be.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "quadrix/import/brlcad/brlcad_import.h"
#include "quadrix/import/brlcad/g_writer.h"
#include "quadrix/import/brlcad/pipe_solid.h"
#include "quadrix/import/brlcad/primitives.h"
#include "quadrix/import/brlcad/readers.h"
#include "quadrix/import/rt_view.h"
#include "quadrix/pipeline/pipeline.h"

namespace quadrix::import {
namespace {

using brlcad::Primitive;

const char* kSampleDir = "/work/shared/data/brlcad";
constexpr double kPi = std::numbers::pi;

struct Imported {
    scene::Scene scene;
    Diagnostics diags;
    ImportReport report;
    bool ok = false;
};

std::unique_ptr<Imported> Import(const std::string& text, ImportOptions options = {},
                                 const std::string& file = "test.asc") {
    auto r = std::make_unique<Imported>();
    r->ok = ImportBrlcad(text, file, options, r->scene, r->diags, r->report);
    return r;
}

std::string AllMessages(const Diagnostics& d) {
    std::string s;
    for (const Diagnostic& x : d.Items()) s += x.Format(false) + "\n";
    return s;
}

// --- membership in the imported scene (Quadrix coordinates) ---

double Eval(const scene::HalfSpace& h, const Vec3& p) {
    switch (h.kind) {
        case scene::HalfSpace::Kind::kPlane:
            return h.plane.Evaluate(p);
        case scene::HalfSpace::Kind::kQuadric:
            return h.quadric.Evaluate(p);
        case scene::HalfSpace::Kind::kQuartic:
            return h.quartic->Evaluate(p);
    }
    return 1;
}

bool NodeContains(const scene::Scope& s, const scene::Csg& c, int n, const Vec3& p) {
    const scene::CsgNode& node = c.nodes[n];
    if (node.isLeaf) {
        for (const scene::Literal& l : s.bodies[node.ref.index].literals)
            if ((Eval(s.halfSpaces[l.halfSpace], p) <= 0) == l.complemented) return false;
        return true;
    }
    bool l = NodeContains(s, c, node.left, p), r = NodeContains(s, c, node.right, p);
    switch (node.op) {
        case scene::CsgOp::kUnion:
            return l || r;
        case scene::CsgOp::kIntersection:
            return l && r;
        default:
            return l && !r;
    }
}

// Model (Z-up) point → Quadrix point.
Vec3 Q(double x, double y, double z) { return {x, z, y}; }

bool Inside(const scene::Scene& s, const std::string& id, const Vec3& p) {
    for (const scene::Csg& c : s.top.csgs)
        if (c.id == id) return NodeContains(s.top, c, c.root, p);
    ADD_FAILURE() << "no solid " << id;
    return false;
}

std::string ReadAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Torus, elliptical torus and general cone, each checked just inside and just outside its
// defining surface, in v5 and v4 form; the torus's box is exact.
TEST(ImportBrlcadQuartics, TorusEtoAndGeneralConeMembership) {
    const std::string v5 =
        "title {q}\n"
        "put {tor} tor V {0 0 0} H {0 0 2} r_a 5 r_h 1\n"  // H need not be unit
        "put {eto} eto V {20 0 0} N {0 0 1} C {0 0 2} r 5 r_d 1\n"
        "put {cone} tgc V {40 0 0} H {0 0 4} A {2 0 0} B {0 1 0} C {1 0 0} D {0 1 0}\n";
    auto im = Import(v5);
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    EXPECT_TRUE(im->report.skipped.empty());
    EXPECT_EQ(im->report.census,
              (std::map<std::string, int>{{"eto", 1}, {"tgc (quartic)", 1}, {"tor", 1}}));
    const scene::Scene& s = im->scene;
    // Torus: (ρ − 5)² + z² <= 1.
    EXPECT_TRUE(Inside(s, "tor", Q(5, 0, 0)));
    EXPECT_TRUE(Inside(s, "tor", Q(0, -5.95, 0)));
    EXPECT_FALSE(Inside(s, "tor", Q(0, -6.05, 0)));
    EXPECT_FALSE(Inside(s, "tor", Q(0, 0, 0)));  // the hole
    EXPECT_FALSE(Inside(s, "tor", Q(3.95, 0, 0)));
    EXPECT_TRUE(Inside(s, "tor", Q(3.6, 3.6, 0.5)));  // ρ = 5.09, z = 0.5
    EXPECT_FALSE(Inside(s, "tor", Q(5, 0, 1.05)));
    // Elliptical torus: semi-axis 2 along the axis, 1 along the radius, ring radius 5.
    EXPECT_TRUE(Inside(s, "eto", Q(25, 0, 1.95)));
    EXPECT_FALSE(Inside(s, "eto", Q(25, 0, 2.05)));
    EXPECT_TRUE(Inside(s, "eto", Q(25.95, 0, 0)));
    EXPECT_FALSE(Inside(s, "eto", Q(26.05, 0, 0)));
    EXPECT_TRUE(Inside(s, "eto", Q(20, 4.05, 0)));
    EXPECT_FALSE(Inside(s, "eto", Q(20, 3.95, 0)));
    // General cone: semi-axes α = 2 − z/4 along x and β = 1 along y, 0 <= z <= 4.
    EXPECT_TRUE(Inside(s, "cone", Q(41.45, 0, 2)));
    EXPECT_FALSE(Inside(s, "cone", Q(41.55, 0, 2)));
    EXPECT_TRUE(Inside(s, "cone", Q(40, 0.95, 2)));
    EXPECT_FALSE(Inside(s, "cone", Q(40, 1.05, 2)));
    EXPECT_TRUE(Inside(s, "cone", Q(40.8, 0.5, 2)));   // (0.8/1.5)² + 0.5² = 0.53
    EXPECT_FALSE(Inside(s, "cone", Q(41.2, 0.7, 2)));  // (1.2/1.5)² + 0.7² = 1.13
    EXPECT_TRUE(Inside(s, "cone", Q(40, 0, 0.05)));
    EXPECT_FALSE(Inside(s, "cone", Q(40, 0, -0.05)));
    EXPECT_FALSE(Inside(s, "cone", Q(40, 0, 4.05)));
    EXPECT_TRUE(Inside(s, "cone", Q(40.95, 0, 3.95)));
    // The torus alone: its box is exact (ring circle ⊕ ball), here rotated so that the axis is
    // not a coordinate axis: axis (0, 1, 1)/√2, the box half extents are 5·sqrt(1 − n_i²) + 1.
    auto t = Import("title {t}\nput {t} tor V {1 2 3} H {0 1 1} r_a 5 r_h 1\n");
    ASSERT_TRUE(t->ok) << AllMessages(t->diags);
    const Box3 b = t->report.bounds;  // Quadrix (x, z, y)
    const double ex = 5 + 1, eyz = 5 * std::sqrt(0.5) + 1;
    EXPECT_NEAR(b.lo.x, 1 - ex, 1e-9);
    EXPECT_NEAR(b.hi.x, 1 + ex, 1e-9);
    EXPECT_NEAR(b.lo.z, 2 - eyz, 1e-9);
    EXPECT_NEAR(b.hi.y, 3 + eyz, 1e-9);
    // v4: S 16 (V, H = normal·r2, A, B with |A| = r1, …) and S 30 eto (V N C r rd).
    std::string v4 = "I 1 v4\nt\n";
    v4 += "S 16 t 0 0 0 0  0 0 1  5 0 0  0 5 0  4 0 0  0 4 0  6 0 0  0 6 0\n";
    v4 += "S 30 e 0 20 0 0  0 0 1  0 0 2  5 1 0  0 0 0  0 0 0  0 0 0  0 0 0\n";
    auto im4 = Import(v4);
    ASSERT_TRUE(im4->ok) << AllMessages(im4->diags);
    EXPECT_TRUE(Inside(im4->scene, "t", Q(5.95, 0, 0)));
    EXPECT_FALSE(Inside(im4->scene, "t", Q(6.05, 0, 0)));
    EXPECT_TRUE(Inside(im4->scene, "e", Q(25, 0, 1.95)));
    EXPECT_FALSE(Inside(im4->scene, "e", Q(26.05, 0, 0)));
    // Bad parameters are degenerate primitives with the reason, not crashes.
    ImportOptions allow;
    allow.allowMissing = true;
    auto bad = Import("title {b}\nput {t} tor V {0 0 0} H {0 0 1} r_a 1 r_h 2\n", allow);
    EXPECT_EQ(bad->report.skipped, (std::map<std::string, int>{{"tor (degenerate)", 1}}));
}

// The test pipe: from (0,0,0) to (20,0,0) to (20,20,0), a 90° bend of radius 8 at the corner;
// the first run tapers from od 4 (solid) to od 6 with a bore of id 2 (a cone with a conical bore),
// the bend and the second run keep od 6, id 2.
std::vector<Primitive::PipePoint> TestPipe() {
    return {{{0, 0, 0}, 4, 0, 0}, {{20, 0, 0}, 6, 2, 8}, {{20, 20, 0}, 6, 2, 0}};
}

std::string PipePut(const std::string& name, const std::vector<Primitive::PipePoint>& pts) {
    std::string s = fmt::format("put {{{}}} pipe", name);
    for (std::size_t k = 0; k < pts.size(); ++k)
        s += fmt::format(" V{} {{{} {} {}}} O{} {} I{} {} R{} {}", k, pts[k].at.x, pts[k].at.y,
                         pts[k].at.z, k, pts[k].od, k, pts[k].id, k, pts[k].bend);
    return s + "\n";
}

TEST(ImportBrlcadPipe, LayoutOfOneBend) {
    brlcad::PipeLayout l = brlcad::LayOutPipe(TestPipe());
    ASSERT_TRUE(l.ok) << l.problem;
    ASSERT_EQ(l.pieces.size(), 3u);
    using K = brlcad::PipePiece::Kind;
    const auto &r1 = l.pieces[0], &b = l.pieces[1], &r2 = l.pieces[2];
    EXPECT_EQ(r1.kind, K::kRun);
    EXPECT_EQ(b.kind, K::kBend);
    EXPECT_EQ(r2.kind, K::kRun);
    // Tangent distance 8·tan 45° = 8: the bend runs from (12,0,0) to (20,8,0) about (12,8,0).
    auto near = [](const Vec3& a, const Vec3& w) { return Length(a - w) < 1e-12; };
    EXPECT_TRUE(near(r1.b, {12, 0, 0}));
    EXPECT_TRUE(near(b.a, r1.b));  // joints meet
    EXPECT_TRUE(near(b.b, {20, 8, 0}));
    EXPECT_TRUE(near(r2.a, b.b));
    EXPECT_TRUE(near(r2.b, {20, 20, 0}));
    EXPECT_TRUE(near(b.centre, {12, 8, 0}));
    EXPECT_NEAR(std::fabs(b.normal.z), 1, 1e-12);
    EXPECT_NEAR(b.angle, kPi / 2, 1e-12);
    EXPECT_NEAR(b.bend, 8, 0);
    // The radii are continuous across the joints (the run tapers to the bend's).
    EXPECT_EQ(r1.ro0, 2);
    EXPECT_EQ(r1.ri0, 0);
    EXPECT_EQ(r1.ro1, b.ro0);
    EXPECT_EQ(r1.ri1, b.ri0);
    EXPECT_EQ(b.ro1, r2.ro0);
    EXPECT_EQ(b.ro0, 3);
    EXPECT_EQ(b.ri0, 1);
    // Refusals (librt's rt_pipe_ck): bend radius below the outer radius, overlapping bends.
    auto tight = TestPipe();
    tight[1].bend = 2.5;
    EXPECT_NE(brlcad::LayOutPipe(tight).problem.find("smaller than the outer radius"),
              std::string::npos);
    auto overlap = TestPipe();
    overlap[1].bend = 25;
    EXPECT_NE(brlcad::LayOutPipe(overlap).problem.find("overlap"), std::string::npos);
    auto oneRun = TestPipe();
    oneRun[1].at = {10, 0, 0};  // collinear: a straight run through the middle point
    oneRun[2].at = {20, 0, 0};
    brlcad::PipeLayout straight = brlcad::LayOutPipe(oneRun);
    ASSERT_TRUE(straight.ok);
    EXPECT_EQ(straight.pieces.size(), 2u);
    EXPECT_EQ(straight.pieces[0].kind, K::kRun);
}

// Volume by midpoint sampling of the shape against the analytic value (runs: frustum minus
// frustum; bend: Pappus, area of the annulus × length of the centre arc), and the joints: on
// both sides of each joint plane the same points are inside.
TEST(ImportBrlcadPipe, VolumeAndJoints) {
    Primitive p;
    p.type = "pipe";
    p.name = "p";
    p.pipe = TestPipe();
    brlcad::ConvertResult cr = brlcad::ConvertPrimitive(p);
    ASSERT_EQ(cr.status, brlcad::ConvertResult::Status::kOk) << cr.problem;
    ASSERT_EQ(cr.shape.bodies.size(), 3u);
    const Shape& shape = cr.shape;
    const double frustum = kPi * 12 / 3 * (4 + 6 + 9) - kPi * 12 / 3 * 1;  // ro 2→3, ri 0→1
    const double bend = kPi * (9 - 1) * 8 * (kPi / 2);
    const double run2 = kPi * (9 - 1) * 12;
    const double want = frustum + bend + run2;
    const double h = 0.15;
    double vol = 0;
    for (double x = -3 + h / 2; x < 24; x += h)
        for (double y = -4 + h / 2; y < 21; y += h)
            for (double z = -3.2 + h / 2; z < 3.2; z += h)
                if (ShapeContains(shape, {x, y, z})) vol += h * h * h;
    EXPECT_NEAR(vol, want, 0.005 * want) << "analytic " << want;
    // Joint planes x = 12 (run → bend) and y = 8 (bend → run): no crack, no overlap.
    for (int k = 0; k < 24; ++k) {
        const double phi = 2 * kPi * k / 24;
        for (double rad : {0.5, 1.5, 2.5, 2.95, 3.05}) {
            const double u = rad * std::cos(phi), v = rad * std::sin(phi);
            const bool wall = rad > 1 && rad < 3;
            for (double eps : {-1e-7, 1e-7}) {
                EXPECT_EQ(ShapeContains(shape, {12 + eps, u, v}), wall) << rad << " " << phi;
                EXPECT_EQ(ShapeContains(shape, {20 + u, 8 + eps, v}), wall) << rad << " " << phi;
            }
        }
    }
    // The box covers the pipe and is tight where the runs end (x = −2 at the solid start).
    const Box3 box = ShapeBox(shape, Mat4::Identity());
    EXPECT_NEAR(box.lo.x, 0, 2 + 1e-9);
    EXPECT_GE(box.hi.x, 23 - 1e-9);
    EXPECT_NEAR(box.hi.x, 23, 0.05 * 8);
    EXPECT_NEAR(box.lo.z, -3, 1e-9);
    EXPECT_NEAR(box.hi.y, 20, 1e-9);
}

// The pipe drawn by the render context from a v5 database: the covered area of a top view matches
// the analytic projected area (trapezoid, annulus sector, rectangle), the centre line is covered
// without a gap and the top surface's depth is continuous across the joints.
TEST(ImportBrlcadPipe, RenderedPipeCoversItsProjectedArea) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "quadrix_pipe_test";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "pipe.asc").string();
    {
        std::ofstream out(path);
        out << "title {pipe}\n" << PipePut("p", TestPipe());
    }
    PipelineOptions po;
    po.scenePaths = {path};
    po.width = po.height = 300;
    RtView rt;
    rt.viewsize = 30.7;
    // Looking down −z, the image spans x, y ∈ centre ± 15; the centre is off the pixel grid of the
    // pipe's edges (edges on sample points would count a row or column twice).
    rt.eye = {10.05, 9.05, 50};
    po.rtView = rt;
    PipelineResult res;
    Diagnostics d;
    ASSERT_TRUE(RunPipeline(po, res, d)) << AllMessages(d);
    const Frame& f = res.frame;
    const double cell = rt.viewsize / f.width;
    int covered = 0;
    for (int r = 0; r < f.height; ++r)
        for (int c = 0; c < f.width; ++c) covered += f.Covered(c, r) ? 1 : 0;
    const double want = 12 * 5 + (kPi / 4) * (11 * 11 - 5 * 5) + 12 * 6;  // mm²
    // Each of the ~800 outline pixels is in or out by its centre: a 2 % tolerance at 0.1 mm cells.
    EXPECT_NEAR(covered * cell * cell, want, 0.02 * want);
    // Pixel of a model point (x, y): column i at x = eye.x − vs/2 + i·cell, row from the top.
    auto pixel = [&](double x, double y) {
        const int c = static_cast<int>(std::lround((x - (rt.eye.x - rt.viewsize / 2)) / cell));
        const int r =
            f.height - 1 - static_cast<int>(std::lround((y - (rt.eye.y - rt.viewsize / 2)) / cell));
        return std::pair{c, r};
    };
    std::vector<Vec3> centreLine;
    for (double x = 0.5; x <= 12; x += 0.1) centreLine.push_back({x, 0, 0});
    for (double a = 0; a <= kPi / 2; a += 0.01)
        centreLine.push_back({12 + 8 * std::sin(a), 8 - 8 * std::cos(a), 0});
    for (double y = 8; y <= 19.5; y += 0.1) centreLine.push_back({20, y, 0});
    double prevDepth = NAN;
    for (const Vec3& q : centreLine) {
        auto [c, r] = pixel(q.x, q.y);
        ASSERT_TRUE(f.Covered(c, r)) << q.x << " " << q.y;
        const double depth = f.depth[static_cast<std::size_t>(r) * f.width + c];
        if (!std::isnan(prevDepth)) {
            EXPECT_LT(std::fabs(depth - prevDepth), 0.05 * std::fabs(prevDepth) + 0.5)
                << q.x << " " << q.y;
        }
        prevDepth = depth;
    }
}

// `solid pipe` in the language (docs/language.md §3.13) is the imported pipe: TestPipe written
// with the same points (Quadrix coordinates: model (x, y, z) is (x, z, y)) draws the same picture
// as the .asc, through the same view of a .uq file: the same covered pixels except where a
// silhouette passes within rounding of a pixel centre, and the same depths.
TEST(ImportBrlcadPipe, LanguagePipeDrawsLikeTheAscPipe) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "quadrix_pipe_lang_test";
    std::filesystem::create_directories(dir);
    const std::string asc = (dir / "pipe.asc").string(), view = (dir / "view.uq").string(),
                      uq = (dir / "pipe.uq").string();
    const std::string viewText = "view v vrp 10 0 10 dop .3 -.8 -.45 whw 17 whh 14;\n";
    {
        std::ofstream(asc) << "title {pipe}\n" << PipePut("p", TestPipe());
        std::ofstream(view) << viewText;
        std::ofstream(uq) << "solid pipe hose =p 0 0 0 4 0 0 =p 20 0 0 6 2 8 =p 20 0 20 6 2 0;\n"
                          << viewText;
    }
    auto render = [&](std::vector<std::string> paths, PipelineResult& res) {
        PipelineOptions po;
        po.scenePaths = std::move(paths);
        po.viewName = "v";
        po.width = 220;
        po.height = 180;
        Diagnostics d;
        EXPECT_TRUE(RunPipeline(po, res, d)) << AllMessages(d);
    };
    PipelineResult a, b;
    render({asc, view}, a);
    render({uq}, b);
    ASSERT_EQ(a.frame.width, b.frame.width);
    int covered = 0, differ = 0;
    double worstDepth = 0;
    for (int y = 0; y < a.frame.height; ++y)
        for (int x = 0; x < a.frame.width; ++x) {
            const bool ca = a.frame.Covered(x, y), cb = b.frame.Covered(x, y);
            covered += ca;
            if (ca != cb) {
                ++differ;
            } else if (ca) {
                const std::size_t i = a.frame.Index(x, y);
                worstDepth =
                    std::max<double>(worstDepth, std::fabs(a.frame.depth[i] - b.frame.depth[i]));
            }
        }
    EXPECT_GT(covered, 3000);
    EXPECT_LE(differ, 3) << "of " << covered << " covered pixels";
    EXPECT_LT(worstDepth, 1e-3);
}

// Readers: the v5 `put` form and the binary .g round trip keep every point.
TEST(ImportBrlcadPipe, ReadFromV5AndG) {
    const std::string text = "title {p}\n" + PipePut("p", TestPipe());
    brlcad::Database db;
    Diagnostics d;
    ASSERT_TRUE(brlcad::ParseV5(text, "p.asc", db, d)) << AllMessages(d);
    ASSERT_EQ(db.primitives.size(), 1u);
    ASSERT_EQ(db.primitives[0].pipe.size(), 3u);
    std::string err;
    auto g = brlcad::WriteG(db, &err);
    ASSERT_TRUE(g) << err;
    brlcad::Database back;
    ASSERT_TRUE(brlcad::ParseG(*g, "p.g", back, d)) << AllMessages(d);
    ASSERT_EQ(back.primitives.size(), 1u);
    const auto &a = db.primitives[0].pipe, &b = back.primitives[0].pipe;
    ASSERT_EQ(b.size(), a.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(b[k].at, a[k].at);
        EXPECT_EQ(b[k].od, a[k].od);
        EXPECT_EQ(b[k].id, a[k].id);
        EXPECT_EQ(b[k].bend, a[k].bend);
    }
    EXPECT_EQ(a[1].od, 6);
    EXPECT_EQ(a[1].id, 2);
    EXPECT_EQ(a[1].bend, 8);
    // The imported scene: a point in the bend's wall, the bore, and beyond the end.
    auto im = Import(text);
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    const double c45 = std::cos(kPi / 4);
    EXPECT_TRUE(Inside(im->scene, "p", Q(12 + 10 * c45, 8 - 10 * c45, 0)));  // radius 2 from arc
    EXPECT_FALSE(Inside(im->scene, "p", Q(12 + 8 * c45, 8 - 8 * c45, 0)));   // on the bore axis
    EXPECT_FALSE(Inside(im->scene, "p", Q(20, 20.1, 2)));
    EXPECT_TRUE(Inside(im->scene, "p", Q(20, 19.9, 2)));
}

// ars (issue 20): curves of points joined into a closed mesh, drawn as the solid it bounds. The
// test ars is a square prism (±1, ±1, z from 0 to 2) with a pyramid at each end (apexes at z = −1
// and z = 3): the first and last curves are single points repeated. Read from v5 (nested and
// flat point lists), v4 (A/B records, points relative to the first) and .g (written and read
// back); an ars whose last curve does not close it is refused by name.
std::string ArsV5(const std::string& name, bool closeTop) {
    const std::string top = closeTop ? "{0 0 3} {0 0 3} {0 0 3} {0 0 3}"
                                     : "{.5 .5 3} {-.5 .5 3} {-.5 -.5 3} {.5 -.5 3}";
    return fmt::format(
        "put {{{}}} ars NC 4 PPC 4 C0 {{{{0 0 -1}} {{0 0 -1}} {{0 0 -1}} {{0 0 -1}}}} "
        "C1 {{1 1 0 -1 1 0 -1 -1 0 1 -1 0}} C2 {{{{1 1 2}} {{-1 1 2}} {{-1 -1 2}} {{1 -1 2}}}} "
        "C3 {{{}}}\n",
        name, top);
}

// A v4 granule record: `B 5 curve 0` and 8 points (the given ones, then zeros).
std::string Granule(int curve, const std::string& points) {
    std::istringstream in(points);
    std::string s = fmt::format("B 5 {} 0", curve), v;
    int n = 0;
    while (in >> v) s += " " + v, ++n;
    for (; n < 24; ++n) s += " 0";
    return s + "\n";
}

const std::string kArsV4 =
    "I 1 v4\nars test\nA 5 a 4 4 1 4\n" + Granule(0, "0 0 -1 0 0 0 0 0 0 0 0 0") +
    Granule(1, "1 1 1 -1 1 1 -1 -1 1 1 -1 1") + Granule(2, "1 1 3 -1 1 3 -1 -1 3 1 -1 3") +
    Granule(3, "0 0 4 0 0 4 0 0 4 0 0 4");

// g2asc's arsadump writes the A record with the solid's extent after the four counts
// (`A type name m n curlen totlen xmax xmin ymax ymin zmax zmin`, librt's struct ars_rec); the
// extent is redundant (the granules hold the points) and is not read.
const std::string kArsV4WithExtent =
    "I 1 v4\nars test\nA 5 a 4 4 1 4 1.0e+00 -1.0e+00 1.0e+00 -1.0e+00 3.0e+00 -1.0e+00\n" +
    Granule(0, "0 0 -1 0 0 0 0 0 0 0 0 0") + Granule(1, "1 1 1 -1 1 1 -1 -1 1 1 -1 1") +
    Granule(2, "1 1 3 -1 1 3 -1 -1 3 1 -1 3") + Granule(3, "0 0 4 0 0 4 0 0 4 0 0 4");

void ExpectTheArsSolid(const scene::Scene& s, const std::string& id) {
    EXPECT_TRUE(Inside(s, id, Q(0, 0, 1)));
    EXPECT_TRUE(Inside(s, id, Q(0.95, -0.95, 1.9)));
    EXPECT_TRUE(Inside(s, id, Q(0, 0, -0.9)));    // near the bottom apex
    EXPECT_TRUE(Inside(s, id, Q(0.1, 0, 2.85)));  // near the top apex
    EXPECT_FALSE(Inside(s, id, Q(1.05, 0, 1)));
    EXPECT_FALSE(Inside(s, id, Q(0.5, 0.5, -0.9)));  // beside the bottom pyramid
    EXPECT_FALSE(Inside(s, id, Q(0, 0, 3.05)));
}

TEST(ImportBrlcadArs, ClosedArsIsDrawnFromV5V4AndG) {
    auto v5 = Import("title {a}\n" + ArsV5("a", true));
    ASSERT_TRUE(v5->ok) << AllMessages(v5->diags);
    EXPECT_TRUE(v5->report.skipped.empty());
    ExpectTheArsSolid(v5->scene, "a");
    auto v4 = Import(kArsV4);
    ASSERT_TRUE(v4->ok) << AllMessages(v4->diags);
    ExpectTheArsSolid(v4->scene, "a");
    // .g: written from the v5 database, read back with the same curves.
    brlcad::Database db;
    Diagnostics d;
    ASSERT_TRUE(brlcad::ParseV5("title {a}\n" + ArsV5("a", true), "a.asc", db, d));
    ASSERT_EQ(db.primitives.size(), 1u);
    ASSERT_EQ(db.primitives[0].arsCurves.size(), 4u);
    std::string err;
    auto g = brlcad::WriteG(db, &err);
    ASSERT_TRUE(g) << err;
    brlcad::Database back;
    ASSERT_TRUE(brlcad::ParseG(*g, "a.g", back, d)) << AllMessages(d);
    ASSERT_EQ(back.primitives.size(), 1u);
    EXPECT_EQ(back.primitives[0].arsCurves, db.primitives[0].arsCurves);
    brlcad::Database v4db;
    ASSERT_TRUE(brlcad::ParseV4(kArsV4, "a.asc", v4db, d)) << AllMessages(d);
    ASSERT_EQ(v4db.primitives.size(), 1u);
    EXPECT_EQ(v4db.primitives[0].arsCurves, db.primitives[0].arsCurves);
    brlcad::Database withExtent;
    ASSERT_TRUE(brlcad::ParseV4(kArsV4WithExtent, "a.asc", withExtent, d)) << AllMessages(d);
    ASSERT_EQ(withExtent.primitives.size(), 1u);
    EXPECT_EQ(withExtent.primitives[0].arsCurves, db.primitives[0].arsCurves);
    // Rendered: the prism and pyramids seen from above (model z) cover the 2 × 2 square.
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "quadrix_ars_test";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "ars.asc").string();
    std::ofstream(path) << "title {a}\n" << ArsV5("a", true);
    PipelineOptions po;
    po.scenePaths = {path};
    po.width = po.height = 100;
    RtView rt;
    rt.viewsize = 4;
    rt.eye = {0.013, 0.017, 10};
    po.rtView = rt;
    PipelineResult res;
    ASSERT_TRUE(RunPipeline(po, res, d)) << AllMessages(d);
    int covered = 0;
    for (int r = 0; r < 100; ++r)
        for (int c = 0; c < 100; ++c) covered += res.frame.Covered(c, r);
    EXPECT_NEAR(covered * 0.04 * 0.04, 4.0, 0.1);
}

TEST(ImportBrlcadArs, OpenArsIsAnErrorNamingIt) {
    auto open = Import("title {a}\n" + ArsV5("cup", false));
    EXPECT_FALSE(open->ok);
    const std::string all = AllMessages(open->diags);
    EXPECT_NE(all.find("test.asc:2:1: error: primitive 'cup' (ars) cannot be drawn: its curves "
                       "do not bound a closed solid"),
              std::string::npos)
        << all;
    // Bad v4 records are positioned errors.
    brlcad::Database db;
    Diagnostics d;
    EXPECT_FALSE(brlcad::ParseV4("I 1 v4\nt\nA 5 a 4 4 1 3\n", "b.asc", db, d));
    EXPECT_NE(AllMessages(d).find("b.asc:3:"), std::string::npos) << AllMessages(d);
    Diagnostics missing;
    EXPECT_FALSE(
        brlcad::ParseV4("I 1 v4\nt\nA 5 a 2 3 1 2\n" + Granule(0, "0 0 0"), "m.asc", db, missing));
    EXPECT_NE(AllMessages(missing).find("has 1 granules"), std::string::npos)
        << AllMessages(missing);
}

// The truck (shared sample): its 11 tyres are tori. Seen from below, the bottom of the tread of
// each of the 10 road wheels (straight below the tyre's centre) and of the spare, which lies flat
// (axis ∥ z) under the bed (the bottom of its tube, one ring radius from its centre), are drawn by
// that tyre's torus: the Frame's body at those pixels is the tyre, by name.
TEST(ImportBrlcadSamples, TruckTyresArePresent) {
    const std::string path = std::string(kSampleDir) + "/truck.asc";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
    brlcad::Database db;
    Diagnostics d;
    ASSERT_TRUE(brlcad::ParseV4(ReadAll(path), "truck.asc", db, d)) << AllMessages(d);
    std::vector<const Primitive*> tyres;
    for (const Primitive& p : db.primitives)
        if (p.type == "tor") tyres.push_back(&p);
    ASSERT_EQ(tyres.size(), 11u);
    // rt's explicit view from below: view X = model x, view Y = −model y, looking up (+z).
    PipelineOptions po;
    po.scenePaths = {path};
    po.width = po.height = 160;
    RtView rt;
    rt.viewsize = 10500;
    rt.eye = {4700, 0, -2000};
    rt.viewrot = Mat4::Identity();
    rt.viewrot.m[1][1] = -1;
    rt.viewrot.m[2][2] = -1;
    po.rtView = rt;
    PipelineResult res;
    ASSERT_TRUE(RunPipeline(po, res, d)) << AllMessages(d);
    EXPECT_TRUE(res.inputs.imports[0].second.skipped.empty());
    const Frame& f = res.frame;
    const double cell = rt.viewsize / f.width;
    auto bodyNameAt = [&](double x, double y) -> std::string {
        const int c = static_cast<int>(std::floor((x - (rt.eye.x - rt.viewsize / 2)) / cell));
        const int j = static_cast<int>(std::floor((-y + rt.viewsize / 2) / cell));
        const int r = f.height - 1 - j;
        if (c < 0 || r < 0 || c >= f.width || r >= f.height) return "(outside)";
        const int b = f.body[static_cast<std::size_t>(r) * f.width + c];
        return b < 0 ? "(background)" : res.flat.bodies[b].name;
    };
    int roadWheels = 0, spare = 0;
    for (const Primitive* t : tyres) {
        if (std::fabs(Normalize(t->H).z) < 0.1) {
            EXPECT_EQ(bodyNameAt(t->V.x, t->V.y), "r" + t->name.substr(1) + "/" + t->name);
            ++roadWheels;
        } else {
            const std::string name = "r" + t->name.substr(1) + "/" + t->name;  // region/solid
            EXPECT_EQ(bodyNameAt(t->V.x + t->r1, t->V.y), name) << "spare";
            EXPECT_EQ(bodyNameAt(t->V.x - t->r1, t->V.y), name) << "spare";
            EXPECT_NE(bodyNameAt(t->V.x, t->V.y), name) << "the spare's hole";
            ++spare;
        }
    }
    EXPECT_EQ(roadWheels, 10);
    EXPECT_EQ(spare, 1);
}

}  // namespace
}  // namespace quadrix::import
