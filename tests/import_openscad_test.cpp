// OpenSCAD CSG import: a model of 24 primitives rendered from above with rt's explicit camera, its
// silhouette compared pixel for pixel with the analytic one (and with what OpenSCAD's faceted
// preview would cover), transforms checked by point membership, and bad input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "quadrix/import/openscad/openscad_import.h"
#include "quadrix/import/rt_view.h"
#include "quadrix/math/srgb.h"
#include "quadrix/pipeline/inputs.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/scene/css_colors.h"
#include "test_util.h"

namespace quadrix::import {
namespace {

struct Disc {
    double x, y, r;
};
struct Rect {
    double x0, y0, x1, y1;
};

// The model: 8 spheres and 8 cylinders/cones along two rows, 4 cubes, a cube with a vertical
// hole, a sphere ∩ cube, and a lying cylinder (rotate), all seen from +z. `Covered` is the
// analytic top-view silhouette; `Facets` the same with every circle replaced by OpenSCAD's
// default polygon (fragments = max(min(360/$fa, 2πr/$fs), 5) with $fa = 12, $fs = 2).
struct Model {
    std::string text;
    std::vector<Disc> discs;
    std::vector<Rect> rects;
    Disc holeDisc{};
    Rect holeRect{};
    Disc capDisc{};
    Rect capRect{};

    static bool InDisc(const Disc& d, double x, double y, int facets) {
        double dx = x - d.x, dy = y - d.y;
        if (facets == 0) return dx * dx + dy * dy <= d.r * d.r;
        // Regular polygon with vertices at angles 360 k / n (OpenSCAD's circle), inscribed.
        double a = std::atan2(dy, dx);
        double step = 2 * std::numbers::pi / facets;
        double k = std::floor(a / step);
        double a0 = k * step, a1 = a0 + step;
        double px = d.r * std::cos(a0), py = d.r * std::sin(a0);
        double qx = d.r * std::cos(a1), qy = d.r * std::sin(a1);
        // Inside the triangle (0, p, q): on the origin's side of the chord pq.
        double cross = (qx - px) * (dy - py) - (qy - py) * (dx - px);
        return cross >= 0;
    }
    static int Fragments(double r) {
        return static_cast<int>(std::max(std::min(360.0 / 12, 2 * std::numbers::pi * r / 2), 5.0));
    }
    static bool InRect(const Rect& r, double x, double y) {
        return x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1;
    }
    bool Covered(double x, double y, bool faceted) const {
        auto f = [&](const Disc& d) { return faceted ? Fragments(d.r) : 0; };
        for (const Disc& d : discs)
            if (InDisc(d, x, y, f(d))) return true;
        for (const Rect& r : rects)
            if (InRect(r, x, y)) return true;
        if (InRect(holeRect, x, y) && !InDisc(holeDisc, x, y, f(holeDisc))) return true;
        if (InRect(capRect, x, y) && InDisc(capDisc, x, y, f(capDisc))) return true;
        return false;
    }
    // Distance-like margin to the nearest analytic boundary (to skip pixels centred on one).
    double Margin(double x, double y) const {
        double m = 1e9;
        auto disc = [&](const Disc& d) {
            m = std::min(m, std::fabs(std::hypot(x - d.x, y - d.y) - d.r));
        };
        auto rect = [&](const Rect& r) {
            m = std::min({m, std::fabs(x - r.x0), std::fabs(x - r.x1), std::fabs(y - r.y0),
                          std::fabs(y - r.y1)});
        };
        for (const Disc& d : discs) disc(d);
        for (const Rect& r : rects) rect(r);
        disc(holeDisc), rect(holeRect), disc(capDisc), rect(capRect);
        return m;
    }
};

Model MakeModel() {
    Model m;
    std::string& t = m.text;
    t = "// written by the test suite\ngroup() {\n";
    for (int i = 0; i < 8; ++i) {  // spheres, r = 3 + 0.5 i, centres along y = 0
        double x = -70 + 18 * i, r = 3 + 0.5 * i;
        t += fmt::format(
            "  multmatrix([[1, 0, 0, {}], [0, 1, 0, 0], [0, 0, 1, {}], [0, 0, 0, 1]]) "
            "{{ sphere($fn = 0, $fa = 12, $fs = 2, r = {}); }}\n",
            x, i, r);
        m.discs.push_back({x, 0, r});
    }
    for (int i = 0; i < 8; ++i) {  // cylinders and cones (r1/r2), along y = 25
        double x = -70 + 18 * i, r1 = 2 + i, r2 = i % 2 ? 0 : 6 - 0.5 * i;
        t += fmt::format(
            "  translate([{}, 25, 0]) color([0.2, 0.6, 1]) cylinder($fn = 30, "
            "h = {}, r1 = {}, r2 = {}, center = {});\n",
            x, 5 + i, r1, r2, i % 3 == 0 ? "true" : "false");
        m.discs.push_back({x, 25, std::max(r1, r2)});
    }
    for (int i = 0; i < 4; ++i) {  // cubes along y = -25
        double x = -70 + 30 * i, s = 6 + 2 * i;
        t += fmt::format("  translate([{}, -25, 0]) cube(size = [{}, {}, 4], center = true);\n", x,
                         s, s + 1);
        m.rects.push_back({x - s / 2, -25 - (s + 1) / 2, x + s / 2, -25 + (s + 1) / 2});
    }
    // A cube with a vertical hole: difference of 2 primitives.
    t += "  difference() { translate([60, -25, 0]) cube([16, 16, 8]); "
         "translate([68, -17, -1]) cylinder(h = 10, r = 5); }\n";
    m.holeRect = {60, -25, 76, -9};
    m.holeDisc = {68, -17, 5};
    // Sphere ∩ cube, centred at (60, 45).
    t += "  translate([60, 45, 0]) intersection() { sphere(d = 20); cube(14, center = true); }\n";
    m.capRect = {53, 38, 67, 52};
    m.capDisc = {60, 45, 10};
    // A cylinder lying along y (rotate about x): a rectangle from above.
    t += "  translate([-60, 50, 0]) rotate([90, 0, 0]) cylinder(h = 12, r = 3, center = true);\n";
    m.rects.push_back({-63, 44, -57, 56});
    t += "}\n";
    return m;
}

TEST(ImportOpenScad, SilhouetteIsExactWhereFacetsAreNot) {
    testing::TempDir dir;
    Model model = MakeModel();
    std::string path = dir.Write("model.csg", model.text);
    PipelineOptions po;
    po.scenePaths = {path};
    po.width = po.height = 400;
    RtView rt;  // looking down -z, x right, y up (viewrot = identity)
    rt.viewsize = 200;
    rt.eye = {0, 10, 100};
    po.rtView = rt;
    PipelineResult res;
    Diagnostics diags;
    ASSERT_TRUE(RunPipeline(po, res, diags)) << diags.Items().size();
    ASSERT_EQ(res.inputs.imports.size(), 1u);
    const ImportReport& rep = res.inputs.imports[0].second;
    EXPECT_EQ(rep.census,
              (std::map<std::string, int>{{"cube", 6}, {"cylinder", 10}, {"sphere", 9}}));
    EXPECT_TRUE(rep.skipped.empty());
    const double cell = rt.viewsize / po.width;
    int compared = 0, wrong = 0, facetWrong = 0;
    for (int r = 0; r < po.height; ++r)
        for (int c = 0; c < po.width; ++c) {
            // rt's sample point of pixel (c, row r from the top), FORMAT.md §9.4.
            double x = rt.eye.x - rt.viewsize / 2 + c * cell;
            double y = rt.eye.y - rt.viewsize / 2 + (po.height - 1 - r) * cell;
            // Pixels whose sample lies within 1e-6 mm of an edge could go either way in floating
            // point; none should, on this grid, but the guard keeps the test honest.
            if (model.Margin(x, y) < 1e-6) continue;
            ++compared;
            bool want = model.Covered(x, y, false);
            wrong += res.frame.Covered(c, r) != want;
            facetWrong += model.Covered(x, y, true) != want;
        }
    // Samples that fall exactly on a straight edge (cube faces at multiples of the 0.5 mm cell)
    // are skipped: about 1 % of the 160000.
    EXPECT_GT(compared, 140000);
    EXPECT_EQ(wrong, 0);
    // The faceted preview would differ along the curved outlines (its chords cut inside the
    // circles by r(1 - cos(180°/n)), 0.05-0.2 mm here, i.e. a fraction of a 0.5 mm cell, so only
    // some tens of pixel samples flip).
    EXPECT_GT(facetWrong, 40);
}

Vec3 Q(double x, double y, double z) { return {x, z, y}; }

bool Inside(const scene::Scene& s, const Vec3& p) {
    std::function<bool(const scene::Csg&, int)> node = [&](const scene::Csg& c, int n) {
        const scene::CsgNode& nd = c.nodes[n];
        if (nd.isLeaf) {
            for (const scene::Literal& l : s.top.bodies[nd.ref.index].literals) {
                const scene::HalfSpace& h = s.top.halfSpaces[l.halfSpace];
                double v = h.kind == scene::HalfSpace::Kind::kQuartic ? h.quartic->Evaluate(p)
                           : h.kind == scene::HalfSpace::Kind::kPlane ? h.plane.Evaluate(p)
                                                                      : h.quadric.Evaluate(p);
                if (!(v <= 0)) return false;
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

TEST(ImportOpenScad, TransformsMatchOpenScad) {
    struct Case {
        const char* label;
        const char* text;
        Vec3 in, out;  // model coordinates
    };
    const Case cases[] = {
        {"translate", "translate([10, 0, 0]) sphere(1);", {10.9, 0, 0}, {0, 0, 0}},
        {"rotate xyz", "rotate([0, 0, 90]) translate([5, 0, 0]) sphere(1);", {0, 5, 0}, {5, 0, 0}},
        {"rotate axis",
         "rotate(a = 90, v = [1, 0, 0]) translate([0, 5, 0]) sphere(1);",
         {0, 0, 5},
         {0, 5, 0}},
        {"scale", "scale([3, 1, 1]) sphere(1);", {2.9, 0, 0}, {0, 1.1, 0}},
        {"mirror",
         "mirror([1, 0, 0]) translate([5, 0, 0]) cube(1);",
         {-5.5, 0.5, 0.5},
         {5.5, 0.5, 0.5}},
        {"cone", "cylinder(h = 10, r1 = 4, r2 = 0);", {0, 0, 0.5}, {0, 2.1, 5}},
        {"d", "cylinder(h = 2, d = 4, center = true);", {1.9, 0, -0.9}, {0, 0, 1.1}},
        {"scad positional", "$fn = 64; cube(2, true); // comment\n", {0.9, 0.9, -0.9}, {1.1, 0, 0}},
    };
    for (const Case& c : cases) {
        scene::Scene s;
        Diagnostics d;
        ImportReport r;
        ASSERT_TRUE(ImportOpenScad(c.text, "t.scad", {}, s, d, r)) << c.label;
        EXPECT_TRUE(Inside(s, Q(c.in.x, c.in.y, c.in.z))) << c.label;
        EXPECT_FALSE(Inside(s, Q(c.out.x, c.out.y, c.out.z))) << c.label;
    }
}

TEST(ImportOpenScad, ColorAppliesToItsSubtree) {
    scene::Scene s;
    Diagnostics d;
    ImportReport r;
    ASSERT_TRUE(ImportOpenScad("color(\"red\") { sphere(1); color([0, 0, 1]) cube(1); }", "t.csg",
                               {}, s, d, r));
    ASSERT_EQ(s.top.bodies.size(), 2u);
    EXPECT_EQ(s.top.bodies[0].color, (scene::Color{1, 0, 0}));
    EXPECT_EQ(s.top.bodies[1].color, (scene::Color{0, 0, 1}));
}

// Every CSS/SVG name, hex strings and alpha; OpenSCAD's values are sRGB, decoded to linear.
TEST(ImportOpenScad, ColorNamesHexAndAlpha) {
    scene::Scene s;
    Diagnostics d;
    ImportReport r;
    ASSERT_TRUE(
        ImportOpenScad("color(\"SteelBlue\", 0.5) sphere(1);\n"
                       "color([1, 0.5, 0, 0.25]) cube(1);\n"
                       "color(\"#ff8000\") cube(1);\n"
                       "color(c = \"#0f08\") cube(1);\n"
                       "color(\"rebeccapurple\") cube(1);\n",
                       "t.csg", {}, s, d, r));
    ASSERT_EQ(s.top.bodies.size(), 5u);
    const auto& b = s.top.bodies;
    EXPECT_EQ(*b[0].color, *scene::CssColor("steelblue"));
    EXPECT_EQ(*b[0].finish.opacity, 0.5);
    EXPECT_NEAR(b[1].color->g, LinearFromSrgb(0.5), 1e-15);  // 0.214
    EXPECT_NEAR(b[1].color->g, 0.2140, 1e-4);
    EXPECT_EQ(*b[1].finish.opacity, 0.25);
    EXPECT_EQ(b[2].color->r, 1);
    EXPECT_NEAR(b[2].color->g, LinearFromSrgb(128 / 255.0), 1e-15);
    EXPECT_FALSE(b[2].finish.opacity);
    EXPECT_EQ(*b[3].color, (scene::Color{0, 1, 0}));
    EXPECT_NEAR(*b[3].finish.opacity, 0x88 / 255.0, 1e-15);
    EXPECT_EQ(*b[4].color, *scene::CssColor("RebeccaPurple"));
    EXPECT_EQ(d.WarningCount(), 0);
    // An unknown name warns and is ignored.
    scene::Scene s2;
    Diagnostics d2;
    ASSERT_TRUE(ImportOpenScad("color(\"notacolor\") sphere(1);", "t.csg", {}, s2, d2, r));
    EXPECT_FALSE(s2.top.bodies[0].color);
    EXPECT_EQ(d2.WarningCount(), 1);
}

TEST(ImportOpenScad, UnsupportedAndBadInput) {
    {
        scene::Scene s;
        Diagnostics d;
        ImportReport r;
        // What cannot be drawn is an error naming it and its line (nothing dropped silently);
        // with allowMissing a warning, and the rest is drawn.
        const char* text =
            "sphere(1);\npolyhedron(points = [[0, 0, 0]], faces = []);\nhull() { cube(1); }\n";
        EXPECT_FALSE(ImportOpenScad(text, "t.csg", {}, s, d, r));
        ASSERT_GE(d.Items().size(), 2u);
        EXPECT_EQ(d.Items()[1].Format(false),
                  "t.csg:3:1: error: 'hull' cannot be drawn exactly with quadrics and planes; it "
                  "is left out (--allow-missing draws the model without it)");
        ImportOptions allow;
        allow.allowMissing = true;
        Diagnostics d2;
        scene::Scene s2;
        ImportReport r2;
        EXPECT_TRUE(ImportOpenScad(text, "t.csg", allow, s2, d2, r2));
        EXPECT_EQ(r2.skipped, (std::map<std::string, int>{{"hull", 1}, {"polyhedron", 1}}));
        EXPECT_EQ(d2.Items()[0].Format(false).substr(0, 31), "t.csg:2:1: warning: polyhedron:");
        Diagnostics strictDiags;
        scene::Scene s3;
        ImportOptions strict;
        strict.strict = true;
        strict.allowMissing = true;
        EXPECT_FALSE(ImportOpenScad("hull() { cube(1); }", "t.csg", strict, s3, strictDiags, r));
    }
    const std::pair<const char*, const char*> bad[] = {
        {"sphere(r = 1;", "t.csg:1:13: error: expected ')'"},
        {"group() {\n sphere(1);\n", "t.csg:1:9: error: unbalanced '{'"},
        {"sphere(r = a + 1);", "t.csg:1:12: error: 'a': variables and expressions"},
        {"module m() { }", "t.csg:1:1: error: 'module' is not supported"},
        {"multmatrix([[1, 0]]) sphere(1);", "multmatrix: 'm' must be"},
        {"scale([0, 1, 1]) sphere(1);", "singular"},
    };
    for (const auto& [text, expect] : bad) {
        scene::Scene s;
        Diagnostics d;
        ImportReport r;
        EXPECT_FALSE(ImportOpenScad(text, "t.csg", {}, s, d, r)) << text;
        std::string all;
        for (const Diagnostic& x : d.Items()) all += x.Format(false) + "\n";
        EXPECT_NE(all.find(expect), std::string::npos) << text << "\n" << all;
    }
}

}  // namespace
}  // namespace quadrix::import

namespace quadrix::import {
namespace {

// Truncated and mutated copies of the test model: errors or a scene, never a crash or a hang.
TEST(ImportOpenScad, MutatedInputNeverCrashes) {
    std::string text = MakeModel().text;
    std::mt19937 rng(11);
    const char noise[] = "{}[]();,=*%#!$\"/ \n-+.0123456789eabc";
    for (int trial = 0; trial < 200; ++trial) {
        std::string t = text;
        if (trial % 2 == 0) {
            t.resize(std::uniform_int_distribution<std::size_t>(0, t.size())(rng));
        } else {
            for (int k = 0; k < 6; ++k)
                t[std::uniform_int_distribution<std::size_t>(0, t.size() - 1)(rng)] =
                    noise[std::uniform_int_distribution<int>(0, sizeof noise - 2)(rng)];
        }
        scene::Scene s;
        Diagnostics d;
        ImportReport r;
        bool ok = ImportOpenScad(t, "m.csg", {}, s, d, r);
        EXPECT_TRUE(ok || d.HasErrors()) << trial;
    }
}

}  // namespace
}  // namespace quadrix::import
