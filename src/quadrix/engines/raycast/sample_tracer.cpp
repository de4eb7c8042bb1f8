#include "quadrix/engines/raycast/sample_tracer.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/flatten/wide_node_trees.h"
#include "quadrix/util/ray_work.h"

namespace quadrix::raycast {

SampleTracer::SampleTracer(const FlatScene& scene, bool spatialIndex,
                           std::shared_ptr<const WideNodeTrees> wide)
    : scene_(scene), tables_(scene), wideTrees_(std::move(wide)) {
    byDepth_.resize(scene.solids.size());
    for (std::size_t s = 0; s < byDepth_.size(); ++s) byDepth_[s] = static_cast<std::int32_t>(s);
    std::stable_sort(byDepth_.begin(), byDepth_.end(), [&](std::int32_t a, std::int32_t b) {
        return scene.solids[static_cast<std::size_t>(a)].bounds.lo.z <
               scene.solids[static_cast<std::size_t>(b)].bounds.lo.z;
    });
    for (const FlatSolid& solid : scene.solids) maxDepth_ = std::max(maxDepth_, Depth(solid.root));
    rank_.resize(byDepth_.size());
    for (std::size_t r = 0; r < byDepth_.size(); ++r)
        rank_[static_cast<std::size_t>(byDepth_[r])] = static_cast<std::int32_t>(r);
    std::vector<Box3> boxes;
    for (const FlatSolid& solid : scene.solids) boxes.push_back(solid.bounds);
    solidTree_ = BoxTree(boxes, spatialIndex);
    if (!wideTrees_) wideTrees_ = WideNodeTrees::Shared(scene, spatialIndex);
    wide_ = wideTrees_->trees.data();
    wideOf_ = wideTrees_->of.data();
    // Depth windows for the solids with a wide node and finite depth bounds (see Trace).
    windowed_.assign(scene.solids.size(), 0);
    if (spatialIndex)
        for (std::size_t s = 0; s < scene.solids.size(); ++s) {
            const Box3& b = scene.solids[s].bounds;
            windowed_[s] = std::isfinite(b.lo.z) && std::isfinite(b.hi.z) && b.lo.z < b.hi.z &&
                           HasWideNode(scene.solids[s].root);
        }
}

bool SampleTracer::HasWideNode(std::int32_t n) const {
    if (wideOf_[static_cast<std::size_t>(n)] >= 0) return true;
    const FlatCsgNode& node = scene_.nodes[static_cast<std::size_t>(n)];
    if (!node.isLeaf)
        for (int c : node.children)
            if (HasWideNode(c)) return true;
    return false;
}

int SampleTracer::Depth(std::int32_t n) const {
    const FlatCsgNode& node = scene_.nodes[static_cast<std::size_t>(n)];
    int d = 0;
    if (!node.isLeaf)
        for (int c : node.children) d = std::max(d, 1 + Depth(c));
    return d;
}

void SampleTracer::SetRegion(const Rect& r, SampleScratch& scratch) const {
    if (!scratch.region) {
        scratch.region = std::make_unique<SampleRegion>(tables_);
        scratch.region->bodies.resize(tables_.bodyValid.size());
    }
    SampleRegion& g = *scratch.region;
    g.rect = r;
    g.active = true;
    g.tags.clear();
    if (++g.stamp == 0) {  // wrapped: forget every body's stamp
        for (SampleRegion::Body& b : g.bodies) b.stamp = 0;
        g.stamp = 1;
    }
}

void SampleTracer::ClearRegion(SampleScratch& scratch) const {
    if (scratch.region) scratch.region->active = false;
}

SampleScratch::SampleScratch(const SampleTracer& tracer) {
    lists.resize(static_cast<std::size_t>(tracer.MaxDepth()) + 3);
    for (IntervalList& l : lists) slots.push_back(&l);
}

void SampleTracer::Node(std::int32_t n, double x, double y, double zMax, SampleScratch& s,
                        std::size_t slot) const {
    const FlatCsgNode& node = scene_.nodes[static_cast<std::size_t>(n)];
    IntervalList& out = *s.slots[slot];
    out.clear();
    if (node.isLeaf) {
        const auto b = static_cast<std::size_t>(node.body);
        if (tables_.BodyVoid(b)) return;
        const std::int32_t* tag = tables_.BodyTags(b);
        std::size_t count = tables_.BodyTagCount(b);
        if (s.region && s.region->active) {  // the body's literals reduced on the region
            SampleRegion& g = *s.region;
            SampleRegion::Body& rb = g.bodies[b];
            if (rb.stamp != g.stamp) {
                rb.stamp = g.stamp;
                rb.begin = static_cast<std::int32_t>(g.tags.size());
                rb.empty = g.reduction.ReduceLiterals(tag, count, g.rect, g.tags);
                rb.end = static_cast<std::int32_t>(g.tags.size());
            }
            if (rb.empty) return;  // ∅ on every ray of the region
            tag = g.tags.data() + rb.begin;
            count = static_cast<std::size_t>(rb.end - rb.begin);
        }
        // The body's set as one interval while every literal gives one piece (ClipOne: ClipTo's
        // rules, interval_list.h), as a list from the first that gives two.
        Interval run{-HUGE_VAL, HUGE_VAL, Interval::kNoId, Interval::kNoId};
        bool one = true;
        LiteralCounters unused;
        for (std::size_t k = 0; k < count; ++k) {
            ++tRayLiterals;  // the shading budget's count (shade/shade_budget.h)
            const Tag& t = tables_.TagOf(tag[k]);
            const RaySet set =
                LiteralOnRay(tables_.halfSpaces[static_cast<std::size_t>(t.halfSpace)],
                             t.complemented, x, y, tag[k], unused);
            if (set.count == 0) {
                s.slots[slot]->clear();
                return;
            }
            if (one && set.count == 1) {
                if (!ClipOne(run, set.piece[0])) return;  // out is empty
                continue;
            }
            if (one) {
                one = false;
                out.Append(run.lo, run.loId, run.hi, run.hiId);
            }
            IntervalList& acc = *s.slots[slot];
            if (set.count == 1) {  // in place, the same result as Intersection (interval_list.h)
                ClipTo(acc, set.piece[0]);
            } else {
                IntervalList& lit = *s.slots[slot + 1];
                lit.clear();
                for (int p = 0; p < set.count; ++p)
                    lit.Append(set.piece[p].lo, set.piece[p].loId, set.piece[p].hi,
                               set.piece[p].hiId);
                Intersection(acc, lit, *s.slots[slot + 2]);
                std::swap(s.slots[slot], s.slots[slot + 2]);
            }
            if (s.slots[slot]->empty()) return;
        }
        if (one) out.Append(run.lo, run.loId, run.hi, run.hiId);
        return;
    }
    // The children to fold: all of them, or for a wide node the first of a difference and those
    // its tree finds, in their order in the node. The wide node's list is a range [base, end) of
    // s.hits, a stack: the children's own lists go above it and are popped when they return; read
    // by index (pushes may reallocate).
    const std::int32_t wide = wideOf_[static_cast<std::size_t>(n)];
    std::vector<std::int32_t>& hits = s.hits;
    const std::size_t base = hits.size();
    struct Pop {
        std::vector<std::int32_t>& v;
        std::size_t size;
        ~Pop() {
            if (v.size() != size) v.resize(size);  // (a node that is not wide pushed nothing)
        }
    } pop{hits, base};
    std::size_t count = node.children.size();
    if (wide >= 0) {
        const std::int32_t from = node.op == scene::CsgOp::kDifference ? 1 : 0;
        if (from) hits.push_back(0);
        wide_[static_cast<std::size_t>(wide)].ColumnBefore(
            x, y, zMax, [&](std::int32_t k) { hits.push_back(k + from); });
        std::sort(hits.begin() + static_cast<std::ptrdiff_t>(base) + from, hits.end());
        count = hits.size() - base;
        if (count == 0) return;  // a union met by no child: ∅
    }
    auto child = [&](std::size_t i) {
        return wide >= 0 ? node.children[static_cast<std::size_t>(hits[base + i])]
                         : node.children[i];
    };
    bool first = true;
    for (std::size_t i = 0; i < count; ++i) {
        const int c = child(i);
        const Box3& cb = scene_.nodes[static_cast<std::size_t>(c)].bounds;
        // A child whose bounds miss the ray is ∅ there (bounds are conservative), and one that
        // starts at or beyond zMax is ∅ before it.
        const bool misses = x < cb.lo.x || x > cb.hi.x || y < cb.lo.y || y > cb.hi.y ||
                            (zMax < HUGE_VAL && cb.lo.z >= zMax);
        if (first) {
            first = false;
            if (!misses) Node(c, x, y, zMax, s, slot);
            if (s.slots[slot]->empty() && node.op != scene::CsgOp::kUnion) return;
            continue;
        }
        if (misses) {
            if (node.op == scene::CsgOp::kIntersection) {
                s.slots[slot]->clear();
                return;
            }
            continue;  // A ∪ ∅ = A − ∅ = A
        }
        Node(c, x, y, zMax, s, slot + 1);
        IntervalList& acc = *s.slots[slot];
        const IntervalList& operand = *s.slots[slot + 1];
        IntervalList& result = *s.slots[slot + 2];
        switch (node.op) {
            case scene::CsgOp::kUnion:
                Union(acc, operand, result);
                break;
            case scene::CsgOp::kIntersection:
                Intersection(acc, operand, result);
                break;
            case scene::CsgOp::kDifference:
                Difference(acc, operand, result);
                break;
        }
        std::swap(s.slots[slot], s.slots[slot + 2]);
        if (s.slots[slot]->empty() && node.op != scene::CsgOp::kUnion) return;
    }
}

SampleTracer::Window SampleTracer::FirstVisible(const IntervalList& set, double zMax, double& t,
                                                std::int32_t& tag) const {
    for (const Interval& v : set) {
        if (!(v.lo < zMax)) return Window::kUndecided;
        if (tables_.VisibleEnd(v.lo, v.loId, v.hi, v.hiId, t, tag))
            return t < zMax ? Window::kFound : Window::kUndecided;
        // No visible end: known only when the whole interval lies before zMax.
        if (!(v.hi < zMax)) return Window::kUndecided;
    }
    return zMax == HUGE_VAL ? Window::kNone : Window::kUndecided;
}

Sample SampleTracer::Trace(double x, double y, SampleScratch& scratch, double depthHint) const {
    double bestT = HUGE_VAL;
    std::int32_t bestTag = -1, bestSolid = -1;
    // The solids whose bounds may contain (x, y), in byDepth_ order.
    std::vector<std::int32_t>& met = scratch.solids;
    met.clear();
    if (byDepth_.size() == 1) {  // one solid (one part): the loop below tests its bounds
        met.push_back(0);
    } else {
        solidTree_.Column(
            x, y, [&](std::int32_t k) { met.push_back(rank_[static_cast<std::size_t>(k)]); });
        std::sort(met.begin(), met.end());
    }
    for (std::int32_t r : met) {
        const std::int32_t s = byDepth_[static_cast<std::size_t>(r)];
        const FlatSolid& solid = scene_.solids[static_cast<std::size_t>(s)];
        if (bestT < solid.bounds.lo.z) break;  // strictly: a tie may go to a lower index
        if (x < solid.bounds.lo.x || x > solid.bounds.hi.x || y < solid.bounds.lo.y ||
            y > solid.bounds.hi.y)
            continue;
        // Windows: the solid's set is made before zMax = the hint, then lo + (hi − lo)/64, /32,
        // … /2 of its depth bounds beyond it, then whole, until its visible point lies before zMax
        // (windowed_ solids; others whole at once). Each window's set equals the solid's before
        // zMax, ids included. A window that decides nothing, beyond which the best point so far
        // already lies, leaves the solid losing.
        const Box3& b = solid.bounds;
        const bool windowed = windowed_[static_cast<std::size_t>(s)];
        double zMax = windowed && depthHint > b.lo.z && depthHint < b.hi.z ? depthHint : -HUGE_VAL;
        for (int w = windowed ? -1 : kWindows; w <= kWindows; ++w) {
            if (w >= 0) {
                const double next =
                    w == kWindows ? HUGE_VAL : b.lo.z + (b.hi.z - b.lo.z) * kWindowFraction[w];
                if (!(next > zMax)) continue;  // within the window already tried
                zMax = next;
            } else if (zMax == -HUGE_VAL) {
                continue;  // no hint inside the bounds
            }
            Node(solid.root, x, y, zMax, scratch, 0);
            double t;
            std::int32_t tag;
            const Window found = FirstVisible(*scratch.slots[0], zMax, t, tag);
            if (found == Window::kFound) {
                if (t < bestT || (t == bestT && s < bestSolid)) {
                    bestT = t;
                    bestTag = tag;
                    bestSolid = s;
                }
                break;
            }
            if (found == Window::kNone || bestT < zMax) break;
        }
    }
    Sample out;
    if (bestTag < 0) return out;
    const Tag& tag = tables_.TagOf(bestTag);
    const auto h = static_cast<std::size_t>(tag.halfSpace);
    out.depth = bestT;
    out.normal = tables_.constantNormal[h] ? tables_.planeNormal[h]
                                           : scene_.WorldNormal(tag.halfSpace, {x, y, bestT});
    out.surface = tag.halfSpace;
    out.body = tag.body;
    out.solid = bestSolid;
    return out;
}

}  // namespace quadrix::raycast
