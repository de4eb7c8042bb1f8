#include "quadrix/eval/csg_program.h"

#include <gtest/gtest.h>

#include "quadrix/flatten/test_scene_builder.h"

namespace quadrix::eval {
namespace {

using scene::CsgOp;
using testing_util::TestSceneBuilder;

Box3 BoxXY(double x0, double x1, double y0, double y1, double z0 = 0, double z1 = 10) {
    return {{x0, y0, z0}, {x1, y1, z1}};
}

// Four bodies in four screen quadrants of a 100×100 image; only their bounds matter here.
struct Quadrants {
    TestSceneBuilder b{100, 100};
    int body[4];
    int leaf[4];
    Quadrants() {
        int p = b.AddPlane(0, 0, 1, -1);
        const Box3 boxes[4] = {BoxXY(0, 40, 0, 40, 5), BoxXY(60, 100, 0, 40, 1),
                               BoxXY(0, 40, 60, 100, 3), BoxXY(60, 100, 60, 100, 2)};
        for (int i = 0; i < 4; ++i) {
            body[i] = b.AddBody({{p, false}}, boxes[i]);
            leaf[i] = b.AddLeaf(body[i], boxes[i]);
        }
    }
};

TEST(RaycastProgram, PruningSimplifiesTheTree) {
    Quadrants q;
    int u = q.b.AddNode(CsgOp::kUnion, {q.leaf[0], q.leaf[1], q.leaf[2]}, BoxXY(0, 100, 0, 100));
    int d = q.b.AddNode(CsgOp::kDifference, {u, q.leaf[3]}, BoxXY(0, 100, 0, 100));
    q.b.AddSolid(d, BoxXY(0, 100, 0, 100));
    CsgProgram full, pruned;
    BuildProgram(q.b.scene(), full);
    ASSERT_EQ(full.solids.size(), 1u);
    EXPECT_EQ(full.maxDepth, 2);
    std::vector<std::int32_t> stack;

    // Top-left quadrant: the union keeps one leaf, the subtrahend misses → the solid is leaf 0.
    PruneProgram(full, {0.5, 39.5, 0.5, 39.5}, pruned, stack);
    ASSERT_EQ(pruned.solids.size(), 1u);
    const ProgNode& root = pruned.nodes[static_cast<std::size_t>(pruned.solids[0].root)];
    EXPECT_EQ(root.kind, NodeKind::kBody);
    EXPECT_EQ(root.first, q.body[0]);
    EXPECT_EQ(pruned.solids[0].zlo, 5);  // tightened from the union's 1 to the leaf's 5

    // Bottom-right: the minuend (the union) misses → ∅ − B = ∅, no solid.
    PruneProgram(full, {60.5, 99.5, 60.5, 99.5}, pruned, stack);
    EXPECT_TRUE(pruned.solids.empty());

    // A strip across the top: union of leaves 0 and 1, difference collapsed.
    PruneProgram(full, {0.5, 99.5, 0.5, 39.5}, pruned, stack);
    ASSERT_EQ(pruned.solids.size(), 1u);
    const ProgNode& u2 = pruned.nodes[static_cast<std::size_t>(pruned.solids[0].root)];
    EXPECT_EQ(u2.kind, NodeKind::kUnion);
    ASSERT_EQ(u2.count, 2);
    EXPECT_EQ(pruned.solids[0].zlo, 1);

    // Everything: nothing pruned; pruning a pruned program is idempotent.
    PruneProgram(full, {0.5, 99.5, 0.5, 99.5}, pruned, stack);
    EXPECT_EQ(pruned.nodes.size(), full.nodes.size());
    CsgProgram again;
    PruneProgram(pruned, {0.5, 99.5, 0.5, 99.5}, again, stack);
    EXPECT_EQ(again.nodes.size(), pruned.nodes.size());
    EXPECT_TRUE(stack.empty());
}

TEST(RaycastProgram, IntersectionWithAMissingOperandIsEmpty) {
    Quadrants q;
    int i = q.b.AddNode(CsgOp::kIntersection, {q.leaf[0], q.leaf[1]}, Box3::Everything());
    q.b.AddSolid(i);
    CsgProgram full, pruned;
    BuildProgram(q.b.scene(), full);
    // The intersection's bounds are tightened to the (empty) overlap of its operands' boxes.
    EXPECT_TRUE(full.solids.empty());
}

TEST(RaycastProgram, SolidsAreSortedByNearestDepthThenIndex) {
    Quadrants q;
    for (int k : {0, 1, 2, 3}) q.b.AddSolid(q.leaf[k], Box3::Everything());
    int e = q.b.AddBody({{0, false}}, Box3{});  // empty bounds: never drawn
    q.b.AddSolidOfBody(e);
    CsgProgram full;
    BuildProgram(q.b.scene(), full);
    ASSERT_EQ(full.solids.size(), 4u);
    EXPECT_EQ(full.solids[0].solid, 1);  // zlo 1
    EXPECT_EQ(full.solids[1].solid, 3);  // zlo 2
    EXPECT_EQ(full.solids[2].solid, 2);  // zlo 3
    EXPECT_EQ(full.solids[3].solid, 0);  // zlo 5
}

}  // namespace
}  // namespace quadrix::eval
