// Bottom-up passes over a FlatScene's CSG nodes (TreeBounds, FitTreeBounds): node(i) for every
// node, each after its children, in parallel over runs of whole solids.
//
// The walk (hierarchy.h) emits a solid's nodes together, children before parents, and the solids
// one after another, so the nodes up to a solid's root that follow the previous solid's root are
// that solid's alone. The runs are cut at roots, a few per processor; in each, node(i) is called
// in order once every child of i is known to lie in the run before i. Where one does not (a scene
// built otherwise), nothing of it is read: the whole pass is made again serially, in order. node(i)
// must be a function of node i and of its children's results only (it may be called twice).
#pragma once

#include <atomic>
#include <cstddef>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/util/parallel.h"

namespace quadrix {

// Below this many nodes a pass is serial (a parallel loop's start costs more).
inline constexpr std::size_t kBottomUpParallelNodes = 4096;

template <class Node>
void BottomUp(const FlatScene& scene, const Node& node) {
    const std::size_t n = scene.nodes.size();
    auto serial = [&] {
        for (std::size_t i = 0; i < n; ++i) node(i);
    };
    if (n < kBottomUpParallelNodes || SerialLoopsOnThisThread()) return serial();
    const std::size_t runs = 4 * static_cast<std::size_t>(AvailableProcessors());
    std::vector<std::size_t> cuts{0};
    for (const FlatSolid& s : scene.solids) {
        const auto end = static_cast<std::size_t>(s.root) + 1;
        if (s.root < 0 || end > n || end <= cuts.back()) continue;
        if (end - cuts.back() >= n / runs) cuts.push_back(end);
    }
    if (cuts.back() != n) cuts.push_back(n);
    if (cuts.size() < 3) return serial();
    std::atomic<bool> outside{false};
    ParallelFor(std::size_t{0}, cuts.size() - 1, [&](std::size_t k) {
        const std::size_t begin = cuts[k];
        for (std::size_t i = begin; i < cuts[k + 1]; ++i) {
            bool inside = true;
            for (int c : scene.nodes[i].children)
                inside = inside && c >= 0 && static_cast<std::size_t>(c) >= begin &&
                         static_cast<std::size_t>(c) < i;
            if (!inside) {
                outside.store(true, std::memory_order_relaxed);
                return;
            }
            node(i);
        }
    });
    if (outside.load(std::memory_order_relaxed)) serial();
}

}  // namespace quadrix
