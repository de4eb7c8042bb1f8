// The scalar path of engine `raycast` (step 5 of a render, raycast.cpp; DESIGN.md "Engines in
// more detail"): the visible point of one pixel from its sub-tile's program. Trace visits the
// solids by nearest depth until the best depth found is nearer than the next solid can be; a
// solid's interval list is computed by recursion over its pruned tree (Evaluate: bodies clip
// their literals' sets into each other, operators fold their operands left to right, with short
// cuts on ∅) using lists preallocated per thread, so no pixel allocates once warm. The solid's
// visible point is its first finite endpoint whose surface is opaque (transparent half-spaces and
// clipping planes bound but are not drawn); across solids the nearest wins and exact ties keep
// the lower solid index. Every fast path (body_batch.h, kernel.h, tile_reduction.h) gives this
// result bit for bit.
//
// Depth cuts: evaluating a tree with every node whose zlo >= T replaced by ∅ gives its set
// exactly on t < T (set operations are pointwise in t, and a node with zlo >= T is empty there),
// ids included (the dropped nodes have no endpoints before T, so no sweep sees a different event
// before T). A first visible endpoint found below T is therefore the exact one. Big unions
// (thousands of spheres) are evaluated with growing cuts and most pixels stop at the first: cost
// grows with the depth complexity near the visible surface, not with every primitive behind it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "quadrix/engines/raycast/body_batch.h"
#include "quadrix/engines/raycast/counters.h"
#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/engines/raycast/tile_reduction.h"
#include "quadrix/math/interval_list.h"

namespace quadrix::raycast {

class Tracer {
  public:
    // `maxDepth`: the deepest node of the programs traced (CsgProgram::maxDepth).
    Tracer(const SceneTables& tables, int maxDepth, const TileReduction& reduction,
           BodyBatches& batches, Counters& counters);
    // For another render (worker.h Worker::Bind): its tables, and room for programs `maxDepth`
    // deep (the lists kept are never fewer).
    void Bind(const SceneTables& tables, int maxDepth);

    // Cut levels for a sub-tile program: the 8th, 32nd, 128th and 512th nearest leaf depths
    // (zlo) when the program has more leaves than that, then +inf.
    void SetCuts(const CsgProgram& program);
    // No depth cut but +inf (at most 8 leaves): Trace evaluates each solid's whole tree.
    bool Uncut() const { return cuts_.size() == 1; }
    // The first cut level (+inf when Uncut): Trace's first pass evaluates the tree with the nodes
    // whose zlo is not below it taken as ∅.
    double FirstCut() const { return cuts_.front(); }

    // The visible point of the pixel (x, y): per solid in order of nearest depth, its first
    // opaque endpoint.
    Hit Trace(const CsgProgram& program, double x, double y);

    // The set of body `body` (program node `node`) at the current pixel (BodyBatches::SetPixel)
    // (x, y) into Slot(slot): from its batch when the pixel is ordinary there, else literal by
    // literal over the literals TileReduction kept.
    void EvaluateBody(std::int32_t body, std::int32_t node, double x, double y, std::size_t slot);
    const IntervalList& Slot(std::size_t slot) const { return *slots_[slot]; }

    // The first finite endpoint on an opaque surface.
    bool FirstVisible(const IntervalList& list, double& t, std::int32_t& tag) const {
        for (const Interval& v : list)
            if (tables_->VisibleEnd(v.lo, v.loId, v.hi, v.hiId, t, tag)) return true;
        return false;
    }

  private:
    // *slots_[slot] = the set of node n on the ray through (x, y), exact on t < cut (nodes with
    // zlo >= cut are taken as ∅; see Trace).
    inline void Evaluate(const CsgProgram& p, std::int32_t n, double x, double y, std::size_t slot,
                         double cut);
    // Operands 1.. of a union or difference of more than kFilteredOperands (see trace.cpp).
    inline void EvaluateWide(const CsgProgram& p, const ProgNode& node, std::int32_t n, double x,
                             double y, std::size_t slot, double cut);
    static constexpr std::int32_t kFilteredOperands = 8;
    // Folds the non-empty operand in slot+1 into the running set in `slot` by the node's
    // operation (∅ ∪ B = B by a swap; Evaluate and EvaluateWide have returned for ∅ ∩ B, ∅ − B).
    inline void Fold(NodeKind kind, std::size_t slot);
    // The rest of a body from the first literal with a two-piece set: the running interval `run`
    // intersected with `set`, then literals [next, last) as interval lists.
    inline void EvaluateBodyLists(const Interval& run, const RaySet& set, const std::int32_t* next,
                                  const std::int32_t* last, double x, double y, std::size_t slot);
    static void AppendPiece(IntervalList& l, const Interval& v) {
        l.Append(v.lo, v.loId, v.hi, v.hiId);
    }

    const SceneTables* tables_;  // Bind
    const TileReduction& reduction_;
    BodyBatches& batches_;
    Counters& counters_;
    // Depth cuts of the current sub-tile (SetCuts), ascending, the last one +inf.
    std::vector<double> cuts_{HUGE_VAL};
    std::vector<double> zlos_;  // SetCuts scratch
    // Slot d holds the result of a node at depth d; a node at depth d also uses d+1 and d+2
    // (operand and scratch). Results move between slots by swapping pointers.
    std::vector<IntervalList> lists_;
    std::vector<IntervalList*> slots_;
    // EvaluateWide's operands that hold the pixel, a stack shared by the nested wide nodes
    // (hitTop_ its height): as long as the program's `children` (SetCuts), so never reallocated
    // during a pixel.
    std::vector<std::int32_t> hits_;
    std::size_t hitTop_ = 0;
    // The operands 1.. of every wide union or difference grouped by cut level (SetCuts): level L
    // holds the operands whose zlo is below cuts_[L] and not below the cuts before it (NaN zlo,
    // never cut: level 0), each level in operand order. byLevel_[first + 1 ..] lists their
    // positions (1..count-1), levelEnd_[n * kLevels + L] the end of levels 0..L there. A pass
    // with cut cuts_[L] visits levels 0..L only: the operands a cut leaves, not every operand.
    static constexpr std::size_t kLevels = 5;  // at most four finite cuts, then +inf
    void GroupWideOperands(const CsgProgram& program);
    std::vector<std::int32_t> byLevel_;
    std::vector<std::uint8_t> levelOf_;  // GroupWideOperands scratch: each operand's level
    std::vector<std::int32_t> levelEnd_;
    std::size_t level_ = 0;  // the index in cuts_ of the pass under way (Trace)
};

// Per sub-tile (tiling.cpp), so defined here.
inline void Tracer::SetCuts(const CsgProgram& program) {
    cuts_.clear();
    zlos_.clear();
    if (hits_.size() < program.children.size()) hits_.resize(program.children.size());
    for (const ProgNode& n : program.nodes)
        if (n.kind == NodeKind::kBody) zlos_.push_back(n.zlo);
    for (std::size_t k : {8u, 32u, 128u, 512u}) {
        if (zlos_.size() <= k) break;
        std::nth_element(zlos_.begin(), zlos_.begin() + static_cast<std::ptrdiff_t>(k),
                         zlos_.end());
        const double cut = zlos_[k];
        if (std::isfinite(cut) && (cuts_.empty() || cut > cuts_.back())) cuts_.push_back(cut);
    }
    cuts_.push_back(HUGE_VAL);
    GroupWideOperands(program);
}

}  // namespace quadrix::raycast
