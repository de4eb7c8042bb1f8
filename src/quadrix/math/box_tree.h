// A bounding-volume hierarchy over a list of boxes: which items' boxes may a segment or a column
// meet? Used by the rays that walk the CSG trees outside the engines' tiles — shadow rays
// (shade/shadows.h, segments in any direction) and anti-aliasing samples (engines/raycast/
// sample_tracer.h, columns along z) — over the solids of a scene and over the children of wide
// CSG nodes (a union of 10,000 spheres is one node with 10,000 children).
//
// Structure: a binary tree in one array, built top-down by splitting the items at the median of
// their box centres along the axis where the centres spread most, down to leaves of at most
// kLeafSize items; each node's box is the union of its items' boxes. Items are referred to by
// their index in the list given to the constructor; a leaf's items are a range of `order_`.
//
// The queries are conservative pre-filters: they visit (at least) every item whose own box
// passes the test, and the caller applies its own test to each visited item. Boxes with a
// coordinate that is NaN or lo > hi (empty, or unknown) are never culled: such items are visited
// by every query. Infinite coordinates are fine (an unbounded solid's box). The node tests are
// monotone in the box (a box containing another passes whenever the smaller one passes, with the
// same floating-point operations), so nothing an item's own test would accept is skipped.
//
// Grids: a tree of at least kGridItems items also keeps a uniform grid over its items' (x, y)
// extents for the column queries, and a view along a direction one over its leaves' extents
// across that direction for the half-lines (ColumnGrid, HalfLineView::Grid): in a dense scene a
// query then reads one cell's short list instead of walking the tree from its root. They visit
// what the tree would (every item whose own box passes), in their own order.
//
// Order: items are visited in tree order, not index order (a segment visits the nearer of two
// subtrees first), or in a grid cell's order (by depth); a caller whose result depends on the
// order (the sample tracer folds children left to right) sorts what it collects.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "quadrix/math/vec.h"

namespace quadrix {

class BoxTree {
  public:
    static constexpr int kLeafSize = 4;

    BoxTree() = default;
    // index = false builds no tree: every query visits every item (the benchmark's "before").
    explicit BoxTree(const std::vector<Box3>& boxes, bool index = true);

    std::size_t size() const { return count_; }

    // Calls visit(k) (k: item index) for the items whose box the segment p + s·d, s in [s0, s1],
    // may meet; visit returns true to stop the query. Returns true when a visit stopped it.
    template <class Visit>
    bool Segment(const Vec3& p, const Vec3& d, double s0, double s1, Visit&& visit) const;

    // Calls visit(k) for the items whose box's (x, y) projection may contain (x, y) (closed).
    template <class Visit>
    void Column(double x, double y, Visit&& visit) const {
        ColumnBefore(x, y, HUGE_VAL, visit);
    }
    // The same, skipping the items whose box starts at or beyond depth zMax (box.lo.z >= zMax;
    // with zMax = +inf, Column): the part of the column before zMax. A tree of at least
    // kGridItems items answers it from its column grid (below) instead of its nodes.
    template <class Visit>
    void ColumnBefore(double x, double y, double zMax, Visit&& visit) const;

    // The column grid: a uniform grid over the (x, y) extents of the items, each cell listing
    // the items whose extent meets it by the depth where they start. A column at (x, y) looks at
    // one cell's list, in depth order, up to zMax, instead of walking the tree from its root:
    // the anti-aliasing samples of a union of 10,000 spheres tested about 55 tree nodes each.
    // Cell sides about the items' median extent, so that an item lies in a few cells.
    static constexpr std::size_t kGridItems = 256;

    // The slab test of one box against a segment (used by the tree and by its callers).
    static bool SegmentHitsBox(const Box3& b, const Vec3& p, const Vec3& d, double s0, double s1);
    // The slab test of a box against every segment p + s·d, s in [s0', s1], of one direction
    // whose start p lies in the box [pLo, pHi] and s0' >= s0: false only when SegmentHitsBox
    // gives false for each of them. Each slab's bounds are those SegmentHitsBox computes at the
    // extreme starts (a rounded difference and a rounded quotient are monotone), so the latest
    // entry is bounded below and the earliest exit above for every start at once.
    static bool SegmentsMayHitBox(const Box3& b, const Vec3& pLo, const Vec3& pHi, const Vec3& d,
                                  double s0, double s1);

    // The cells of a uniform grid over the plane of two axes (a column grid's x and y, a view
    // grid's u and v): cell i along the first axis covers [x0 + i / invX, x0 + (i + 1) / invX),
    // the first and last cells reaching to ∓∞. CellX is floor((x − x0) · invX) clamped to
    // [0, nx), monotone in x (a rounded subtraction and a product by a positive number are), so
    // an item listed in the cells from CellX(lo) to CellX(hi) is in the cell of every x it holds;
    // likewise along the second axis.
    struct GridCells {
        double x0 = 0, y0 = 0, invX = 0, invY = 0;
        int nx = 1, ny = 1;
        std::vector<std::int32_t> start;  // cell j·nx + i: entries [start[c], start[c + 1])
        static int Cell(double t, int n) {
            if (!(t >= 0)) return 0;
            return t < n ? static_cast<int>(t) : n - 1;
        }
        int CellX(double x) const { return Cell((x - x0) * invX, nx); }
        int CellY(double y) const { return Cell((y - y0) * invY, ny); }
        std::size_t Index(int i, int j) const {
            return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) +
                   static_cast<std::size_t>(i);
        }
        // Lays the cells over rectangles {xLo, xHi, yLo, yHi} (finite): their bounding rectangle
        // in cells about the median rectangle's size, at most twice as many as the rectangles.
        // False when there is none or the spans exceed doubles.
        bool Frame(const std::vector<std::array<double, 4>>& rects);
    };

    // The tree seen along one direction d, for the half-lines p + s·d, s >= 0, that all share it
    // (the shadow rays of a parallel light under a parallel view: one per covered pixel). Per
    // node: its box's extent on two unit axes u, v across d and on w = d/|d|, padded outward.
    // A half-line that meets a box at x has x·u = p·u, x·v = p·v and x·w >= p·w, so a node is
    // tested with five comparisons instead of three slab divisions. The test is looser than the
    // slab test (the rectangle around the box's projection), never tighter: every item whose box
    // the half-line meets is visited, as by Segment with s1 = +inf.
    struct HalfLineView {
        struct Extent {
            double uLo, uHi, vLo, vHi, wHi, wMid;
        };
        Vec3 u, v, w;
        std::vector<Extent> nodes;  // per node of the tree
        // Any box's extent on the view's axes, as the nodes' (padded outward).
        Extent Project(const Box3& b) const;
        // A half-line's start p on the view's axes, widened as HalfLine widens it; Meets is
        // HalfLine's node test: false only when the half-line from p misses a box of extent e.
        struct Probe {
            double uLo, uHi, vLo, vHi, wLo;
        };
        Probe At(const Vec3& p) const;
        static bool Meets(const Extent& e, const Probe& q) {
            // Written so that a NaN extent culls nothing.
            return !(q.uHi < e.uLo || q.uLo > e.uHi || q.vHi < e.vLo || q.vLo > e.vHi ||
                     q.wLo > e.wHi);
        }
        // A tree of at least kGridItems items: a uniform grid over its leaves' extents on u and
        // v (GridCells), each cell listing the leaves whose extent meets it by wHi ascending. A
        // half-line whose probe lies in one cell looks at that cell's leaves from the first that
        // reaches past its start, nearest first, instead of walking the tree (a probe across a
        // cell border walks the tree). Entries are rounded outward to floats, so every leaf the
        // tree would reach is listed.
        struct Grid : GridCells {
            struct Entry {
                float uLo, uHi, vLo, vHi, wHi;
                std::int32_t leaf;
            };
            std::vector<Entry> entries;
            // Leaves with a NaN or infinite u or v extent, or a NaN wHi: tested one by one.
            std::vector<std::int32_t> loose;
        };
        std::vector<Grid> grid;  // one, or none
        // A tree of at least kGridItems items: each item's own extent, by its place in the
        // leaves (order_), rounded outward to floats. HalfLine tests it before it visits the
        // item: a leaf of four spheres spreads over about four times the area of each, and a
        // half-line through a leaf's extent used to visit all four, for the caller's slab test
        // to reject three (10,000 spheres: 7.6 visits a shadow ray, 1.7 of them hits). The
        // test is Meets' on the item's extent: looser than the slab test, never tighter.
        struct ItemExtent {
            float uLo, uHi, vLo, vHi, wHi;
        };
        std::vector<ItemExtent> items;  // empty: every item of a visited leaf is visited
        bool ItemMeets(std::size_t place, const Probe& q) const {
            if (items.empty()) return true;
            const ItemExtent& e = items[place];
            // Written so that a NaN extent culls nothing.
            return !(q.uHi < e.uLo || q.uLo > e.uHi || q.vHi < e.vLo || q.vLo > e.vHi ||
                     q.wLo > e.wHi);
        }
    };
    HalfLineView ViewAlong(const Vec3& d) const;
    // Calls visit(k) for the items whose box the half-line p + s·d, s >= 0, may meet (d the
    // view's direction); visit returns true to stop. Returns true when a visit stopped it.
    template <class Visit>
    bool HalfLine(const HalfLineView& view, const Vec3& p, Visit&& visit) const;

  private:
    // The column grid (GridCells over x and y). Entries keep the item's extents as floats
    // rounded outward and its lo.z rounded down: a looser test than the item's own (every item
    // that passes that is visited), in 24 bytes.
    struct ColumnGrid : GridCells {
        struct Entry {
            float loX, hiX, loY, hiY, loZ;
            std::int32_t item;
        };
        std::vector<Entry> entries;      // per cell, by loZ ascending
        std::vector<std::int32_t> wide;  // items with an infinite side in x or y: in no cell
    };
    void BuildGrid(const std::vector<Box3>& boxes, const std::vector<std::int32_t>& items);
    void BuildViewGrid(HalfLineView& view) const;

    struct Node {
        Box3 box;
        // Inner node: children at `first` and `first + 1` of nodes_ (count = 0). Leaf: items
        // order_[first .. first + count).
        std::int32_t first = 0, count = 0;
    };
    void Build(std::int32_t self, std::vector<std::int32_t>& items, std::size_t lo, std::size_t hi,
               const std::vector<Box3>& boxes, const std::vector<Vec3>& centres);

    std::size_t count_ = 0;
    std::vector<Node> nodes_;           // nodes_[0] is the root (when any item is bounded)
    std::vector<std::int32_t> order_;   // the items of the leaves
    std::vector<std::int32_t> always_;  // items whose boxes are never culled
    std::vector<ColumnGrid> grid_;      // the column grid: one, or none (fewer items)
    // With at least kGridItems items: the items' boxes by their place in order_, for the views'
    // item extents (HalfLineView::items).
    std::vector<Box3> placed_;
    static constexpr int kMaxDepth = 64;  // the median split gives depth <= log2(n) + 1
};

// (always_inline: every shadow ray tests boxes with it; out of line, as the compiler once chose,
// its calls cost about 1 % of a whole render of the machined part.)
[[gnu::always_inline]] inline bool BoxTree::SegmentHitsBox(const Box3& b, const Vec3& p,
                                                           const Vec3& d, double s0, double s1) {
    // Slab test; NaN or empty boxes are not culled (conservative).
    for (int k = 0; k < 3; ++k) {
        const double lo = b.lo[k], hi = b.hi[k];
        if (!(lo <= hi)) return true;
        if (d[k] == 0) {
            if (p[k] < lo || p[k] > hi) return false;
            continue;
        }
        double t0 = (lo - p[k]) / d[k], t1 = (hi - p[k]) / d[k];
        if (t0 > t1) std::swap(t0, t1);
        // std::fmax / std::fmin by comparison (the same values: t0, t1 are never NaN for a
        // finite p, and a NaN one is ignored either way), without a call into libm per slab.
        s0 = t0 > s0 ? t0 : s0;
        s1 = t1 < s1 ? t1 : s1;
        if (s0 > s1) return false;
    }
    return true;
}

inline bool BoxTree::SegmentsMayHitBox(const Box3& b, const Vec3& pLo, const Vec3& pHi,
                                       const Vec3& d, double s0, double s1) {
    bool bounded = false;  // SegmentHitsBox compares its bounds only after a slab with d[k] != 0
    for (int k = 0; k < 3; ++k) {
        const double lo = b.lo[k], hi = b.hi[k];
        // SegmentHitsBox may pass a NaN or inverted box; starts not finite are not looked at.
        if (!(lo <= hi) || !(pLo[k] <= pHi[k]) || !std::isfinite(pLo[k]) || !std::isfinite(pHi[k]))
            return true;
        if (d[k] == 0) {
            if (pHi[k] < lo || pLo[k] > hi) return false;  // every start outside the slab
            continue;
        }
        // d > 0: a start's entry (lo − p)/d is at least (lo − pHi)/d, its exit (hi − p)/d at
        // most (hi − pLo)/d; d < 0: its entry (hi − p)/d at least (hi − pLo)/d, its exit
        // (lo − p)/d at most (lo − pHi)/d.
        const double enter = d[k] > 0 ? (lo - pHi[k]) / d[k] : (hi - pLo[k]) / d[k];
        const double leave = d[k] > 0 ? (hi - pLo[k]) / d[k] : (lo - pHi[k]) / d[k];
        s0 = enter > s0 ? enter : s0;
        s1 = leave < s1 ? leave : s1;
        bounded = true;
    }
    return !bounded || !(s0 > s1);
}

template <class Visit>
bool BoxTree::Segment(const Vec3& p, const Vec3& d, double s0, double s1, Visit&& visit) const {
    for (std::int32_t k : always_)
        if (visit(k)) return true;
    if (nodes_.empty()) return false;
    std::int32_t stack[kMaxDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
        if (!SegmentHitsBox(n.box, p, d, s0, s1)) continue;
        if (n.count == 0) {
            // The child whose box centre lies earlier along d is visited first (pushed last), so
            // that a caller that stops at its first hit (a shadow ray) meets the blockers near
            // the segment's start sooner. (lo + hi)·d orders the centres; NaN keeps the order.
            const Box3& a = nodes_[static_cast<std::size_t>(n.first)].box;
            const Box3& b = nodes_[static_cast<std::size_t>(n.first + 1)].box;
            const double ca = Dot(a.lo + a.hi, d), cb = Dot(b.lo + b.hi, d);
            const bool bFirst = cb < ca;
            stack[top++] = bFirst ? n.first : n.first + 1;
            stack[top++] = bFirst ? n.first + 1 : n.first;
            continue;
        }
        for (std::int32_t i = n.first; i < n.first + n.count; ++i)
            if (visit(order_[static_cast<std::size_t>(i)])) return true;
    }
    return false;
}

template <class Visit>
bool BoxTree::HalfLine(const HalfLineView& view, const Vec3& p, Visit&& visit) const {
    for (std::int32_t k : always_)
        if (visit(k)) return true;
    if (nodes_.empty()) return false;
    const HalfLineView::Probe q = view.At(p);
    if (!view.grid.empty()) {
        const HalfLineView::Grid& g = view.grid.front();
        const int i = g.CellX(q.uLo), j = g.CellY(q.vLo);
        // (A NaN in the probe passes every extent: the tree's walk.)
        if (i == g.CellX(q.uHi) && j == g.CellY(q.vHi) &&
            !std::isnan(q.uLo + q.uHi + q.vLo + q.vHi + q.wLo)) {
            auto leaf = [&](std::int32_t l) {
                const Node& n = nodes_[static_cast<std::size_t>(l)];
                for (std::int32_t k = n.first; k < n.first + n.count; ++k)
                    if (view.ItemMeets(static_cast<std::size_t>(k), q) &&
                        visit(order_[static_cast<std::size_t>(k)]))
                        return true;
                return false;
            };
            for (std::int32_t l : g.loose)
                if (HalfLineView::Meets(view.nodes[static_cast<std::size_t>(l)], q) && leaf(l))
                    return true;
            const std::size_t c = g.Index(i, j);
            const HalfLineView::Grid::Entry* e = g.entries.data() + g.start[c];
            const HalfLineView::Grid::Entry* end = g.entries.data() + g.start[c + 1];
            // The first leaf reaching past the start: wHi >= q.wLo (floats rounded up).
            e = std::lower_bound(e, end, q.wLo, [](const HalfLineView::Grid::Entry& x, double w) {
                return x.wHi < w;
            });
            for (; e != end; ++e) {
                if (q.uHi < e->uLo || q.uLo > e->uHi || q.vHi < e->vLo || q.vLo > e->vHi) continue;
                if (leaf(e->leaf)) return true;
            }
            return false;
        }
    }
    std::int32_t stack[kMaxDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const std::int32_t i = stack[--top];
        if (!HalfLineView::Meets(view.nodes[static_cast<std::size_t>(i)], q)) continue;
        const Node& n = nodes_[static_cast<std::size_t>(i)];
        if (n.count == 0) {
            // The nearer child along d first (pushed last), as Segment does.
            const bool bFirst = view.nodes[static_cast<std::size_t>(n.first + 1)].wMid <
                                view.nodes[static_cast<std::size_t>(n.first)].wMid;
            stack[top++] = bFirst ? n.first : n.first + 1;
            stack[top++] = bFirst ? n.first + 1 : n.first;
            continue;
        }
        for (std::int32_t k = n.first; k < n.first + n.count; ++k)
            if (view.ItemMeets(static_cast<std::size_t>(k), q) &&
                visit(order_[static_cast<std::size_t>(k)]))
                return true;
    }
    return false;
}

template <class Visit>
void BoxTree::ColumnBefore(double x, double y, double zMax, Visit&& visit) const {
    for (std::int32_t k : always_) visit(k);
    if (nodes_.empty()) return;
    // The grid, for a column at a point (a NaN coordinate passes every box: the tree's walk).
    if (!grid_.empty() && x == x && y == y) {
        const ColumnGrid& g = grid_.front();
        for (std::int32_t k : g.wide) visit(k);
        const std::size_t c = g.Index(g.CellX(x), g.CellY(y));
        const ColumnGrid::Entry* e = g.entries.data() + g.start[c];
        const ColumnGrid::Entry* end = g.entries.data() + g.start[c + 1];
        const bool cut = zMax < HUGE_VAL;
        for (; e != end; ++e) {
            if (cut && e->loZ >= zMax) break;
            if (x < e->loX || x > e->hiX || y < e->loY || y > e->hiY) continue;
            visit(e->item);
        }
        return;
    }
    std::int32_t stack[kMaxDepth + 2];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
        if (x < n.box.lo.x || x > n.box.hi.x || y < n.box.lo.y || y > n.box.hi.y) continue;
        if (zMax < HUGE_VAL && n.box.lo.z >= zMax) continue;
        if (n.count == 0) {
            stack[top++] = n.first;
            stack[top++] = n.first + 1;
            continue;
        }
        for (std::int32_t i = n.first; i < n.first + n.count; ++i)
            visit(order_[static_cast<std::size_t>(i)]);
    }
}

}  // namespace quadrix
