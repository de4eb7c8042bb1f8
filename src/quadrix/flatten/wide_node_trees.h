// Box trees over the children of a flat scene's wide CSG nodes, shared by the rays that are not
// the engines' (shadow rays, shade/shadows.h; anti-aliasing samples, engines/raycast/
// sample_tracer.h): a union or a difference of more than kWideNode children gets a BoxTree
// (math/box_tree.h) over its operands' device bounds (a difference's: its subtrahends), so a
// ray visits only the operands it may meet. Intersections get none (every operand matters).
// kWideNode = 16, not 8 as before: below 17 children a ray's test of every child's box costs
// less than the tree's query and the sorting of what it finds (callgrind, 640 × 360 and
// 1280 × 720, one thread: the machined part's difference of 10 children −3.3 % of the whole
// process, the 2,211-body helicopter −2.7 %, a plate minus 12 or 15 holes −1.8 % and −1.2 %;
// minus 30 holes, still a tree, unchanged, and +2.1 % at kWideNode = 32). The answers are the
// same either way.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/box_tree.h"

namespace quadrix {

struct WideNodeTrees {
    static constexpr std::size_t kWideNode = 16;
    std::vector<BoxTree> trees;    // one per wide node
    std::vector<std::int32_t> of;  // node → index into trees, or -1
    // A difference's tree is over its subtrahends: item k is child k + 1; a union's item k is
    // child k. `index` false: trees that list every operand (to measure the trees' gain).
    static WideNodeTrees Build(const FlatScene& scene, bool index) {
        WideNodeTrees t;
        t.of.assign(scene.nodes.size(), -1);
        std::vector<Box3> boxes;
        for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
            const FlatCsgNode& node = scene.nodes[n];
            if (node.isLeaf || node.children.size() <= kWideNode ||
                node.op == scene::CsgOp::kIntersection)
                continue;
            const std::size_t from = node.op == scene::CsgOp::kDifference ? 1 : 0;
            boxes.clear();
            for (std::size_t c = from; c < node.children.size(); ++c)
                boxes.push_back(scene.nodes[static_cast<std::size_t>(node.children[c])].bounds);
            t.of[n] = static_cast<std::int32_t>(t.trees.size());
            t.trees.emplace_back(boxes, index);
        }
        return t;
    }
    // Build, to be shared: one build serves every tracer of a flat scene (the render context keeps
    // it for the shadow rays and the anti-aliasing samples of its pictures).
    static std::shared_ptr<const WideNodeTrees> Shared(const FlatScene& scene, bool index) {
        return std::make_shared<const WideNodeTrees>(Build(scene, index));
    }
};

}  // namespace quadrix
