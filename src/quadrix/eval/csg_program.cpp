#include "quadrix/eval/csg_program.h"

#include <algorithm>
#include <cmath>

namespace quadrix::eval {
namespace {

constexpr double kInf = HUGE_VAL;
// Deeper trees are treated as empty: a guard against malformed (cyclic) node graphs, far beyond
// any tree a scene produces (the Flattener merges chains of one operator into n-ary nodes).
constexpr int kMaxDepth = 10000;

Rect RectOf(const Box3& b) { return {b.lo.x, b.hi.x, b.lo.y, b.hi.y}; }
double ZloOf(const Box3& b) { return std::isnan(b.lo.z) ? -kInf : b.lo.z; }

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

// Shared recursion of BuildProgram and PruneProgram. `Source` adapts the input tree.
template <class Source>
std::int32_t Copy(const Source& src, std::int32_t n, const Rect& r, int depth, CsgProgram& dst,
                  std::vector<std::int32_t>& stack) {
    if (depth > kMaxDepth) return -1;
    ProgNode proto;
    if (!src.Node(n, proto) || IsEmpty(proto.xy) || proto.Misses(r)) return -1;
    dst.maxDepth = std::max(dst.maxDepth, depth);
    if (proto.kind == NodeKind::kBody) {
        dst.nodes.push_back(proto);
        return static_cast<std::int32_t>(dst.nodes.size() - 1);
    }
    std::size_t base = stack.size();
    int count = src.ChildCount(n);
    for (int i = 0; i < count; ++i) {
        std::int32_t c = Copy(src, src.Child(n, i), r, depth + 1, dst, stack);
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
    const Rect everywhere{-kInf, kInf, -kInf, kInf};
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

void PruneProgram(const CsgProgram& src, const Rect& r, CsgProgram& dst,
                  std::vector<std::int32_t>& stack) {
    dst.Clear();
    ProgramSource source{src};
    for (const ProgSolid& s : src.solids) {
        if (s.xy.x1 < r.x0 || s.xy.x0 > r.x1 || s.xy.y1 < r.y0 || s.xy.y0 > r.y1) continue;
        std::int32_t root = Copy(source, s.root, r, 0, dst, stack);
        if (root < 0) continue;
        const ProgNode& n = dst.nodes[static_cast<std::size_t>(root)];
        dst.solids.push_back({s.solid, root, n.xy, n.zlo});
    }
    // Tightened zlo values may reorder the solids.
    std::sort(dst.solids.begin(), dst.solids.end(), SolidLess);
}

}  // namespace quadrix::eval
