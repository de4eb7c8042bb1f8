#include "quadrix/eval/csg_program.h"

#include <algorithm>
#include <cmath>

namespace quadrix::eval {
namespace {

constexpr double kInfinite = HUGE_VAL;
// Deeper trees are treated as empty: a guard against malformed (cyclic) node graphs, far beyond
// any tree a scene produces (the Flattener merges chains of one operator into n-ary nodes).
constexpr int kMaxDepth = 10000;

Rect RectOf(const Box3& b) { return {b.lo.x, b.hi.x, b.lo.y, b.hi.y}; }
double ZloOf(const Box3& b) { return std::isnan(b.lo.z) ? -kInfinite : b.lo.z; }

Rect Intersect(const Rect& a, const Rect& b) {
    return {std::max(a.x0, b.x0), std::min(a.x1, b.x1), std::max(a.y0, b.y0), std::min(a.y1, b.y1)};
}
Rect Hull(const Rect& a, const Rect& b) {
    return {std::min(a.x0, b.x0), std::max(a.x1, b.x1), std::min(a.y0, b.y0), std::max(a.y1, b.y1)};
}
bool IsEmpty(const Rect& r) { return r.x0 > r.x1 || r.y0 > r.y1; }

// Emits an operator node over the surviving operands stack[base..] (already in dst), applying the
// simplifications of the header; returns its index or -1 for the empty set. Pops the operands.
// The node's xy range and zlo are tightened from its operands: a union lies in the hull of its
// operands and no nearer than the nearest; an intersection lies in all of them; a difference in its
// minuend.
std::int32_t EmitOperator(const ProgNode& proto, std::size_t base, CsgProgram& dst,
                          std::vector<std::int32_t>& stack) {
    std::size_t count = stack.size() - base;
    if (count == 0) return -1;
    if (count == 1) {
        std::int32_t only = stack[base];
        stack.resize(base);
        ProgNode& n = dst.nodes[static_cast<std::size_t>(only)];
        n.xy = Intersect(n.xy, proto.xy);
        n.zlo = std::max(n.zlo, proto.zlo);
        return IsEmpty(n.xy) ? -1 : only;
    }
    ProgNode node = proto;
    const ProgNode& c0 = dst.nodes[static_cast<std::size_t>(stack[base])];
    Rect xy = c0.xy;
    double zlo = c0.zlo;
    if (proto.kind != NodeKind::kDifference) {
        for (std::size_t i = base + 1; i < stack.size(); ++i) {
            const ProgNode& c = dst.nodes[static_cast<std::size_t>(stack[i])];
            if (proto.kind == NodeKind::kUnion) {
                xy = Hull(xy, c.xy);
                zlo = std::min(zlo, c.zlo);
            } else {
                xy = Intersect(xy, c.xy);
                zlo = std::max(zlo, c.zlo);
            }
        }
    }
    node.xy = Intersect(xy, proto.xy);
    node.zlo = std::max(zlo, proto.zlo);
    if (IsEmpty(node.xy)) {
        stack.resize(base);
        return -1;
    }
    node.first = static_cast<std::int32_t>(dst.children.size());
    node.count = static_cast<std::int32_t>(count);
    dst.children.insert(dst.children.end(), stack.begin() + static_cast<std::ptrdiff_t>(base),
                        stack.end());
    stack.resize(base);
    dst.nodes.push_back(node);
    return static_cast<std::int32_t>(dst.nodes.size() - 1);
}

// One bin of a ProgramBins (null: none).
struct BinView {
    const ProgramBins* bins = nullptr;
    std::size_t bin = 0;
    // The positions of node n's operands that may meet the bin's rectangle, or false when n is
    // not binned.
    bool List(std::int32_t n, const std::int32_t*& first, const std::int32_t*& last) const {
        if (!bins) return false;
        const std::int32_t w = bins->binnedOf[static_cast<std::size_t>(n)];
        if (w < 0) return false;
        const std::size_t at = static_cast<std::size_t>(w) * (bins->Bins() + 1) + bin;
        first = bins->items.data() + bins->starts[at];
        last = bins->items.data() + bins->starts[at + 1];
        return true;
    }
};

// Shared recursion of BuildProgram and PruneProgram. `Source` adapts the input tree.
template <class Source>
std::int32_t Copy(const Source& src, std::int32_t n, const Rect& r, int depth, CsgProgram& dst,
                  std::vector<std::int32_t>& stack, const BinView& view = {}) {
    if (depth > kMaxDepth) return -1;
    ProgNode proto;
    if (!src.Node(n, proto) || IsEmpty(proto.xy) || proto.Misses(r)) return -1;
    dst.maxDepth = std::max(dst.maxDepth, depth);
    if (proto.kind == NodeKind::kBody) {
        dst.nodes.push_back(proto);
        return static_cast<std::int32_t>(dst.nodes.size() - 1);
    }
    std::size_t base = stack.size();
    const std::int32_t *listFirst = nullptr, *listLast = nullptr;
    if (view.List(n, listFirst, listLast)) {
        // A binned union or difference: the operands left out miss r along the bin's axis, so
        // Copy would return -1 for them, which drops an operand of a union and a subtrahend.
        if (proto.kind == NodeKind::kDifference) {
            std::int32_t c = Copy(src, src.Child(n, 0), r, depth + 1, dst, stack, view);
            if (c < 0) {
                stack.resize(base);
                return -1;
            }
            stack.push_back(c);
        }
        for (const std::int32_t* it = listFirst; it != listLast; ++it) {
            std::int32_t c = Copy(src, src.Child(n, *it), r, depth + 1, dst, stack, view);
            if (c >= 0) stack.push_back(c);
        }
        return EmitOperator(proto, base, dst, stack);
    }
    int count = src.ChildCount(n);
    for (int i = 0; i < count; ++i) {
        std::int32_t c = Copy(src, src.Child(n, i), r, depth + 1, dst, stack, view);
        if (c >= 0) {
            stack.push_back(c);
            continue;
        }
        // An empty operand empties an intersection, and a difference whose minuend it is.
        if (proto.kind == NodeKind::kIntersection ||
            (proto.kind == NodeKind::kDifference && i == 0)) {
            stack.resize(base);
            return -1;
        }
    }
    return EmitOperator(proto, base, dst, stack);
}

struct SceneSource {
    const FlatScene& scene;

    bool Node(std::int32_t n, ProgNode& out) const {
        if (n < 0 || static_cast<std::size_t>(n) >= scene.nodes.size()) return false;
        const FlatCsgNode& node = scene.nodes[static_cast<std::size_t>(n)];
        if (node.bounds.Empty()) return false;
        out.xy = RectOf(node.bounds);
        out.zlo = ZloOf(node.bounds);
        if (node.isLeaf) {
            if (node.body < 0 || static_cast<std::size_t>(node.body) >= scene.bodies.size())
                return false;
            const Box3& b = scene.bodies[static_cast<std::size_t>(node.body)].bounds;
            if (b.Empty()) return false;
            out.xy = Intersect(out.xy, RectOf(b));
            out.zlo = std::max(out.zlo, ZloOf(b));
            out.kind = NodeKind::kBody;
            out.first = node.body;
            out.count = 0;
            return true;
        }
        switch (node.op) {
            case scene::CsgOp::kUnion:
                out.kind = NodeKind::kUnion;
                break;
            case scene::CsgOp::kIntersection:
                out.kind = NodeKind::kIntersection;
                break;
            case scene::CsgOp::kDifference:
                out.kind = NodeKind::kDifference;
                break;
        }
        return true;
    }
    int ChildCount(std::int32_t n) const {
        return static_cast<int>(scene.nodes[static_cast<std::size_t>(n)].children.size());
    }
    std::int32_t Child(std::int32_t n, int i) const {
        return scene.nodes[static_cast<std::size_t>(n)].children[static_cast<std::size_t>(i)];
    }
};

struct ProgramSource {
    const CsgProgram& program;

    bool Node(std::int32_t n, ProgNode& out) const {
        out = program.nodes[static_cast<std::size_t>(n)];
        return true;
    }
    int ChildCount(std::int32_t n) const {
        return program.nodes[static_cast<std::size_t>(n)].count;
    }
    std::int32_t Child(std::int32_t n, int i) const {
        return program.children[static_cast<std::size_t>(
            program.nodes[static_cast<std::size_t>(n)].first + i)];
    }
};

bool SolidLess(const ProgSolid& a, const ProgSolid& b) {
    return a.zlo != b.zlo ? a.zlo < b.zlo : a.solid < b.solid;
}

}  // namespace

void BuildProgram(const FlatScene& scene, CsgProgram& out) {
    out.Clear();
    std::vector<std::int32_t> stack;
    const Rect everywhere{-kInfinite, kInfinite, -kInfinite, kInfinite};
    SceneSource src{scene};
    for (std::size_t s = 0; s < scene.solids.size(); ++s) {
        const FlatSolid& solid = scene.solids[s];
        if (solid.bounds.Empty()) continue;
        std::int32_t root = Copy(src, solid.root, everywhere, 0, out, stack);
        if (root < 0) continue;
        ProgNode& n = out.nodes[static_cast<std::size_t>(root)];
        n.xy = Intersect(n.xy, RectOf(solid.bounds));
        n.zlo = std::max(n.zlo, ZloOf(solid.bounds));
        if (IsEmpty(n.xy)) continue;
        out.solids.push_back({static_cast<std::int32_t>(s), root, n.xy, n.zlo});
    }
    std::sort(out.solids.begin(), out.solids.end(), SolidLess);
}

namespace {

// Room in dst for all of src (a pruned program is never bigger than its source). A thread's
// scratch program grows once to the size it needs instead of by doubling: each doubling moved the
// nodes into fresh memory, and on the engines' worker threads (whose heaps start empty) the pages
// of every size up to the full program were first-touched, about 2 × its size in page faults
// (the 10,131-body helicopter: 560 faults of about 11 µs in the frame). Reserving writes nothing:
// pages a small program does not reach are never touched.
void ReserveFor(const CsgProgram& src, CsgProgram& dst) {
    dst.nodes.reserve(src.nodes.size());
    dst.children.reserve(src.children.size());
    dst.solids.reserve(src.solids.size());
}

// One solid of PruneProgram.
void PruneSolid(const ProgramSource& source, const ProgSolid& s, const Rect& r, CsgProgram& dst,
                std::vector<std::int32_t>& stack, const BinView& view) {
    if (s.xy.x1 < r.x0 || s.xy.x0 > r.x1 || s.xy.y1 < r.y0 || s.xy.y0 > r.y1) return;
    std::int32_t root = Copy(source, s.root, r, 0, dst, stack, view);
    if (root < 0) return;
    const ProgNode& n = dst.nodes[static_cast<std::size_t>(root)];
    dst.solids.push_back({s.solid, root, n.xy, n.zlo});
}

// The bins k whose rectangles an operand of range [a, b] on the axis may meet: those with
// neither hi_k < a nor b < lo_k (the negation of Rect's miss test on that axis; a NaN end meets
// every bin, as Misses never culls on NaN). Calls f(k) in ascending order.
template <class F>
void ForBinsMet(const ProgramBins& bins, double a, double b, F&& f) {
    const std::size_t nb = bins.Bins();
    // hi is ascending: the first bin not entirely left of a (all of them when a is NaN).
    std::size_t k = static_cast<std::size_t>(
        std::partition_point(bins.hi.begin(), bins.hi.end(), [&](double h) { return h < a; }) -
        bins.hi.begin());
    for (; k < nb && !(b < bins.lo[k]); ++k) f(k);
}

// Counting sort of (bin, position) pairs into starts/items, in the order given per bin.
template <class Each>
void FillLists(std::size_t nb, std::int32_t* starts, std::vector<std::int32_t>& items,
               Each&& each) {
    const std::size_t base = items.size();
    std::vector<std::int32_t> count(nb + 1, 0);
    each([&](std::size_t k, std::int32_t) { ++count[k + 1]; });
    for (std::size_t k = 0; k < nb; ++k) count[k + 1] += count[k];
    items.resize(base + static_cast<std::size_t>(count[nb]));
    for (std::size_t k = 0; k <= nb; ++k) starts[k] = static_cast<std::int32_t>(base) + count[k];
    std::vector<std::int32_t> next(count.begin(), count.end() - 1);
    each([&](std::size_t k, std::int32_t pos) {
        items[base + static_cast<std::size_t>(next[k]++)] = pos;
    });
}

}  // namespace

void PruneProgram(const CsgProgram& src, const Rect& r, CsgProgram& dst,
                  std::vector<std::int32_t>& stack) {
    dst.Clear();
    ReserveFor(src, dst);
    ProgramSource source{src};
    for (const ProgSolid& s : src.solids) PruneSolid(source, s, r, dst, stack, {});
    // Tightened zlo values may reorder the solids.
    std::sort(dst.solids.begin(), dst.solids.end(), SolidLess);
}

void BinProgram(const CsgProgram& src, const std::vector<Rect>& rects, bool alongX,
                ProgramBins& out) {
    const std::size_t nb = rects.size();
    out.alongX = alongX;
    out.lo.resize(nb);
    out.hi.resize(nb);
    for (std::size_t k = 0; k < nb; ++k) {
        out.lo[k] = alongX ? rects[k].x0 : rects[k].y0;
        out.hi[k] = alongX ? rects[k].x1 : rects[k].y1;
    }
    auto lo = [&](const Rect& xy) { return alongX ? xy.x0 : xy.y0; };
    auto hi = [&](const Rect& xy) { return alongX ? xy.x1 : xy.y1; };
    out.binnedOf.assign(src.nodes.size(), -1);
    out.starts.clear();
    out.items.clear();
    std::int32_t binned = 0;
    for (std::size_t n = 0; n < src.nodes.size(); ++n) {
        const ProgNode& node = src.nodes[n];
        const bool unionNode = node.kind == NodeKind::kUnion;
        if (!(unionNode || node.kind == NodeKind::kDifference)) continue;
        const std::int32_t from = unionNode ? 0 : 1;  // a difference's minuend is walked always
        if (node.count - from <= ProgramBins::kBinnedOperands) continue;
        out.binnedOf[n] = binned++;
        out.starts.resize(out.starts.size() + nb + 1);
        FillLists(nb, out.starts.data() + out.starts.size() - (nb + 1), out.items, [&](auto&& add) {
            for (std::int32_t i = from; i < node.count; ++i) {
                const ProgNode& c = src.nodes[static_cast<std::size_t>(
                    src.children[static_cast<std::size_t>(node.first + i)])];
                ForBinsMet(out, lo(c.xy), hi(c.xy), [&](std::size_t k) { add(k, i); });
            }
        });
    }
    out.solidStarts.assign(nb + 1, 0);
    out.solidItems.clear();
    FillLists(nb, out.solidStarts.data(), out.solidItems, [&](auto&& add) {
        for (std::size_t i = 0; i < src.solids.size(); ++i)
            ForBinsMet(out, lo(src.solids[i].xy), hi(src.solids[i].xy),
                       [&](std::size_t k) { add(k, static_cast<std::int32_t>(i)); });
    });
}

void PruneProgram(const CsgProgram& src, const ProgramBins& bins, std::size_t bin, const Rect& r,
                  CsgProgram& dst, std::vector<std::int32_t>& stack) {
    dst.Clear();
    ReserveFor(src, dst);
    ProgramSource source{src};
    const BinView view{&bins, bin};
    for (std::int32_t i = bins.solidStarts[bin]; i < bins.solidStarts[bin + 1]; ++i)
        PruneSolid(
            source,
            src.solids[static_cast<std::size_t>(bins.solidItems[static_cast<std::size_t>(i)])], r,
            dst, stack, view);
    std::sort(dst.solids.begin(), dst.solids.end(), SolidLess);
}

}  // namespace quadrix::eval
