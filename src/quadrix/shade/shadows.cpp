#include "quadrix/shade/shadows.h"

#include <cmath>
#include <utility>

#include "quadrix/flatten/wide_node_trees.h"
#include "quadrix/math/quadratic.h"

namespace quadrix {

namespace {

constexpr double kInf = HUGE_VAL;

// Where a·s² + 2h·s + c <= 0 (regularised).
IntervalList NonPositive(double a, double h, double c) {
    const QuadraticRoots r = SolveQuadratic(a, h, c);
    IntervalList out;
    switch (r.kind) {
        case RootKind::kAll:
            return IntervalList::All();
        case RootKind::kNone:
        case RootKind::kDouble:
            // No sign change: the sign of a (of c when a = 0, h = 0).
            if (a < 0 || (a == 0 && h == 0 && c <= 0)) return IntervalList::All();
            return out;
        case RootKind::kSingle:
            if (h > 0)
                out.Append(-kInf, Interval::kNoId, r.t0, 0);
            else
                out.Append(r.t0, 0, kInf, Interval::kNoId);
            return out;
        case RootKind::kTwo:
            if (a > 0) {
                out.Append(r.t0, 0, r.t1, 0);
            } else {
                out.Append(-kInf, Interval::kNoId, r.t0, 0);
                out.Append(r.t1, 0, kInf, Interval::kNoId);
            }
            return out;
    }
    return out;
}

bool HitsBox(const Box3& b, const Vec3& p, const Vec3& d, double s0, double s1) {
    return BoxTree::SegmentHitsBox(b, p, d, s0, s1);
}

}  // namespace

DeviceRay DeviceShadowRay(const Mat4& deviceFromWorld, const Vec4& lightWorld, const Vec3& p,
                          const Vec3& pWorld) {
    Vec4 h = deviceFromWorld * lightWorld;
    const Vec4 row3{deviceFromWorld.m[3][0], deviceFromWorld.m[3][1], deviceFromWorld.m[3][2],
                    deviceFromWorld.m[3][3]};
    if (Dot(row3, Vec4(pWorld, 1.0)) < 0) h = -h;  // w_p > 0 on the same map
    if (h.w > 0) return {Dehomogenize(h) - p, 1.0};
    if (h.w == 0) return {h.xyz(), HUGE_VAL};
    return {h.xyz() - p * h.w, HUGE_VAL};
}

ShadowTester::ShadowTester(const FlatScene& scene, bool spatialIndex) : scene_(scene) {
    std::vector<Box3> boxes;
    for (const FlatSolid& solid : scene.solids)
        boxes.push_back(scene.nodes[static_cast<std::size_t>(solid.root)].bounds);
    solids_ = BoxTree(boxes, spatialIndex);
    WideNodeTrees wide = WideNodeTrees::Build(scene, spatialIndex);
    wide_ = std::move(wide.trees);
    wideOf_ = std::move(wide.of);
}

IntervalList ShadowTester::Wide(const FlatCsgNode& node, const BoxTree& tree, IntervalList acc,
                                const Vec3& p, const Vec3& d, double s0, double s1) const {
    const std::size_t from = node.op == scene::CsgOp::kDifference ? 1 : 0;
    IntervalList tmp;
    tree.Segment(p, d, s0, s1, [&](std::int32_t k) {
        const int c = node.children[from + static_cast<std::size_t>(k)];
        if (!HitsBox(scene_.nodes[static_cast<std::size_t>(c)].bounds, p, d, s0, s1)) return false;
        const IntervalList child = Node(c, p, d, s0, s1);
        if (node.op == scene::CsgOp::kUnion)
            Union(acc, child, tmp);
        else
            Difference(acc, child, tmp);
        std::swap(acc, tmp);
        return node.op == scene::CsgOp::kDifference && acc.empty();
    });
    return acc;
}

IntervalList ShadowTester::LiteralOnLine(const FlatHalfSpace& h, bool complemented, const Vec3& p,
                                         const Vec3& d) {
    IntervalList set;
    if (h.IsQuartic()) {
        // Any direction: the homogeneous line (p, 1) + s (d, 0) (math/quartic_surface.h).
        const QuarticLineSet l = h.quartic->OnLine(Vec4(p, 1), Vec4(d, 0));
        for (int i = 0; i < l.count; ++i)
            set.Append(l.lo[static_cast<std::size_t>(i)], 0, l.hi[static_cast<std::size_t>(i)], 0);
    } else if (h.isPlane) {
        const Plane& pl = h.plane;
        set = NonPositive(0, 0.5 * (pl.a * d.x + pl.b * d.y + pl.c * d.z), pl.Evaluate(p));
    } else {
        const Quadric& q = h.quadric;
        const double a = q.A() * d.x * d.x + q.B() * d.y * d.y + q.C() * d.z * d.z +
                         2 * (q.D() * d.x * d.y + q.E() * d.y * d.z + q.F() * d.x * d.z);
        const double hh = 0.5 * Dot(q.Gradient(p), d);
        set = NonPositive(a, hh, q.Evaluate(p));
    }
    if (!complemented) return set;
    IntervalList out;
    Complement(set, out);
    return out;
}

IntervalList ShadowTester::Node(int n, const Vec3& p, const Vec3& d, double s0, double s1) const {
    const FlatCsgNode& node = scene_.nodes[static_cast<std::size_t>(n)];
    if (node.isLeaf) {
        // The fold starts from the window (s0, s1) rather than the whole line: every node's set is
        // then its exact set ∩ (s0, s1) (∩ distributes over ∪, ∩ and −), all that Blocked looks
        // at, and a body the segment leaves at once (a surface facing the light) empties after a
        // few literals, so a difference skips its subtrahends.
        IntervalList acc, tmp;
        acc.Append(s0, Interval::kNoId, s1, Interval::kNoId);
        for (const FlatLiteral& l : scene_.bodies[static_cast<std::size_t>(node.body)].literals) {
            Intersection(acc,
                         LiteralOnLine(scene_.halfSpaces[static_cast<std::size_t>(l.halfSpace)],
                                       l.complemented, p, d),
                         tmp);
            std::swap(acc, tmp);
            if (acc.empty()) break;
        }
        return acc;
    }
    const std::int32_t wide = wideOf_[static_cast<std::size_t>(n)];
    if (wide >= 0) {
        IntervalList acc;
        if (node.op == scene::CsgOp::kDifference) {
            const int c = node.children[0];
            if (!HitsBox(scene_.nodes[static_cast<std::size_t>(c)].bounds, p, d, s0, s1))
                return acc;
            acc = Node(c, p, d, s0, s1);
            if (acc.empty()) return acc;
        }
        return Wide(node, wide_[static_cast<std::size_t>(wide)], std::move(acc), p, d, s0, s1);
    }
    IntervalList acc, tmp;
    bool first = true;
    for (int c : node.children) {
        // A child whose box the segment misses is ∅ on it (boxes are conservative), which is all
        // that matters here: the answer only looks at (s0, s1).
        const bool misses =
            !HitsBox(scene_.nodes[static_cast<std::size_t>(c)].bounds, p, d, s0, s1);
        if (first) {
            first = false;
            if (!misses) acc = Node(c, p, d, s0, s1);
            if (acc.empty() && node.op != scene::CsgOp::kUnion) return acc;
            continue;
        }
        if (misses) {
            if (node.op == scene::CsgOp::kIntersection) return {};
            continue;  // A ∪ ∅ = A − ∅ = A
        }
        const IntervalList child = Node(c, p, d, s0, s1);
        switch (node.op) {
            case scene::CsgOp::kUnion:
                Union(acc, child, tmp);
                break;
            case scene::CsgOp::kIntersection:
                Intersection(acc, child, tmp);
                break;
            case scene::CsgOp::kDifference:
                Difference(acc, child, tmp);
                break;
        }
        std::swap(acc, tmp);
        if (acc.empty() && node.op != scene::CsgOp::kUnion) return acc;
    }
    return acc;
}

bool ShadowTester::Blocked(const Vec3& p, const Vec3& d, double sMax) const {
    const double len = Length(d);
    if (!(len > 0)) return false;
    const double s0 = 1e-4 / len;
    return solids_.Segment(p, d, s0, sMax, [&](std::int32_t k) {
        const FlatSolid& solid = scene_.solids[static_cast<std::size_t>(k)];
        const FlatCsgNode& root = scene_.nodes[static_cast<std::size_t>(solid.root)];
        if (!HitsBox(root.bounds, p, d, s0, sMax)) return false;
        for (const Interval& i : Node(solid.root, p, d, s0, sMax))
            if (i.hi > s0 && i.lo < sMax) return true;
        return false;
    });
}

}  // namespace quadrix
