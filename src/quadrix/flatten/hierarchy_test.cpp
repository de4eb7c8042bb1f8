// Tests of the hierarchy walk (hierarchy.h): instances and arrays placed by delta^k · init,
// names, colors, CSG trees (n-ary merging, difference chains, operands not drawn, instances as
// operands, nesting) and the explosion guard. Scenes are built programmatically.
#include "quadrix/flatten/hierarchy.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "quadrix/flatten/flatten_test_util.h"

namespace quadrix {
namespace {

using namespace flatten_test;
using scene::Color;
using scene::CsgOp;

struct Walked {
    bool ok = false;
    FlatScene flat;
    HierarchyResult result;
    Diagnostics diags;
};

Walked Walk(const scene::Scene& s, HierarchyLimits limits = {}) {
    Walked w;
    w.ok = FlattenHierarchy(s, Transform(), limits, w.flat, w.result, w.diags);
    return w;
}

// The paper's tube (seed 001 §2.1.2): radius 1..2, length 4 along y.
int AddTubeDefinition(scene::Scene& s) {
    scene::Scope def;
    def.id = "tube";
    int outer = AddQuadric(def, "outer_tube", {1, 0, 1, 0, 0, 0, 0, 0, 0, -4});
    int inner = AddQuadric(def, "inner_tube", {1, 0, 1, 0, 0, 0, 0, 0, 0, -1});
    int top = AddPlane(def, "top_surf", {0, 1, 0, -2});
    int bot = AddPlane(def, "bot_surf", {0, 1, 0, 2});
    AddBody(def, "tube", {outer, ~inner, top, ~bot});
    s.definitions.push_back(def);
    return static_cast<int>(s.definitions.size()) - 1;
}

// §2.1.4: array bundle_of_tubes (tube =tx 2) 6 =ry 60; array stack_of_bundles
// (bundle_of_tubes =ty -7) 3 =ty 5.
scene::Scene StackOfBundles() {
    scene::Scene s;
    int tube = AddTubeDefinition(s);
    scene::Scope bundle;
    bundle.id = "bundle_of_tubes";
    AddInstance(bundle, "bundle_of_tubes", tube, Transform::Translate({2, 0, 0}), 6,
                Transform::Rotate(1, 60));
    s.definitions.push_back(bundle);
    AddInstance(s.top, "stack_of_bundles", 1, Transform::Translate({0, -7, 0}), 3,
                Transform::Translate({0, 5, 0}));
    return s;
}

TEST(FlattenHierarchy, StackOfBundlesYields18TubesAtTheExpectedPlaces) {
    Walked w = Walk(StackOfBundles());
    ASSERT_TRUE(w.ok);
    ASSERT_EQ(w.flat.bodies.size(), 18u);
    ASSERT_EQ(w.flat.solids.size(), 18u);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 6; ++j) {
            const FlatBody& b = w.flat.bodies[6 * i + j];
            EXPECT_EQ(b.name, fmt::format("stack_of_bundles[{}]/bundle_of_tubes[{}]/tube", i, j));
            EXPECT_EQ(b.solid, 6 * i + j);
            // Axis of tube (i, j): Ry(60 j)·(2, 0, 0) + (0, -7 + 5 i, 0), along y. The rigid
            // placement keeps values: the outer cylinder x² + z² - 4 is -4 on the axis and 0 two
            // units away from it, the inner one -1 and 0 one unit away. Tolerances: a few ulps
            // of the coefficients (magnitude ~100).
            double a = j * M_PI / 3;
            Vec3 axisDir{0, 1, 0}, radial{std::cos(a), 0, -std::sin(a)};
            Vec3 tangent = Cross(axisDir, radial);
            for (double t : {-2.0, 0.0, 1.5}) {
                Vec3 p = radial * 2 + Vec3{0, -7.0 + 5 * i + t, 0};
                const Quadric& outer = w.flat.halfSpaces[b.literals[0].halfSpace].quadric;
                const Quadric& inner = w.flat.halfSpaces[b.literals[1].halfSpace].quadric;
                EXPECT_NEAR(outer.Evaluate(p), -4, 1e-11);
                EXPECT_NEAR(inner.Evaluate(p), -1, 1e-11);
                EXPECT_NEAR(outer.Evaluate(p + tangent * 2), 0, 1e-11);
                EXPECT_NEAR(inner.Evaluate(p + radial), 0, 1e-11);
            }
            // Top and bottom planes at y = -7 + 5i ± 2.
            const Plane& top = w.flat.halfSpaces[b.literals[2].halfSpace].plane;
            EXPECT_NEAR(top.Evaluate({0, -5.0 + 5 * i, 0}), 0, 1e-12);
            EXPECT_TRUE(b.literals[1].complemented);
            EXPECT_TRUE(b.literals[3].complemented);
        }
    // Half-spaces are transformed once per scope instance: 4 per tube copy.
    EXPECT_EQ(w.flat.halfSpaces.size(), 18u * 4u);
    EXPECT_EQ(w.flat.halfSpaces[0].name, "stack_of_bundles[0]/bundle_of_tubes[0]/outer_tube");
}

TEST(FlattenHierarchy, ArrayOfNCopiesRotatedBy360OverN) {
    for (int n : {1, 5, 12}) {
        scene::Scene s;
        scene::Scope def;
        def.id = "ball";
        int q = AddSphere(def, "s", {1, 0, 0}, 0.25);
        AddBody(def, "b", {q});
        s.definitions.push_back(def);
        AddInstance(s.top, "ring_array", 0, Transform(), n, Transform::Rotate(2, 360.0 / n));
        Walked w = Walk(s);
        ASSERT_TRUE(w.ok);
        ASSERT_EQ(w.flat.bodies.size(), size_t(n));
        for (int k = 0; k < n; ++k) {
            // Copy k's centre is at angle 360 k/n about z; its sphere is -r² there.
            double a = 2 * M_PI * k / n;
            Vec3 c{std::cos(a), std::sin(a), 0};
            const Quadric& q = w.flat.halfSpaces[w.flat.bodies[k].literals[0].halfSpace].quadric;
            // delta^k accumulates k rotations: rounding grows like k ulps.
            EXPECT_NEAR(q.Evaluate(c), -0.0625, 1e-13 * (k + 1)) << "n=" << n << " k=" << k;
        }
    }
}

TEST(FlattenHierarchy, InitThenDeltasAccumulate) {
    // Copy k is placed by delta^k · init: init =sx 2 then deltas =tx 10. The unit sphere at the
    // origin becomes an ellipsoid of x-radius 2 centred at (10k, 0, 0) (the scale is applied
    // before the translations, so it does not scale them).
    scene::Scene s;
    scene::Scope def;
    int q = AddSphere(def, "s", {0, 0, 0}, 1);
    AddBody(def, "b", {q});
    s.definitions.push_back(def);
    AddInstance(s.top, "row_array", 0, Transform::Scale({2, 1, 1}), 3,
                Transform::Translate({10, 0, 0}));
    Walked w = Walk(s);
    ASSERT_TRUE(w.ok);
    for (int k = 0; k < 3; ++k) {
        const Quadric& e = w.flat.halfSpaces[w.flat.bodies[k].literals[0].halfSpace].quadric;
        EXPECT_NEAR(e.Evaluate({10.0 * k + 2, 0, 0}), 0, 1e-12);
        EXPECT_NEAR(e.Evaluate({10.0 * k, 1, 0}), 0, 1e-12);
        EXPECT_NEAR(e.Evaluate({10.0 * k, 0, 0}), -1, 1e-12);
    }
}

TEST(FlattenHierarchy, NamesAndColorPrecedence) {
    scene::Scene s;
    scene::Scope def;
    def.id = "pair";
    int q = AddSphere(def, "s", {0, 0, 0}, 1);
    AddBody(def, "own", {q}, Color{1, 0, 0});
    AddBody(def, "plain", {q});
    s.definitions.push_back(def);
    AddInstance(s.top, "", 0, Transform(), 1, {}, Color{0, 0, 1});  // instance color
    AddInstance(s.top, "bare", 0, Transform());                     // no color anywhere
    Walked w = Walk(s);
    ASSERT_TRUE(w.ok);
    ASSERT_EQ(w.flat.bodies.size(), 4u);
    EXPECT_EQ(w.flat.bodies[0].color, (Color{1, 0, 0}));  // own color beats the instance's
    EXPECT_EQ(w.flat.bodies[1].color, (Color{0, 0, 1}));  // instance color
    EXPECT_EQ(w.flat.bodies[2].color, (Color{1, 0, 0}));
    EXPECT_EQ(w.flat.bodies[3].color, (Color{1, 1, 1}));  // white
    EXPECT_EQ(w.flat.bodies[1].name, "pair/plain");       // unnamed instance: the definition id
    EXPECT_EQ(w.flat.bodies[3].name, "bare/plain");
}

// Four spheres a, b, c, d in the top scope.
scene::Scene FourSpheres() {
    scene::Scene s;
    for (int i = 0; i < 4; ++i) {
        int q = AddSphere(s.top, fmt::format("q{}", i), {double(i), 0, 0}, 0.75);
        AddBody(s.top, std::string(1, char('a' + i)), {q});
    }
    return s;
}

TEST(FlattenCsg, UnionChainIsOneNaryNodeAndOperandsAreNotDrawn) {
    scene::Scene s = FourSpheres();
    CsgBuilder b;
    // ((a | b) | c) | d as the reader builds it (left-associative).
    int n =
        b.Op(CsgOp::kUnion,
             b.Op(CsgOp::kUnion, b.Op(CsgOp::kUnion, b.Body(0), b.Body(1)), b.Body(2)), b.Body(3));
    AddCsg(s.top, "u", b, n);
    Walked w = Walk(s);
    ASSERT_TRUE(w.ok);
    ASSERT_EQ(w.flat.solids.size(), 1u);  // the operands are not drawn on their own
    const FlatCsgNode& root = w.flat.nodes[w.flat.solids[0].root];
    ASSERT_FALSE(root.isLeaf);
    EXPECT_EQ(root.op, CsgOp::kUnion);
    ASSERT_EQ(root.children.size(), 4u);
    for (int i = 0; i < 4; ++i) {
        const FlatCsgNode& leaf = w.flat.nodes[root.children[i]];
        ASSERT_TRUE(leaf.isLeaf);
        EXPECT_EQ(w.flat.bodies[leaf.body].name, fmt::format("u/{}", char('a' + i)));
        EXPECT_EQ(w.flat.bodies[leaf.body].solid, 0);
    }
    // Children are emitted before their parents.
    for (std::size_t i = 0; i < w.flat.nodes.size(); ++i)
        for (int c : w.flat.nodes[i].children) EXPECT_LT(c, int(i));
}

TEST(FlattenCsg, DifferenceChainsAndUnionSubtrahendsMerge) {
    {
        scene::Scene s = FourSpheres();
        CsgBuilder b;  // ((a - b) - c) - d → [a, b, c, d]
        int n = b.Op(
            CsgOp::kDifference,
            b.Op(CsgOp::kDifference, b.Op(CsgOp::kDifference, b.Body(0), b.Body(1)), b.Body(2)),
            b.Body(3));
        AddCsg(s.top, "d", b, n);
        Walked w = Walk(s);
        ASSERT_TRUE(w.ok);
        const FlatCsgNode& root = w.flat.nodes[w.flat.solids[0].root];
        EXPECT_EQ(root.op, CsgOp::kDifference);
        ASSERT_EQ(root.children.size(), 4u);
        for (int i = 0; i < 4; ++i)
            EXPECT_EQ(w.flat.bodies[w.flat.nodes[root.children[i]].body].name,
                      fmt::format("d/{}", char('a' + i)));
    }
    {
        scene::Scene s = FourSpheres();
        CsgBuilder b;  // a - (b | c) → [a, b, c]; and (a - (b | c)) & d stays a tree
        int diff = b.Op(CsgOp::kDifference, b.Body(0), b.Op(CsgOp::kUnion, b.Body(1), b.Body(2)));
        int n = b.Op(CsgOp::kIntersection, diff, b.Body(3));
        AddCsg(s.top, "x", b, n);
        Walked w = Walk(s);
        ASSERT_TRUE(w.ok);
        const FlatCsgNode& root = w.flat.nodes[w.flat.solids[0].root];
        EXPECT_EQ(root.op, CsgOp::kIntersection);
        ASSERT_EQ(root.children.size(), 2u);
        const FlatCsgNode& d = w.flat.nodes[root.children[0]];
        EXPECT_EQ(d.op, CsgOp::kDifference);
        EXPECT_EQ(d.children.size(), 3u);
    }
    {
        scene::Scene s = FourSpheres();
        CsgBuilder b;  // a - (b - c) must NOT merge: [a, [b, c]]
        int n = b.Op(CsgOp::kDifference, b.Body(0), b.Op(CsgOp::kDifference, b.Body(1), b.Body(2)));
        AddCsg(s.top, "y", b, n);
        Walked w = Walk(s);
        ASSERT_TRUE(w.ok);
        ASSERT_EQ(w.flat.solids.back().name, "y");  // bodies first, then csg solids
        const FlatCsgNode& root = w.flat.nodes[w.flat.solids.back().root];
        ASSERT_EQ(root.children.size(), 2u);
        EXPECT_TRUE(w.flat.nodes[root.children[0]].isLeaf);
        EXPECT_EQ(w.flat.nodes[root.children[1]].op, CsgOp::kDifference);
        EXPECT_EQ(w.flat.solids.size(), 2u);  // d is not an operand: drawn on its own
    }
}

TEST(FlattenCsg, NestedCsgOperandsMergeAcrossReferencesWithColors) {
    scene::Scene s = FourSpheres();
    s.top.bodies[2].color = Color{0, 1, 0};
    CsgBuilder b1;
    int n1 = b1.Op(CsgOp::kUnion, b1.Body(0), b1.Body(1));
    AddCsg(s.top, "x", b1, n1, Color{1, 0, 0});
    CsgBuilder b2;  // y = x | c | d
    int n2 = b2.Op(CsgOp::kUnion, b2.Op(CsgOp::kUnion, b2.Csg(0), b2.Body(2)), b2.Body(3));
    AddCsg(s.top, "y", b2, n2, Color{0, 0, 1});
    Walked w = Walk(s);
    ASSERT_TRUE(w.ok);
    ASSERT_EQ(w.flat.solids.size(), 1u);
    const FlatCsgNode& root = w.flat.nodes[w.flat.solids[0].root];
    ASSERT_EQ(root.children.size(), 4u);
    auto body = [&](int i) { return w.flat.bodies[w.flat.nodes[root.children[i]].body]; };
    EXPECT_EQ(body(0).name, "y/x/a");
    EXPECT_EQ(body(0).color, (Color{1, 0, 0}));  // innermost csg color
    EXPECT_EQ(body(2).color, (Color{0, 1, 0}));  // own color
    EXPECT_EQ(body(3).color, (Color{0, 0, 1}));  // outer csg color
    EXPECT_EQ(w.flat.solids[0].name, "y");
}

TEST(FlattenCsg, InstanceOperandIsTheUnionOfWhatItDraws) {
    scene::Scene s;
    scene::Scope def;
    def.id = "ball";
    int q = AddSphere(def, "s", {0, 0, 0}, 0.4);
    AddBody(def, "b", {q});
    s.definitions.push_back(def);
    int arr = AddInstance(s.top, "balls_array", 0, Transform(), 3, Transform::Translate({1, 0, 0}),
                          Color{1, 1, 0});
    int slab = AddPlane(s.top, "slab", {0, 1, 0, 0});
    int cut = AddBody(s.top, "cut", {slab});
    CsgBuilder b;  // balls - cut
    int n = b.Op(CsgOp::kDifference, b.Inst(arr), b.Body(cut));
    AddCsg(s.top, "halves", b, n);
    // The same inside a definition, instanced twice: csg in definitions works.
    scene::Scope wrap;
    wrap.id = "wrap";
    int q2 = AddSphere(wrap, "s", {0, 0, 0}, 1);
    int p2 = AddPlane(wrap, "p", {1, 0, 0, 0});
    AddBody(wrap, "ball", {q2});
    AddBody(wrap, "half", {p2});
    CsgBuilder b2;
    int n2 = b2.Op(CsgOp::kIntersection, b2.Body(0), b2.Body(1));
    AddCsg(wrap, "hemi", b2, n2);
    s.definitions.push_back(wrap);
    AddInstance(s.top, "two_array", 1, Transform(), 2, Transform::Translate({0, 0, 5}));

    Walked w = Walk(s);
    ASSERT_TRUE(w.ok);
    ASSERT_EQ(w.flat.solids.size(), 3u);
    // Top csg "halves": [union of 3 balls, cut].
    int halves = -1;
    for (std::size_t i = 0; i < w.flat.solids.size(); ++i)
        if (w.flat.solids[i].name == "halves") halves = int(i);
    ASSERT_GE(halves, 0);
    const FlatCsgNode& h = w.flat.nodes[w.flat.solids[halves].root];
    EXPECT_EQ(h.op, CsgOp::kDifference);
    ASSERT_EQ(h.children.size(), 2u);
    const FlatCsgNode& u = w.flat.nodes[h.children[0]];
    EXPECT_EQ(u.op, CsgOp::kUnion);
    ASSERT_EQ(u.children.size(), 3u);
    for (int k = 0; k < 3; ++k) {
        const FlatBody& ball = w.flat.bodies[w.flat.nodes[u.children[k]].body];
        EXPECT_EQ(ball.name, fmt::format("halves/balls_array[{}]/b", k));
        EXPECT_EQ(ball.color, (Color{1, 1, 0}));  // the instance's color
        const Quadric& qq = w.flat.halfSpaces[ball.literals[0].halfSpace].quadric;
        EXPECT_NEAR(qq.Evaluate({double(k), 0, 0}), -0.16, 1e-12);
    }
    // Two hemispheres from the definition, each an intersection of two leaves.
    int hemis = 0;
    for (const FlatSolid& sol : w.flat.solids)
        if (sol.name.find("hemi") != std::string::npos) {
            ++hemis;
            EXPECT_EQ(w.flat.nodes[sol.root].op, CsgOp::kIntersection);
        }
    EXPECT_EQ(hemis, 2);
}

// ∪ᵢ (xᵢ − d) is made as (∪ᵢ xᵢ) − d: the same tree as the nested form, one leaf of d.
TEST(FlattenCsg, DifferencesSubtractingTheSameBodyAreGroupedIntoTheNestedForm) {
    auto names = [](const Walked& w, int node) {
        std::vector<std::string> out;
        for (int c : w.flat.nodes[node].children) {
            const FlatCsgNode& n = w.flat.nodes[c];
            out.push_back(n.isLeaf ? w.flat.bodies[n.body].name : "<node>");
        }
        return out;
    };
    scene::Scene distributed = FourSpheres();
    {
        CsgBuilder b;  // ((a - d) | (b - d)) | (c - d)
        int n = b.Op(CsgOp::kUnion,
                     b.Op(CsgOp::kUnion, b.Op(CsgOp::kDifference, b.Body(0), b.Body(3)),
                          b.Op(CsgOp::kDifference, b.Body(1), b.Body(3))),
                     b.Op(CsgOp::kDifference, b.Body(2), b.Body(3)));
        AddCsg(distributed.top, "u", b, n);
    }
    scene::Scene nested = FourSpheres();
    {
        CsgBuilder b;  // ((a | b) | c) - d
        int n = b.Op(CsgOp::kDifference,
                     b.Op(CsgOp::kUnion, b.Op(CsgOp::kUnion, b.Body(0), b.Body(1)), b.Body(2)),
                     b.Body(3));
        AddCsg(nested.top, "u", b, n);
    }
    for (const scene::Scene* s : {&distributed, &nested}) {
        Walked w = Walk(*s);
        ASSERT_TRUE(w.ok);
        ASSERT_EQ(w.flat.solids.size(), 1u);
        EXPECT_EQ(w.flat.bodies.size(), 4u);  // one d, not three
        const int root = w.flat.solids[0].root;
        ASSERT_FALSE(w.flat.nodes[root].isLeaf);
        EXPECT_EQ(w.flat.nodes[root].op, CsgOp::kDifference);
        EXPECT_EQ(names(w, root), (std::vector<std::string>{"<node>", "u/d"}));
        const int u = w.flat.nodes[root].children[0];
        EXPECT_EQ(w.flat.nodes[u].op, CsgOp::kUnion);
        EXPECT_EQ(names(w, u), (std::vector<std::string>{"u/a", "u/b", "u/c"}));
        for (const FlatBody& body : w.flat.bodies) EXPECT_EQ(body.solid, 0);
        for (std::size_t i = 0; i < w.flat.nodes.size(); ++i)
            for (int c : w.flat.nodes[i].children) EXPECT_LT(c, int(i));
        // Every node is reachable: nothing was made and left over.
        std::vector<int> parents(w.flat.nodes.size(), 0);
        for (const FlatCsgNode& n : w.flat.nodes)
            for (int c : n.children) ++parents[c];
        for (std::size_t i = 0; i < w.flat.nodes.size(); ++i)
            EXPECT_EQ(parents[i], int(i) == root ? 0 : 1) << "node " << i;
    }
}

TEST(FlattenCsg, IntersectionsOfDifferencesAreGroupedAndTheGroupStandsAtItsFirstMember) {
    {
        scene::Scene s = FourSpheres();
        CsgBuilder b;  // (a - d) & (b - d) → (a & b) - d
        int n = b.Op(CsgOp::kIntersection, b.Op(CsgOp::kDifference, b.Body(0), b.Body(3)),
                     b.Op(CsgOp::kDifference, b.Body(1), b.Body(3)));
        AddCsg(s.top, "i", b, n);
        Walked w = Walk(s);
        ASSERT_TRUE(w.ok);
        EXPECT_EQ(w.flat.bodies.size(), 4u);  // a, d, b; and c, drawn on its own
        ASSERT_EQ(w.flat.solids.back().name, "i");
        const FlatCsgNode& root = w.flat.nodes[w.flat.solids.back().root];
        EXPECT_EQ(root.op, CsgOp::kDifference);
        ASSERT_EQ(root.children.size(), 2u);
        EXPECT_EQ(w.flat.nodes[root.children[0]].op, CsgOp::kIntersection);
        EXPECT_EQ(w.flat.nodes[root.children[0]].children.size(), 2u);
        EXPECT_EQ(w.flat.bodies[w.flat.nodes[root.children[1]].body].name, "i/d");
    }
    {
        scene::Scene s = FourSpheres();
        CsgBuilder b;  // (((a - d) | b) | (c - d)) | (a - c) → [(a | c) - d, b, a - c]
        int n = b.Op(
            CsgOp::kUnion,
            b.Op(CsgOp::kUnion,
                 b.Op(CsgOp::kUnion, b.Op(CsgOp::kDifference, b.Body(0), b.Body(3)), b.Body(1)),
                 b.Op(CsgOp::kDifference, b.Body(2), b.Body(3))),
            b.Op(CsgOp::kDifference, b.Body(0), b.Body(2)));
        AddCsg(s.top, "m", b, n);
        Walked w = Walk(s);
        ASSERT_TRUE(w.ok);
        EXPECT_EQ(w.flat.bodies.size(), 6u);  // a, c, d; b; a, c
        const FlatCsgNode& root = w.flat.nodes[w.flat.solids[0].root];
        EXPECT_EQ(root.op, CsgOp::kUnion);
        ASSERT_EQ(root.children.size(), 3u);
        const FlatCsgNode& g = w.flat.nodes[root.children[0]];
        EXPECT_EQ(g.op, CsgOp::kDifference);
        ASSERT_EQ(g.children.size(), 2u);
        EXPECT_EQ(w.flat.nodes[g.children[0]].children.size(), 2u);  // a | c
        EXPECT_TRUE(w.flat.nodes[root.children[1]].isLeaf);
        EXPECT_EQ(w.flat.bodies[w.flat.nodes[root.children[1]].body].name, "m/b");
        EXPECT_EQ(w.flat.nodes[root.children[2]].op, CsgOp::kDifference);
    }
}

// Copies that would not be the same leaf are not grouped: another inherited color, another
// instance copy (another transform), a subtrahend that is not a single body.
TEST(FlattenCsg, DifferencesAreGroupedOnlyWhenTheirSubtrahendsAreTheSameLeaves) {
    {
        scene::Scene s = FourSpheres();
        CsgBuilder b1;  // x = a - d, red
        // (The root first: AddCsg takes the builder by value, and argument order is unspecified.)
        const int x = b1.Op(CsgOp::kDifference, b1.Body(0), b1.Body(3));
        AddCsg(s.top, "x", b1, x, Color{1, 0, 0});
        CsgBuilder b2;  // u = x | (b - d)
        int n = b2.Op(CsgOp::kUnion, b2.Csg(0), b2.Op(CsgOp::kDifference, b2.Body(1), b2.Body(3)));
        AddCsg(s.top, "u", b2, n);
        Walked w = Walk(s);
        ASSERT_TRUE(w.ok);
        ASSERT_EQ(w.flat.bodies.size(), 5u);  // c drawn on its own; a, d; b, d
        ASSERT_EQ(w.flat.solids.back().name, "u");
        const FlatCsgNode& root = w.flat.nodes[w.flat.solids.back().root];
        EXPECT_EQ(root.op, CsgOp::kUnion);
        ASSERT_EQ(root.children.size(), 2u);
        const FlatCsgNode& first = w.flat.nodes[root.children[0]];
        const FlatCsgNode& second = w.flat.nodes[root.children[1]];
        EXPECT_EQ(w.flat.bodies[w.flat.nodes[first.children[1]].body].color, (Color{1, 0, 0}));
        EXPECT_EQ(w.flat.bodies[w.flat.nodes[second.children[1]].body].color, (Color{1, 1, 1}));
    }
    {
        scene::Scene s;
        scene::Scope def;
        def.id = "holed";
        AddBody(def, "ball", {AddSphere(def, "s", {0, 0, 0}, 1)});
        AddBody(def, "hole", {AddSphere(def, "h", {0, 0, 0}, 0.5)});
        CsgBuilder b;
        const int shellRoot = b.Op(CsgOp::kDifference, b.Body(0), b.Body(1));
        AddCsg(def, "shell", b, shellRoot);
        s.definitions.push_back(def);
        int arr = AddInstance(s.top, "row", 0, Transform(), 3, Transform::Translate({3, 0, 0}));
        int q = AddSphere(s.top, "q", {0, 5, 0}, 1);
        AddBody(s.top, "extra", {q});
        CsgBuilder u;
        const int unionRoot = u.Op(CsgOp::kUnion, u.Inst(arr), u.Body(0));
        AddCsg(s.top, "u", u, unionRoot);
        Walked w = Walk(s);
        ASSERT_TRUE(w.ok);
        EXPECT_EQ(w.flat.bodies.size(), 7u);  // three shells of two bodies, and extra
        const FlatCsgNode& root = w.flat.nodes[w.flat.solids[0].root];
        ASSERT_EQ(root.children.size(), 4u);
        for (int k = 0; k < 3; ++k) {
            const FlatCsgNode& shell = w.flat.nodes[root.children[k]];
            EXPECT_EQ(shell.op, CsgOp::kDifference);
            EXPECT_EQ(shell.children.size(), 2u);
        }
    }
    {
        scene::Scene s = FourSpheres();
        CsgBuilder b;  // (a - (c | d)) | (b - (c | d)): the subtrahends are spliced unions
        int n =
            b.Op(CsgOp::kUnion,
                 b.Op(CsgOp::kDifference, b.Body(0), b.Op(CsgOp::kUnion, b.Body(2), b.Body(3))),
                 b.Op(CsgOp::kDifference, b.Body(1), b.Op(CsgOp::kUnion, b.Body(2), b.Body(3))));
        AddCsg(s.top, "v", b, n);
        Walked w = Walk(s);
        ASSERT_TRUE(w.ok);
        EXPECT_EQ(w.flat.bodies.size(), 6u);
        const FlatCsgNode& root = w.flat.nodes[w.flat.solids[0].root];
        ASSERT_EQ(root.children.size(), 2u);
        EXPECT_EQ(w.flat.nodes[root.children[0]].children.size(), 3u);
    }
}

TEST(FlattenCsg, ZeroCopyOperandIsAnEmptyUnion) {
    scene::Scene s = FourSpheres();
    scene::Scope def;
    int q = AddSphere(def, "s", {0, 0, 0}, 1);
    AddBody(def, "b", {q});
    s.definitions.push_back(def);
    int none = AddInstance(s.top, "none_array", 0, Transform(), 0);
    CsgBuilder b;  // none & a: an intersection with the empty set
    int n = b.Op(CsgOp::kIntersection, b.Inst(none), b.Body(0));
    AddCsg(s.top, "e", b, n);
    Walked w = Walk(s);
    ASSERT_TRUE(w.ok);
    const FlatSolid& e = w.flat.solids.back();
    const FlatCsgNode& root = w.flat.nodes[e.root];
    ASSERT_EQ(root.children.size(), 2u);
    const FlatCsgNode& empty = w.flat.nodes[root.children[0]];
    EXPECT_FALSE(empty.isLeaf);
    EXPECT_EQ(empty.op, CsgOp::kUnion);
    EXPECT_TRUE(empty.children.empty());
}

TEST(FlattenCsg, LongChainsDoNotRecurse) {
    // A union of 20,000 spheres as a left-deep binary tree: one node, no deep recursion (this
    // also runs under ASan, whose frames are large).
    scene::Scene s;
    int q = AddSphere(s.top, "s", {0, 0, 0}, 1);
    const int n = 20000;
    for (int i = 0; i < n; ++i) AddBody(s.top, "", {q});
    CsgBuilder b;
    int acc = b.Body(0);
    for (int i = 1; i < n; ++i) acc = b.Op(CsgOp::kUnion, acc, b.Body(i));
    AddCsg(s.top, "many", b, acc);
    Walked w = Walk(s);
    ASSERT_TRUE(w.ok);
    ASSERT_EQ(w.flat.solids.size(), 1u);
    EXPECT_EQ(w.flat.nodes[w.flat.solids[0].root].children.size(), size_t(n));
    EXPECT_EQ(w.flat.halfSpaces.size(), 1u);  // shared within the scope instance
}

TEST(FlattenHierarchy, ExplosionGuardStopsArraysOfArraysQuickly) {
    // 3000 × 3000 × 3000 copies: counted, not built.
    scene::Scene s;
    scene::Scope a;
    int q = AddSphere(a, "s", {0, 0, 0}, 1);
    AddBody(a, "b", {q});
    s.definitions.push_back(a);
    scene::Scope b;
    AddInstance(b, "inner_array", 0, Transform(), 3000, Transform::Translate({1, 0, 0}));
    s.definitions.push_back(b);
    scene::Scope c;
    AddInstance(c, "middle_array", 1, Transform(), 3000, Transform::Translate({0, 1, 0}));
    s.definitions.push_back(c);
    AddInstance(s.top, "outer_array", 2, Transform(), 3000, Transform::Translate({0, 0, 1}));
    s.top.instances[0].loc = Loc(7, 3);
    auto t0 = std::chrono::steady_clock::now();
    Walked w = Walk(s);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_FALSE(w.ok);
    ASSERT_EQ(w.diags.ErrorCount(), 1);
    EXPECT_NE(w.diags.Items()[0].message.find("2.7e+10 bodies"), std::string::npos)
        << w.diags.Items()[0].message;
    EXPECT_EQ(w.diags.Items()[0].loc.line, 7);
    EXPECT_TRUE(w.flat.bodies.empty());
    EXPECT_LT(seconds, 1.0);  // generous: it is microseconds (counting only)
    // Just under the limit is built.
    HierarchyLimits small;
    small.maxBodies = 9;
    scene::Scene ok;
    ok.definitions.push_back(a);
    AddInstance(ok.top, "nine_array", 0, Transform(), 9, Transform::Translate({1, 0, 0}));
    EXPECT_TRUE(Walk(ok, small).ok);
    small.maxBodies = 8;
    EXPECT_FALSE(Walk(ok, small).ok);
}

TEST(FlattenHierarchy, SelfInstancingDefinitionIsAnError) {
    scene::Scene s;
    scene::Scope a;
    a.id = "loop";
    AddInstance(a, "again", 0, Transform());
    a.instances[0].loc = Loc(2, 5);
    s.definitions.push_back(a);
    AddInstance(s.top, "start", 0, Transform());
    Walked w = Walk(s);
    EXPECT_FALSE(w.ok);
    ASSERT_GE(w.diags.ErrorCount(), 1);
    EXPECT_NE(w.diags.Items()[0].message.find("instances itself"), std::string::npos);
}

}  // namespace
}  // namespace quadrix
