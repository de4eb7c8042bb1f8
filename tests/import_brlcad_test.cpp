// BRL-CAD databases → Scene: boolean trees (GIFT precedence in v4, explicit trees in v5), member
// matrices, colours, air regions, error reporting, and the sample databases of
// shared/data/brlcad (census, skipped primitives, rendering, bounding boxes).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <pthread.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

#include "quadrix/engines/registry.h"
#include "quadrix/flatten/flattener.h"
#include "quadrix/frame/frame.h"
#include "quadrix/import/brlcad/brlcad_import.h"
#include "quadrix/import/rt_view.h"
#include "quadrix/pipeline/inputs.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/util/sanitizers.h"

namespace quadrix::import {
namespace {

const char* kSampleDir = "/work/shared/data/brlcad";

// --- evaluating an imported scene at a point (Quadrix coordinates) ---

bool BodyContains(const scene::Scope& s, int b, const Vec3& p) {
    for (const scene::Literal& l : s.bodies[b].literals) {
        const scene::HalfSpace& h = s.halfSpaces[l.halfSpace];
        double v = h.kind == scene::HalfSpace::Kind::kQuartic ? h.quartic->Evaluate(p)
                   : h.kind == scene::HalfSpace::Kind::kPlane ? h.plane.Evaluate(p)
                                                              : h.quadric.Evaluate(p);
        if ((v <= 0) == l.complemented) return false;
    }
    return true;
}

bool NodeContains(const scene::Scope& s, const scene::Csg& c, int n, const Vec3& p) {
    const scene::CsgNode& node = c.nodes[n];
    if (node.isLeaf) return BodyContains(s, node.ref.index, p);
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

const scene::Csg* FindCsg(const scene::Scene& s, const std::string& id) {
    for (const scene::Csg& c : s.top.csgs)
        if (c.id == id) return &c;
    return nullptr;
}

bool Inside(const scene::Scene& s, const std::string& id, const Vec3& p) {
    const scene::Csg* c = FindCsg(s, id);
    EXPECT_NE(c, nullptr) << id;
    return c && NodeContains(s.top, *c, c->root, p);
}

// --- writing v4 records ---

std::string Matrix16(const Mat4& m) {
    std::string s;
    for (int k = 0; k < 16; ++k) s += fmt::format(" {:.12e}", m.m[k / 4][k % 4]);
    return s;
}

// An axis-aligned box [lo, hi] as a v4 GENARB8 record (V then 7 relative vectors).
std::string V4Box(const std::string& name, Vec3 lo, Vec3 hi) {
    const Vec3 d = hi - lo;
    const Vec3 rel[8] = {{0, 0, 0},   {d.x, 0, 0},   {d.x, d.y, 0},   {0, d.y, 0},
                         {0, 0, d.z}, {d.x, 0, d.z}, {d.x, d.y, d.z}, {0, d.y, d.z}};
    std::string s = fmt::format("S 20 {} 0 {:.12e} {:.12e} {:.12e}", name, lo.x, lo.y, lo.z);
    for (int i = 1; i < 8; ++i)
        s += fmt::format(" {:.12e} {:.12e} {:.12e}", rel[i].x, rel[i].y, rel[i].z);
    return s + "\n";
}

std::string V4Member(char op, const std::string& name, const Mat4& m = Mat4::Identity()) {
    return fmt::format("M {} {}{} 0\n", op, name, Matrix16(m));
}

struct Imported {
    scene::Scene scene;
    Diagnostics diags;
    ImportReport report;
    bool ok = false;
};

std::unique_ptr<Imported> Import(const std::string& text, ImportOptions options = {}) {
    auto r = std::make_unique<Imported>();
    r->ok = ImportBrlcad(text, "test.asc", options, r->scene, r->diags, r->report);
    return r;
}

std::string AllMessages(const Diagnostics& d) {
    std::string s;
    for (const Diagnostic& x : d.Items()) s += x.Format(false) + "\n";
    return s;
}

// Five unit-wide slabs along x, so that each point (i + 0.5, 0.5, 0.5) is in exactly one.
std::string FiveBoxes() {
    std::string s = "I 1 v4\nboxes\n";
    for (int i = 0; i < 5; ++i)
        s += V4Box(fmt::format("b{}", i), {double(i), 0, 0}, {i + 1.0, 1, 1});
    // "w" spans all five; "h" spans b1..b3.
    s += V4Box("w", {0, 0, 0}, {5, 1, 1});
    s += V4Box("h", {1, 0, 0}, {4, 1, 1});
    return s;
}

TEST(ImportBrlcad, V4GiftPrecedence) {
    // r = b0 u w - b1 - b2 + h u b4 = b0 ∪ ((w − b1 − b2) ∩ h) ∪ b4
    //   → slabs 0 (b0), 3 (w−b1−b2 ∩ h covers slab 3 only), 4 (b4).
    std::string text = FiveBoxes() + "C Y r 1 0 0 0 0 0 0 0 0 0 0 0 0\n" + V4Member('u', "b0") +
                       V4Member('u', "w") + V4Member('-', "b1") + V4Member('-', "b2") +
                       V4Member('+', "h") + V4Member('u', "b4");
    auto im = Import(text, {{"r"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    const bool want[5] = {true, false, false, true, true};
    for (int i = 0; i < 5; ++i)
        EXPECT_EQ(Inside(im->scene, "r", Q(i + 0.5, 0.5, 0.5)), want[i]) << "slab " << i;
}

TEST(ImportBrlcad, V4FirstOperatorIsUnion) {
    // m35 writes "M + s1" first: it is a union, not an intersection with nothing.
    std::string text = FiveBoxes() + "C Y r 1 0 0 0 0 0 0 0 0 0 0 0 0\n" + V4Member('+', "b2");
    auto im = Import(text, {{"r"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    EXPECT_TRUE(Inside(im->scene, "r", Q(2.5, 0.5, 0.5)));
}

TEST(ImportBrlcad, V5TreeMatricesAndInverseScale) {
    // A sphere of radius 1 at the origin, placed by a member matrix: rotation by 90° about z,
    // translation (10, 0, 0), and m15 = 0.5 (an inverse scale: the sphere doubles).
    std::string text =
        "title {t}\nunits mm\n"
        "put {s} ell V {1 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
        "put {r} comb region yes tree {l s {0 -1 0 5  1 0 0 0  0 0 1 0  0 0 0 0.5}}\n"
        "put {top} comb region no tree {u {l r} {l r {1 0 0 0  0 1 0 100  0 0 1 0  0 0 0 1}}}\n";
    auto im = Import(text, {{"top"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    ASSERT_EQ(im->report.solids, 2);
    // The centre (1, 0, 0) → rotated (0, 1, 0) → + (5, 0, 0) → /0.5: (10, 2, 0); radius 2.
    EXPECT_TRUE(Inside(im->scene, "r", Q(10, 2, 0)));
    EXPECT_TRUE(Inside(im->scene, "r", Q(11.9, 2, 0)));
    EXPECT_FALSE(Inside(im->scene, "r", Q(12.1, 2, 0)));
    EXPECT_TRUE(Inside(im->scene, "r#2", Q(10, 102, 1.9)));
    EXPECT_FALSE(Inside(im->scene, "r#2", Q(10, 2, 0)));
    EXPECT_NEAR(im->report.bounds.lo.x, 8, 1e-9);
    EXPECT_NEAR(im->report.bounds.hi.z, 104, 1e-9);  // Quadrix z = model y
}

TEST(ImportBrlcad, PlacementsOfOnePrimitiveAreSharedAndNamedByIndex) {
    // One sphere used four times: twice with the identity, once with an identity written with a
    // negative zero (equal entries: the same placement), once moved. Each distinct placement is
    // one body, and its half-spaces are named "<primitive>.<index in the scene>".
    std::string text =
        "title {t}\nunits mm\n"
        "put {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
        "put {r} comb region yes tree {u {u {l s} {l s}} {u {l s {1 -0 0 0  0 1 0 0  0 0 1 0  "
        "0 0 0 1}} {l s {1 0 0 10  0 1 0 0  0 0 1 0  0 0 0 1}}}}\n";
    auto im = Import(text, {{"r"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    ASSERT_EQ(im->scene.top.bodies.size(), 2u);
    ASSERT_EQ(im->scene.top.halfSpaces.size(), 2u);
    EXPECT_EQ(im->scene.top.halfSpaces[0].id, "s.0");
    EXPECT_EQ(im->scene.top.halfSpaces[1].id, "s.1");
    EXPECT_TRUE(Inside(im->scene, "r", Q(0, 0, 0)));
    EXPECT_TRUE(Inside(im->scene, "r", Q(10, 0, 0)));
    EXPECT_FALSE(Inside(im->scene, "r", Q(5, 0, 0)));
}

TEST(ImportBrlcad, ManyPlacementsEachUsedTwiceAreOneBodyEach) {
    // 300 placements of one sphere, each written twice (the second time with -0 for 0): the
    // leaf table grows past its first size several times and still finds every placement.
    std::string tree = "{l s {1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1}}";
    for (int twice = 0; twice < 2; ++twice)
        for (int i = 0; i < 300; ++i)
            tree = fmt::format("{{u {} {{l s {{1 0 0 {}  0 1 0 {}  0 0 1 0  0 0 0 1}}}}}}", tree,
                               3 * (i + 1), twice ? "-0" : "0");
    std::string text =
        "title {t}\nunits mm\nput {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
        "put {r} comb region yes tree " +
        tree + "\n";
    auto im = Import(text, {{"r"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    ASSERT_EQ(im->scene.top.bodies.size(), 301u);
    ASSERT_EQ(im->scene.top.halfSpaces.size(), 301u);
    EXPECT_EQ(im->scene.top.halfSpaces[300].id, "s.300");
    for (int i = 0; i <= 300; i += 50) {
        EXPECT_TRUE(Inside(im->scene, "r", Q(3 * i, 0, 0))) << i;
        EXPECT_FALSE(Inside(im->scene, "r", Q(3 * i + 1.5, 0, 0))) << i;
    }
}

TEST(ImportBrlcad, RegionBooleansAboveRegionsAreDistributed) {
    // FORMAT.md §5.2: group-level (R1 ∪ R2) − R3 → (R1 − R3) ∪ (R2 − R3), named after R1, R2.
    std::string text =
        "title {t}\n"
        "put {w} arb8 V1 {0 0 0} V2 {5 0 0} V3 {5 1 0} V4 {0 1 0} V5 {0 0 1} V6 {5 0 1} "
        "V7 {5 1 1} V8 {0 1 1}\n"
        "put {h} arb8 V1 {1 0 0} V2 {4 0 0} V3 {4 1 0} V4 {1 1 0} V5 {1 0 1} V6 {4 0 1} "
        "V7 {4 1 1} V8 {1 1 1}\n"
        "put {r1} comb region yes tree {l w}\n"
        "put {r2} comb region yes tree {l w {1 0 0 0  0 1 0 10  0 0 1 0  0 0 0 1}}\n"
        "put {r3} comb region yes tree {l h}\n"
        "put {g} comb region no tree {- {u {l r1} {l r2}} {l r3}}\n";
    auto im = Import(text, {{"g"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    ASSERT_EQ(im->report.solids, 2);
    EXPECT_TRUE(Inside(im->scene, "r1", Q(0.5, 0.5, 0.5)));
    EXPECT_FALSE(Inside(im->scene, "r1", Q(2.5, 0.5, 0.5)));  // cut by r3
    EXPECT_TRUE(Inside(im->scene, "r2", Q(2.5, 10.5, 0.5)));  // r3 does not reach it
}

TEST(ImportBrlcad, ColoursAirAndColorTable) {
    std::string text =
        "title {t}\n"
        "put {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
        "put {red} comb region yes tree {l s}\n"
        "attr set {red} {region} {R} {region_id} {7} {rgb} {255/0/0}\n"
        "put {tabled} comb region yes tree {l s {1 0 0 5  0 1 0 0  0 0 1 0  0 0 0 1}}\n"
        "attr set {tabled} {region} {R} {region_id} {1001}\n"
        "put {air} comb region yes tree {l s}\n"
        "attr set {air} {region} {R} {aircode} {1}\n"
        "put {locked} comb region no tree {u {l red} {l tabled}}\n"
        "attr set {locked} {rgb} {0/0/255} {inherit} {1}\n"
        "put {open} comb region no tree {u {u {l red} {l tabled}} {l air}}\n"
        "attr set {open} {rgb} {0/255/0}\n"
        "color 1000 1002 255 255 0\n";
    {
        auto im = Import(text, {{"open"}, false});
        ASSERT_TRUE(im->ok) << AllMessages(im->diags);
        ASSERT_EQ(im->report.solids, 2);  // the air region is skipped
        // The region's own colour beats an unlocked group colour; a region without one takes the
        // group's (§5.5).
        EXPECT_EQ(FindCsg(im->scene, "red")->color, (scene::Color{1, 0, 0}));
        EXPECT_EQ(FindCsg(im->scene, "tabled")->color, (scene::Color{0, 1, 0}));
    }
    {
        auto im = Import(text, {{"locked"}, false});
        ASSERT_TRUE(im->ok);
        EXPECT_EQ(FindCsg(im->scene, "red")->color, (scene::Color{0, 0, 1}));  // inherit locks
    }
    {
        auto im = Import(text, {{"tabled"}, false});
        ASSERT_TRUE(im->ok);
        EXPECT_EQ(FindCsg(im->scene, "tabled")->color, (scene::Color{1, 1, 0}));  // colour table
    }
}

// Region colours are sRGB bytes (decoded to linear light); rt shader names give finishes.
TEST(ImportBrlcad, RegionColoursAreSrgbAndShadersGiveFinishes) {
    std::string text =
        "title {t}\n"
        "put {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
        "put {pane} comb region yes tree {l s}\n"
        "attr set {pane} {region} {R} {rgb} {128/64/255} {oshader} {glass}\n"
        "put {cup} comb region yes tree {l s {1 0 0 5  0 1 0 0  0 0 1 0  0 0 0 1}}\n"
        "attr set {cup} {region} {R} {shader} {plastic {sh 20}}\n"
        "put {all} comb region no tree {u {l pane} {l cup}}\n";
    auto im = Import(text, {{"all"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    const scene::Csg* pane = FindCsg(im->scene, "pane");
    ASSERT_TRUE(pane && pane->color);
    EXPECT_NEAR(pane->color->r, 0.2158605, 1e-6);  // sRGB 128/255 → linear
    EXPECT_NEAR(pane->color->g, 0.0512695, 1e-6);
    EXPECT_EQ(pane->color->b, 1);
    EXPECT_NEAR(*pane->finish.opacity, 0.2, 1e-15);
    const scene::Csg* cup = FindCsg(im->scene, "cup");
    ASSERT_TRUE(cup);
    EXPECT_EQ(*cup->finish.shininess, 10);
    EXPECT_FALSE(cup->finish.opacity);
}

// --- bad input: clear messages naming the record, never a crash ---

struct BadCase {
    const char* label;
    std::string text;
    std::string expect;  // substring of the first error
};

TEST(ImportBrlcad, BadInputIsReportedWithPosition) {
    std::string box = V4Box("b", {0, 0, 0}, {1, 1, 1});
    std::string truncated = box.substr(0, box.size() / 2) + "\n";
    const BadCase cases[] = {
        {"truncated solid", "I 1 v4\nt\n" + truncated, "test.asc:3:"},
        {"truncated solid message", "I 1 v4\nt\n" + truncated, "truncated solid record 'b'"},
        {"bad number",
         "I 1 v4\nt\nS 19 e 0 1 2 x" +
             [] {
                 std::string zeros;
                 for (int i = 0; i < 21; ++i) zeros += " 0";
                 return zeros + "\n";
             }(),
         "'x' is not a finite number"},
        {"unknown record", "I 1 v4\nt\nZ foo\n", "test.asc:3:1: error: unknown or unsupported v4"},
        {"unknown solid type", "I 1 v4\nt\nS 99 q 0\n", "unknown solid type 99"},
        {"member outside comb", "I 1 v4\nt\n" + V4Member('u', "b"), "outside a combination"},
        {"bad operator", "I 1 v4\nt\nC Y r 1\nM x b\n", "unknown boolean operator 'x'"},
        {"cycle",
         "I 1 v4\nt\n" + box + "C N a 0\n" + V4Member('u', "b") + V4Member('u', "c") + "C N c 0\n" +
             V4Member('u', "a"),
         "contains itself"},
        {"v5 unbalanced", "title {t}\nput {s} ell V {0 0 0 A {1 0 0}\n", "test.asc:2:"},
        {"v5 unknown command", "title {t}\nkill all\n", "test.asc:2:1: error: unknown command"},
        {"v5 missing key", "title {t}\nput {s} ell V {0 0 0} A {1 0 0} B {0 1 0}\n",
         "missing parameter 'C'"},
        {"v5 short vector", "title {t}\nput {s} ell V {0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n",
         "expected a vector"},
        {"v5 bad tree", "title {t}\nput {c} comb region no tree {^ {l a} {l b}}\n",
         "unsupported tree operator '^'"},
        {"v5 cycle",
         "title {t}\nput {a} comb region no tree {l b}\n"
         "put {b} comb region no tree {l a}\n",
         "contains itself"},
        {"not a database", "hello world\nthis is not brl-cad\n", "not a BRL-CAD database"},
    };
    for (const BadCase& c : cases) {
        auto im = Import(c.text);
        EXPECT_FALSE(im->ok) << c.label;
        std::string all = AllMessages(im->diags);
        EXPECT_NE(all.find(c.expect), std::string::npos) << c.label << ":\n" << all;
    }
}

TEST(ImportBrlcad, MissingMembersWarnAndAreEmpty) {
    std::string text = FiveBoxes() + "C Y r 1 0 0 0 0 0 0 0 0 0 0 0 0\n" + V4Member('u', "b0") +
                       V4Member('u', "nosuch") + V4Member('-', "gone");
    auto im = Import(text, {{"r"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    EXPECT_EQ(im->diags.WarningCount(), 2);
    EXPECT_NE(AllMessages(im->diags).find("'r' names 'nosuch'"), std::string::npos);
    EXPECT_TRUE(Inside(im->scene, "r", Q(0.5, 0.5, 0.5)));
}

// Nothing is dropped silently: a primitive that cannot be drawn is an error naming it and its
// line, unless allowMissing (then a warning with the counts, and the rest is drawn); strict forces
// the error back.
TEST(ImportBrlcad, PrimitivesThatCannotBeDrawnAreErrorsUnlessAllowMissing) {
    std::string text =
        "title {t}\n"
        "put {t1} superell V {0 0 0} A {5 0 0} B {0 5 0} C {0 0 1} n 1 e 1\n"
        "put {t2} superell V {0 0 9} A {5 0 0} B {0 5 0} C {0 0 1} n 1 e 1\n"
        "put {q} dsp file {terra.bin} sm 0 w 256 n 256\n"
        "put {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
        "put {r} comb region yes tree {u {u {l t1} {l t2}} {u {l q} {l s}}}\n";
    {
        ImportOptions allow;
        allow.allowMissing = true;
        auto im = Import(text, allow);
        ASSERT_TRUE(im->ok) << AllMessages(im->diags);
        EXPECT_EQ(im->report.skipped, (std::map<std::string, int>{{"dsp", 1}, {"superell", 2}}));
        EXPECT_NE(AllMessages(im->diags).find("dsp ×1, superell ×2"), std::string::npos);
        EXPECT_TRUE(Inside(im->scene, "r", Q(0, 0, 0)));
    }
    {
        auto im = Import(text);
        EXPECT_FALSE(im->ok);
        const std::string all = AllMessages(im->diags);
        EXPECT_NE(all.find("test.asc:2:1: error: primitive 't1' (superell) cannot be drawn"),
                  std::string::npos)
            << all;
        EXPECT_NE(all.find("test.asc:3:1: error: primitive 't2' (superell)"), std::string::npos);
        EXPECT_NE(all.find("test.asc:4:1: error: primitive 'q' (dsp)"), std::string::npos);
        EXPECT_NE(all.find("--allow-missing"), std::string::npos);
        EXPECT_EQ(im->diags.ErrorCount(), 3);
    }
    {
        ImportOptions both;
        both.allowMissing = true;
        both.strict = true;
        EXPECT_FALSE(Import(text, both)->ok);
    }
    {
        // Only what the top objects reach counts: the sphere alone draws without error.
        std::string withTop = text + "put {ball} comb region yes tree {l s}\n";
        ImportOptions top;
        top.topObjects = {"ball"};
        auto im = Import(withTop, top);
        EXPECT_TRUE(im->ok) << AllMessages(im->diags);
        EXPECT_TRUE(im->report.skipped.empty());
    }
}

// --- the sample databases ---

std::string ReadAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

struct Sample {
    const char* file;
    std::map<std::string, int> census;   // FORMAT.md §7
    std::map<std::string, int> skipped;  // what cannot be drawn exactly
};

const Sample kSamples[] = {
    {"annual_gift_man.asc", {{"arb8", 41}, {"tgc", 41}, {"ell", 4}}, {}},
    {"arb8_showcase.asc", {{"arb8", 35}}, {}},
    {"axis.asc", {{"arb8", 11}, {"tgc", 4}, {"ell", 2}, {"tor", 2}}, {}},
    {"boolean-ops.asc", {{"arb8", 2}, {"tgc", 1}}, {}},
    {"castle.asc", {{"arb8", 36}, {"tgc", 8}, {"ell", 1}, {"half", 1}}, {}},
    {"chess/chessboard.asc", {{"arb8", 65}, {"tgc", 4}}, {}},
    {"cornell.asc", {{"arb8", 9}, {"ell", 1}}, {}},
    {"cornell-kunigami.asc", {{"arb8", 9}}, {}},
    {"cray.asc", {{"arb8", 15}, {"tgc", 4}, {"ell", 2}, {"half", 1}, {"tor", 1}}, {}},
    {"crod.asc", {{"arb8", 7}, {"tgc", 10}}, {}},
    {"cube.asc", {{"tgc", 12}, {"ell", 12}, {"half", 1}}, {}},
    {"demo.asc", {{"arb8", 42}, {"tgc", 74}, {"ell", 2}}, {}},
    {"die.asc", {{"arb8", 2}, {"tgc", 3}, {"ell", 23}}, {}},
    {"earth.asc", {{"arb8", 5}, {"ell", 8}}, {}},
    {"galileo.asc", {{"arb8", 13}, {"tgc", 13}, {"ell", 9}}, {}},
    {"ktank.asc", {{"arb8", 54}, {"tgc", 48}, {"ell", 4}}, {}},
    {"operators.asc", {{"ell", 1}, {"ehy", 1}}, {}},
    {"truck.asc", {{"arb8", 125}, {"tgc", 41}, {"ell", 5}, {"tor", 11}}, {}},
    {"wave.asc", {{"arb8", 3}, {"tgc", 5}, {"ell", 6}}, {}},
    {"xmp.asc", {{"arb8", 14}, {"tgc", 6}, {"ell", 1}, {"tor", 2}}, {}},
};

TEST(ImportBrlcadSamples, EveryDatabaseLoadsWithItsCensus) {
    if (!std::filesystem::exists(kSampleDir)) GTEST_SKIP() << "no " << kSampleDir;
    for (const Sample& s : kSamples) {
        // Every primitive of every sample is drawn (tori included): no allowMissing needed.
        auto im = Import(ReadAll(std::string(kSampleDir) + "/" + s.file));
        EXPECT_TRUE(im->ok) << s.file << "\n" << AllMessages(im->diags);
        EXPECT_EQ(im->report.census, s.census) << s.file << ": " << im->report.CensusText();
        EXPECT_EQ(im->report.skipped, s.skipped) << s.file;
        EXPECT_GT(im->report.solids, 0) << s.file;
    }
}

TEST(ImportBrlcadSamples, ComgeomDeckLoads) {
    std::string path = std::string(kSampleDir) + "/comgeom/ADA073408.comgeom";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
    auto im = Import(ReadAll(path));
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    // FORMAT.md §4: 201 RCC + 1 TRC (tgc), 59 RPP + 21 ARB8 (arb8); 282 regions of which the
    // ident table marks 46 as air.
    EXPECT_EQ(im->report.census, (std::map<std::string, int>{{"arb8", 80}, {"tgc", 202}}));
    EXPECT_TRUE(im->report.skipped.empty());
    EXPECT_EQ(im->report.solids, 282 - 46);
}

TEST(ImportBrlcad, ComgeomCardsAndErrors) {
    // Two RPPs and an RCC; region 1 = s1 − s3, region 2 = s2 OR s3 (a union), region 3 is air.
    std::string deck =
        "test deck\n"
        "3    3\n"
        "1    RPP  0.0       10.0      0.0       10.0      0.0       10.0      BOX\n"
        "2    RPP  20.0      30.0      0.0       10.0      0.0       10.0      BOX2\n"
        "3    RCC  5.0       5.0       -1.0      0.0       0.0       12.0      HOLE\n"
        "          2.0       0.0       0.0       0.0       0.0       0.0       HOLE\n"
        "  1      1      -3     0      0      0      0      0      0      0      R1\n"
        "  2      2      OR 3   0      0      0      0      0      0      0      R2\n"
        "  3      1      0      0      0      0      0      0      0      0      AIR\n"
        "-1\n"
        "1    1    0    1    100  R1\n"
        "2    2    0    1    100  R2\n"
        "3    3    1    0    0    AIR\n";
    auto im = Import(deck);
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    EXPECT_EQ(im->report.format, "COMGEOM");
    EXPECT_EQ(im->report.solids, 2);
    EXPECT_TRUE(Inside(im->scene, "r1", Q(1, 1, 5)));
    EXPECT_FALSE(Inside(im->scene, "r1", Q(5, 5, 5)));  // the hole
    EXPECT_TRUE(Inside(im->scene, "r2", Q(25, 5, 5)));
    EXPECT_TRUE(Inside(im->scene, "r2", Q(5, 5, 5)));  // OR s3
    std::string bad = deck;
    bad.replace(bad.find("RCC"), 3, "XYZ");
    auto b = Import(bad);
    EXPECT_FALSE(b->ok);
    EXPECT_NE(AllMessages(b->diags).find("test.asc:5:6: error: unknown COMGEOM solid type 'XYZ'"),
              std::string::npos)
        << AllMessages(b->diags);
}

// COMGEOM ellipsoids of revolution: ELL by its foci (0,0,0), (8,0,0) and major axis 10 (centre
// (4,0,0), semi-axes 5, 3, 3), ELL1 by centre (20,0,0), semi-major axis (0,0,4) and radius 2.
TEST(ImportBrlcad, ComgeomEllipsoidsOfRevolution) {
    std::string deck =
        "ell deck\n"
        "2    2\n"
        "1    ELL  0.0       0.0       0.0       8.0       0.0       0.0       E1\n"
        "          10.0      0.0       0.0       0.0       0.0       0.0       E1\n"
        "2    ELL1 20.0      0.0       0.0       0.0       0.0       4.0       E2\n"
        "          2.0       0.0       0.0       0.0       0.0       0.0       E2\n"
        "  1      1      0      0      0      0      0      0      0      0      R1\n"
        "  2      2      0      0      0      0      0      0      0      0      R2\n"
        "-1\n"
        "1    1    0    1    100  R1\n"
        "2    2    0    1    100  R2\n";
    auto im = Import(deck);
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    EXPECT_EQ(im->report.solids, 2);
    EXPECT_TRUE(Inside(im->scene, "r1", Q(8.9, 0, 0)));
    EXPECT_FALSE(Inside(im->scene, "r1", Q(9.1, 0, 0)));
    EXPECT_TRUE(Inside(im->scene, "r1", Q(4, 2.9, 0)));
    EXPECT_FALSE(Inside(im->scene, "r1", Q(4, 3.1, 0)));
    EXPECT_TRUE(Inside(im->scene, "r1", Q(4, 0, -2.9)));
    EXPECT_FALSE(Inside(im->scene, "r1", Q(4, 0, -3.1)));
    EXPECT_TRUE(Inside(im->scene, "r2", Q(20, 0, 3.9)));
    EXPECT_FALSE(Inside(im->scene, "r2", Q(20, 0, 4.1)));
    EXPECT_TRUE(Inside(im->scene, "r2", Q(21.9, 0, 0)));
    EXPECT_FALSE(Inside(im->scene, "r2", Q(20, 2.1, 0)));
    std::string bad = deck;
    bad.replace(bad.find("10.0      0.0"), 4, "7.0 ");
    auto b = Import(bad);
    EXPECT_FALSE(b->ok);
    EXPECT_NE(AllMessages(b->diags).find("must exceed the foci's distance 8"), std::string::npos)
        << AllMessages(b->diags);
}

// Renders every sample (so each renders without error) from above (rt view: X right, Y up,
// looking down -Z) with a window 10 % larger than its computed box, and compares the covered
// pixels' extent with the box projected: the rendered silhouette must lie inside the box (to a
// pixel) and, for these models whose boxes are reached by some solid on every side, touch each side
// to within 2 pixels (1 px for pixel quantisation, 1 px for boxes of intersections, which are
// conservative).
TEST(ImportBrlcadSamples, RenderedBoundsAgreeWithComputedBounds) {
    if (!std::filesystem::exists(kSampleDir)) GTEST_SKIP() << "no " << kSampleDir;
    const char* files[] = {"annual_gift_man.asc",
                           "arb8_showcase.asc",
                           "axis.asc",
                           "boolean-ops.asc",
                           "castle.asc",
                           "chess/chessboard.asc",
                           "cornell.asc",
                           "cornell-kunigami.asc",
                           "cray.asc",
                           "crod.asc",
                           "cube.asc",
                           "demo.asc",
                           "die.asc",
                           "earth.asc",
                           "galileo.asc",
                           "ktank.asc",
                           "operators.asc",
                           "truck.asc",
                           "wave.asc",
                           "xmp.asc",
                           "comgeom/ADA073408.comgeom"};
    for (const char* f : files) {
        PipelineOptions po;
        po.scenePaths = {std::string(kSampleDir) + "/" + f};
        po.width = po.height = 128;
        // The bounds computed from the file (Quadrix space) by the importer alone.
        auto im = Import(ReadAll(po.scenePaths[0]));
        ASSERT_TRUE(im->ok) << f << AllMessages(im->diags);
        Box3 qb = im->report.bounds;  // Quadrix space: (x, z_model, y_model)
        Box3 mb{{qb.lo.x, qb.lo.z, qb.lo.y}, {qb.hi.x, qb.hi.z, qb.hi.y}};
        RtView rt;
        double vs = 1.1 * std::max(mb.hi.x - mb.lo.x, mb.hi.y - mb.lo.y);
        rt.viewsize = vs;
        rt.eye = {0.5 * (mb.lo.x + mb.hi.x), 0.5 * (mb.lo.y + mb.hi.y), mb.hi.z + 1};
        po.rtView = rt;
        PipelineResult res;
        Diagnostics d1;
        ASSERT_TRUE(RunPipeline(po, res, d1)) << f << AllMessages(d1);
        const Frame& fr = res.frame;
        int c0 = fr.width, c1 = -1, r0 = fr.height, r1 = -1;
        for (int r = 0; r < fr.height; ++r)
            for (int c = 0; c < fr.width; ++c)
                if (fr.Covered(c, r)) {
                    c0 = std::min(c0, c), c1 = std::max(c1, c);
                    r0 = std::min(r0, r), r1 = std::max(r1, r);
                }
        ASSERT_GE(c1, 0) << f;
        double cell = vs / fr.width;
        // rt samples column i at x = eye.x - vs/2 + i·cell; row r (from the top) at
        // y = eye.y - vs/2 + (H - 1 - r)·cell.
        double x0 = rt.eye.x - vs / 2, y0 = rt.eye.y - vs / 2;
        double wantC0 = (mb.lo.x - x0) / cell, wantC1 = (mb.hi.x - x0) / cell;
        double wantR1 = fr.height - 1 - (mb.lo.y - y0) / cell;
        double wantR0 = fr.height - 1 - (mb.hi.y - y0) / cell;
        std::string name = f;
        if (name == "castle.asc" || name == "cray.asc" || name == "cube.asc") {
            // These hold a half-space (a ground plane), which is unbounded: it is left out of the
            // computed box, as rt leaves it out of its model RPP, and covers the whole window.
            EXPECT_EQ(c0, 0) << f;
            EXPECT_EQ(c1, fr.width - 1) << f;
            EXPECT_EQ(r0, 0) << f;
            EXPECT_EQ(r1, fr.height - 1) << f;
            continue;
        }
        EXPECT_NEAR(c0, wantC0, 2) << f;
        EXPECT_NEAR(c1, wantC1, 2) << f;
        EXPECT_NEAR(r0, wantR0, 2) << f;
        EXPECT_NEAR(r1, wantR1, 2) << f;
    }
}

}  // namespace
}  // namespace quadrix::import

namespace quadrix::import {
namespace {

// Truncated and byte-mutated copies of real databases (and an OpenSCAD file) must give errors or
// a scene, never a crash or a hang (DESIGN.md "Reliability rules"); run under the sanitizers too.
TEST(ImportBrlcadSamples, MutatedInputNeverCrashes) {
    if (!std::filesystem::exists(kSampleDir)) GTEST_SKIP() << "no " << kSampleDir;
    std::mt19937 rng(9);
    const char* files[] = {"boolean-ops.asc", "operators.asc", "die.asc",
                           "comgeom/ADA073408.comgeom"};
    const char noise[] = "{}[]() \n-+u0123456789.eE;lI#\"\\";
    for (const char* f : files) {
        std::string text = ReadAll(std::string(kSampleDir) + "/" + f);
        for (int trial = 0; trial < 40; ++trial) {
            std::string t = text;
            if (trial % 2 == 0) {
                t.resize(std::uniform_int_distribution<std::size_t>(0, t.size())(rng));
            } else {
                for (int k = 0; k < 8; ++k)
                    t[std::uniform_int_distribution<std::size_t>(0, t.size() - 1)(rng)] =
                        noise[std::uniform_int_distribution<int>(0, sizeof noise - 2)(rng)];
            }
            auto im = Import(t);
            EXPECT_TRUE(im->ok || im->diags.HasErrors()) << f << " trial " << trial;
        }
    }
}

}  // namespace
}  // namespace quadrix::import

namespace quadrix::import {
namespace {

// Every quadric primitive in its v5 `put` form (keys as FORMAT.md §3.1 lists them) and in v4 form.
TEST(ImportBrlcad, EveryPrimitiveParsesInV5AndV4) {
    std::string v5 =
        "title {all}\n"
        "put {h} half N {0 0 1} d 5\n"
        "put {n} arbn N 6 P0 {1 0 0 1} P1 {-1 0 0 1} P2 {0 1 0 1} P3 {0 -1 0 1} P4 {0 0 1 1} "
        "P5 {0 0 -1 1}\n"
        "put {rpc} rpc V {10 0 0} H {0 0 2} B {0 1 0} r 1\n"
        "put {rhc} rhc V {20 0 0} H {0 0 2} B {0 1 0} r 1 c 0.5\n"
        "put {epa} epa V {30 0 0} H {0 0 2} A {1 0 0} r_1 1 r_2 0.5\n"
        "put {ehy} ehy V {40 0 0} H {0 0 2} A {1 0 0} r_1 1 r_2 0.5 c 0.3\n"
        "put {hyp} hyp V {50 0 0} H {0 0 2} A {1 0 0} b 0.5 bnr 0.6\n"
        "put {part} part V {60 0 0} H {0 0 2} r_v 1 r_h 0.5\n"
        "put {all} comb region no tree {u {u {u {l n} {l rpc}} {u {l rhc} {l epa}}} "
        "{u {u {l ehy} {l hyp}} {l part}}}\n";
    auto im = Import(v5, {{"all", "h"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    EXPECT_EQ(im->report.census.size(), 8u);
    EXPECT_EQ(im->report.solids, 8);  // bare primitives are regions of their own
    EXPECT_TRUE(Inside(im->scene, "n", Q(0.5, 0.5, 0.5)));
    EXPECT_FALSE(Inside(im->scene, "n", Q(1.5, 0, 0)));
    EXPECT_TRUE(Inside(im->scene, "rpc", Q(10, 0.5, 1)));
    EXPECT_TRUE(Inside(im->scene, "rhc", Q(20, 0.5, 1)));
    EXPECT_TRUE(Inside(im->scene, "epa", Q(30, 0, 1.5)));
    EXPECT_FALSE(Inside(im->scene, "epa", Q(30, 0, 2.1)));
    EXPECT_TRUE(Inside(im->scene, "ehy", Q(40, 0, 1.5)));
    // The neck (z = 1) has semi-axes 0.6 along A (x) and 0.3 along H×A (y).
    EXPECT_TRUE(Inside(im->scene, "hyp", Q(50.55, 0, 1)));
    EXPECT_FALSE(Inside(im->scene, "hyp", Q(50.65, 0, 1)));
    EXPECT_TRUE(Inside(im->scene, "hyp", Q(50, 0.25, 1)));
    EXPECT_FALSE(Inside(im->scene, "hyp", Q(50, 0.35, 1)));
    EXPECT_TRUE(Inside(im->scene, "part", Q(60, 0, 2.4)));
    EXPECT_TRUE(Inside(im->scene, "h", Q(1000, -1000, 4.9)));
    EXPECT_FALSE(Inside(im->scene, "h", Q(0, 0, 5.1)));
    // v4: S 26 rpc and S 33 hyp with their 24 numbers.
    std::string v4 =
        "I 1 v4\nt\n"
        "S 26 r 0 10 0 0  0 0 2  0 1 0  1 0 0  0 0 0  0 0 0  0 0 0  0 0 0\n"
        "S 33 y 0 50 0 0  0 0 2  1 0 0  0.5 0.6 0  0 0 0  0 0 0  0 0 0  0 0 0\n";
    auto im4 = Import(v4);
    ASSERT_TRUE(im4->ok) << AllMessages(im4->diags);
    EXPECT_TRUE(Inside(im4->scene, "r", Q(10, 0.5, 1)));
    EXPECT_TRUE(Inside(im4->scene, "y", Q(50.55, 0, 1)));
    EXPECT_FALSE(Inside(im4->scene, "y", Q(50.65, 0, 1)));
}

}  // namespace
}  // namespace quadrix::import

namespace quadrix::import {
namespace {

// Runs `f` on a thread with a 1 MiB stack (a small thread stack, as a worker or a host program
// may give the importer): a recursive parser that overflows it crashes the test binary.
void OnSmallStack(const std::function<void()>& f) {
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    // 1 MiB, the stack the issue names. AddressSanitizer's redzones make every frame several
    // times larger (the importer's walk of the accepted depth is still recursive), so the
    // sanitizer build gives the same depth a proportionally larger stack; the Release build
    // checks the real 1 MiB.
#if QUADRIX_ASAN
    pthread_attr_setstacksize(&attr, std::size_t{8} << 20);
#else
    pthread_attr_setstacksize(&attr, std::size_t{1} << 20);
#endif
    pthread_t thread;
    auto body = [](void* arg) -> void* {
        (*static_cast<const std::function<void()>*>(arg))();
        return nullptr;
    };
    ASSERT_EQ(pthread_create(&thread, &attr, body, const_cast<std::function<void()>*>(&f)), 0);
    pthread_join(thread, nullptr);
    pthread_attr_destroy(&attr);
}

std::string DeepV5Tree(int depth) {
    std::string tree = "{l s}";
    for (int i = 0; i < depth; ++i) tree = "{u " + tree + " {l s}}";
    return "title {t}\nput {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
           "put {r} comb region yes tree " +
           tree + "\n";
}

TEST(ImportBrlcad, V5DeepTreesOnAOneMebibyteStack) {
    // Issue 23: the recursive tree parser accepted depth 2,000 but overflowed a 1 MiB stack near
    // 1,990. The parser is iterative now; the importer's walk of the accepted depth fits too.
    for (int depth : {100, 2000}) {
        OnSmallStack([&] {
            auto im = Import(DeepV5Tree(depth), {{"r"}, false});
            EXPECT_TRUE(im->ok) << depth << ": " << AllMessages(im->diags);
            EXPECT_TRUE(Inside(im->scene, "r", Q(0, 0, 0))) << depth;
        });
    }
    for (int depth : {2001, 20000}) {
        OnSmallStack([&] {
            auto im = Import(DeepV5Tree(depth), {{"r"}, false});
            EXPECT_FALSE(im->ok);
            EXPECT_NE(AllMessages(im->diags).find("test.asc:3:"), std::string::npos);
            EXPECT_NE(AllMessages(im->diags).find("deeper than 2000"), std::string::npos)
                << AllMessages(im->diags);
        });
    }
}

TEST(ImportBrlcad, V5NestedListsFindTheirBracesOnce) {
    // Every brace of a tree is matched once (ReadWord remembers the matches it passes): the
    // nested operands are the same words, a backslash still escapes a brace, and a brace that is
    // never closed is reported where it opens.
    const std::string head =
        "title {t}\nunits mm\n"
        "put {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
        "put {t\\}u} ell V {10 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n";
    auto im = Import(head +
                         "put {r} comb region yes tree {u {u {l s} {l t\\}u}} {u {l s {1 0 0 "
                         "0  0 1 0 5  0 0 1 0  0 0 0 1}} {l s {1 0 0 0  0 1 0 0  0 0 1 5  0 0 0 "
                         "1}}}}\n",
                     {{"r"}, false});
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    EXPECT_EQ(im->report.solids, 1);  // one region of four placed spheres
    for (const Vec3& p : {Q(0, 0, 0), Q(10, 0, 0), Q(0, 5, 0), Q(0, 0, 5)})
        EXPECT_TRUE(Inside(im->scene, "r", p)) << p.x << " " << p.y << " " << p.z;
    EXPECT_FALSE(Inside(im->scene, "r", Q(5, 0, 0)));
    // A tree given as a quoted word: its braced operands are matched at their places too.
    auto quoted = Import(head +
                             "put {r} comb region yes tree \"u {u {l s} {l t\\}u}} {l s {1 0 0 "
                             "0  0 1 0 5  0 0 1 0  0 0 0 1}}\"\n",
                         {{"r"}, false});
    ASSERT_TRUE(quoted->ok) << AllMessages(quoted->diags);
    for (const Vec3& p : {Q(0, 0, 0), Q(10, 0, 0), Q(0, 5, 0)})
        EXPECT_TRUE(Inside(quoted->scene, "r", p)) << p.x << " " << p.y << " " << p.z;
    EXPECT_FALSE(Inside(quoted->scene, "r", Q(0, 0, 5)));
    const std::string open = "put {r} comb region yes tree {u {l s} {u {l s} {l s}}\n";
    auto bad = Import(head + open, {{"r"}, false});
    EXPECT_FALSE(bad->ok);
    const std::string where = fmt::format("test.asc:5:{}:", open.find("{u") + 1);
    EXPECT_NE(AllMessages(bad->diags).find(where), std::string::npos) << AllMessages(bad->diags);
    EXPECT_NE(AllMessages(bad->diags).find("unbalanced"), std::string::npos)
        << AllMessages(bad->diags);
}

TEST(ImportBrlcad, NumbersBeyondIntAreRangeErrors) {
    // Issue 23: converted to int unchecked (UBSan float-cast-overflow).
    const std::string sphere = "title {t}\nput {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n";
    const std::pair<std::string, std::string> cases[] = {
        {"I 1 v4\nt\nm 4 2.5e12 3 0 0 0\n", "test.asc:3:5: error: colour table record 'm': low"},
        {"I 1 v4\nt\nm 4 1 3 0 0 256\n", "blue '256'"},
        {"I 1 v4\nt\nm 4 1 3.5 0 0 0\n", "high region id '3.5'"},
        {sphere + "color 1 2 1e12 0 0\n", "test.asc:3:11: error: color: red"},
        {sphere + "color -1 2 0 0 0\n", "low region id"},
        {sphere + "put {r} comb region yes tree {l s}\n"
                  "attr set {r} {region} {R} {region_id} {1e12}\n",
         "region_id: '1e12' is not a whole number"},
        {sphere + "put {r} comb region yes tree {l s}\n"
                  "attr set {r} {region} {R} {aircode} {-3e9}\n",
         "aircode: '-3e9' is not a whole number"},
        {"title {t}\nput {a} arbn N 1e12 P0 {1 0 0 1}\n", "N: '1e12' is not a whole number"},
    };
    for (const auto& [text, expect] : cases) {
        auto im = Import(text);
        EXPECT_FALSE(im->ok) << text;
        EXPECT_NE(AllMessages(im->diags).find(expect), std::string::npos) << text << "\n"
                                                                          << AllMessages(im->diags);
    }
}

// --- boxes from the primitives' extents (scene::Body::extent, flattener.cpp ExtentBoxes) ---

// 20 regions of a rod (a cone frustum), a ball (an ellipsoid) and a block (an arb8) less a bore,
// each placed with its own rotation, and a nearly twisted arb8 (a face out of plane by 3e-4:
// bounded directly, its vertices are not its corners).
std::string RotatedAssembly() {
    std::string s =
        "title {extents}\nunits mm\n"
        "put {rod} tgc V {0 0 0} H {0 0 20} A {3 0 0} B {0 3 0} C {2 0 0} D {0 2 0}\n"
        "put {ball} ell V {0 0 25} A {5 0 0} B {0 4 0} C {0 0 3}\n"
        "put {blk} arb8 V1 {-4 -4 -2} V2 {4 -4 -2} V3 {4 4 -2} V4 {-4 4 -2} V5 {-4 -4 2} "
        "V6 {4 -4 2} V7 {4 4 2} V8 {-4 4 2}\n"
        "put {bore} tgc V {0 0 -5} H {0 0 40} A {1 0 0} B {0 1 0} C {1 0 0} D {0 1 0}\n"
        "put {skew} arb8 V1 {0 0 0} V2 {20 0 0} V3 {20 20 0.0003} V4 {0 20 0} V5 {0 0 20} "
        "V6 {20 0 20} V7 {20 20 20} V8 {0 20 20}\n";
    std::string all;
    for (int k = 0; k < 20; ++k) {
        const Mat4 m = (Transform::Translate({30.0 * (k % 5), 35.0 * (k / 5), 3.0 * k}) *
                        Transform::Rotate(0, 17.0 * k) * Transform::Rotate(1, 29.0 + 11 * k))
                           .Matrix();
        std::string mt;
        for (int i = 0; i < 16; ++i)
            mt += fmt::format("{}{:.17g}", i ? " " : "", m.m[i / 4][i % 4]);
        const std::string name = fmt::format("part{}.r", k);
        s += fmt::format(
            "put {{{0}}} comb region yes tree {{- {{u {{u {{l rod {{{1}}}}} {{l ball {{{1}}}}}}} "
            "{{l blk {{{1}}}}}}} {{l bore {{{1}}}}}}}\n"
            "attr set {{{0}}} {{region}} {{R}} {{region_id}} {{{2}}}\n",
            name, mt, 100 + k);
        all = all.empty() ? fmt::format("{{l {}}}", name)
                          : fmt::format("{{u {} {{l {}}}}}", all, name);
    }
    s += "put {skew.r} comb region yes tree {l skew}\n"
         "attr set {skew.r} {region} {R} {region_id} {99}\n";
    s += fmt::format("put {{all.g}} comb region no tree {{u {} {{l skew.r}}}}\n", all);
    return s;
}

Frame DrawWithRaycast(const FlatScene& flat) {
    const EngineInfo* info = FindEngine("raycast");
    Frame frame;
    if (!info) return frame;
    info->make()->Render(flat, RenderOptions{}, frame);
    return frame;
}

template <typename A>
bool SameBytes(const A& a, const A& b) {
    return a.size() == b.size() &&
           std::memcmp(a.data(), b.data(), a.size() * sizeof(*a.data())) == 0;
}

// Flattens `imported` in two views with and without the extents' boxes: the window is bit for
// bit the one of the direct bounds, the same solids are kept, every body's box is within the
// pad 2e-5 × (size + |coordinate|) of its direct one (the allowance the fit and the culling give
// a box that is not the body's own), and raycast draws the same frame bit for bit. Returns how
// many bodies' boxes came from their extents (they differ from the direct ones in some bit).
int ExpectExtentBoxesDrawTheSame(const scene::Scene& imported, const Box3& bounds,
                                 const std::string& what) {
    int fromExtents = 0;
    for (const auto& [az, el] : {std::pair{35.0, 25.0}, std::pair{-120.0, -40.0}}) {
        scene::Scene s = imported;
        const scene::View view = MakeAzElView(az, el, bounds, std::nullopt, 160, 120);
        s.views = {view};
        FlattenOptions o;
        o.width = 160;
        o.height = 120;
        o.viewName = view.id;
        Diagnostics d1, d2;
        const std::optional<FlatScene> extents = Flatten(s, o, d1);
        o.boundsFromExtents = false;
        const std::optional<FlatScene> direct = Flatten(s, o, d2);
        const std::string where = fmt::format("{} az {} el {}", what, az, el);
        EXPECT_TRUE(extents && direct) << where << "\n" << AllMessages(d1) << AllMessages(d2);
        if (!extents || !direct) return fromExtents;
        EXPECT_EQ(extents->projection.deviceFromWorld.Matrix().m,
                  direct->projection.deviceFromWorld.Matrix().m)
            << where;
        EXPECT_EQ(extents->solids.size(), direct->solids.size()) << where;
        EXPECT_EQ(extents->bodies.size(), direct->bodies.size()) << where;
        if (extents->solids.size() != direct->solids.size() ||
            extents->bodies.size() != direct->bodies.size())
            return fromExtents;
        for (std::size_t k = 0; k < extents->solids.size(); ++k)
            EXPECT_EQ(extents->solids[k].name, direct->solids[k].name) << where;
        for (std::size_t b = 0; b < extents->bodies.size(); ++b) {
            const Box3& a = extents->bodies[b].bounds;
            const Box3& e = direct->bodies[b].bounds;
            bool differs = false;
            for (int axis = 0; axis < 3; ++axis) {
                if (a.lo[axis] == e.lo[axis] && a.hi[axis] == e.hi[axis]) continue;  // or infinite
                const double tol = 2e-5 * ((e.hi[axis] - e.lo[axis]) +
                                           std::fmax(std::fabs(e.lo[axis]), std::fabs(e.hi[axis])));
                EXPECT_NEAR(a.lo[axis], e.lo[axis], tol)
                    << where << " body " << extents->bodies[b].name;
                EXPECT_NEAR(a.hi[axis], e.hi[axis], tol)
                    << where << " body " << extents->bodies[b].name;
                differs = true;
            }
            fromExtents += differs;
        }
        const Frame fa = DrawWithRaycast(*extents), fb = DrawWithRaycast(*direct);
        EXPECT_GT(fb.CoveredCount(), 500u) << where;
        EXPECT_TRUE(SameBytes(fa.depth, fb.depth) && SameBytes(fa.normal, fb.normal) &&
                    SameBytes(fa.surface, fb.surface) && SameBytes(fa.body, fb.body))
            << where << ": the frames differ";
    }
    return fromExtents;
}

TEST(ImportBrlcad, BoxesFromExtentsKeepTheWindowTheSolidsAndTheFrame) {
    auto im = Import(RotatedAssembly());
    ASSERT_TRUE(im->ok) << AllMessages(im->diags);
    // 80 bodies: the rods, balls and blocks have extents, the bores too (subtracted), the skewed
    // block none.
    std::size_t withExtent = 0;
    for (const scene::Body& b : im->scene.top.bodies) withExtent += !b.extent.empty();
    EXPECT_EQ(im->scene.top.bodies.size(), 81u);
    EXPECT_EQ(withExtent, 80u);
    EXPECT_GT(ExpectExtentBoxesDrawTheSame(im->scene, im->report.bounds, "assembly"), 100);
}

TEST(ImportBrlcadSamples, BoxesFromExtentsKeepTheWindowTheSolidsAndTheFrame) {
    if (!std::filesystem::exists(kSampleDir)) GTEST_SKIP() << "no " << kSampleDir;
    int fromExtents = 0;
    for (const Sample& sample : kSamples) {
        auto im = Import(ReadAll(std::string(kSampleDir) + "/" + sample.file));
        ASSERT_TRUE(im->ok) << sample.file;
        fromExtents += ExpectExtentBoxesDrawTheSame(im->scene, im->report.bounds, sample.file);
    }
    EXPECT_GT(fromExtents, 1000);
}

}  // namespace
}  // namespace quadrix::import
