#include "quadrix/engines/raycast/trace.h"

#include <algorithm>
#include <utility>

namespace quadrix::raycast {

Tracer::Tracer(const SceneTables& tables, int maxDepth, const TileReduction& reduction,
               BodyBatches& batches, Counters& counters)
    : tables_(&tables), reduction_(reduction), batches_(batches), counters_(counters) {
    Bind(tables, maxDepth);
}

void Tracer::Bind(const SceneTables& tables, int maxDepth) {
    tables_ = &tables;
    // The slots are some order of the lists (a pixel's evaluation swaps them); more lists move
    // them all, so the slots are made again.
    const auto needed = static_cast<std::size_t>(maxDepth) + 3;
    if (lists_.size() >= needed) return;
    lists_.resize(needed);
    slots_.clear();
    for (IntervalList& l : lists_) slots_.push_back(&l);
}

Hit Tracer::Trace(const CsgProgram& program, double x, double y) {
    Hit best;
    for (const ProgSolid& s : program.solids) {
        if (best.t < s.zlo) {  // strictly: a tie at s.zlo may still go to a lower index
            ++counters_.zStops;
            break;
        }
        if (x < s.xy.x0 || x > s.xy.x1 || y < s.xy.y0 || y > s.xy.y1) continue;
        ++counters_.pixelSolids;
        for (level_ = 0; level_ < cuts_.size(); ++level_) {
            const double cut = cuts_[level_];
            if (cut <= s.zlo) continue;  // the whole solid is cut away
            Evaluate(program, s.root, x, y, 0, cut);
            double t;
            std::int32_t tag;
            if (FirstVisible(*slots_[0], t, tag) && t < cut) {
                if (t < best.t || (t == best.t && s.solid < best.solid)) best = {t, tag, s.solid};
                break;
            }
            // Nothing visible before the cut: this solid cannot beat a best nearer than it.
            if (best.t < cut) break;
            if (cut != HUGE_VAL) ++counters_.cutRetries;
        }
    }
    return best;
}

inline void Tracer::Evaluate(const CsgProgram& p, std::int32_t n, double x, double y,
                             std::size_t slot, double cut) {
    const ProgNode& node = p.nodes[static_cast<std::size_t>(n)];
    if (node.MissesPoint(x, y) || node.zlo >= cut ||
        reduction_.NodeEmpty(static_cast<std::size_t>(n))) {
        slots_[slot]->clear();
        return;
    }
    if (node.kind == NodeKind::kBody) {
        EvaluateBody(node.first, n, x, y, slot);
        return;
    }
    const std::int32_t* child = p.children.data() + node.first;
    Evaluate(p, child[0], x, y, slot, cut);
    if (node.count > kFilteredOperands && node.kind != NodeKind::kIntersection) {
        EvaluateWide(p, node, n, x, y, slot, cut);
        return;
    }
    for (std::int32_t i = 1; i < node.count; ++i) {
        IntervalList& out = *slots_[slot];
        if (out.empty() && node.kind != NodeKind::kUnion) return;  // ∅ ∩ B = ∅ − B = ∅
        // The operand's bounds are tested here as well as in the call, to skip the call for the
        // many operands of a big union that miss this pixel.
        const ProgNode& c = p.nodes[static_cast<std::size_t>(child[i])];
        if (c.MissesPoint(x, y) || c.zlo >= cut ||
            reduction_.NodeEmpty(static_cast<std::size_t>(child[i]))) {
            slots_[slot + 1]->clear();
        } else {
            Evaluate(p, child[i], x, y, slot + 1, cut);
        }
        IntervalList& operand = *slots_[slot + 1];
        if (operand.empty()) {
            if (node.kind == NodeKind::kIntersection) {
                out.clear();
                return;
            }
            continue;  // A ∪ ∅ = A − ∅ = A
        }
        Fold(node.kind, slot);
    }
}

inline void Tracer::Fold(NodeKind kind, std::size_t slot) {
    IntervalList& out = *slots_[slot];
    if (out.empty()) {  // union: ∅ ∪ B = B
        std::swap(slots_[slot], slots_[slot + 1]);
        return;
    }
    ++counters_.csgOps;
    IntervalList& operand = *slots_[slot + 1];
    IntervalList& scratch = *slots_[slot + 2];
    switch (kind) {
        case NodeKind::kUnion:
            Union(out, operand, scratch);
            break;
        case NodeKind::kIntersection:
            Intersection(out, operand, scratch);
            break;
        default:
            Difference(out, operand, scratch);
            break;
    }
    std::swap(slots_[slot], slots_[slot + 2]);
}

// The operands after the first of a wide union or difference: those whose bounds hold the pixel
// found first, without a branch per operand (their bounds are met in no order a predictor could
// learn: about half of a sub-tile's spheres cover any one of its pixels), then folded in their
// order exactly as Evaluate folds them (an operand that misses is ∅, which leaves a union and a
// difference as they are), so the result is the same bits.
//
// Only the operands the cut leaves are visited (levels 0..level_ of GroupWideOperands: zlo below
// the cut, or NaN, exactly those that Evaluate's test `zlo >= cut` keeps); the positions found
// are put back in operand order when they come from more than one level.
inline void Tracer::EvaluateWide(const CsgProgram& p, const ProgNode& node, std::int32_t n0,
                                 double x, double y, std::size_t slot, double cut) {
    const std::int32_t* child = p.children.data() + node.first;
    const std::int32_t* const order = byLevel_.data() + node.first + 1;
    const std::int32_t* const ends = levelEnd_.data() + static_cast<std::size_t>(n0) * kLevels;
    const std::int32_t end = ends[level_];
    std::int32_t* const hits = hits_.data() + hitTop_;
    std::int32_t n = 0;
    for (std::int32_t k = 0; k < end; ++k) {
        const std::int32_t i = order[k];
        const ProgNode& c = p.nodes[static_cast<std::size_t>(child[i])];
        const bool miss = (x < c.xy.x0) | (x > c.xy.x1) | (y < c.xy.y0) | (y > c.xy.y1);
        hits[n] = i;
        n += !miss;
    }
    if (ends[0] < end) std::sort(hits, hits + n);  // from several levels: back in operand order
    for (std::int32_t k = 0; k < n; ++k) hits[k] = child[hits[k]];
    hitTop_ += static_cast<std::size_t>(n);
    for (std::int32_t k = 0; k < n; ++k) {
        IntervalList& out = *slots_[slot];
        if (out.empty() && node.kind != NodeKind::kUnion) break;  // ∅ − B = ∅
        if (reduction_.NodeEmpty(static_cast<std::size_t>(hits[k]))) continue;
        Evaluate(p, hits[k], x, y, slot + 1, cut);
        if (slots_[slot + 1]->empty()) continue;  // A ∪ ∅ = A − ∅ = A
        Fold(node.kind, slot);
    }
    hitTop_ -= static_cast<std::size_t>(n);
}

void Tracer::GroupWideOperands(const CsgProgram& program) {
    if (byLevel_.size() < program.children.size()) {
        byLevel_.resize(program.children.size());
        levelOf_.resize(program.children.size());
    }
    if (levelEnd_.size() < program.nodes.size() * kLevels)
        levelEnd_.resize(program.nodes.size() * kLevels);
    const std::size_t levels = cuts_.size();
    for (std::size_t n = 0; n < program.nodes.size(); ++n) {
        const ProgNode& node = program.nodes[n];
        if (node.kind == NodeKind::kBody || node.kind == NodeKind::kIntersection ||
            node.count <= kFilteredOperands)
            continue;
        const std::int32_t* child = program.children.data() + node.first;
        std::int32_t* const order = byLevel_.data() + node.first + 1;
        std::int32_t* const ends = levelEnd_.data() + n * kLevels;
        // Each operand's level: the first level whose cut is above its zlo (a NaN zlo is never
        // cut: level 0); the last cut is +inf, so every operand has one.
        std::uint8_t* const level = levelOf_.data() + node.first;
        std::int32_t count[kLevels] = {0, 0, 0, 0, 0};
        for (std::int32_t i = 1; i < node.count; ++i) {
            const double z = program.nodes[static_cast<std::size_t>(child[i])].zlo;
            std::size_t l = 0;
            while (l + 1 < levels && !(z < cuts_[l]) && !std::isnan(z)) ++l;
            level[i] = static_cast<std::uint8_t>(l);
            ++count[l];
        }
        // Counting sort by level, stable: each level keeps operand order.
        std::int32_t start[kLevels], sum = 0;
        for (std::size_t l = 0; l < kLevels; ++l) {
            start[l] = sum;
            sum += count[l];
            ends[l] = sum;
        }
        for (std::int32_t i = 1; i < node.count; ++i) order[start[level[i]]++] = i;
    }
}

// A body is the intersection of its literals, taken in the body's order: each literal's set clips
// the running set. While that set is one interval (always, for bodies of planes and of quadrics
// cut by planes, the common case) it is kept in registers and planes are evaluated inline; the
// first literal whose set has two pieces switches to interval lists. The tie rules are ClipTo's
// in both paths (a later literal wins a tie at the near end, an earlier one at the far end), so
// the result does not depend on the path taken.
//
// `node` is the body's node in the sub-tile program: its literals are the ones TileReduction
// kept (planes that cannot bound the body anywhere in the sub-tile are dropped).
void Tracer::EvaluateBody(std::int32_t body, std::int32_t node, double x, double y,
                          std::size_t slot) {
    ++counters_.bodies;
    IntervalList& result = *slots_[slot];
    result.clear();  // a body without literals is empty
    if (!tables_->bodyValid[static_cast<std::size_t>(body)]) return;
    if (tables_->bodyFirstTag[static_cast<std::size_t>(body)] ==
        tables_->bodyFirstTag[static_cast<std::size_t>(body) + 1])
        return;
    if (batches_.On()) {
        if (const BodyBatch* batch = batches_.Find(node)) {
            const std::size_t p = batches_.Pixel();
            if (batch->state[p] == BodyBatch::kEmpty) return;
            if (batch->state[p] == BodyBatch::kOne) {
                result.Append(batch->lo[p], static_cast<std::int32_t>(batch->loId[p]), batch->hi[p],
                              static_cast<std::int32_t>(batch->hiId[p]));
                return;
            }
            // kScalar, kCut: evaluated below, literal by literal, exactly as without batches.
        }
    }
    const auto [begin, end] = reduction_.NodeTags(static_cast<std::size_t>(node));
    const std::int32_t* const tileTags = reduction_.TileTags();
    const std::int32_t* const tagsEnd = tileTags + end;
    Interval run{-HUGE_VAL, HUGE_VAL, Interval::kNoId, Interval::kNoId};
    for (const std::int32_t* it = tileTags + begin; it != tagsEnd; ++it) {
        const std::int32_t tag = *it;
        const Tag& t = tables_->TagOf(tag);
        const RayHalfSpace& hs = tables_->halfSpaces[static_cast<std::size_t>(t.halfSpace)];
        Interval w;
        if (hs.isPlane) {
            // LiteralOnRay's plane case, inline: c t + e <= 0 (or its closed complement).
            ++counters_.literals.planes;
            const double e = hs.px * x + hs.py * y + hs.pd;
            if (!std::isfinite(e) || !std::isfinite(hs.c)) return;  // empty both ways
            if (hs.c == 0) {
                if ((e <= 0) == t.complemented) return;  // holds nowhere on this ray
                continue;                                // holds everywhere
            }
            const double r = -e / hs.c;
            const bool below = (hs.c > 0) != t.complemented;  // the set is t <= r
            w = below ? Interval{-HUGE_VAL, r, Interval::kNoId, tag}
                      : Interval{r, HUGE_VAL, tag, Interval::kNoId};
            if (std::isinf(r)) {
                if (!(w.lo < w.hi)) return;  // r overflowed to the empty side
                continue;                    // r overflowed to the full side
            }
        } else {
            RaySet set = LiteralOnRay(hs, t.complemented, x, y, tag, counters_.literals);
            if (set.count == 0) return;
            if (set.count >= 2) {  // two pieces (three for a complemented quartic)
                EvaluateBodyLists(run, set, it + 1, tagsEnd, x, y, slot);
                return;
            }
            w = set.piece[0];
        }
        if (!ClipOne(run, w)) return;  // ClipTo's rules for one piece
    }
    AppendPiece(result, run);
}

inline void Tracer::EvaluateBodyLists(const Interval& run, const RaySet& set,
                                      const std::int32_t* next, const std::int32_t* last, double x,
                                      double y, std::size_t slot) {
    {
        IntervalList& out = *slots_[slot];
        out.clear();
        for (int i = 0; i < set.count; ++i) AppendPiece(out, set.piece[i]);
        // run ∩ set, the running set first (the earlier operand), as in the loop below.
        IntervalList& runList = *slots_[slot + 1];
        runList.clear();
        AppendPiece(runList, run);
        Intersection(runList, out, *slots_[slot + 2]);
        std::swap(slots_[slot], slots_[slot + 2]);
        if (slots_[slot]->empty()) return;
    }
    for (const std::int32_t* it = next; it != last; ++it) {
        const std::int32_t tag = *it;
        const Tag& t = tables_->TagOf(tag);
        const RayHalfSpace& hs = tables_->halfSpaces[static_cast<std::size_t>(t.halfSpace)];
        RaySet s = LiteralOnRay(hs, t.complemented, x, y, tag, counters_.literals);
        IntervalList& out = *slots_[slot];
        if (s.count == 0) {
            out.clear();
            return;
        }
        if (s.count == 1) {
            ClipTo(out, s.piece[0]);
        } else {
            IntervalList& literal = *slots_[slot + 1];
            literal.clear();
            for (int i = 0; i < s.count; ++i) AppendPiece(literal, s.piece[i]);
            Intersection(out, literal, *slots_[slot + 2]);
            std::swap(slots_[slot], slots_[slot + 2]);
        }
        if (slots_[slot]->empty()) return;
    }
}

}  // namespace quadrix::raycast
