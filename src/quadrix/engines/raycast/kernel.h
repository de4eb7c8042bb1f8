// Sub-tile kernels of engine `raycast` (step 5 of a render, raycast.cpp). Most pixels that are not
// background, flat or one body lie in sub-tiles whose program is a small tree of bodies — the
// machined part's "block ∪ bosses minus the holes that reach here" — and Trace (trace.h) spends
// most of its time there on the machinery around the set operations: the depth-cut loop,
// Evaluate's recursion with its bounds tests and list slots, EvaluateBody's look-ups. Compile
// turns such a program, once per sub-tile, into postfix code, already simplified by the
// identities of TileReduction::SingleBody for the bodies TileReduction proved empty; RunTile runs
// it over lanes of pixels (kernel_lanes.h), and Run evaluates it per pixel, for the pixels the
// lanes cannot decide, on a small stack of lists with the same set operations (the one-interval
// ones inline), reading each body's set from its batch (body_batch.h) where it has one and the
// pixel is ordinary there, else from EvaluateBody.
//
// Exactness. Without depth cuts (at most 8 leaves: SetCuts leaves only +inf) Trace evaluates each
// solid's whole tree; the identities ∅ ∪ B = B, A ∪ ∅ = A, A − ∅ = A, ∅ − B = ∅, A ∩ ∅ = ∅ hold
// for the lists ids included (math/interval_list.h), so dropping empty operands at compile time
// (proved empty on the sub-tile) or at run time (a body whose bounds miss the pixel, or empty
// there) gives Evaluate's list bit for bit; the solids are combined by Trace's rule (nearest, ties
// to the lower solid index).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "quadrix/engines/raycast/body_batch.h"
#include "quadrix/engines/raycast/counters.h"
#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/engines/raycast/kernel_lanes.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/engines/raycast/settings.h"
#include "quadrix/engines/raycast/tile_reduction.h"
#include "quadrix/engines/raycast/trace.h"
#include "quadrix/math/interval_list.h"

namespace quadrix::raycast {

class Kernel {
  public:
    Kernel(const SceneTables& tables, Settings settings, const TileReduction& reduction,
           BodyBatches& batches, Tracer& tracer, Counters& counters)
        : tables_(&tables),
          settings_(settings),
          reduction_(reduction),
          batches_(batches),
          tracer_(tracer),
          counters_(counters) {}
    // For another render (worker.h Worker::Bind).
    void Bind(const SceneTables& tables, Settings settings) {
        tables_ = &tables;
        settings_ = settings;
    }

    // Compiles the sub-tile program (after BodyBatches::Start and Tracer::SetCuts); false when it
    // cannot be compiled (kernel=off, more than kMaxBodies bodies, an operator whose bounds do
    // not contain r). With depth cuts (a program of more than 8 leaves: a big union), the code is
    // that of Trace's first pass, the tree with the nodes whose zlo is not below the first cut
    // taken as ∅ (at most 8 bodies by the cut's choice): its first visible point below the cut
    // is the pixel's (the depth-cut rule, trace.h), and the pixels with none below it are traced.
    bool Compile(const CsgProgram& program, const Rect& r);

    // The kernel's visible point of the current pixel (BodyBatches::SetPixel) at (x, y).
    Hit Run(double x, double y);

    // The kernel's visible points of all the pixels of the sub-tile, row-major, into `hits`: the
    // code run over lanes of pixels, then Run for the pixels marked `over` (a set of several
    // intervals, or a body without a batch there).
    void RunTile(Hit* hits);

  private:
    // Kernel code: bodies push their set at the pixel (∅ outside their bounds), operators combine
    // the two sets on top of the stack.
    struct KernelOp {
        NodeKind kind;
        std::int32_t node;  // kBody: the body's program node
        Rect xy;            // kBody: the node's bounds
    };
    struct KernelSolid {
        std::int32_t begin, end;  // its code
        std::int32_t solid;
        Rect xy;
        double zlo;
    };
    static constexpr int kMaxBodies = 8;  // bodies a kernel may hold

    // Appends the code of node n: 1 when code was emitted, 0 when the node is ∅ on every pixel of
    // r (nothing emitted), -1 when the node cannot be compiled (an operator whose bounds do not
    // contain r: MissesPoint could then empty it at some pixels).
    inline int Emit(const CsgProgram& p, std::int32_t n, const Rect& r, int& bodies);
    // Run's body operation: the body's set at the pixel into l.
    inline void PushBody(const KernelOp& op, double x, double y, IntervalList& l);
    // Run's operator: *stack[sp - 1] = *stack[sp - 1] op *stack[sp] (stack[sp + 1] is scratch).
    inline void ApplyOp(NodeKind kind, IntervalList** stack, std::size_t sp);
    // RunTile for one solid: its code over the lanes (the result in lanes_[0]).
    inline void RunLanes(const KernelSolid& s, int np, std::int64_t* over);
    // FirstVisible of the solid's lanes where it lies below the lane's cut (else `over`),
    // combined into hits by Trace's rule.
    inline void MergeLanes(const KernelSolid& s, int np, Hit* hits, std::int64_t* over) const;

    const SceneTables* tables_;  // Bind
    Settings settings_;
    const TileReduction& reduction_;
    BodyBatches& batches_;
    Tracer& tracer_;
    Counters& counters_;
    const CsgProgram* program_ = nullptr;  // the sub-tile program compiled
    double cut_ = HUGE_VAL;                // Tracer::FirstCut of the program compiled
    std::vector<KernelOp> code_;
    std::vector<KernelSolid> solids_;
    std::vector<IntervalList> lists_;
    std::vector<IntervalList*> stack_;
    std::vector<Lane> lanes_;
};

}  // namespace quadrix::raycast
