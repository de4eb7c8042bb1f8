#include "quadrix/math/box_tree.h"

#include <algorithm>
#include <array>
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

// v as a float no greater (Down) or no less (Up) than v.
float Down(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) > v) f = std::nextafter(f, -HUGE_VALF);
    return f;
}
float Up(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) < v) f = std::nextafter(f, HUGE_VALF);
    return f;
}

double Median(std::vector<double> v) {
    if (v.empty()) return 0;
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

// Lists items[k] in the cells its rectangle rects[k] meets (cells.start[c] .. cells.start[c + 1]
// are cell c's entries, make(item) each, sorted by `before`). False, with nothing filled, when that
// would take more than 16 entries an item (boxes much larger than the median: the tree serves them
// better).
template <class Entry, class Make, class Before>
bool Bin(const std::vector<std::int32_t>& items, const std::vector<std::array<double, 4>>& rects,
         const Make& make, const Before& before, BoxTree::GridCells& cells,
         std::vector<Entry>& entries) {
    auto cellsOf = [&](std::size_t k) {
        const std::array<double, 4>& r = rects[k];
        return std::array<int, 4>{cells.CellX(r[0]), cells.CellX(r[1]), cells.CellY(r[2]),
                                  cells.CellY(r[3])};
    };
    auto each = [&](std::size_t k, auto&& f) {
        const std::array<int, 4> c = cellsOf(k);
        for (int j = c[2]; j <= c[3]; ++j)
            for (int i = c[0]; i <= c[1]; ++i) f(cells.Index(i, j));
    };
    const std::size_t nCells =
        static_cast<std::size_t>(cells.nx) * static_cast<std::size_t>(cells.ny);
    std::vector<std::int32_t>& start = cells.start;
    std::size_t refs = 0;
    for (std::size_t k = 0; k < items.size(); ++k) {
        const std::array<int, 4> c = cellsOf(k);
        refs +=
            static_cast<std::size_t>(c[1] - c[0] + 1) * static_cast<std::size_t>(c[3] - c[2] + 1);
    }
    if (refs > 16 * items.size()) return false;
    start.assign(nCells + 1, 0);
    for (std::size_t k = 0; k < items.size(); ++k) each(k, [&](std::size_t c) { ++start[c + 1]; });
    for (std::size_t c = 0; c < nCells; ++c) start[c + 1] += start[c];
    entries.resize(refs);
    std::vector<std::int32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < items.size(); ++k) {
        const Entry e = make(items[k]);
        each(k, [&](std::size_t c) { entries[static_cast<std::size_t>(fill[c]++)] = e; });
    }
    for (std::size_t c = 0; c < nCells; ++c)
        std::sort(entries.begin() + start[c], entries.begin() + start[c + 1], before);
    return true;
}

}  // namespace

bool BoxTree::GridCells::Frame(const std::vector<std::array<double, 4>>& rects) {
    if (rects.empty()) return false;
    double xLo = HUGE_VAL, xHi = -HUGE_VAL, yLo = HUGE_VAL, yHi = -HUGE_VAL;
    std::vector<double> widths, heights;
    widths.reserve(rects.size());
    heights.reserve(rects.size());
    for (const std::array<double, 4>& r : rects) {
        xLo = std::min(xLo, r[0]);
        xHi = std::max(xHi, r[1]);
        yLo = std::min(yLo, r[2]);
        yHi = std::max(yHi, r[3]);
        widths.push_back(r[1] - r[0]);
        heights.push_back(r[3] - r[2]);
    }
    auto cells = [](double span, double item) {
        if (!(span > 0)) return 1.0;
        return item > 0 ? std::clamp(std::ceil(span / item), 1.0, 4096.0) : 4096.0;
    };
    double cx = cells(xHi - xLo, Median(widths)), cy = cells(yHi - yLo, Median(heights));
    const double most = 2.0 * static_cast<double>(rects.size());
    if (cx * cy > most) {
        const double f = std::sqrt(cx * cy / most);
        cx = std::max(1.0, std::floor(cx / f));
        cy = std::max(1.0, std::floor(cy / f));
    }
    nx = static_cast<int>(cx);
    ny = static_cast<int>(cy);
    x0 = xLo;
    y0 = yLo;
    invX = xHi > xLo ? cx / (xHi - xLo) : 0;
    invY = yHi > yLo ? cy / (yHi - yLo) : 0;
    return std::isfinite(invX) && std::isfinite(invY);  // false: spans beyond doubles
}

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
    if (items.size() >= kGridItems) BuildGrid(boxes, items);
    Build(0, items, 0, items.size(), boxes, centres);
    if (items.size() >= kGridItems) {
        placed_.reserve(order_.size());
        for (std::int32_t k : order_) placed_.push_back(boxes[static_cast<std::size_t>(k)]);
    }
}

void BoxTree::BuildGrid(const std::vector<Box3>& boxes, const std::vector<std::int32_t>& items) {
    ColumnGrid g;
    std::vector<std::int32_t> binned;
    std::vector<std::array<double, 4>> rects;
    for (std::int32_t k : items) {
        const Box3& b = boxes[static_cast<std::size_t>(k)];
        if (!std::isfinite(b.lo.x) || !std::isfinite(b.hi.x) || !std::isfinite(b.lo.y) ||
            !std::isfinite(b.hi.y)) {
            g.wide.push_back(k);
            continue;
        }
        binned.push_back(k);
        rects.push_back({b.lo.x, b.hi.x, b.lo.y, b.hi.y});
    }
    if (!g.Frame(rects)) return;
    auto make = [&](std::int32_t k) {
        const Box3& b = boxes[static_cast<std::size_t>(k)];
        return ColumnGrid::Entry{Down(b.lo.x), Up(b.hi.x),   Down(b.lo.y),
                                 Up(b.hi.y),   Down(b.lo.z), k};
    };
    auto before = [](const ColumnGrid::Entry& a, const ColumnGrid::Entry& b) {
        return a.loZ < b.loZ || (a.loZ == b.loZ && a.item < b.item);
    };
    if (!Bin(binned, rects, make, before, g, g.entries)) return;
    grid_.push_back(std::move(g));
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
    view.items.reserve(placed_.size());
    for (const Box3& b : placed_) {
        const HalfLineView::Extent x = view.Project(b);
        view.items.push_back({Down(x.uLo), Up(x.uHi), Down(x.vLo), Up(x.vHi), Up(x.wHi)});
    }
    if (order_.size() >= kGridItems) BuildViewGrid(view);
    return view;
}

void BoxTree::BuildViewGrid(HalfLineView& view) const {
    using Grid = HalfLineView::Grid;
    Grid g;
    std::vector<std::int32_t> leaves;
    std::vector<std::array<double, 4>> rects;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        if (nodes_[i].count == 0) continue;
        const HalfLineView::Extent& x = view.nodes[i];
        const auto l = static_cast<std::int32_t>(i);
        if (!std::isfinite(x.uLo) || !std::isfinite(x.uHi) || !std::isfinite(x.vLo) ||
            !std::isfinite(x.vHi) || !(x.uLo <= x.uHi) || !(x.vLo <= x.vHi) ||
            std::isnan(x.wHi)) {  // (a NaN wHi could not be sorted)
            g.loose.push_back(l);
            continue;
        }
        leaves.push_back(l);
        rects.push_back({x.uLo, x.uHi, x.vLo, x.vHi});
    }
    if (!g.Frame(rects)) return;
    auto make = [&](std::int32_t l) {
        const HalfLineView::Extent& x = view.nodes[static_cast<std::size_t>(l)];
        return Grid::Entry{Down(x.uLo), Up(x.uHi), Down(x.vLo), Up(x.vHi), Up(x.wHi), l};
    };
    auto before = [](const Grid::Entry& a, const Grid::Entry& b) {
        return a.wHi < b.wHi || (a.wHi == b.wHi && a.leaf < b.leaf);
    };
    if (!Bin(leaves, rects, make, before, g, g.entries)) return;
    view.grid.push_back(std::move(g));
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
