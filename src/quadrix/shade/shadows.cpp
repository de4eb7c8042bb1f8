#include "quadrix/shade/shadows.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "quadrix/flatten/wide_node_trees.h"
#include "quadrix/frame/frame.h"
#include "quadrix/math/quadratic.h"
#include "quadrix/util/ray_work.h"

namespace quadrix {

namespace {

constexpr double kInf = HUGE_VAL;

// Where a·s² + 2h·s + c <= 0 (regularised), into `out` (cleared first).
void NonPositive(double a, double h, double c, IntervalList& out) {
    const QuadraticRoots r = SolveQuadratic(a, h, c);
    out.clear();
    switch (r.kind) {
        case RootKind::kAll:
            out.Append(-kInf, Interval::kNoId, kInf, Interval::kNoId);
            return;
        case RootKind::kNone:
        case RootKind::kDouble:
            // No sign change: the sign of a (of c when a = 0, h = 0).
            if (a < 0 || (a == 0 && h == 0 && c <= 0))
                out.Append(-kInf, Interval::kNoId, kInf, Interval::kNoId);
            return;
        case RootKind::kSingle:
            if (h > 0)
                out.Append(-kInf, Interval::kNoId, r.t0, 0);
            else
                out.Append(r.t0, 0, kInf, Interval::kNoId);
            return;
        case RootKind::kTwo:
            if (a > 0) {
                out.Append(r.t0, 0, r.t1, 0);
            } else {
                out.Append(-kInf, Interval::kNoId, r.t0, 0);
                out.Append(r.t1, 0, kInf, Interval::kNoId);
            }
            return;
    }
}

// The set of a half-space literal on the line, into `set`; `tmp` is scratch.
void LiteralInto(const FlatHalfSpace& h, bool complemented, const Vec3& p, const Vec3& d,
                 IntervalList& set, IntervalList& tmp) {
    IntervalList& raw = complemented ? tmp : set;
    if (h.IsQuartic()) {
        // Any direction: the homogeneous line (p, 1) + s (d, 0) (math/quartic_surface.h).
        const QuarticLineSet l = h.quartic->OnLine(Vec4(p, 1), Vec4(d, 0));
        raw.clear();
        for (int i = 0; i < l.count; ++i)
            raw.Append(l.lo[static_cast<std::size_t>(i)], 0, l.hi[static_cast<std::size_t>(i)], 0);
    } else if (h.isPlane) {
        const Plane& pl = h.plane;
        NonPositive(0, 0.5 * (pl.a * d.x + pl.b * d.y + pl.c * d.z), pl.Evaluate(p), raw);
    } else {
        const Quadric& q = h.quadric;
        const double a = q.A() * d.x * d.x + q.B() * d.y * d.y + q.C() * d.z * d.z +
                         2 * (q.D() * d.x * d.y + q.E() * d.y * d.z + q.F() * d.x * d.z);
        const double hh = 0.5 * Dot(q.Gradient(p), d);
        NonPositive(a, hh, q.Evaluate(p), raw);
    }
    if (complemented) Complement(tmp, set);
}

// The interval lists of one thread's shadow rays, reused from ray to ray (no ray allocates once
// warm): a node evaluated at slot k leaves its set in *slots[k] and uses slots k+1, k+2, ...
// below it (a child's set at k+1, the fold's output at k+2, taken only after the child
// returned; a body's literal at k+1 and k+2 and its fold's output at k+3). Results move between
// slots by swapping pointers.
struct ShadowScratch {
    std::vector<IntervalList> lists;
    std::vector<IntervalList*> slots;
    void Reserve(std::size_t n) {
        if (slots.size() >= n) return;
        lists = std::vector<IntervalList>(n);
        slots.resize(n);
        for (std::size_t i = 0; i < n; ++i) slots[i] = &lists[i];
    }
};

ShadowScratch& ThreadScratch(std::size_t slots) {
    thread_local ShadowScratch scratch;
    scratch.Reserve(slots);
    return scratch;
}

// Union, intersection or difference of *slots[k] with *slots[k+1], left in *slots[k].
void Fold(scene::CsgOp op, std::vector<IntervalList*>& slots, std::size_t k) {
    switch (op) {
        case scene::CsgOp::kUnion:
            Union(*slots[k], *slots[k + 1], *slots[k + 2]);
            break;
        case scene::CsgOp::kIntersection:
            Intersection(*slots[k], *slots[k + 1], *slots[k + 2]);
            break;
        case scene::CsgOp::kDifference:
            Difference(*slots[k], *slots[k + 1], *slots[k + 2]);
            break;
    }
    std::swap(slots[k], slots[k + 2]);
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
    // The deepest node below a root (the root at depth 0), without recursion: a node's depth is
    // its parent's + 1, walked from every root.
    std::vector<std::pair<std::int32_t, int>> stack;
    for (const FlatSolid& solid : scene.solids) stack.emplace_back(solid.root, 0);
    while (!stack.empty()) {
        const auto [n, depth] = stack.back();
        stack.pop_back();
        maxDepth_ = std::max(maxDepth_, depth);
        const FlatCsgNode& node = scene.nodes[static_cast<std::size_t>(n)];
        if (!node.isLeaf)
            for (int c : node.children) stack.emplace_back(c, depth + 1);
    }
}

void ShadowTester::Wide(const FlatCsgNode& node, const BoxTree& tree, const Vec3& p, const Vec3& d,
                        double s0, double s1, std::vector<IntervalList*>& slots, std::size_t k,
                        bool anyHit) const {
    const std::size_t from = node.op == scene::CsgOp::kDifference ? 1 : 0;
    const bool union_ = node.op == scene::CsgOp::kUnion;
    tree.Segment(p, d, s0, s1, [&](std::int32_t i) {
        const int c = node.children[from + static_cast<std::size_t>(i)];
        if (!HitsBox(scene_.nodes[static_cast<std::size_t>(c)].bounds, p, d, s0, s1)) return false;
        Node(c, p, d, s0, s1, slots, k + 1, anyHit && union_);
        Fold(node.op, slots, k);
        // A union asked only whether it meets the segment is answered by its first child that
        // does; a difference whose minuend is used up stays empty.
        return union_ ? anyHit && !slots[k]->empty() : slots[k]->empty();
    });
}

IntervalList ShadowTester::LiteralOnLine(const FlatHalfSpace& h, bool complemented, const Vec3& p,
                                         const Vec3& d) {
    IntervalList set, tmp;
    LiteralInto(h, complemented, p, d, set, tmp);
    return set;
}

void ShadowTester::Node(int n, const Vec3& p, const Vec3& d, double s0, double s1,
                        std::vector<IntervalList*>& slots, std::size_t k, bool anyHit) const {
    const FlatCsgNode& node = scene_.nodes[static_cast<std::size_t>(n)];
    if (node.isLeaf) {
        // The fold starts from the window (s0, s1) rather than the whole line: every node's set is
        // then its exact set ∩ (s0, s1) (∩ distributes over ∪, ∩ and −), all that Blocked looks
        // at, and a body the segment leaves at once (a surface facing the light) empties after a
        // few literals, so a difference skips its subtrahends.
        slots[k]->clear();
        slots[k]->Append(s0, Interval::kNoId, s1, Interval::kNoId);
        for (const FlatLiteral& l : scene_.bodies[static_cast<std::size_t>(node.body)].literals) {
            ++tRayLiterals;  // the shading budget's count (shade_budget.h)
            LiteralInto(scene_.halfSpaces[static_cast<std::size_t>(l.halfSpace)], l.complemented, p,
                        d, *slots[k + 1], *slots[k + 2]);
            Intersection(*slots[k], *slots[k + 1], *slots[k + 3]);
            std::swap(slots[k], slots[k + 3]);
            if (slots[k]->empty()) break;
        }
        return;
    }
    if (anyHit && node.op == scene::CsgOp::kDifference && node.children.size() >= 2) {
        const FlatCsgNode& minuend = scene_.nodes[static_cast<std::size_t>(node.children[0])];
        if (!minuend.isLeaf && minuend.op == scene::CsgOp::kUnion) {
            DistributedDifference(n, p, d, s0, s1, slots, k);
            return;
        }
    }
    const bool union_ = node.op == scene::CsgOp::kUnion;
    // anyHit: the caller only asks whether the set is empty, so a union may stop at its first
    // child that meets the segment (its set is then not the whole union's, but not empty).
    const std::int32_t wide = wideOf_[static_cast<std::size_t>(n)];
    if (wide >= 0) {
        slots[k]->clear();
        if (node.op == scene::CsgOp::kDifference) {
            const int c = node.children[0];
            if (!HitsBox(scene_.nodes[static_cast<std::size_t>(c)].bounds, p, d, s0, s1)) return;
            Node(c, p, d, s0, s1, slots, k, false);
            if (slots[k]->empty()) return;
        }
        Wide(node, wide_[static_cast<std::size_t>(wide)], p, d, s0, s1, slots, k, anyHit);
        return;
    }
    bool first = true;
    slots[k]->clear();
    for (int c : node.children) {
        // A child whose box the segment misses is ∅ on it (boxes are conservative), which is all
        // that matters here: the answer only looks at (s0, s1).
        const bool misses =
            !HitsBox(scene_.nodes[static_cast<std::size_t>(c)].bounds, p, d, s0, s1);
        if (first) {
            first = false;
            if (!misses) Node(c, p, d, s0, s1, slots, k, anyHit && union_);
            if (slots[k]->empty() ? !union_ : union_ && anyHit) return;
            continue;
        }
        if (misses) {
            if (node.op == scene::CsgOp::kIntersection) {
                slots[k]->clear();
                return;
            }
            continue;  // A ∪ ∅ = A − ∅ = A
        }
        Node(c, p, d, s0, s1, slots, k + 1, anyHit && union_);
        Fold(node.op, slots, k);
        if (slots[k]->empty() ? !union_ : union_ && anyHit) return;
    }
}

void ShadowTester::DistributedDifference(int n, const Vec3& p, const Vec3& d, double s0, double s1,
                                         std::vector<IntervalList*>& slots, std::size_t k) const {
    const FlatCsgNode& node = scene_.nodes[static_cast<std::size_t>(n)];
    const int m = node.children[0];
    const FlatCsgNode& minuend = scene_.nodes[static_cast<std::size_t>(m)];
    slots[k]->clear();
    if (!HitsBox(minuend.bounds, p, d, s0, s1)) return;
    bool haveSubtrahends = false;
    // Operand c of the minuend's union: its set in slots[k + 1]; the subtrahends' union, made
    // the first time an operand meets the segment, in slots[k]; true (the difference's set, not
    // empty, left in slots[k]) when c − subtrahends meets the segment.
    auto operand = [&](int c) {
        if (!HitsBox(scene_.nodes[static_cast<std::size_t>(c)].bounds, p, d, s0, s1)) return false;
        Node(c, p, d, s0, s1, slots, k + 1, false);
        if (slots[k + 1]->empty()) return false;
        if (!haveSubtrahends) {
            haveSubtrahends = true;
            auto subtrahend = [&](int b) {
                if (!HitsBox(scene_.nodes[static_cast<std::size_t>(b)].bounds, p, d, s0, s1))
                    return false;
                Node(b, p, d, s0, s1, slots, k + 2, false);
                Union(*slots[k], *slots[k + 2], *slots[k + 3]);
                std::swap(slots[k], slots[k + 3]);
                return false;
            };
            const std::int32_t wide = wideOf_[static_cast<std::size_t>(n)];
            if (wide >= 0) {
                wide_[static_cast<std::size_t>(wide)].Segment(p, d, s0, s1, [&](std::int32_t i) {
                    return subtrahend(node.children[1 + static_cast<std::size_t>(i)]);
                });
            } else {
                for (std::size_t j = 1; j < node.children.size(); ++j) subtrahend(node.children[j]);
            }
        }
        Difference(*slots[k + 1], *slots[k], *slots[k + 2]);
        if (slots[k + 2]->empty()) return false;
        std::swap(slots[k], slots[k + 2]);
        return true;
    };
    const std::int32_t wide = wideOf_[static_cast<std::size_t>(m)];
    bool found = false;
    if (wide >= 0) {
        found = wide_[static_cast<std::size_t>(wide)].Segment(p, d, s0, s1, [&](std::int32_t i) {
            return operand(minuend.children[static_cast<std::size_t>(i)]);
        });
    } else {
        for (int c : minuend.children)
            if ((found = operand(c))) break;
    }
    if (!found) slots[k]->clear();
}

bool ShadowTester::Blocked(const Vec3& p, const Vec3& d, double sMax) const {
    const double len = Length(d);
    if (!(len > 0)) return false;
    // The segment starts past the surface p lies on: 1e-4 pixel, plus far more than the rounding
    // of p's depth to the Frame's float (frame.h; half an ulp, 1.5e-5 pixel at |z| = 256), so
    // that a point rounded into its own solid does not shadow itself unless the light grazes
    // the surface within about 0.06 degrees. The start is then 0.015 pixel out at |z| = 256.
    const double s0 = (1e-4 + 1024 * DepthRounding(p.z)) / len;
    std::vector<IntervalList*>& slots =
        ThreadScratch(static_cast<std::size_t>(maxDepth_) + 6).slots;
    return solids_.Segment(p, d, s0, sMax, [&](std::int32_t i) {
        const FlatSolid& solid = scene_.solids[static_cast<std::size_t>(i)];
        const FlatCsgNode& root = scene_.nodes[static_cast<std::size_t>(solid.root)];
        if (!HitsBox(root.bounds, p, d, s0, sMax)) return false;
        Node(solid.root, p, d, s0, sMax, slots, 0, true);
        for (const Interval& in : *slots[0])
            if (in.hi > s0 && in.lo < sMax) return true;
        return false;
    });
}

}  // namespace quadrix
