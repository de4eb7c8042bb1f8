// Exact per-ray evaluation for engine `scanline` (the same interval semantics as `raycast`,
// DESIGN.md "Engines in more detail"): the set of a body or a CSG tree on the ray through a pixel
// centre, as an interval list whose endpoints carry tags naming (half-space, body). The renderer
// uses it where the seed's Renderer has no incremental answer: a span's sample pixel for the
// bodies drawn exactly, CSG templates (seed 001 §5.5 turned to CSG, csg_spans.h), pixels on a
// crossing, refused bodies, the face stacks' row seed S0 and the verifier (face_stack.h).
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "quadrix/eval/ray_literal.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/interval_list.h"

namespace quadrix::eval {

// Exact per-ray evaluation of bodies and CSG trees (the same interval semantics as `raycast`).
class RayEvaluator {
  public:
    explicit RayEvaluator(const FlatScene& scene);
    struct Hit {
        double t = HUGE_VAL;
        int halfSpace = -1, body = -1;
    };
    // The first opaque finite endpoint of the body's / tree's set on the ray through (x, y).
    bool Body(int body, double x, double y, Hit& hit);
    bool Node(int node, double x, double y, Hit& hit);
    // The set of a body on the ray (ids are tags: see TagHalfSpace).
    void BodySet(int body, double x, double y, IntervalList& out);
    // The set of a tree whose leaves' sets are given by `leaf(body, out)`.
    template <class LeafFn>
    void TreeSet(int node, LeafFn&& leaf, IntervalList& out);
    // The first opaque finite endpoint of a list built from tags.
    bool First(const IntervalList& l, Hit& hit) const;
    // Which sheet of the half-space's quadric holds the endpoint at depth t on the ray through
    // (x, y): 1 when the back root is the nearer one to t, else 0 (planes: 0).
    int SheetOf(int halfSpace, double t, double x, double y) const;
    int TagHalfSpace(int tag) const { return tags_[static_cast<std::size_t>(tag)].halfSpace; }
    const RayHalfSpace& Ray(int halfSpace) const {
        return halfSpaces_[static_cast<std::size_t>(halfSpace)];
    }

  private:
    struct Tag {
        int halfSpace, body;
        bool complemented, opaque;
    };

    const FlatScene& scene_;
    std::vector<RayHalfSpace> halfSpaces_;
    std::vector<Tag> tags_;
    std::vector<int> bodyFirstTag_;
    LiteralCounters literalCounters_;
};

// One step of a left-to-right CSG fold: out = out op operand (tmp is scratch), with the empty
// operand identities (A ∪ ∅ = A − ∅ = A, A ∩ ∅ = ∅, ∅ ∪ B = B) taken without a sweep.
inline void CombineOperand(scene::CsgOp op, IntervalList& out, IntervalList& operand,
                           IntervalList& tmp) {
    if (operand.empty()) {
        if (op == scene::CsgOp::kIntersection) out.clear();
        return;
    }
    if (out.empty()) {  // (the caller stops an intersection or difference at an empty out)
        std::swap(out, operand);
        return;
    }
    switch (op) {
        case scene::CsgOp::kUnion:
            Union(out, operand, tmp);
            break;
        case scene::CsgOp::kIntersection:
            Intersection(out, operand, tmp);
            break;
        default:
            Difference(out, operand, tmp);
            break;
    }
    std::swap(out, tmp);
}

template <class LeafFn>
void RayEvaluator::TreeSet(int node, LeafFn&& leaf, IntervalList& out) {
    const FlatCsgNode& n = scene_.nodes[static_cast<std::size_t>(node)];
    if (n.isLeaf) {
        out.clear();
        if (n.body >= 0 && static_cast<std::size_t>(n.body) < scene_.bodies.size())
            leaf(n.body, out);
        return;
    }
    out.clear();
    IntervalList operand, tmp;
    for (std::size_t i = 0; i < n.children.size(); ++i) {
        if (i > 0 && out.empty() && n.op != scene::CsgOp::kUnion) return;  // ∅ ∩ B = ∅ − B = ∅
        TreeSet(n.children[i], leaf, i == 0 ? out : operand);
        if (i == 0) continue;
        CombineOperand(n.op, out, operand, tmp);
    }
}

}  // namespace quadrix::eval
