#include "quadrix/engines/raycast/kernel.h"

#include <cmath>
#include <utility>

namespace quadrix::raycast {
namespace {

// LanePush's inputs for a body without a batch: every pixel in its bounds goes to Kernel::Run.
constexpr std::uint8_t kAllScalar[kLanePixels] = {
    2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2,
    2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2};
constexpr double kNoValues[kLanePixels] = {};
constexpr std::int64_t kNoIds[kLanePixels] = {};
static_assert(BodyBatch::kScalar == 2);

}  // namespace

bool Kernel::Compile(const CsgProgram& program, const Rect& r) {
    if (!settings_.kernel) return false;
    // With depth cuts, the tree of Trace's first pass (kernel.h).
    cut_ = tracer_.FirstCut();
    program_ = &program;
    code_.clear();
    solids_.clear();
    int bodies = 0;
    for (const ProgSolid& s : program.solids) {
        const auto begin = static_cast<std::int32_t>(code_.size());
        const int e = Emit(program, s.root, r, bodies);
        if (e < 0 || bodies > kMaxBodies) return false;
        if (e == 0) continue;  // ∅ on the whole sub-tile
        solids_.push_back({begin, static_cast<std::int32_t>(code_.size()), s.solid, s.xy, s.zlo});
    }
    const std::size_t depth = static_cast<std::size_t>(bodies) + 2;
    if (lists_.size() < depth) lists_.resize(depth);
    stack_.clear();
    for (IntervalList& l : lists_) stack_.push_back(&l);
    ++counters_.kernelTiles;
    if (cut_ != HUGE_VAL) ++counters_.kernelCutTiles;
    return true;
}

inline int Kernel::Emit(const CsgProgram& p, std::int32_t n, const Rect& r, int& bodies) {
    const ProgNode& node = p.nodes[static_cast<std::size_t>(n)];
    // ∅ at every pixel, as Trace's Evaluate takes it: proved empty on the sub-tile, or cut.
    // (The cut first: the reduction of a cut body is then never made, tile_reduction.h.)
    if (node.zlo >= cut_ || reduction_.NodeEmpty(static_cast<std::size_t>(n))) return 0;
    if (node.kind == NodeKind::kBody) {
        // EvaluateBody gives ∅ for these at every pixel.
        if (tables_->BodyVoid(static_cast<std::size_t>(node.first))) return 0;
        code_.push_back({NodeKind::kBody, n, node.xy});
        ++bodies;
        // Under a cut every body is batched: the few nearest bodies of a big union (spheres a
        // few pixels wide) would otherwise send their pixels to Trace.
        if (cut_ == HUGE_VAL)
            batches_.WantIfHalfCovered(n, node.xy);
        else
            batches_.Want(n);
        return 1;
    }
    if (!(node.xy.x0 <= r.x0 && node.xy.x1 >= r.x1 && node.xy.y0 <= r.y0 && node.xy.y1 >= r.y1))
        return -1;
    const std::size_t mark = code_.size();
    const std::int32_t* child = p.children.data() + node.first;
    bool have = false;  // an accumulated operand is on the stack
    for (std::int32_t i = 0; i < node.count; ++i) {
        const int e = Emit(p, child[i], r, bodies);
        if (e < 0) return -1;
        if (e == 0) {
            // ∅ ∩ B = A ∩ ∅ = ∅ and ∅ − B = ∅; a union or a subtrahend just drops it.
            if (node.kind == NodeKind::kIntersection ||
                (node.kind == NodeKind::kDifference && i == 0)) {
                code_.resize(mark);
                return 0;
            }
            continue;
        }
        if (have) code_.push_back({node.kind, -1, {}});
        have = true;
    }
    return have ? 1 : 0;
}

Hit Kernel::Run(double x, double y) {
    Hit best;
    for (const KernelSolid& s : solids_) {
        if (best.t < s.zlo) break;  // as Trace: no later solid can be nearer
        if (x < s.xy.x0 || x > s.xy.x1 || y < s.xy.y0 || y > s.xy.y1) continue;
        IntervalList** stack = stack_.data();
        std::size_t sp = 0;
        for (std::int32_t k = s.begin; k < s.end; ++k) {
            const KernelOp& op = code_[static_cast<std::size_t>(k)];
            if (op.kind == NodeKind::kBody) {
                PushBody(op, x, y, *stack[sp++]);
                continue;
            }
            ApplyOp(op.kind, stack, --sp);
        }
        double t;
        std::int32_t tag;
        if (tracer_.FirstVisible(*stack[0], t, tag) &&
            (t < best.t || (t == best.t && s.solid < best.solid)))
            best = {t, tag, s.solid};
    }
    return best;
}

inline void Kernel::PushBody(const KernelOp& op, double x, double y, IntervalList& l) {
    l.clear();
    if (x < op.xy.x0 || x > op.xy.x1 || y < op.xy.y0 || y > op.xy.y1) return;
    // The body's batch when it has one (BodyBatches::Start batches the bodies that cover the
    // sub-tile) and the pixel is ordinary there; else EvaluateBody.
    if (batches_.On() && batches_.Wanted(op.node)) {
        const BodyBatch& batch = *batches_.Find(op.node);
        const std::size_t p = batches_.Pixel();
        const std::uint8_t state = batch.state[p];
        if (state == BodyBatch::kEmpty) return;
        if (state == BodyBatch::kOne) {
            l.AssignOne(batch.lo[p], static_cast<std::int32_t>(batch.loId[p]), batch.hi[p],
                        static_cast<std::int32_t>(batch.hiId[p]));
            return;
        }
    }
    ++counters_.kernelScalarBodies;
    tracer_.EvaluateBody(program_->nodes[static_cast<std::size_t>(op.node)].first, op.node, x, y,
                         0);
    l = tracer_.Slot(0);
}

inline void Kernel::ApplyOp(NodeKind kind, IntervalList** stack, std::size_t sp) {
    IntervalList& b = *stack[sp];
    IntervalList& a = *stack[sp - 1];
    IntervalList& out = *stack[sp + 1];  // free: above the operand
    if (kind == NodeKind::kUnion) {
        if (b.empty()) return;  // A ∪ ∅ = A
        if (a.empty()) {        // ∅ ∪ B = B
            std::swap(stack[sp - 1], stack[sp]);
            return;
        }
        if (a.size() == 1 && b.size() == 1)
            UnionOfOne(a[0], b[0], out);
        else
            Union(a, b, out);
    } else if (kind == NodeKind::kIntersection) {
        if (a.empty()) return;  // ∅ ∩ B = ∅
        if (b.empty()) {
            a.clear();
            return;
        }
        if (a.size() == 1 && b.size() == 1)
            IntersectionOfOne(a[0], b[0], out);
        else
            Intersection(a, b, out);
    } else {
        if (a.empty() || b.empty()) return;  // ∅ − B = ∅, A − ∅ = A
        if (b.size() == 1) {
            out.clear();
            for (const Interval& v : a) AppendDifferenceOfOne(v, b[0], out);
        } else {
            Difference(a, b, out);
        }
    }
    ++counters_.csgOps;
    std::swap(stack[sp - 1], stack[sp + 1]);
}

void Kernel::RunTile(Hit* hits) {
    const int np = batches_.PixelCount();
    for (int p = 0; p < np; ++p) hits[p] = Hit{};
    std::int64_t over[kLanePixels] = {};
    if (lanes_.size() < stack_.size()) lanes_.resize(stack_.size());
    for (const KernelSolid& s : solids_) {
        RunLanes(s, np, over);
        MergeLanes(s, np, hits, over);
    }
    const double* xs = batches_.Xs();
    const double* ys = batches_.Ys();
    if (cut_ != HUGE_VAL)
        for (int p = 0; p < np; ++p) over[p] |= !(hits[p].t < cut_);  // nothing visible below it
    for (int p = 0; p < np; ++p) {
        if (!over[p]) continue;
        batches_.SetPixelIndex(static_cast<std::size_t>(p));
        hits[p] = Run(xs[p], ys[p]);
        // Run's lists are the cut tree's: exact below the cut, Trace's passes beyond it.
        if (cut_ != HUGE_VAL && !(hits[p].t < cut_))
            hits[p] = tracer_.Trace(*program_, xs[p], ys[p]);
        ++counters_.kernelScalarPixels;
    }
    counters_.kernelPixels += static_cast<std::uint64_t>(np);
}

inline void Kernel::RunLanes(const KernelSolid& s, int np, std::int64_t* over) {
    const double* xs = batches_.Xs();
    const double* ys = batches_.Ys();
    std::size_t sp = 0;
    for (std::int32_t k = s.begin; k < s.end; ++k) {
        const KernelOp& op = code_[static_cast<std::size_t>(k)];
        if (op.kind == NodeKind::kBody) {
            Lane& l = lanes_[sp++];
            if (batches_.On() && batches_.Wanted(op.node)) {
                const BodyBatch& batch = *batches_.Find(op.node);
                LanePush(np, xs, ys, op.xy, batch.state, batch.lo, batch.hi, batch.cut, batch.loId,
                         batch.hiId, l, over);
            } else {  // no batch: every pixel in its bounds goes to Run
                LanePush(np, xs, ys, op.xy, kAllScalar, kNoValues, kNoValues, kNoValues, kNoIds,
                         kNoIds, l, over);
            }
            continue;
        }
        --sp;
        if (op.kind == NodeKind::kUnion)
            LaneUnion(np, lanes_[sp - 1], lanes_[sp]);
        else if (op.kind == NodeKind::kIntersection)
            LaneIntersection(np, lanes_[sp - 1], lanes_[sp]);
        else
            LaneDifference(np, lanes_[sp - 1], lanes_[sp]);
    }
}

inline void Kernel::MergeLanes(const KernelSolid& s, int np, Hit* hits, std::int64_t* over) const {
    const double* xs = batches_.Xs();
    const double* ys = batches_.Ys();
    const Lane& l = lanes_[0];
    for (int p = 0; p < np; ++p) {
        if (over[p]) continue;
        if (xs[p] < s.xy.x0 || xs[p] > s.xy.x1 || ys[p] < s.xy.y0 || ys[p] > s.xy.y1) continue;
        double t = HUGE_VAL;
        std::int32_t tag = -1;
        if (l.n[p])  // (t stays +inf when neither end is visible)
            tables_->VisibleEnd(l.lo[p], static_cast<std::int32_t>(l.loId[p]), l.hi[p],
                                static_cast<std::int32_t>(l.hiId[p]), t, tag);
        if (!(t < l.cut[p] && t < cut_)) {
            // Nothing visible below the lane's cut: exact only without one below the kernel's
            // (a solid with nothing below the kernel's own cut adds no hit there; RunTile sends
            // the pixels left with none below it to Run and Trace).
            if (l.cut[p] < cut_) over[p] = 1;
            continue;
        }
        Hit& best = hits[p];
        if (t < best.t || (t == best.t && s.solid < best.solid)) best = {t, tag, s.solid};
    }
}

}  // namespace quadrix::raycast
