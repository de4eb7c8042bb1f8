#include "quadrix/shade/shadows.h"

#include <cmath>

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
        s0 = std::fmax(s0, t0);
        s1 = std::fmin(s1, t1);
        if (s0 > s1) return false;
    }
    return true;
}

}  // namespace

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
        IntervalList acc = IntervalList::All(), tmp;
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
    for (const FlatSolid& solid : scene_.solids) {
        const FlatCsgNode& root = scene_.nodes[static_cast<std::size_t>(solid.root)];
        if (!HitsBox(root.bounds, p, d, s0, sMax)) continue;
        for (const Interval& i : Node(solid.root, p, d, s0, sMax))
            if (i.hi > s0 && i.lo < sMax) return true;
    }
    return false;
}

}  // namespace quadrix
