// Compact CSG programs for the raycast engine, and their pruning against screen rectangles.
//
// A CsgProgram is a flattened copy of the FlatScene's solids: n-ary nodes with their children in
// one array, each node carrying the xy range of pixel centres it can cover and the nearest depth it
// can reach (from FlatBody::bounds, FlatCsgNode::bounds and FlatSolid::bounds, which are
// conservative). Solids are sorted by that nearest depth so that a pixel can stop looking once its
// best depth is nearer than the next solid's.
//
// Pruning (libfive-style interval pruning, STYLE.md) specialises a program to a rectangle of pixel
// centres: a node whose bounds miss the rectangle is the empty set there and the tree is
// simplified with
//     A ∪ ∅ = A,   A ∩ ∅ = ∅,   A − ∅ = A,   ∅ − B = ∅,   op(A) = A (one operand left),
// so that per pixel only the few leaves that can matter are evaluated. These identities hold
// exactly for the interval lists, ids included (math/interval_list.h), so a pruned program renders
// bit for bit what the full one does. The order of the surviving operands is kept.
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/flatten/flat_scene.h"

namespace quadrix::eval {

enum class NodeKind : std::uint8_t { kBody, kUnion, kIntersection, kDifference };

// The pixel-centre rectangle [x0, x1] × [y0, y1] (device units; may be infinite).
struct Rect {
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};

struct ProgNode {
    Rect xy;         // pixel centres outside it see the empty set
    double zlo = 0;  // no point of the node's set is nearer than this (−inf if unknown)
    NodeKind kind = NodeKind::kBody;
    std::int32_t first = 0;  // kBody: the FlatScene body index; else first child in `children`
    std::int32_t count = 0;  // number of children (0 for kBody)

    bool Misses(const Rect& r) const {
        // NaN bounds compare false and are never culled (conservative).
        return xy.x1 < r.x0 || xy.x0 > r.x1 || xy.y1 < r.y0 || xy.y0 > r.y1;
    }
    bool MissesPoint(double x, double y) const {
        return x < xy.x0 || x > xy.x1 || y < xy.y0 || y > xy.y1;
    }
};

struct ProgSolid {
    std::int32_t solid = -1;  // FlatScene solid index
    std::int32_t root = -1;   // index into CsgProgram::nodes
    Rect xy;
    double zlo = 0;
};

struct CsgProgram {
    std::vector<ProgNode> nodes;
    std::vector<std::int32_t> children;
    std::vector<ProgSolid> solids;  // sorted by (zlo, solid)
    int maxDepth = 0;               // deepest node (root = 0)

    void Clear() {
        nodes.clear();
        children.clear();
        solids.clear();
        maxDepth = 0;
    }
};

// The whole scene as a program. Nodes with empty bounds, and references to missing bodies or
// nodes, are the empty set.
void BuildProgram(const FlatScene& scene, CsgProgram& out);

// `dst` = `src` specialised to the pixel centres in `r`. `stack` is scratch (kept to avoid
// allocations). dst.maxDepth <= src.maxDepth (pruning only makes trees shallower).
void PruneProgram(const CsgProgram& src, const Rect& r, CsgProgram& dst,
                  std::vector<std::int32_t>& stack);

// Screen-space bins of a program (issue 24: the per-tile pruning of a wide union became the
// cost): for a row or column of disjoint rectangles, sorted along one axis (the 32 sub-tiles of
// a tile, the 32 tiles of a block), which solids and which operands of every wide union or
// difference (more than kBinnedOperands; a difference's minuend excepted) can meet each
// rectangle, found once per program by a binary search per operand. Pruning with the bins
// visits only those instead of every operand for every rectangle; the others would fail the
// same test (a rectangle they miss along the axis), so the pruned program is the same bits.
// Intersections are not binned (one operand that misses empties them: they are walked whole).
struct ProgramBins {
    static constexpr std::int32_t kBinnedOperands = 8;
    bool alongX = true;
    std::vector<double> lo, hi;  // per bin: its rectangle's range on the axis (ascending)
    // Per node of the program: its index among the binned nodes, or -1. Binned node w's list for
    // bin k is items[starts[w * (bins + 1) + k] .. starts[w * (bins + 1) + k + 1]), positions of
    // its operands in their order; the solid lists likewise in solidStarts / solidItems.
    std::vector<std::int32_t> binnedOf, starts, items;
    std::vector<std::int32_t> solidStarts, solidItems;
    std::size_t Bins() const { return lo.size(); }
};

// The bins of `src` over `rects` (disjoint and in ascending order along x when alongX, else y).
void BinProgram(const CsgProgram& src, const std::vector<Rect>& rects, bool alongX,
                ProgramBins& out);

// PruneProgram(src, r, dst, stack) for r, the rectangle of bin `bin` of `bins` (made from src).
void PruneProgram(const CsgProgram& src, const ProgramBins& bins, std::size_t bin, const Rect& r,
                  CsgProgram& dst, std::vector<std::int32_t>& stack);

}  // namespace quadrix::eval
