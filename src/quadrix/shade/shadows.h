// Shadow rays through the CSG (issue 17, deliverable 3): is the segment from a shaded surface
// point toward a light blocked by a solid of the scene?
//
// The shadow ray is a device-space line p + s·d in an arbitrary direction (not along z as the
// engines' rays), so each literal is evaluated along it directly, the same way the shared exact
// evaluator does along z (eval/ray_literal.h):
//   plane    P(p + s d) = (n·d) s + P(p)
//   quadric  Q(p + s d) = (dᵀA d) s² + 2 ((A p + b)·d) s + Q(p)      (A, b: quadric.h)
// solved by SolveQuadratic (math/quadratic.h); the literal's set is where the polynomial is <= 0
// (regularised: tangent rays give no point interval), the complemented literal its closed
// complement. Bodies intersect their literals (transparent ones bound too, and the clip planes
// the Flattener appends keep clipped-away geometry from casting shadows), CSG nodes combine their
// children's interval lists (math/interval_list.h), and the point is in shadow when some solid's
// set meets s in (ε, sMax). ε = 1e-4 pixel along the ray keeps a surface from shadowing itself
// where the ray leaves it (the set's end at s ≈ 0 carries the rounding of the hit point).
//
// The segment toward a light in device space (DeviceShadowRay): the device map M is projective
// under perspective, and a projective map sends lines to lines, so the world segment from the
// surface point P toward the light is still a device segment or half-line, with one care: where it
// crosses the eye plane (device w = 0) the image passes through infinity. In homogeneous
// coordinates the world segment is { a·(P, 1) + b·H : a, b >= 0 }, H = (L, 1) for a point or spot
// light at L and (D, 0) for a parallel light toward D (the light itself is a = 0). With
// M (P, 1) = w_p (p, 1), w_p > 0 (negate M's image H' = M H otherwise: the same projective map),
// and H' = (h, h_w), the image of a point of the segment is
//     x(u) = (w_p p + u h) / (w_p + u h_w),   u = b / a in [0, ∞],
// which is in front of the eye (on P's side of w = 0) while w_p + u h_w > 0. Hence:
//   h_w > 0  (a point light in front of the eye plane): x = p + s (l − p), l = h / h_w the light's
//            device image, s = u h_w / (w_p + u h_w) in [0, 1): the segment from p to l;
//   h_w = 0  (a parallel light under a parallel view, or a light on the eye plane): x = p + s h,
//            s = u / w_p in [0, ∞): a half-line along the device vector h;
//   h_w < 0  (a point light behind the eye plane, or under perspective a parallel light that
//            shines from behind the viewer): x = p + s (h − h_w p), s = u / (w_p + u h_w) in
//            [0, ∞) as u runs from 0 to the crossing w_p / −h_w: the half-line from p AWAY from
//            the light's image (h / h_w, which is the image of the part behind the eye).
// Under perspective a parallel light with D·n > 0 (from beyond the scene) has h_w > 0 and l its
// vanishing point, on the far plane z = d. The part of the world segment behind the eye plane has
// no device image in front of the eye; nothing there is drawn (the Flattener clips everything
// behind the eye), so it casts no shadow. Under a parallel view M is affine: h_w = 1 for point
// lights (d = l − p, sMax = 1) and 0 for parallel lights (d = M D, sMax = ∞), bit for bit what
// the parallel-only shadows computed before.
//
// Acceleration (math/box_tree.h): a box tree over the solids' bounds finds the solids a shadow
// segment may meet, and one over the children of every wide CSG node (a union, or a difference's
// subtrahends, of more than kWideNode children) the children it may meet; the others are ∅ on the
// segment. The per-literal evaluation is untouched; only which literals are evaluated changes.
// A shadow ray's answer does not depend on the order of a union or of the subtrahends.
//
// The surface a ray starts on (ShadowOrigin: the Frame's surface and body at the shaded point): a
// body's set on the segment is empty when one of its literals' is, so the origin body's literal
// of that surface is evaluated first, alone. The segment leaves that surface at once where it
// faces the light (every lit point but those on the inside of a hole), and the body is then known
// empty after one literal instead of after all those that come before it (the machined part's
// block has 14). Where that literal's set does meet the segment the body is evaluated as without
// an origin. Either way the answer is the body's evaluation in its own order: the fold only ever
// shrinks the set (exact max/min of the same roots), so a literal whose set misses the segment
// empties it in any order.
//
// Limits: only solids the Flattener kept (those whose bounds meet the image and lie in front of
// the eye) cast shadows.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/flatten/wide_node_trees.h"
#include "quadrix/math/box_tree.h"
#include "quadrix/math/interval_list.h"
#include "quadrix/math/mat4.h"

namespace quadrix {

// A shadow ray in device space: the light is unblocked when no solid meets p + s·d for s in
// (ε/|d|, sMax). length = |d|, computed once with d (a parallel light under a parallel view has
// the same ray at every pixel, and the shader keeps it).
struct DeviceRay {
    Vec3 d;
    double sMax = HUGE_VAL;
    double length = 0;
    // ShadowTester::AddDirection's id for d when the shader made views of the box trees along it
    // (a parallel light under a parallel view: sMax = +inf at every pixel), else -1.
    int view = -1;
};

// The device ray from the visible point p (device; pWorld is the same point in world space) toward
// a light given homogeneously in world space: (position, 1) or (direction toward it, 0), under the
// device map deviceFromWorld (see above). d = 0 when the light's image coincides with p.
DeviceRay DeviceShadowRay(const Mat4& deviceFromWorld, const Vec4& lightWorld, const Vec3& p,
                          const Vec3& pWorld);

// The surface a shadow ray starts on: the Frame's ids at the shaded point (a half-space index and
// its body), or -1 for none (see the file comment).
struct ShadowOrigin {
    int body = -1;
    int halfSpace = -1;
};

class ShadowTester {
  public:
    // spatialIndex = false: no box trees, every solid and child is box-tested per ray (the
    // benchmark's "before"; the answers are the same).
    // `wide`: the scene's wide-node trees made once for every tracer of one flat scene
    // (WideNodeTrees::Shared); null: made here.
    explicit ShadowTester(const FlatScene& scene, bool spatialIndex = true,
                          std::shared_ptr<const WideNodeTrees> wide = nullptr);
    // Nodes with more children than this get a box tree over them.
    static constexpr std::size_t kWideNode = WideNodeTrees::kWideNode;

    // Views of the box trees along d (BoxTree::ViewAlong), for the half-lines of one direction
    // that every shadow ray of a parallel light under a parallel view follows; returns the id to
    // put in DeviceRay::view. Called before any Blocked (not concurrently with it). The answers
    // are the same with or without a view; only the trees' node tests are cheaper.
    int AddDirection(const Vec3& d);

    // True when a solid's set meets p + s·d for some s in (ε/|d|, sMax), p and d in device space;
    // ε = 1e-4 + 1024 · DepthRounding(p.z) pixels (shadows.cpp).
    bool Blocked(const Vec3& p, const Vec3& d, double sMax) const;
    // The same for a DeviceRay (its length already computed), starting on `origin`'s surface
    // (the same answer as without it; fewer literals evaluated). `reach`: MayMeet's answer for a
    // set of starts that holds p, along this ray (the same answer; see Reach).
    bool Blocked(const Vec3& p, const DeviceRay& ray, const ShadowOrigin& origin = {},
                 std::uint64_t reach = kReachAll) const;

    // Reach: the shadow rays of one direction from a run of pixels (a parallel light under a
    // parallel view: every ray is the same DeviceRay) pass near few of a small scene's CSG nodes.
    // For a scene of at most kReachNodes nodes, MayMeet(lo, hi, ray) sets bit n unless no ray
    // from a start in the box [lo, hi] meets node n's box by Blocked's slab test
    // (BoxTree::SegmentsMayHitBox, from the earliest start Blocked uses, 1e-4 pixel), nor a
    // leaf whose body has a plane every such ray starts outside of and leaves
    // (BodyBehindAPlane: Body finds the body ∅ on each of them). Blocked
    // given that mask takes a node without its bit as missed without testing it: the answer is
    // the same. And where no leaf but those of the origin's body has its bit, every other body
    // is ∅ on the ray, so the solids' sets are ∅ as soon as the origin body's is: a ray from a
    // lit face is then answered by that body's literal of the face alone, in Body, without a
    // walk of the trees. Leaves inside a difference's subtrahends do not count: with every
    // leaf outside them ∅, each node is ∅ (∪ and ∩ of ∅, and ∅ − Y). kReachAll (every bit)
    // for a larger scene or another kind of ray.
    static constexpr std::uint64_t kReachAll = ~std::uint64_t{0};
    static constexpr std::size_t kReachNodes = 64;
    std::uint64_t MayMeet(const Vec3& lo, const Vec3& hi, const DeviceRay& ray) const;

    // The set of s where a half-space literal holds on the line (exposed for tests).
    static IntervalList LiteralOnLine(const FlatHalfSpace& h, bool complemented, const Vec3& p,
                                      const Vec3& d);
    // A body's set on the line clipped to [s0, s1]: the way Node computes it (a convex body kept
    // as one interval, lists only once a literal splits it), and with interval lists throughout
    // (generic = true, the reference of the tests: the same endpoints). tRayLiterals counts the
    // literals evaluated, the same either way.
    IntervalList BodyOnSegment(int body, const Vec3& p, const Vec3& d, double s0, double s1,
                               bool generic) const;

  private:
    // What a segment's traversal carries: the trees' view along d (AddDirection's id, or -1)
    // and the surface it starts on.
    struct Walk {
        int view = -1;
        ShadowOrigin origin;
        std::uint64_t reach = kReachAll;  // MayMeet's mask (bit n & 63 of node n)
    };
    // Whether the segment meets CSG node n's box by the slab test (false: n is ∅ on it), or
    // false at once when n's bit is not in walk.reach.
    bool NodeHits(int n, const Vec3& p, const Vec3& d, double s0, double s1,
                  const Walk& walk) const;
    // MayMeet's second test for a leaf: whether a plane literal of `body` has every segment
    // p + s·d, s > 0, from a start p in [lo, hi] outside its set and leaving it (or parallel to
    // it), as Body computes that literal's piece (PlanePiece: the root −c / 2h below 0, the
    // piece below it): then Body finds the body ∅ on each of those segments.
    bool BodyBehindAPlane(int body, const Vec3& lo, const Vec3& hi, const Vec3& d) const;
    // Whether the literal of `halfSpace` in `body` meets p + s·d for some s in [s0, s1] as Body
    // cuts it (false: the body's set misses the segment); true also when the body has no such
    // literal or it is quartic (no answer from it alone).
    bool OriginLiteralMeets(int body, int halfSpace, const Vec3& p, const Vec3& d, double s0,
                            double s1) const;
    // BodyOnSegment into *slots[k] (slots k+1.. scratch), without and with the one-interval path.
    // `first`: a half-space whose literal in the body is tried first, alone (-1: none).
    void Body(int body, const Vec3& p, const Vec3& d, double s0, double s1,
              std::vector<IntervalList*>& slots, std::size_t k, int first = -1) const;
    void BodyGeneric(int body, const Vec3& p, const Vec3& d, double s0, double s1,
                     std::vector<IntervalList*>& slots, std::size_t k) const;
    // The node's set on the line, clipped to [s0, s1] (the bodies' folds start from it), left in
    // *slots[k]; slots k+1, ... are its scratch (shadows.cpp). Children whose boxes the segment
    // misses are taken as ∅. With anyHit only the set's emptiness matters: a union stops at its
    // first child that meets the segment.
    void Node(int node, const Vec3& p, const Vec3& d, double s0, double s1,
              std::vector<IntervalList*>& slots, std::size_t k, bool anyHit,
              const Walk& walk) const;
    // *slots[k] (the minuend's set for a difference, else empty) folded by the node's union or
    // difference with the set of each child the segment may meet: children 0, 1, ... of a
    // union, 1, 2, ... of a difference.
    void Wide(const FlatCsgNode& node, std::int32_t wide, const Vec3& p, const Vec3& d, double s0,
              double s1, std::vector<IntervalList*>& slots, std::size_t k, bool anyHit,
              const Walk& walk) const;
    // Node n, a difference whose minuend is a union, asked only whether its set meets the
    // segment: (∪ Aᵢ) − B₁ − … − Bₘ = ∪ (Aᵢ − (B₁ ∪ … ∪ Bₘ)) (regularised sets are a Boolean
    // algebra), so the operands Aᵢ are tried one at a time and the first one left non-empty
    // by the subtrahends (made once, when an operand first meets the segment) answers; a
    // shadow ray through a dense union minus a tool stops at its first blocker instead of
    // making the union of every operand it crosses. slots[k] as Node.
    void DistributedDifference(int n, const Vec3& p, const Vec3& d, double s0, double s1,
                               std::vector<IntervalList*>& slots, std::size_t k,
                               const Walk& walk) const;
    // For a difference node of which the segment's origin body is a subtrahend leaf: that body's
    // set on the segment (its literal of the surface first, as Body evaluates it) into
    // *slots[k+1]; when it holds the segment's start, its first interval [s0, t] is not in the
    // node's set, and the node's set is wholly made on (t, s1): returns t, else s0. A ray from a
    // hole's wall or a slot's floor starts in the removed tool, and the part is then looked at
    // only beyond it (where the tool's own set, made again, is usually empty at once).
    double PastOrigin(const Vec3& p, const Vec3& d, double s0, double s1,
                      std::vector<IntervalList*>& slots, std::size_t k, const Walk& walk) const;
    // tree.Segment(p, d, s0, s1, visit), or its view's HalfLine when `view` >= 0 (s1 = +inf):
    // tree 0 is solids_, tree w + 1 is wide_[w].
    template <class Visit>
    bool Query(std::size_t tree, int view, const Vec3& p, const Vec3& d, double s0, double s1,
               Visit&& visit) const {
        const BoxTree& t = tree == 0 ? solids_ : wide_[tree - 1];
        if (view >= 0) return t.HalfLine(views_[static_cast<std::size_t>(view)][tree], p, visit);
        return t.Segment(p, d, s0, s1, visit);
    }
    const FlatScene& scene_;
    BoxTree solids_;  // over scene_.solids[k].bounds
    // The trees of the wide nodes (shared, kept alive here) and, read per node visited, their
    // arrays: wideOf_[node] = index into wide_, or -1.
    std::shared_ptr<const WideNodeTrees> wideTrees_;
    const BoxTree* wide_ = nullptr;
    const std::int32_t* wideOf_ = nullptr;
    int maxDepth_ = 0;  // the deepest node below a solid's root (root: 0)
    // Per body: the difference node of which it is a subtrahend leaf (a child other than the
    // first), else -1, and that leaf (PastOrigin).
    std::vector<std::int32_t> subtrahendOf_, leafOf_;
    // With at most kReachNodes nodes (else empty / 0): per body, the mask of the leaves of that
    // body; and the mask of the leaves in a positive place: reached from a solid's root through
    // unions, intersections and the first children of differences, never a subtrahend.
    std::vector<std::uint64_t> leavesOf_;
    std::uint64_t positiveLeaves_ = 0;
    // AddDirection's views: views_[id][tree], trees numbered as Query numbers them.
    std::vector<std::vector<BoxTree::HalfLineView>> views_;
};

}  // namespace quadrix
