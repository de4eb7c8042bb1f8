#include "quadrix/engines/scanline/csg_spans.h"

#include <algorithm>
#include <cmath>

#include "quadrix/engines/scanline/csg_spans_inline.h"

namespace quadrix::scanline {
namespace {

constexpr double kRangeMargin = 1e-3;  // px: exact pixels take operands this near their range

}  // namespace

// Tree parents and child positions of every node, each body's leaves in the CSG units' trees,
// and interval lists for EvalPruned by depth.
CsgSpans::CsgSpans(ScanContext& ctx, const RowBodies& row) : ctx_(ctx), row_(row) {
    const FlatScene& scene = ctx.scene;
    const std::size_t nn = scene.nodes.size(), nb = scene.bodies.size();
    parent_.assign(nn, -1);
    childPos_.assign(nn, 0);
    for (std::size_t n = 0; n < nn; ++n) {
        const FlatCsgNode& node = scene.nodes[n];
        if (node.isLeaf) continue;
        for (std::size_t c = 0; c < node.children.size(); ++c) {
            const int ch = node.children[c];
            if (ch < 0 || static_cast<std::size_t>(ch) >= nn) continue;
            parent_[static_cast<std::size_t>(ch)] = static_cast<int>(n);
            childPos_[static_cast<std::size_t>(ch)] = static_cast<int>(c);
        }
    }
    touchGen_.assign(nn, 0);
    leafPNode_.assign(nn, -1);
    touchedKids_.assign(nn, {});
    bodyLeaves_.assign(nb, {});
    std::size_t depth = 1;
    for (std::size_t u = 0; u < ctx.units.size(); ++u) {
        const Unit& unit = ctx.units[u];
        if (unit.kind == Unit::Kind::kBody) continue;
        VisitTree(scene, unit.node, [&](int n, std::size_t d) {
            depth = std::max(depth, d);
            const FlatCsgNode& node = scene.nodes[static_cast<std::size_t>(n)];
            if (!node.isLeaf || node.body < 0 || static_cast<std::size_t>(node.body) >= nb) return;
            bodyLeaves_[static_cast<std::size_t>(node.body)].push_back({static_cast<int>(u), n});
        });
    }
    pool_.resize(2 * depth + 4);
    tmplCache_.assign(nb, {});
}

void CsgSpans::BeginSpan() {
    units_.clear();
    templates_.clear();
    tIntervals_.clear();
    tFaces_.clear();
    pNodes_.clear();
    pKids_.clear();
    spanLeaves_.clear();
}

void CsgSpans::PruneSpanUnits() {
    std::sort(spanLeaves_.begin(), spanLeaves_.end(),
              [](const SpanLeaf& p, const SpanLeaf& q) { return p.unit < q.unit; });
    for (std::size_t a = 0; a < spanLeaves_.size();) {
        std::size_t e = a;
        pruneLeaves_.clear();
        for (; e < spanLeaves_.size() && spanLeaves_[e].unit == spanLeaves_[a].unit; ++e)
            pruneLeaves_.push_back({spanLeaves_[e].leaf, spanLeaves_[e].tmpl});
        const int u = spanLeaves_[a].unit;
        const int root = BuildPruned(ctx_.UnitOf(u).node, pruneLeaves_);
        if (root >= 0) units_.push_back({u, root});
        a = e;
    }
}

bool CsgSpans::EvaluateExact(int u, double x, double y, eval::RayEvaluator::Hit& hit) {
    const Unit& unit = ctx_.UnitOf(u);
    pruneLeaves_.clear();
    for (int b : row_.Bodies()) {
        if (row_.Lo(b) > x + kRangeMargin) break;  // sorted on lo
        if (row_.Hi(b) < x - kRangeMargin) continue;
        for (auto [lu, leaf] : bodyLeaves_[static_cast<std::size_t>(b)])
            if (lu == u) pruneLeaves_.push_back({leaf, -1});
    }
    // Appended after the span's pruned trees (an exact pixel inside a span), then dropped.
    const std::size_t nodes = pNodes_.size(), kids = pKids_.size();
    const int root = BuildPruned(unit.node, pruneLeaves_);
    bool found = false;
    if (root >= 0) {
        IntervalList& l = Pool(0);
        bool broken = false;
        EvalPruned(root, 1, x, y, l, broken, true);
        found = ctx_.eval.First(l, hit);
    }
    pNodes_.resize(nodes);
    pKids_.resize(kids);
    return found;
}

// The template of one CSG operand body in this span (see csg_spans.h); its index. A body's
// interval structure holds from one of its own crossings to the next (every boundary of
// its faces is one of its show-edges), not only within one span: spans are also cut by the
// crossings of other bodies. So the structure read at one span's sample (which faces bound
// which intervals) is kept per body and reused, with the faces re-seeked to the span's
// first pixel, until the row passes another crossing of the body (RowBodies::OwnPassed).
int CsgSpans::BuildTemplate(int body, int i0, int sample, double y) {
    const auto k = static_cast<std::size_t>(body);
    BodyTemplate t;
    t.body = body;
    t.first = tIntervals_.size();
    if (ctx_.pixelBody[k]) {
        t.exact = true;
    } else {
        const int row = static_cast<int>(std::floor(y));
        CachedTemplate& cache = tmplCache_[k];
        if (cache.row != row || cache.passed != row_.OwnPassed(body)) {
            ReadTemplate(body, sample, y, cache);
        } else {
            ++ctx_.c.csgTemplateReuses;
        }
        for (const std::array<CachedEnd, 2>& ends : cache.ends) {
            TemplateInterval ti;
            for (int end = 0; end < 2; ++end) {
                const CachedEnd& ce = ends[static_cast<std::size_t>(end)];
                if (ce.tag < 0) continue;
                StackFace f;
                f.halfSpace = ctx_.eval.TagHalfSpace(ce.tag);
                f.ray = &ctx_.eval.Ray(f.halfSpace);
                f.sheet = ce.sheet;
                SeekFace(f, i0, y);
                (end == 0 ? ti.lo : ti.hi) = static_cast<int>(tFaces_.size());
                (end == 0 ? ti.loTag : ti.hiTag) = ce.tag;
                tFaces_.push_back(f);
            }
            tIntervals_.push_back(ti);
        }
    }
    t.count = tIntervals_.size() - t.first;
    templates_.push_back(t);
    return static_cast<int>(templates_.size()) - 1;
}

// The structure of the body's set at the sample pixel: per interval the tags and sheets of its
// ends (−1: an infinite end).
void CsgSpans::ReadTemplate(int body, int sample, double y, CachedTemplate& cache) {
    ++ctx_.c.csgTemplateBodies;
    cache.row = static_cast<int>(std::floor(y));
    cache.passed = row_.OwnPassed(body);
    cache.ends.clear();
    IntervalList l;
    ctx_.eval.BodySet(body, sample + 0.5, y, l);
    for (const Interval& v : l) {
        std::array<CachedEnd, 2> ends;
        for (int end = 0; end < 2; ++end) {
            const double tv = end == 0 ? v.lo : v.hi;
            const int id = end == 0 ? v.loId : v.hiId;
            if (id < 0 || !std::isfinite(tv)) continue;  // an infinite end
            const int hs = ctx_.eval.TagHalfSpace(id);
            ends[static_cast<std::size_t>(end)] = {id, ctx_.eval.SheetOf(hs, tv, sample + 0.5, y)};
        }
        cache.ends.push_back(ends);
    }
}

// ---- CSG trees pruned to the operands present (per span, or per exact pixel) ----
//
// A leaf whose body's x range on the row misses the span (or the pixel) has an empty set
// there, and ∅ is the identity of union and of the subtrahends of a difference and absorbs
// intersections and minuends. So the tree is rebuilt over the leaves present only: each
// present leaf marks its ancestors (stopping at one already marked), and the marked nodes
// are assembled bottom-up with their present children in the original order (the interval
// operations then run on the same operands in the same order as the full tree's: the same
// result, bit for bit). The cost is the present leaves × the tree depth, not the tree size:
// a union of 10,000 spheres costs per span the few spheres the span meets.
// ---- CSG trees pruned to the operands present (per span, or per exact pixel) ----
//
// A leaf whose body's x range on the row misses the span (or the pixel) has an empty set
// there, and ∅ is the identity of union and of the subtrahends of a difference and absorbs
// intersections and minuends. So the tree is rebuilt over the leaves present only: each
// present leaf marks its ancestors (stopping at one already marked), and the marked nodes
// are assembled bottom-up with their present children in the original order (the interval
// operations then run on the same operands in the same order as the full tree's: the same
// result, bit for bit). The cost is the present leaves × the tree depth, not the tree size:
// a union of 10,000 spheres costs per span the few spheres the span meets.
int CsgSpans::BuildPruned(int root, const std::vector<std::pair<int, int>>& leaves) {
    if (++pruneGen_ == 0) {
        std::fill(touchGen_.begin(), touchGen_.end(), 0);
        pruneGen_ = 1;
    }
    for (auto [leaf, tmpl] : leaves) {
        const auto l = static_cast<std::size_t>(leaf);
        if (touchGen_[l] == pruneGen_) continue;  // a leaf listed twice
        touchGen_[l] = pruneGen_;
        leafPNode_[l] = static_cast<int>(pNodes_.size());
        PNode pn;
        pn.leaf = true;
        pn.body = ctx_.scene.nodes[l].body;
        pn.tmpl = tmpl;
        pNodes_.push_back(pn);
        int c = leaf;
        for (int p = parent_[l]; p >= 0; c = p, p = parent_[static_cast<std::size_t>(p)]) {
            const auto pk = static_cast<std::size_t>(p);
            if (touchGen_[pk] == pruneGen_) {
                touchedKids_[pk].push_back(c);
                break;
            }
            touchGen_[pk] = pruneGen_;
            touchedKids_[pk].assign(1, c);
        }
    }
    if (touchGen_[static_cast<std::size_t>(root)] != pruneGen_) return -1;
    return Assemble(root);
}

int CsgSpans::Assemble(int node) {
    const auto nk = static_cast<std::size_t>(node);
    const FlatCsgNode& n = ctx_.scene.nodes[nk];
    if (n.isLeaf) return leafPNode_[nk];
    std::vector<int>& kids = touchedKids_[nk];
    std::sort(kids.begin(), kids.end(), [&](int p, int q) {
        return childPos_[static_cast<std::size_t>(p)] < childPos_[static_cast<std::size_t>(q)];
    });
    std::vector<int> built;
    built.reserve(kids.size());
    if (n.op == scene::CsgOp::kIntersection) {
        if (kids.size() != n.children.size()) return -1;  // an operand is empty: ∅
        for (int k : kids) {
            const int r = Assemble(k);
            if (r < 0) return -1;
            built.push_back(r);
        }
    } else if (n.op == scene::CsgOp::kUnion) {
        for (int k : kids)
            if (const int r = Assemble(k); r >= 0) built.push_back(r);
        if (built.empty()) return -1;
    } else {  // difference: the minuend must be present; absent subtrahends drop out
        if (kids.empty() || kids.front() != n.children.front()) return -1;
        for (std::size_t i = 0; i < kids.size(); ++i) {
            const int r = Assemble(kids[i]);
            if (i == 0 && r < 0) return -1;
            if (r >= 0) built.push_back(r);
        }
    }
    if (built.size() == 1) return built.front();
    PNode pn;
    pn.op = n.op;
    pn.first = pKids_.size();
    pn.count = built.size();
    pKids_.insert(pKids_.end(), built.begin(), built.end());
    pNodes_.push_back(pn);
    return static_cast<int>(pNodes_.size()) - 1;
}

}  // namespace quadrix::scanline
