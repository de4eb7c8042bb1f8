// OpenSCAD solids made of planes (polygon_solids.h, brlcad/mesh_solid.h): the hex nut ($fn = 6),
// an extruded L-profile, a polyhedron die with pips, rotate-extruded polygons, $fn spheres, and
// the refusals (twist, a revolved circle) with their positions. Shapes are checked against the
// exact expected solid: point membership on a dense grid and rendered top-view coverage against
// the analytic area.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "quadrix/import/openscad/openscad_import.h"
#include "quadrix/import/openscad/polygon_solids.h"
#include "quadrix/import/rt_view.h"
#include "quadrix/import/shapes/mesh_solid.h"
#include "quadrix/pipeline/inputs.h"
#include "quadrix/pipeline/pipeline.h"
#include "test_util.h"

namespace quadrix::import {
namespace {

Vec3 Q(double x, double y, double z) { return {x, z, y}; }  // model (Z up) → Quadrix

bool Inside(const scene::Scene& s, const Vec3& p) {
    std::function<bool(const scene::Csg&, int)> node = [&](const scene::Csg& c, int n) {
        const scene::CsgNode& nd = c.nodes[n];
        if (nd.isLeaf) {
            for (const scene::Literal& l : s.top.bodies[nd.ref.index].literals) {
                const scene::HalfSpace& h = s.top.halfSpaces[l.halfSpace];
                double v = h.kind == scene::HalfSpace::Kind::kQuartic ? h.quartic->Evaluate(p)
                           : h.kind == scene::HalfSpace::Kind::kPlane ? h.plane.Evaluate(p)
                                                                      : h.quadric.Evaluate(p);
                if ((v <= 0) == l.complemented) return false;
            }
            return true;
        }
        bool a = node(c, nd.left), b = node(c, nd.right);
        return nd.op == scene::CsgOp::kUnion          ? a || b
               : nd.op == scene::CsgOp::kIntersection ? a && b
                                                      : a && !b;
    };
    for (const scene::Csg& c : s.top.csgs)
        if (!c.usedAsOperand && node(c, c.root)) return true;
    return false;
}

std::string Messages(const Diagnostics& d) {
    std::string s;
    for (const Diagnostic& x : d.Items()) s += x.Format(false) + "\n";
    return s;
}

struct Loaded {
    scene::Scene scene;
    Diagnostics diags;
    ImportReport report;
    bool ok = false;
};

std::unique_ptr<Loaded> Load(const std::string& text, bool allowMissing = false) {
    auto l = std::make_unique<Loaded>();
    ImportOptions o;
    o.allowMissing = allowMissing;
    l->ok = ImportOpenScad(text, "t.scad", o, l->scene, l->diags, l->report);
    return l;
}

// Compares membership with `want` on a grid over [lo, hi]³, skipping points within `margin` of a
// boundary (`dist` gives the distance to the nearest boundary of the expected solid).
void ExpectSameSolid(const scene::Scene& s, const Vec3& lo, const Vec3& hi, int n,
                     const std::function<bool(const Vec3&)>& want,
                     const std::function<double(const Vec3&)>& dist, const char* label) {
    int compared = 0, wrong = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                Vec3 p{lo.x + (hi.x - lo.x) * (i + 0.37) / n, lo.y + (hi.y - lo.y) * (j + 0.41) / n,
                       lo.z + (hi.z - lo.z) * (k + 0.43) / n};
                if (dist(p) < 1e-7) continue;
                ++compared;
                wrong += Inside(s, Q(p.x, p.y, p.z)) != want(p);
            }
    EXPECT_GT(compared, n * n * n / 2) << label;
    EXPECT_EQ(wrong, 0) << label;
}

// Top-view (looking down -z) coverage in mm² of a file, at `width` pixels over `viewsize` mm.
double TopArea(const std::string& text, double viewsize, int width) {
    testing::TempDir dir;
    PipelineOptions po;
    po.scenePaths = {dir.Write("m.scad", text)};
    po.width = po.height = width;
    RtView rt;
    rt.viewsize = viewsize;
    rt.eye = {0, 0, 100};
    po.rtView = rt;
    PipelineResult res;
    Diagnostics d;
    EXPECT_TRUE(RunPipeline(po, res, d)) << Messages(d);
    const double cell = viewsize / width;
    return static_cast<double>(res.frame.CoveredCount()) * cell * cell;
}

// The regular hexagon of circumradius r, vertices at 0°, 60°, ... (OpenSCAD's circle, $fn = 6).
double HexDist(double r, double x, double y) {
    double d = HUGE_VAL;
    for (int i = 0; i < 6; ++i) {
        double a = (30 + 60 * i) * std::numbers::pi / 180;
        d = std::min(d, r * std::cos(std::numbers::pi / 6) - (x * std::cos(a) + y * std::sin(a)));
    }
    return d;  // > 0 inside
}

TEST(ImportOpenScadPolygons, HexNutIsAHexagonalPrism) {
    const char* nut =
        "difference() {\n"
        "  cylinder(r = 10, h = 6, $fn = 6);\n"
        "  translate([0, 0, -1]) cylinder(r = 5, h = 8);\n"
        "}\n";
    auto l = Load(nut);
    ASSERT_TRUE(l->ok) << Messages(l->diags);
    auto want = [](const Vec3& p) {
        return HexDist(10, p.x, p.y) >= 0 && std::hypot(p.x, p.y) > 5 && p.z >= 0 && p.z <= 6;
    };
    auto dist = [](const Vec3& p) {
        return std::min({std::fabs(HexDist(10, p.x, p.y)), std::fabs(std::hypot(p.x, p.y) - 5),
                         std::fabs(p.z), std::fabs(p.z - 6)});
    };
    ExpectSameSolid(l->scene, {-11, -11, -1}, {11, 11, 7}, 24, want, dist, "nut");
    // Between the hexagon and its circumcircle: outside the nut (a washer would hold it).
    EXPECT_FALSE(Inside(l->scene, Q(9.24 * std::cos(0.5236), 9.24 * std::sin(0.5236), 3)));
    EXPECT_TRUE(Inside(l->scene, Q(9.9, 0, 3)));  // near a vertex
    // Top view: the hexagon's area minus the hole, 3√3/2·10² − π·5² = 181.27 mm²; the covered
    // pixels may differ along the outline by half a pixel: perimeter (60 + 10π) × cell / 2.
    const double cell = 24.0 / 480;
    EXPECT_NEAR(TopArea(nut, 24, 480), 1.5 * std::sqrt(3.0) * 100 - std::numbers::pi * 25,
                (60 + 10 * std::numbers::pi) * cell / 2);
    // Above the threshold the circle is exact again.
    auto round = Load("cylinder(r = 10, h = 6, $fn = 64);");
    ASSERT_TRUE(round->ok);
    EXPECT_TRUE(Inside(round->scene, Q(9.995 * std::cos(0.049), 9.995 * std::sin(0.049), 3)));
    // OpenSCAD's own .csg defaults ($fn = 0, $fa = 12, $fs = 2) stay exact circles.
    auto csg = Load("cylinder($fn = 0, $fa = 12, $fs = 2, h = 6, r1 = 10, r2 = 10);");
    ASSERT_TRUE(csg->ok);
    EXPECT_TRUE(Inside(csg->scene, Q(9.24 * std::cos(0.5236), 9.24 * std::sin(0.5236), 3)));
    // A file-level $fn applies to the whole file.
    auto file = Load("$fn = 6;\ncylinder(r = 10, h = 6);\n");
    ASSERT_TRUE(file->ok);
    EXPECT_FALSE(Inside(file->scene, Q(9.24 * std::cos(0.5236), 9.24 * std::sin(0.5236), 3)));
}

// The L-profile (non-convex): the union of its convex pieces, exactly.
TEST(ImportOpenScadPolygons, ExtrudedLProfile) {
    const char* text =
        "linear_extrude(height = 5)\n"
        "  polygon(points = [[0, 0], [10, 0], [10, 2], [2, 2], [2, 8], [0, 8]]);\n";
    auto l = Load(text);
    ASSERT_TRUE(l->ok) << Messages(l->diags);
    auto inL = [](double x, double y) {
        return (x >= 0 && x <= 10 && y >= 0 && y <= 2) || (x >= 0 && x <= 2 && y >= 0 && y <= 8);
    };
    auto want = [&](const Vec3& p) { return inL(p.x, p.y) && p.z >= 0 && p.z <= 5; };
    auto dist = [](const Vec3& p) {
        return std::min({std::fabs(p.x), std::fabs(p.x - 10), std::fabs(p.x - 2), std::fabs(p.y),
                         std::fabs(p.y - 2), std::fabs(p.y - 8), std::fabs(p.z),
                         std::fabs(p.z - 5)});
    };
    ExpectSameSolid(l->scene, {-1, -1, -1}, {11, 9, 6}, 24, want, dist, "L");
    // Area 10·2 + 2·6 = 32 mm²; a half-pixel band along the 36 mm outline.
    EXPECT_NEAR(TopArea(text, 24, 480), 32, 36 * (24.0 / 480) / 2);
    // Centred, scaled to a point: a pyramid-like solid whose section shrinks linearly.
    auto cone = Load(
        "linear_extrude(height = 10, center = true, scale = 0) square(4, center = "
        "true);");
    ASSERT_TRUE(cone->ok) << Messages(cone->diags);
    EXPECT_TRUE(Inside(cone->scene, Q(1.9, 1.9, -4.9)));
    EXPECT_TRUE(Inside(cone->scene, Q(0.9, 0.9, 0.4)));  // half size at z = 0: |x| <= 1
    EXPECT_FALSE(Inside(cone->scene, Q(1.1, 0, 0.4)));
    // An exact circle extruded is a cylinder; a hole in a polygon (two paths) is a hole.
    auto ring = Load(
        "linear_extrude(height = 2) polygon(points = [[-5, -5], [5, -5], [5, 5], [-5, 5], "
        "[-2, -2], [2, -2], [2, 2], [-2, 2]], paths = [[0, 1, 2, 3], [4, 5, 6, 7]]);");
    ASSERT_TRUE(ring->ok) << Messages(ring->diags);
    EXPECT_TRUE(Inside(ring->scene, Q(4, 0, 1)));
    EXPECT_FALSE(Inside(ring->scene, Q(0, 0, 1)));
    auto disc = Load("linear_extrude(height = 2) translate([3, 0]) circle(r = 1);");
    ASSERT_TRUE(disc->ok);
    EXPECT_TRUE(Inside(disc->scene, Q(3.99, 0, 1)));
    EXPECT_FALSE(Inside(disc->scene, Q(3.75, 0.75, 1)));
}

// A die: a polyhedron cube (OpenSCAD's face order, clockwise from outside) minus spherical pips.
TEST(ImportOpenScadPolygons, PolyhedronDie) {
    const char* text =
        "difference() {\n"
        "  polyhedron(points = [[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0],\n"
        "                       [0, 0, 10], [10, 0, 10], [10, 10, 10], [0, 10, 10]],\n"
        "             faces = [[0, 1, 2, 3], [4, 5, 1, 0], [7, 6, 5, 4], [5, 6, 2, 1],\n"
        "                      [6, 7, 3, 2], [7, 4, 0, 3]]);\n"
        "  translate([5, 5, 10]) sphere(r = 1.5);\n"
        "  translate([2.5, 0, 2.5]) sphere(r = 1.5);\n"
        "  translate([7.5, 0, 7.5]) sphere(r = 1.5);\n"
        "}\n";
    auto l = Load(text);
    ASSERT_TRUE(l->ok) << Messages(l->diags);
    const Vec3 pips[] = {{5, 5, 10}, {2.5, 0, 2.5}, {7.5, 0, 7.5}};
    auto want = [&](const Vec3& p) {
        bool cube = p.x >= 0 && p.x <= 10 && p.y >= 0 && p.y <= 10 && p.z >= 0 && p.z <= 10;
        for (const Vec3& c : pips)
            if (Length(p - c) < 1.5) return false;
        return cube;
    };
    auto dist = [&](const Vec3& p) {
        double d = std::min({std::fabs(p.x), std::fabs(p.x - 10), std::fabs(p.y),
                             std::fabs(p.y - 10), std::fabs(p.z), std::fabs(p.z - 10)});
        for (const Vec3& c : pips) d = std::min(d, std::fabs(Length(p - c) - 1.5));
        return d;
    };
    ExpectSameSolid(l->scene, {-1, -1, -1}, {11, 11, 11}, 24, want, dist, "die");
    EXPECT_EQ(l->report.census.at("polyhedron"), 1);
}

// A non-convex closed mesh (an L-shaped prism as 12 triangles' worth of quads) through the BSP:
// the union of its cells is exactly the L, on a dense random sample.
TEST(ImportOpenScadPolygons, NonConvexMeshDecomposesExactly) {
    // L outline (counter-clockwise from above) at z = 0 and z = 3.
    const double xy[6][2] = {{0, 0}, {10, 0}, {10, 2}, {2, 2}, {2, 8}, {0, 8}};
    std::vector<Vec3> v;
    for (double z : {0.0, 3.0})
        for (const auto& p : xy) v.push_back({p[0], p[1], z});
    std::vector<std::vector<int>> faces = {{5, 4, 3, 2, 1, 0}, {6, 7, 8, 9, 10, 11}};
    for (int i = 0; i < 6; ++i) {
        int j = (i + 1) % 6;
        faces.push_back({i, j, 6 + j, 6 + i});
    }
    // The hexagonal caps are not convex: give them as triangles of a convex split.
    faces[0] = {0, 3, 2}, faces[1] = {6, 8, 9};
    faces.push_back({0, 2, 1});
    faces.push_back({0, 5, 4});
    faces.push_back({0, 4, 3});
    faces.push_back({6, 7, 8});
    faces.push_back({6, 9, 10});
    faces.push_back({6, 10, 11});
    MeshSolid m = MeshToSolid(v, faces);
    ASSERT_TRUE(m.ok) << m.problem;
    EXPECT_FALSE(m.convex);
    EXPECT_GE(m.shape.bodies.size(), 2u);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ux(-1, 11), uy(-1, 9), uz(-1, 4);
    int wrong = 0;
    for (int t = 0; t < 20000; ++t) {
        Vec3 p{ux(rng), uy(rng), uz(rng)};
        bool in = ((p.x >= 0 && p.x <= 10 && p.y >= 0 && p.y <= 2) ||
                   (p.x >= 0 && p.x <= 2 && p.y >= 0 && p.y <= 8)) &&
                  p.z >= 0 && p.z <= 3;
        wrong += ShapeContains(m.shape, p) != in;
    }
    EXPECT_EQ(wrong, 0);
    // An open mesh (one face removed) bounds nothing: refused with a reason.
    faces.pop_back();
    MeshSolid open = MeshToSolid(v, faces);
    EXPECT_FALSE(open.ok);
    EXPECT_NE(open.problem.find("bounds no solid"), std::string::npos) << open.problem;
}

TEST(ImportOpenScadPolygons, RotateExtrudedPolygons) {
    // A washer: the rectangle [5, 8] × [0, 2] revolved.
    auto ring = Load("rotate_extrude() polygon(points = [[5, 0], [8, 0], [8, 2], [5, 2]]);");
    ASSERT_TRUE(ring->ok) << Messages(ring->diags);
    auto want = [](const Vec3& p) {
        double r = std::hypot(p.x, p.y);
        return r >= 5 && r <= 8 && p.z >= 0 && p.z <= 2;
    };
    auto dist = [](const Vec3& p) {
        double r = std::hypot(p.x, p.y);
        return std::min({std::fabs(r - 5), std::fabs(r - 8), std::fabs(p.z), std::fabs(p.z - 2)});
    };
    ExpectSameSolid(ring->scene, {-9, -9, -1}, {9, 9, 3}, 24, want, dist, "washer");
    // A cone with a conical hole: the trapezoid profile (2, 0) (6, 0) (3, 4) (1, 4).
    auto cone = Load("rotate_extrude($fn = 100) polygon([[2, 0], [6, 0], [3, 4], [1, 4]]);");
    ASSERT_TRUE(cone->ok) << Messages(cone->diags);
    auto wantCone = [](const Vec3& p) {
        double r = std::hypot(p.x, p.y);
        // outer edge x = 6 − 3z/4, inner edge x = 2 − z/4
        return p.z >= 0 && p.z <= 4 && r <= 6 - 0.75 * p.z && r >= 2 - 0.25 * p.z;
    };
    auto distCone = [](const Vec3& p) {
        double r = std::hypot(p.x, p.y);
        return std::min({std::fabs(p.z), std::fabs(p.z - 4), std::fabs(r - (6 - 0.75 * p.z)) * 0.8,
                         std::fabs(r - (2 - 0.25 * p.z)) * 0.97});
    };
    ExpectSameSolid(cone->scene, {-7, -7, -1}, {7, 7, 5}, 24, wantCone, distCone, "cone");
}

TEST(ImportOpenScadPolygons, RotateExtrudeWithFnIsOpenScadsPolygonalRing) {
    // rotate_extrude($fn = 5) of the square [7, 10] × [0, 2]: OpenSCAD 2021.01's pentagonal ring,
    // vertices at 180° + 72°·i (so a vertex on −x, an edge's middle on +x), faces planar.
    auto ring = Load("rotate_extrude($fn = 5) translate([7, 0]) square([3, 2]);");
    ASSERT_TRUE(ring->ok) << Messages(ring->diags);
    // p·n_k − R cos 36° for the edge normals n_k at 216° + 72°·k: the largest is <= 0 inside.
    auto side = [](const Vec3& p, double r) {
        double worst = -HUGE_VAL;
        for (int k = 0; k < 5; ++k) {
            const double a = (216.0 + 72.0 * k) * std::numbers::pi / 180;
            worst = std::max(
                worst, p.x * std::cos(a) + p.y * std::sin(a) - r * std::cos(std::numbers::pi / 5));
        }
        return worst;
    };
    auto want = [&](const Vec3& p) {
        return side(p, 10) <= 0 && side(p, 7) >= 0 && p.z >= 0 && p.z <= 2;
    };
    auto dist = [&](const Vec3& p) {
        return std::min(
            {std::fabs(side(p, 10)), std::fabs(side(p, 7)), std::fabs(p.z), std::fabs(p.z - 2)});
    };
    ExpectSameSolid(ring->scene, {-11, -11, -1}, {11, 11, 3}, 30, want, dist, "pentagonal ring");
    // $fn given to a transform holds for its children, as OpenSCAD passes it down.
    auto hex = Load("translate([0, 0, 0], $fn = 6) cylinder(r = 10, h = 1);");
    ASSERT_TRUE(hex->ok) << Messages(hex->diags);
    EXPECT_TRUE(Inside(hex->scene, Q(9.5, 0, 0.5)));   // towards a vertex
    EXPECT_FALSE(Inside(hex->scene, Q(0, 9.5, 0.5)));  // beyond the apothem 8.66
}

// rotate_extrude of an exact circle is a torus; a circle scaled into an ellipse, an elliptical
// torus (BRL-CAD eto); both drawn exactly (quartics), and their top-view area is the annulus.
TEST(ImportOpenScadPolygons, RotateExtrudedCircleIsATorus) {
    auto ring = Load("rotate_extrude() translate([5, 0]) circle(r = 1);");
    ASSERT_TRUE(ring->ok) << Messages(ring->diags);
    EXPECT_EQ(ring->report.skipped.size(), 0u);
    auto torus = [](const Vec3& p) { return std::hypot(std::hypot(p.x, p.y) - 5, p.z) - 1; };
    ExpectSameSolid(
        ring->scene, {-7, -7, -2}, {7, 7, 2}, 24, [&](const Vec3& p) { return torus(p) <= 0; },
        [&](const Vec3& p) { return std::fabs(torus(p)) * 0.9; }, "torus");
    // Mirrored to negative x and stretched 2× in height: (ρ − 5)² + (z/2)² <= 1.
    auto oval = Load("rotate_extrude() translate([-5, 1]) scale([1, 2]) circle(r = 1);");
    ASSERT_TRUE(oval->ok) << Messages(oval->diags);
    auto eto = [](const Vec3& p) {
        const double u = std::hypot(p.x, p.y) - 5, v = (p.z - 1) / 2;
        return u * u + v * v - 1;
    };
    ExpectSameSolid(
        oval->scene, {-7, -7, -2}, {7, 7, 4}, 24, [&](const Vec3& p) { return eto(p) <= 0; },
        [&](const Vec3& p) { return std::fabs(eto(p)) * 0.3; }, "eto");
    const double area = TopArea("rotate_extrude() translate([5, 0]) circle(r = 1);", 16, 160);
    const double want = std::numbers::pi * (36 - 16);
    EXPECT_NEAR(area, want, 0.01 * want);
}

TEST(ImportOpenScadPolygons, FnSphereIsItsPolyhedron) {
    auto l = Load("sphere(r = 10, $fn = 8);");
    ASSERT_TRUE(l->ok) << Messages(l->diags);
    // 4 rings at polar angles 22.5°, 67.5°, ...: the widest has radius 10·sin 67.5° = 9.24.
    EXPECT_TRUE(Inside(l->scene, Q(9.2, 0, 0)));
    EXPECT_FALSE(Inside(l->scene, Q(9.5, 0, 0)));  // inside the exact sphere, not the polyhedron
    EXPECT_FALSE(Inside(l->scene, Q(0, 0, 9.5)));  // the top cap is at z = 10·cos 22.5° = 9.24
    EXPECT_TRUE(Inside(l->scene, Q(0, 0, 9.2)));
}

TEST(ImportOpenScadPolygons, RefusalsArePositionedErrors) {
    struct Case {
        const char* text;
        const char* expect;
    };
    const Case cases[] = {
        {"cube(1);\nlinear_extrude(height = 3, twist = 90) square(2);\n",
         "t.scad:2:1: error: linear_extrude with twist"},
        {"rotate_extrude() translate([0.5, 0]) circle(r = 1);\n",
         "t.scad:1:38: error: rotate_extrude: the circle reaches the rotation axis"},
        {"rotate_extrude() polygon([[-1, 0], [1, 0], [1, 1]]);\n", "crosses the axis"},
        {"polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces = [[0, 1, 2]]);\n",
         "t.scad:1:1: error: polyhedron: "},
        {"square(2);\n", "t.scad:1:1: error: 'square' is a 2D shape outside"},
    };
    for (const Case& c : cases) {
        auto l = Load(c.text);
        EXPECT_FALSE(l->ok) << c.text;
        EXPECT_NE(Messages(l->diags).find(c.expect), std::string::npos) << c.text << "\n"
                                                                        << Messages(l->diags);
        auto allowed = Load(c.text, true);
        EXPECT_TRUE(allowed->ok) << c.text << Messages(allowed->diags);
        EXPECT_FALSE(allowed->report.skipped.empty()) << c.text;
    }
}

}  // namespace
}  // namespace quadrix::import
