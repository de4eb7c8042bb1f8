// BRL-CAD binary v5 databases (.g): a hand-assembled file read against the documented layout
// (g_format.h), every shared ASCII sample converted to .g by our writer and read back (the same
// Database objects, the same Scene, the same rendered Frame), the input dispatcher (.g extension
// and the v5 magic bytes), and corrupt files (errors with a byte offset, never a crash).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

#include "quadrix/import/brlcad/brlcad_import.h"
#include "quadrix/import/brlcad/g_writer.h"
#include "quadrix/import/brlcad/readers.h"
#include "quadrix/import/rt_view.h"
#include "quadrix/pipeline/inputs.h"
#include "quadrix/pipeline/pipeline.h"
#include "test_util.h"

namespace quadrix::import {
namespace {

using brlcad::Combination;
using brlcad::Database;
using brlcad::Primitive;
using brlcad::TreeNode;

const char* kSampleDir = "/work/shared/data/brlcad";

const char* kSamples[] = {"annual_gift_man.asc",
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
                          "xmp.asc"};

std::string ReadAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string AllMessages(const Diagnostics& d) {
    std::string s;
    for (const Diagnostic& x : d.Items()) s += x.Format(false) + "\n";
    return s;
}

bool ParseText(const std::string& text, Database& db, Diagnostics& diags) {
    switch (brlcad::DetectFormat(text)) {
        case brlcad::TextFormat::kV4:
            return brlcad::ParseV4(text, "x.asc", db, diags);
        case brlcad::TextFormat::kV5:
            return brlcad::ParseV5(text, "x.asc", db, diags);
        default:
            return false;
    }
}

// A tree as text, with chains of unions flattened into one ordered list: librt (and our reader)
// rebuilds an all-union combination as a balanced tree of the same leaves in the same order.
std::string Canon(const Combination& c, int node) {
    if (node < 0) return "{}";
    const TreeNode& n = c.nodes[node];
    if (n.op == TreeNode::Op::kLeaf) {
        std::string m;
        for (int k = 0; k < 16; ++k) m += fmt::format(" {}", n.matrix.m[k / 4][k % 4]);
        return fmt::format("(l {}{})", n.name, m);
    }
    if (n.op == TreeNode::Op::kUnion) {
        std::vector<std::string> items;
        std::function<void(int)> flat = [&](int i) {
            const TreeNode& x = c.nodes[i];
            if (x.op == TreeNode::Op::kUnion) {
                flat(x.left);
                flat(x.right);
            } else {
                items.push_back(Canon(c, i));
            }
        };
        flat(node);
        std::string s = "(u";
        for (auto& i : items) s += " " + i;
        return s + ")";
    }
    return fmt::format("({} {} {})", n.op == TreeNode::Op::kIntersection ? "n" : "-",
                       Canon(c, n.left), Canon(c, n.right));
}

std::string Describe(const Primitive& p) {
    std::string s = p.type + " " + p.name;
    auto v = [&](const Vec3& x) { s += fmt::format(" <{} {} {}>", x.x, x.y, x.z); };
    for (const Vec3& x : p.pts) v(x);
    for (const Vec3* x : {&p.V, &p.H, &p.A, &p.B, &p.C, &p.D, &p.N}) v(*x);
    for (double x : {p.r, p.r1, p.r2, p.c, p.d, p.b, p.bnr, p.rv, p.rh, p.rd})
        s += fmt::format(" {}", x);
    for (const Plane& q : p.planes) s += fmt::format(" [{} {} {} {}]", q.a, q.b, q.c, q.d);
    for (const Vec3& x : p.vertices) v(x);
    for (const auto& f : p.faces) s += fmt::format(" f{}/{}/{}", f[0], f[1], f[2]);
    s += fmt::format(" m{} o{}", p.botMode, p.botOrientation);
    for (double t : p.thickness) s += fmt::format(" t{}", t);
    for (char a : p.faceAppended) s += a ? " A" : " C";
    return s;
}

std::string Describe(const Combination& c) {
    return fmt::format(
        "comb {} region={} id={} air={} rgb={} inherit={} shader={} tree={}", c.name, c.region,
        c.regionId, c.aircode,
        c.rgb ? fmt::format("{}/{}/{}", (*c.rgb)[0], (*c.rgb)[1], (*c.rgb)[2]) : "none", c.inherit,
        c.shader, Canon(c, c.root));
}

// The current objects (the last definition of each name), described, in file order.
std::vector<std::string> Objects(const Database& db) {
    std::vector<std::string> out;
    for (const auto& [name, ref] : db.objects)
        out.push_back(ref.first ? Describe(db.combinations[ref.second])
                                : Describe(db.primitives[ref.second]));
    return out;
}

std::string ColorTable(const Database& db) {
    std::string s;
    for (const auto& e : db.colorTable)
        s += fmt::format("{} {} {} {} {};", e.low, e.high, e.rgb[0], e.rgb[1], e.rgb[2]);
    return s;
}

// --- a .g assembled by hand from the layout (independent of our writer) ---

struct Be {
    std::string s;
    void U(std::uint64_t v, int n) {
        for (int i = n - 1; i >= 0; --i) s.push_back(static_cast<char>(v >> (8 * i) & 0xff));
    }
    void D(double x) {
        std::uint64_t u;
        std::memcpy(&u, &x, 8);
        U(u, 8);
    }
};

TEST(ImportBrlcadG, HandAssembledDatabase) {
    Be f;
    for (int b : {0x76, 0x01, 0x00, 0x00, 0x00, 0x00, 0x01, 0x35}) f.U(b, 1);  // header object
    // _GLOBAL: hflags 0x20 (name, 8-bit widths), aflags 0x20, no body, major 2; attributes title.
    {
        std::string name("_GLOBAL\0", 8), attrs("title\0Hand\0\0", 12);
        std::size_t len = 6 + 1 + 1 + name.size() + 1 + attrs.size() + 1;
        std::size_t total = (len + 7) / 8 * 8;
        Be o;
        for (int b : {0x76, 0x20, 0x20, 0x00, 0x02, 0x00}) o.U(b, 1);
        o.U(total / 8, 1);
        o.U(name.size(), 1), o.s += name;
        o.U(attrs.size(), 1), o.s += attrs;
        o.s.resize(total - 1, '\0');
        o.U(0x35, 1);
        f.s += o.s;
    }
    // "s": ell (minor 3), V = (1, 2, 3), A B C = 2 × unit axes.
    {
        Be body;
        for (double x : {1.0, 2.0, 3.0, 2.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 2.0}) body.D(x);
        std::string name("s\0", 2);
        std::size_t len = 6 + 1 + 1 + name.size() + 1 + body.s.size() + 1;
        std::size_t total = (len + 7) / 8 * 8;
        Be o;
        for (int b : {0x76, 0x20, 0x00, 0x20, 0x01, 0x03}) o.U(b, 1);
        o.U(total / 8, 1);
        o.U(name.size(), 1), o.s += name;
        o.U(body.s.size(), 1), o.s += body.s;
        o.s.resize(total - 1, '\0');
        o.U(0x35, 1);
        f.s += o.s;
    }
    // "r": a region (comb, minor 31) = {l s} translated by (10, 0, 0), rgb 255/0/0, as an
    // all-union body: width 0, nmat 1, nleaf 1, leafbytes 3, rpn 0, depth 1.
    {
        Be body;
        for (int b : {0, 1, 1, 3, 0, 1}) body.U(b, 1);
        for (double x : {1, 0, 0, 10, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}) body.D(x);
        body.s += std::string("s\0", 2);
        body.U(0, 1);  // matrix 0
        std::string name("r\0", 2),
            attrs = std::string("region\0R\0rgb\0", 13) + "255/0/0" + std::string(2, '\0');
        std::size_t len = 6 + 1 + 1 + name.size() + 1 + attrs.size() + 1 + body.s.size() + 1;
        std::size_t total = (len + 7) / 8 * 8;
        Be o;
        for (int b : {0x76, 0x20, 0x20, 0x20, 0x01, 31}) o.U(b, 1);
        o.U(total / 8, 1);
        o.U(name.size(), 1), o.s += name;
        o.U(attrs.size(), 1), o.s += attrs;
        o.U(body.s.size(), 1), o.s += body.s;
        o.s.resize(total - 1, '\0');
        o.U(0x35, 1);
        f.s += o.s;
    }
    scene::Scene scene;
    Diagnostics diags;
    ImportReport report;
    ASSERT_TRUE(ImportBrlcad(f.s, "hand.g", {}, scene, diags, report)) << AllMessages(diags);
    EXPECT_EQ(report.format, "BRL-CAD v5 binary");
    EXPECT_EQ(report.title, "Hand");
    ASSERT_EQ(scene.top.csgs.size(), 1u);
    EXPECT_EQ(scene.top.csgs[0].id, "r");
    ASSERT_TRUE(scene.top.csgs[0].color.has_value());
    EXPECT_EQ(scene.top.csgs[0].color->r, 1.0);
    // The sphere of radius 2 at (11, 2, 3) (model) = (11, 3, 2) in Quadrix space.
    EXPECT_NEAR(report.bounds.lo.x, 9, 1e-12);
    EXPECT_NEAR(report.bounds.hi.x, 13, 1e-12);
    EXPECT_NEAR(report.bounds.lo.y, 1, 1e-12);
    EXPECT_NEAR(report.bounds.hi.z, 4, 1e-12);
    // Our writer produces the same bytes for the same database.
    Database db;
    Diagnostics d2;
    ASSERT_TRUE(brlcad::ParseG(f.s, "hand.g", db, d2));
    std::string err;
    auto written = brlcad::WriteG(db, &err);
    ASSERT_TRUE(written) << err;
    Database back;
    ASSERT_TRUE(brlcad::ParseG(*written, "w.g", back, d2)) << AllMessages(d2);
    EXPECT_EQ(Objects(back), Objects(db));
}

// Every shared sample: .asc → Database → .g (our writer) → Database: the same objects.
TEST(ImportBrlcadG, SamplesRoundTripThroughTheWriter) {
    if (!std::filesystem::exists(kSampleDir)) GTEST_SKIP() << "no " << kSampleDir;
    for (const char* f : kSamples) {
        Database a;
        Diagnostics d;
        ASSERT_TRUE(ParseText(ReadAll(std::string(kSampleDir) + "/" + f), a, d))
            << f << AllMessages(d);
        std::string err;
        auto g = brlcad::WriteG(a, &err);
        ASSERT_TRUE(g) << f << ": " << err;
        ASSERT_TRUE(brlcad::IsV5Binary(*g));
        EXPECT_EQ(g->size() % 8, 0u) << f;
        Database b;
        ASSERT_TRUE(brlcad::ParseG(*g, "x.g", b, d)) << f << AllMessages(d);
        EXPECT_EQ(b.title, a.title) << f;
        EXPECT_EQ(ColorTable(b), ColorTable(a)) << f;
        EXPECT_EQ(Objects(b), Objects(a)) << f;
    }
}

// The .g renders exactly as the .asc does: the same solids and the same Frame, through the input
// dispatcher (.g by extension, and by the magic bytes under another name) and --top.
TEST(ImportBrlcadG, SamplesRenderTheSameAsTheAsciiDump) {
    if (!std::filesystem::exists(kSampleDir)) GTEST_SKIP() << "no " << kSampleDir;
    testing::TempDir tmp;
    for (const char* f : kSamples) {
        const std::string asc = std::string(kSampleDir) + "/" + f;
        Database a;
        Diagnostics d;
        ASSERT_TRUE(ParseText(ReadAll(asc), a, d)) << f;
        std::string err;
        auto g = brlcad::WriteG(a, &err);
        ASSERT_TRUE(g) << err;
        std::string stem = std::filesystem::path(f).stem().string();
        const std::string gPath = tmp.Write(stem + ".g", *g);
        const std::string binPath = tmp.Write(stem + ".bin", *g);
        PipelineResult ra, rg, rb;
        auto options = [&](const std::string& path) {
            PipelineOptions po;
            po.scenePaths = {path};
            po.width = po.height = 64;
            po.azimuth = 35;
            po.elevation = 25;
            return po;
        };
        Diagnostics da, dg, db;
        ASSERT_TRUE(RunPipeline(options(asc), ra, da)) << f << AllMessages(da);
        ASSERT_TRUE(RunPipeline(options(gPath), rg, dg)) << f << AllMessages(dg);
        ASSERT_TRUE(RunPipeline(options(binPath), rb, db)) << f << AllMessages(db);
        ASSERT_EQ(rg.inputs.imports.size(), 1u);
        EXPECT_EQ(rg.inputs.imports[0].second.format, "BRL-CAD v5 binary") << f;
        EXPECT_EQ(rb.inputs.imports[0].second.format, "BRL-CAD v5 binary") << f;
        const ImportReport &ia = ra.inputs.imports[0].second, &ig = rg.inputs.imports[0].second;
        EXPECT_EQ(ig.census, ia.census) << f;
        EXPECT_EQ(ig.skipped, ia.skipped) << f;
        EXPECT_EQ(ig.solids, ia.solids) << f;
        ASSERT_EQ(rg.scene.top.csgs.size(), ra.scene.top.csgs.size()) << f;
        for (std::size_t i = 0; i < ra.scene.top.csgs.size(); ++i)
            EXPECT_EQ(rg.scene.top.csgs[i].id, ra.scene.top.csgs[i].id) << f;
        // The same half-spaces, coefficient for coefficient (doubles are stored exactly).
        ASSERT_EQ(rg.scene.top.halfSpaces.size(), ra.scene.top.halfSpaces.size()) << f;
        for (std::size_t i = 0; i < ra.scene.top.halfSpaces.size(); ++i) {
            const auto &x = ra.scene.top.halfSpaces[i], &y = rg.scene.top.halfSpaces[i];
            ASSERT_EQ(x.kind, y.kind);
            if (x.kind == scene::HalfSpace::Kind::kPlane) {
                EXPECT_EQ(x.plane.a, y.plane.a);
                EXPECT_EQ(x.plane.d, y.plane.d);
            }
        }
        // The frames agree pixel for pixel.
        ASSERT_EQ(rg.frame.depth.size(), ra.frame.depth.size());
        std::size_t differ = 0;
        for (std::size_t i = 0; i < ra.frame.depth.size(); ++i)
            differ += ra.frame.surface[i] != rg.frame.surface[i] ||
                      ra.frame.Solid(i) != rg.frame.Solid(i) ||
                      !(ra.frame.depth[i] == rg.frame.depth[i] ||
                        (std::isinf(ra.frame.depth[i]) && std::isinf(rg.frame.depth[i])));
        EXPECT_EQ(differ, 0u) << f;
        EXPECT_GT(ra.frame.CoveredCount(), 0u) << f;
    }
}

TEST(ImportBrlcadG, TopObjectsFromTheGFile) {
    if (!std::filesystem::exists(kSampleDir)) GTEST_SKIP() << "no " << kSampleDir;
    Database a;
    Diagnostics d;
    ASSERT_TRUE(ParseText(ReadAll(std::string(kSampleDir) + "/operators.asc"), a, d));
    auto g = brlcad::WriteG(a, nullptr);
    ASSERT_TRUE(g);
    for (const char* top : {"subtraction", "intersection"}) {
        scene::Scene s1, s2;
        Diagnostics d1, d2;
        ImportReport r1, r2;
        ImportOptions o;
        o.topObjects = {top};
        ASSERT_TRUE(ImportBrlcad(ReadAll(std::string(kSampleDir) + "/operators.asc"), "o.asc", o,
                                 s1, d1, r1));
        ASSERT_TRUE(ImportBrlcad(*g, "o.g", o, s2, d2, r2)) << AllMessages(d2);
        EXPECT_EQ(r2.topObjects, r1.topObjects);
        EXPECT_EQ(r2.solids, r1.solids);
        EXPECT_GT(r2.solids, 0);
        EXPECT_EQ(r2.bounds.lo.x, r1.bounds.lo.x);
        EXPECT_EQ(r2.bounds.hi.z, r1.bounds.hi.z);
    }
}

// Corrupt files: every truncation and many random byte changes give an error (with a byte
// offset) or a scene, never a crash, a hang or a read past the end (run under ASan too).
TEST(ImportBrlcadG, CorruptFilesAreErrorsNotCrashes) {
    if (!std::filesystem::exists(kSampleDir)) GTEST_SKIP() << "no " << kSampleDir;
    Database a;
    Diagnostics d;
    ASSERT_TRUE(ParseText(ReadAll(std::string(kSampleDir) + "/die.asc"), a, d));
    auto g = brlcad::WriteG(a, nullptr);
    ASSERT_TRUE(g);
    {
        std::string cut = g->substr(0, g->size() - 5);
        scene::Scene s;
        Diagnostics dd;
        ImportReport r;
        EXPECT_FALSE(ImportBrlcad(cut, "cut.g", {}, s, dd, r));
        EXPECT_NE(AllMessages(dd).find("cut.g: error: byte "), std::string::npos)
            << AllMessages(dd);
    }
    for (std::size_t n = 0; n < g->size(); n += 37) {
        scene::Scene s;
        Diagnostics dd;
        ImportReport r;
        ImportBrlcad(g->substr(0, n), "t.g", {}, s, dd, r);
    }
    std::mt19937 rng(5);
    for (int trial = 0; trial < 300; ++trial) {
        std::string m = *g;
        for (int k = 0; k < 4; ++k) m[8 + rng() % (m.size() - 8)] = static_cast<char>(rng() & 0xff);
        scene::Scene s;
        Diagnostics dd;
        ImportReport r;
        ImportOptions o;
        o.allowMissing = true;
        ImportBrlcad(m, "m.g", o, s, dd, r);
    }
}

TEST(ImportBrlcadG, WriterRefusesWhatItCannotWrite) {
    Database db;
    Primitive p;
    p.type = "dsp";
    p.name = "terrain";
    db.AddPrimitive(p);
    std::string err;
    EXPECT_FALSE(brlcad::WriteG(db, &err));
    EXPECT_NE(err.find("'terrain'"), std::string::npos) << err;
}

TEST(ImportBrlcadG, V4BinaryIsRefusedClearly) {
    std::string v4("I\x01v4\0\0\0\0\0\0\0\0\0\0", 14);  // 14 bytes: 4 of magic, 10 NULs
    scene::Scene s;
    Diagnostics d;
    ImportReport r;
    EXPECT_FALSE(ImportBrlcad(v4, "old.g", {}, s, d, r));
    EXPECT_NE(AllMessages(d).find("v4 binary"), std::string::npos) << AllMessages(d);
}

// Meshes and arbn are planes (brlcad/mesh_solid.h): a solid-mode bot cube, a plate-mode
// triangle, an arbn tetrahedron; read from v5 text, written to .g and read back the same.
TEST(ImportBrlcadG, BotAndArbnAreDrawnAndRoundTrip) {
    const std::string text =
        "title {meshes}\n"
        "put {cube.bot} bot mode volume orient rh V { {0 0 0} {10 0 0} {10 10 0} {0 10 0} "
        "{0 0 10} {10 0 10} {10 10 10} {0 10 10} } F { {0 2 1} {0 3 2} {4 5 6} {4 6 7} {0 1 5} "
        "{0 5 4} {1 2 6} {1 6 5} {2 3 7} {2 7 6} {3 0 4} {3 4 7} }\n"
        "put {plate.bot} bot mode plate orient no V { {20 0 0} {30 0 0} {20 10 0} } F { {0 1 2} } "
        "T { 2 } fm 0\n"
        "put {tet} arbn N 4 P0 {-1 0 0 0} P1 {0 -1 0 0} P2 {0 0 -1 0} P3 {1 1 1 1}\n"
        "put {open.bot} bot mode volume orient rh V { {0 0 0} {1 0 0} {0 1 0} } F { {0 1 2} }\n"
        "put {a.r} comb region yes tree {l cube.bot}\n"
        "put {b.r} comb region yes tree {l plate.bot}\n"
        "put {c.r} comb region yes tree {l tet {1 0 0 40  0 1 0 0  0 0 1 0  0 0 0 1}}\n"
        "put {all.g} comb region no tree {u {u {l a.r} {l b.r}} {l c.r}}\n"
        "put {bad.r} comb region yes tree {l open.bot}\n";
    auto inside = [](const scene::Scene& sc, const std::string& id, double x, double y, double z) {
        const Vec3 p{x, z, y};
        for (const scene::Csg& c : sc.top.csgs) {
            if (c.id != id) continue;
            std::function<bool(int)> node = [&](int n) {
                const scene::CsgNode& nd = c.nodes[n];
                if (nd.isLeaf) {
                    for (const scene::Literal& l : sc.top.bodies[nd.ref.index].literals) {
                        const scene::HalfSpace& h = sc.top.halfSpaces[l.halfSpace];
                        double v =
                            h.kind == scene::HalfSpace::Kind::kQuartic ? h.quartic->Evaluate(p)
                            : h.kind == scene::HalfSpace::Kind::kPlane ? h.plane.Evaluate(p)
                                                                       : h.quadric.Evaluate(p);
                        if ((v <= 0) == l.complemented) return false;
                    }
                    return true;
                }
                bool a = node(nd.left), b = node(nd.right);
                return nd.op == scene::CsgOp::kUnion          ? a || b
                       : nd.op == scene::CsgOp::kIntersection ? a && b
                                                              : a && !b;
            };
            return node(c.root);
        }
        return false;
    };
    ImportOptions top;
    top.topObjects = {"all.g"};
    for (int pass = 0; pass < 2; ++pass) {
        std::string input = text;
        if (pass == 1) {
            Database db;
            Diagnostics d;
            ASSERT_TRUE(brlcad::ParseV5(text, "m.asc", db, d)) << AllMessages(d);
            auto g = brlcad::WriteG(db, nullptr);
            ASSERT_TRUE(g);
            Database back;
            ASSERT_TRUE(brlcad::ParseG(*g, "m.g", back, d)) << AllMessages(d);
            EXPECT_EQ(Objects(back), Objects(db));
            input = *g;
        }
        scene::Scene s;
        Diagnostics d;
        ImportReport r;
        ASSERT_TRUE(ImportBrlcad(input, "m", top, s, d, r)) << AllMessages(d);
        EXPECT_EQ(r.solids, 3);
        EXPECT_TRUE(inside(s, "a.r", 5, 5, 5));
        EXPECT_FALSE(inside(s, "a.r", 5, 5, 10.1));
        EXPECT_TRUE(inside(s, "b.r", 21, 1, 0.9));  // 2 mm plate centred on z = 0
        EXPECT_FALSE(inside(s, "b.r", 21, 1, 1.1));
        EXPECT_FALSE(inside(s, "b.r", 29, 9, 0));  // beyond the hypotenuse
        EXPECT_TRUE(inside(s, "c.r", 40.2, 0.2, 0.2));
        EXPECT_FALSE(inside(s, "c.r", 40.5, 0.5, 0.5));
        // The arbn's box comes from its vertices: x in [40, 41] (Quadrix x = model x).
        EXPECT_NEAR(r.bounds.hi.x, 41, 1e-12);
        EXPECT_NEAR(r.bounds.lo.x, 0, 1e-12);
        // An open mesh bounds no solid: an error naming it, unless allowMissing.
        ImportOptions bad;
        bad.topObjects = {"bad.r"};
        scene::Scene s2;
        Diagnostics d2;
        ImportReport r2;
        EXPECT_FALSE(ImportBrlcad(input, "m", bad, s2, d2, r2));
        EXPECT_NE(AllMessages(d2).find("primitive 'open.bot' (bot)"), std::string::npos)
            << AllMessages(d2);
        EXPECT_NE(AllMessages(d2).find("closed mesh"), std::string::npos);
        if (pass == 0)
            EXPECT_NE(AllMessages(d2).find("m:5:1: error"), std::string::npos) << AllMessages(d2);
        else
            EXPECT_NE(AllMessages(d2).find("(object at byte "), std::string::npos)
                << AllMessages(d2);
    }
}

// The command line: `quadrix render model.g --top ...`, the truck with its tori.
TEST(ImportBrlcadG, RenderCommandReadsG) {
    if (!std::filesystem::exists(kSampleDir)) GTEST_SKIP() << "no " << kSampleDir;
    testing::TempDir tmp;
    for (const char* f : {"operators.asc", "truck.asc"}) {
        Database a;
        Diagnostics d;
        ASSERT_TRUE(ParseText(ReadAll(std::string(kSampleDir) + "/" + f), a, d));
        auto g = brlcad::WriteG(a, nullptr);
        ASSERT_TRUE(g);
        const std::string path = tmp.Write(std::filesystem::path(f).stem().string() + ".g", *g);
        const std::string out = tmp.File("o.png");
        std::filesystem::remove(out);
        const std::string cmd = testing::QuadrixBinary() + " render " + path + " -o " + out +
                                " --size 64x64 --az 35 --el 25";
        if (std::string(f) == "operators.asc") {
            auto r = testing::RunShell(cmd + " --top subtraction");
            EXPECT_EQ(r.exitCode, 0) << r.err;
            EXPECT_TRUE(testing::FileExists(out));
        } else {
            // The truck's 11 tyres are tori: drawn, nothing left out, no --allow-missing.
            auto ok = testing::RunShell(cmd + " --top all --stats");
            EXPECT_EQ(ok.exitCode, 0) << ok.err;
            EXPECT_TRUE(testing::FileExists(out));
            EXPECT_NE(ok.err.find("BRL-CAD v5 binary"), std::string::npos) << ok.err;
            EXPECT_EQ(ok.err.find("left out"), std::string::npos) << ok.err;
        }
    }
}

}  // namespace
}  // namespace quadrix::import
