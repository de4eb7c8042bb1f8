#include "quadrix/engines/raycast/body_batch.h"

#include <cmath>

#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/math/interval_list.h"
#include "quadrix/util/cpu_features.h"

namespace quadrix::raycast {
namespace {

// One plane literal over the n pixels of a body batch: r = -(px x + py y + pd)/c as EvaluateBody
// computes it, a near bound replacing lo unless lo > r, a far bound replacing hi unless hi <= r;
// `bad` becomes non-zero where r is not finite. Branch-free, so the compiler vectorises it; built
// for AVX2 and for the baseline (util/cpu_features.h; the results are the same bits: IEEE
// division and comparisons, no FMA contraction).
// kNear: a near bound (t >= r) into lo/loId; else a far bound (t <= r) into hi/hiId.
template <bool kNear>
[[gnu::always_inline]] inline void PlaneBatchBody(int n, const double* xs, const double* ys,
                                                  double px, double py, double pd, double c,
                                                  std::int64_t tag, double* __restrict bound,
                                                  std::int64_t* __restrict boundId,
                                                  double* __restrict bad) {
    for (int p = 0; p < n; ++p) {
        const double r = -(px * xs[p] + py * ys[p] + pd) / c;
        bad[p] = std::fabs(r) < HUGE_VAL ? bad[p] : 1.0;
        const bool take = kNear ? !(bound[p] > r) : !(bound[p] <= r);
        bound[p] = take ? r : bound[p];
        boundId[p] = take ? tag : boundId[p];
    }
}

template <bool kNear>
QUADRIX_AVX2 void PlaneBatchAvx2(int n, const double* xs, const double* ys, double px, double py,
                                 double pd, double c, std::int64_t tag, double* __restrict bound,
                                 std::int64_t* __restrict boundId, double* __restrict bad) {
    PlaneBatchBody<kNear>(n, xs, ys, px, py, pd, c, tag, bound, boundId, bad);
}
template <bool kNear>
void PlaneBatchBaseline(int n, const double* xs, const double* ys, double px, double py, double pd,
                        double c, std::int64_t tag, double* __restrict bound,
                        std::int64_t* __restrict boundId, double* __restrict bad) {
    PlaneBatchBody<kNear>(n, xs, ys, px, py, pd, c, tag, bound, boundId, bad);
}
template <bool kNear>
void PlaneBatch(int n, const double* xs, const double* ys, double px, double py, double pd,
                double c, std::int64_t tag, double* __restrict bound,
                std::int64_t* __restrict boundId, double* __restrict bad) {
    if (gCpuHasAvx2)
        PlaneBatchAvx2<kNear>(n, xs, ys, px, py, pd, c, tag, bound, boundId, bad);
    else
        PlaneBatchBaseline<kNear>(n, xs, ys, px, py, pd, c, tag, bound, boundId, bad);
}

// One literal of the body over the batch's pixels, in the body's order (as EvaluateBody).
void BatchLiteral(const SceneTables& tables, Counters& counters, const double* xs, const double* ys,
                  std::int32_t tag, int n, BodyBatch& out, std::uint8_t* flag, double* bad) {
    double* const lo = out.lo;
    double* const hi = out.hi;
    std::int64_t* const loId = out.loId;
    std::int64_t* const hiId = out.hiId;
    double* const cut = out.cut;
    const Tag& t = tables.TagOf(tag);
    const RayHalfSpace& hs = tables.halfSpaces[static_cast<std::size_t>(t.halfSpace)];
    if (hs.quartic) {  // a quartic literal: its body goes the scalar way (EvaluateBody)
        for (int p = 0; p < n; ++p)
            if (flag[p] == kBatchLive) flag[p] = kBatchScalar;
        return;
    }
    if (hs.isPlane && std::isfinite(hs.c) && hs.c != 0) {
        counters.literals.planes += static_cast<std::uint64_t>(n);
        const double px = hs.px, py = hs.py, pd = hs.pd, c = hs.c;
        if ((c > 0) != t.complemented)  // t <= r: a far bound
            PlaneBatch<false>(n, xs, ys, px, py, pd, c, tag, hi, hiId, bad);
        else  // t >= r: a near bound
            PlaneBatch<true>(n, xs, ys, px, py, pd, c, tag, lo, loId, bad);
        return;
    }
    // A pixel with a bad plane bound is kScalar in the end whatever follows: skip it.
    for (int p = 0; p < n; ++p)
        if (bad[p] != 0 && flag[p] == kBatchLive) flag[p] = kBatchScalar;
    if (hs.isPlane && hs.c == 0) {
        // Parallel to the rays (a mitre or slot plane seen edge-on): on each ray the literal
        // holds everywhere or nowhere, as EvaluateBody decides it: nowhere where
        // e = px x + py y + pd is not finite or on the wrong side.
        counters.literals.planes += static_cast<std::uint64_t>(n);
        const double px = hs.px, py = hs.py, pd = hs.pd;
        for (int p = 0; p < n; ++p) {
            const double e = px * xs[p] + py * ys[p] + pd;
            const bool none = !std::isfinite(e) || (e <= 0) == t.complemented;
            if (none && flag[p] == kBatchLive) flag[p] = kBatchDead;
        }
        return;
    }
    if (hs.isPlane) {  // a non-finite coefficient: rare
        for (int p = 0; p < n; ++p)
            if (flag[p] == kBatchLive) flag[p] = kBatchScalar;
        return;
    }
    // The quadric's set at every live pixel (one piece clipped in, none: dead, two pieces:
    // kScalar), exactly as LiteralOnRay gives it (ray_literal.h).
    // Cut mode: a two-piece set keeps the first piece below a cut (BodyBatch::kCut).
    QuadricBatch(hs, t.complemented, tag, n, xs, ys, lo, loId, hi, hiId, flag, counters.literals,
                 cut);
}

}  // namespace

void BodyBatches::WantIfHalfCovered(std::int32_t node, const Rect& xy) {
    if (nodeBatch_[static_cast<std::size_t>(node)] != kNoBatchWanted || !settings_.batch) return;
    int covered = 0;  // of the pixels (points)
    if (grid_) {
        int nx = 0, ny = 0;
        for (int i = 0; i < tileW_; ++i) {
            const double x = tileX0_ + i + 0.5;
            nx += x >= xy.x0 && x <= xy.x1;
        }
        for (int j = 0; j < tileH_; ++j) {
            const double y = tileY0_ + j + 0.5;
            ny += y >= xy.y0 && y <= xy.y1;
        }
        covered = nx * ny;
    } else {
        for (int p = 0; p < tileW_; ++p)
            covered += xs_[p] >= xy.x0 && xs_[p] <= xy.x1 && ys_[p] >= xy.y0 && ys_[p] <= xy.y1;
    }
    if (2 * covered < tileW_ * tileH_) return;
    Want(node);
}

void BodyBatches::Want(std::int32_t node) {
    if (nodeBatch_[static_cast<std::size_t>(node)] != kNoBatchWanted || !settings_.batch) return;
    // (Room for its batch now: Trace may compute it even if compiling the kernel fails.)
    nodeBatch_[static_cast<std::size_t>(node)] = kNoBatch;
    batchOn_ = true;
    ++extraBatches_;
    if (batches_.size() < bodyBatchesWanted_ + extraBatches_)
        batches_.resize(bodyBatchesWanted_ + extraBatches_);
}

const BodyBatch* BodyBatches::SingleBodyBatch(const CsgProgram& program, const Rect& r) {
    if (!settings_.tileCull || !batchOn_ || program.solids.size() != 1) return nullptr;
    const ProgSolid& solid = program.solids[0];
    if (!(solid.xy.x0 <= r.x0 && solid.xy.x1 >= r.x1 && solid.xy.y0 <= r.y0 && solid.xy.y1 >= r.y1))
        return nullptr;
    const std::int32_t node = reduction_.SingleBody(program, solid.root, r);
    if (node < 0 || !Wanted(node)) return nullptr;
    if (tables_->BodyVoid(
            static_cast<std::size_t>(program.nodes[static_cast<std::size_t>(node)].first)))
        return nullptr;
    singleSolid_ = solid.solid;
    return Find(node);
}

std::int32_t BodyBatches::Compute(std::int32_t node) {
    const auto b = static_cast<std::int32_t>(batchesUsed_++);
    nodeBatch_[static_cast<std::size_t>(node)] = b;
    BodyBatch& out = batches_[static_cast<std::size_t>(b)];
    const int n = tileW_ * tileH_;
    ++counters_.batchBodies;
    counters_.batchPixels += static_cast<std::uint64_t>(n);
    double* const lo = out.lo;
    double* const hi = out.hi;
    std::int64_t* const loId = out.loId;
    std::int64_t* const hiId = out.hiId;
    double* const cut = out.cut;
    std::uint8_t flag[kLanePixels];  // kBatchLive, kBatchDead or kBatchScalar
    double bad[kLanePixels];         // non-zero: a plane bound was not finite
    for (int p = 0; p < n; ++p) {
        lo[p] = -HUGE_VAL;
        hi[p] = HUGE_VAL;
        cut[p] = HUGE_VAL;
        loId[p] = hiId[p] = Interval::kNoId;
        flag[p] = kBatchLive;
        bad[p] = 0;
    }
    const auto [begin, end] = reduction_.NodeTags(static_cast<std::size_t>(node));
    const std::int32_t* const tileTags = reduction_.TileTags();
    for (std::int32_t k = begin; k < end; ++k)
        BatchLiteral(*tables_, counters_, xs_, ys_, tileTags[k], n, out, flag, bad);
    for (int p = 0; p < n; ++p)
        out.state[p] = flag[p] == kBatchScalar || bad[p] != 0 ? BodyBatch::kScalar
                       : flag[p] == kBatchDead                ? BodyBatch::kEmpty
                       : cut[p] != HUGE_VAL                   ? BodyBatch::kCut
                       : !(lo[p] < hi[p])                     ? BodyBatch::kEmpty
                                                              : BodyBatch::kOne;
    return b;
}

}  // namespace quadrix::raycast
