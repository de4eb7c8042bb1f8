#include "quadrix/flatten/bottom_up.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "quadrix/flatten/bounds.h"
#include "quadrix/util/parallel.h"

namespace quadrix {
namespace {

// Solids of random unions, intersections and differences over random body boxes, their nodes
// emitted as the walk emits them (a solid's nodes together, children first).
FlatScene RandomTrees(int solids, std::mt19937& rng, std::vector<Box3>& bodyBoxes) {
    std::uniform_real_distribution<double> u(-100, 100), size(0.1, 20);
    std::uniform_int_distribution<int> op(0, 2), arity(1, 4);
    FlatScene scene;
    for (int s = 0; s < solids; ++s) {
        std::vector<int> open;
        const int leaves = 1 + s % 9;
        for (int l = 0; l < leaves; ++l) {
            const Vec3 lo{u(rng), u(rng), u(rng)};
            bodyBoxes.push_back(Box3{lo, lo + Vec3{size(rng), size(rng), size(rng)}});
            FlatCsgNode leaf;
            leaf.body = static_cast<int>(bodyBoxes.size()) - 1;
            scene.nodes.push_back(leaf);
            open.push_back(static_cast<int>(scene.nodes.size()) - 1);
            // Now and then combine the last few open nodes.
            while (open.size() >= 2 && op(rng) != 0) {
                const int k = std::min<int>(arity(rng) + 1, static_cast<int>(open.size()));
                FlatCsgNode node;
                node.isLeaf = false;
                node.op = static_cast<scene::CsgOp>(op(rng));
                node.children.assign(open.end() - k, open.end());
                open.resize(open.size() - static_cast<std::size_t>(k));
                scene.nodes.push_back(node);
                open.push_back(static_cast<int>(scene.nodes.size()) - 1);
            }
        }
        if (open.size() > 1) {
            FlatCsgNode root;
            root.isLeaf = false;
            root.op = scene::CsgOp::kUnion;
            root.children = open;
            scene.nodes.push_back(root);
        }
        FlatSolid solid;
        solid.root = static_cast<int>(scene.nodes.size()) - 1;
        scene.solids.push_back(solid);
    }
    return scene;
}

bool SameBoxes(const std::vector<Box3>& a, const std::vector<Box3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Box3)) == 0;
}

// The parallel pass gives the serial pass's boxes, for trees as the walk makes them and for a
// scene where a node's child lies in another solid's run (then the pass is made serially).
TEST(BottomUp, TreeBoundsInParallelAreTheSerialOnes) {
    std::mt19937 rng(5);
    std::vector<Box3> bodies;
    FlatScene scene = RandomTrees(3000, rng, bodies);
    ASSERT_GT(scene.nodes.size(), 2 * kBottomUpParallelNodes);
    std::vector<Box3> serial;
    {
        SerialScope inline_;
        serial = TreeBounds(scene, bodies);
    }
    EXPECT_TRUE(SameBoxes(TreeBounds(scene, bodies), serial));
    std::size_t nonEmpty = 0;
    for (const Box3& b : serial) nonEmpty += !b.Empty();
    EXPECT_GT(nonEmpty, scene.nodes.size() / 2);

    // The last solid's root also takes the first solid's root as a child (a shared subtree).
    scene.nodes.back().isLeaf = false;
    scene.nodes.back().children.push_back(scene.solids.front().root);
    {
        SerialScope inline_;
        serial = TreeBounds(scene, bodies);
    }
    EXPECT_TRUE(SameBoxes(TreeBounds(scene, bodies), serial));
}

// Every node is visited once in the parallel pass when the runs hold their children, and each
// after its children.
TEST(BottomUp, EachNodeAfterItsChildren) {
    std::mt19937 rng(9);
    std::vector<Box3> bodies;
    const FlatScene scene = RandomTrees(2500, rng, bodies);
    std::vector<std::atomic<int>> visits(scene.nodes.size());
    std::atomic<bool> early{false};
    BottomUp(scene, [&](std::size_t i) {
        for (int c : scene.nodes[i].children)
            if (visits[static_cast<std::size_t>(c)].load() == 0) early = true;
        visits[i].fetch_add(1);
    });
    EXPECT_FALSE(early.load());
    for (const std::atomic<int>& v : visits) ASSERT_EQ(v.load(), 1);
}

}  // namespace
}  // namespace quadrix
