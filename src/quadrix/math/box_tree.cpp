#include "quadrix/math/box_tree.h"

#include <algorithm>
#include <cmath>

namespace quadrix {

namespace {

// Every coordinate ordered (lo <= hi, no NaN): the box can be culled.
bool Ordered(const Box3& b) {
    for (int k = 0; k < 3; ++k)
        if (!(b.lo[k] <= b.hi[k])) return false;
    return true;
}

// A point to sort by: the box's centre, with an infinite side replaced by the finite one (0 when
// both are infinite). Only the tree's quality depends on it.
Vec3 Centre(const Box3& b) {
    Vec3 c;
    for (int k = 0; k < 3; ++k) {
        const double lo = b.lo[k], hi = b.hi[k];
        if (std::isfinite(lo) && std::isfinite(hi))
            c[k] = 0.5 * lo + 0.5 * hi;
        else if (std::isfinite(lo))
            c[k] = lo;
        else if (std::isfinite(hi))
            c[k] = hi;
        else
            c[k] = 0;
    }
    return c;
}

}  // namespace

BoxTree::BoxTree(const std::vector<Box3>& boxes, bool index) : count_(boxes.size()) {
    std::vector<std::int32_t> items;
    std::vector<Vec3> centres(boxes.size());
    for (std::size_t k = 0; k < boxes.size(); ++k) {
        if (index && Ordered(boxes[k])) {
            items.push_back(static_cast<std::int32_t>(k));
            centres[k] = Centre(boxes[k]);
        } else {
            always_.push_back(static_cast<std::int32_t>(k));
        }
    }
    if (items.empty()) return;
    nodes_.reserve(2 * (items.size() / kLeafSize + 1));
    nodes_.emplace_back();
    order_.reserve(items.size());
    Build(0, items, 0, items.size(), boxes, centres);
}

BoxTree::HalfLineView BoxTree::ViewAlong(const Vec3& d) const {
    HalfLineView view;
    const double len = Length(d);
    view.w = d / len;
    // u across w: w × the axis least aligned with w, normalised; v = w × u.
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::fabs(view.w[k]) < std::fabs(view.w[axis])) axis = k;
    Vec3 e;
    e[axis] = 1;
    view.u = Normalize(Cross(view.w, e));
    view.v = Normalize(Cross(view.w, view.u));
    view.nodes.resize(nodes_.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i) view.nodes[i] = view.Project(nodes_[i].box);
    return view;
}

BoxTree::HalfLineView::Extent BoxTree::HalfLineView::Project(const Box3& b) const {
    // A box's extent on axis a by interval arithmetic, each term from the end that makes it
    // smallest (largest); a zero component contributes nothing (an infinite side times 0). Padded
    // by 1e-9 of the box's magnitude m = Σ max(|lo_k|, |hi_k|): the sums' rounding, and the
    // rounding-level d·u and d·v times the distance along d from p to a point of the box (at most
    // m + |p|; At pads p's side by 1e-9 |p|). A NaN extent culls nothing.
    auto extent = [](const Box3& box, const Vec3& a, double pad, double& lo, double& hi) {
        lo = 0;
        hi = 0;
        for (int k = 0; k < 3; ++k) {
            if (a[k] == 0) continue;
            const double x = box.lo[k] * a[k], y = box.hi[k] * a[k];
            lo += x < y ? x : y;
            hi += x < y ? y : x;
        }
        lo -= pad;
        hi += pad;
    };
    Extent x;
    double m = 0;
    for (int k = 0; k < 3; ++k) m += std::fmax(std::fabs(b.lo[k]), std::fabs(b.hi[k]));
    const double pad = 1e-9 * m + 1e-300;
    double wLo;
    extent(b, u, pad, x.uLo, x.uHi);
    extent(b, v, pad, x.vLo, x.vHi);
    extent(b, w, pad, wLo, x.wHi);
    x.wMid = 0.5 * wLo + 0.5 * x.wHi;
    return x;
}

BoxTree::HalfLineView::Probe BoxTree::HalfLineView::At(const Vec3& p) const {
    // p's coordinates, widened by far more than their rounding (and than d·u, d·v, which are
    // rounding-level, times the distance to any box: the extents carry that part).
    const double pu = Dot(p, u), pv = Dot(p, v), pw = Dot(p, w);
    const double m = std::fabs(p.x) + std::fabs(p.y) + std::fabs(p.z);
    const double tol = 1e-9 * m + 1e-300;
    return {pu - tol, pu + tol, pv - tol, pv + tol, pw - tol};
}

// Fills node `self` (already allocated) with items[lo, hi).
void BoxTree::Build(std::int32_t self, std::vector<std::int32_t>& items, std::size_t lo,
                    std::size_t hi, const std::vector<Box3>& boxes,
                    const std::vector<Vec3>& centres) {
    // The union of the items' boxes and the spread of their centres, by comparisons: every box
    // here is Ordered (no NaN), where Box3::Extend's fmin/fmax are library calls (a tenth of the
    // shading of 10,000 spheres went into building three trees). Equal values, ±0 aside, which
    // every test of the tree compares as equal.
    Box3 box, spread;
    for (std::size_t i = lo; i < hi; ++i) {
        const auto k = static_cast<std::size_t>(items[i]);
        const Box3& b = boxes[k];
        const Vec3& c = centres[k];
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = b.lo[a] < box.lo[a] ? b.lo[a] : box.lo[a];
            box.hi[a] = b.hi[a] > box.hi[a] ? b.hi[a] : box.hi[a];
            spread.lo[a] = c[a] < spread.lo[a] ? c[a] : spread.lo[a];
            spread.hi[a] = c[a] > spread.hi[a] ? c[a] : spread.hi[a];
        }
    }
    nodes_[static_cast<std::size_t>(self)].box = box;
    if (hi - lo <= static_cast<std::size_t>(kLeafSize)) {
        nodes_[static_cast<std::size_t>(self)].first = static_cast<std::int32_t>(order_.size());
        nodes_[static_cast<std::size_t>(self)].count = static_cast<std::int32_t>(hi - lo);
        order_.insert(order_.end(), items.begin() + static_cast<std::ptrdiff_t>(lo),
                      items.begin() + static_cast<std::ptrdiff_t>(hi));
        return;
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (spread.hi[k] - spread.lo[k] > spread.hi[axis] - spread.lo[axis]) axis = k;
    const std::size_t mid = lo + (hi - lo) / 2;
    std::nth_element(items.begin() + static_cast<std::ptrdiff_t>(lo),
                     items.begin() + static_cast<std::ptrdiff_t>(mid),
                     items.begin() + static_cast<std::ptrdiff_t>(hi),
                     [&](std::int32_t a, std::int32_t b) {
                         const double ca = centres[static_cast<std::size_t>(a)][axis];
                         const double cb = centres[static_cast<std::size_t>(b)][axis];
                         return ca < cb || (ca == cb && a < b);
                     });
    const auto left = static_cast<std::int32_t>(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    nodes_[static_cast<std::size_t>(self)].first = left;
    nodes_[static_cast<std::size_t>(self)].count = 0;
    Build(left, items, lo, mid, boxes, centres);
    Build(left + 1, items, mid, hi, boxes, centres);
}

}  // namespace quadrix
