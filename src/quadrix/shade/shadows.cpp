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

// The polynomial a·s² + 2h·s + c of a plane or quadric half-space along p + s·d (the file
// comment of shadows.h); the literal's set is where it is <= 0.
struct LinePolynomial {
    double a, h, c;
};

// Inlined into its callers (Body: once per literal of every shadow ray): as a call it was about
// 2 % of a shadowed picture's instructions.
[[gnu::always_inline]] inline LinePolynomial OnLine(const FlatHalfSpace& h, const Vec3& p,
                                                    const Vec3& d) {
    if (h.isPlane) {
        const Plane& pl = h.plane;
        return {0, 0.5 * (pl.a * d.x + pl.b * d.y + pl.c * d.z), pl.Evaluate(p)};
    }
    const Quadric& q = h.quadric;
    const double a = q.A() * d.x * d.x + q.B() * d.y * d.y + q.C() * d.z * d.z +
                     2 * (q.D() * d.x * d.y + q.E() * d.y * d.z + q.F() * d.x * d.z);
    return {a, 0.5 * Dot(q.Gradient(p), d), q.Evaluate(p)};
}

// A plane or quadric literal's set on the line: where a·s² + 2h·s + c <= 0 (regularised), or its
// closed complement for a complemented literal, as at most two intervals appended by
// IntervalList::Append's rule (points and NaN dropped, touching pieces merged; the complement
// is Complement's loop). The set is ∅, ℝ, a half-line, [t0, t1] or (−∞, t0] ∪ [t1, ∞), and the
// complement of each is again one of these: two pieces at most.
struct Pieces {
    double lo[2] = {0, 0}, hi[2] = {0, 0};
    int n = 0;
    void Append(double l, double h) {
        if (!(l < h)) return;
        if (n > 0 && l <= hi[n - 1]) {
            if (h > hi[n - 1]) hi[n - 1] = h;
            return;
        }
        lo[n] = l;
        hi[n] = h;
        ++n;
    }
};

// Built in place into `out` (a Pieces returned by value was copied through the stack, and the
// copy's wide loads of narrow stores stalled: 15 % slower than the lists).
void LiteralPieces(const LinePolynomial& q, bool complemented, Pieces& out) {
    Pieces raw;
    Pieces& set = complemented ? raw : out;
    // A plane's root is made inline by SolveQuadratic (quadratic.h) without a call.
    const QuadraticRoots r = SolveQuadratic(q.a, q.h, q.c);
    switch (r.kind) {
        case RootKind::kAll:
            set.Append(-kInf, kInf);
            break;
        case RootKind::kNone:
        case RootKind::kDouble:
            // No sign change: the sign of a (of c when a = 0, h = 0).
            if (q.a < 0 || (q.a == 0 && q.h == 0 && q.c <= 0)) set.Append(-kInf, kInf);
            break;
        case RootKind::kSingle:
            if (q.h > 0)
                set.Append(-kInf, r.t0);
            else
                set.Append(r.t0, kInf);
            break;
        case RootKind::kTwo:
            if (q.a > 0) {
                set.Append(r.t0, r.t1);
            } else {
                set.Append(-kInf, r.t0);
                set.Append(r.t1, kInf);
            }
            break;
    }
    if (!complemented) return;
    double lo = -kInf;  // Complement
    for (int i = 0; i < raw.n; ++i) {
        out.Append(lo, raw.lo[i]);
        lo = raw.hi[i];
    }
    out.Append(lo, kInf);
}

// A plane literal's set on the line where SolveQuadratic takes the root inline (a plane crossed
// by the line, coefficients in its unscaled range: the common case): LiteralPieces' one piece,
// [lo, hi] (below the root where the polynomial rises, above it for the complement; lo >= hi
// where LiteralPieces drops it), from the same numbers and comparisons, without the Pieces.
// false: LiteralPieces decides. q is a plane's (a = 0).
[[gnu::always_inline]] inline bool PlanePiece(const LinePolynomial& q, bool complemented,
                                              double& lo, double& hi) {
    const double ah = std::fabs(q.h), ac = std::fabs(q.c);
    if (!(q.h != 0 && ah <= 0x1p200 && ac <= 0x1p200 && (ah >= 0x1p-200 || ac >= 0x1p-200)))
        return false;
    const double root = -q.c / (2.0 * q.h);  // SolveQuadratic's inline root
    const bool below = (q.h > 0) != complemented;
    lo = below ? -kInf : root;
    hi = below ? root : kInf;
    return true;
}

// The set of a half-space literal on the line, into `set`; `tmp` is scratch.
void LiteralInto(const FlatHalfSpace& h, bool complemented, const Vec3& p, const Vec3& d,
                 IntervalList& set, IntervalList& tmp) {
    if (h.IsQuartic()) {
        IntervalList& raw = complemented ? tmp : set;
        // Any direction: the homogeneous line (p, 1) + s (d, 0) (math/quartic_surface.h).
        const QuarticLineSet l = h.quartic->OnLine(Vec4(p, 1), Vec4(d, 0));
        raw.clear();
        for (int i = 0; i < l.count; ++i)
            raw.Append(l.lo[static_cast<std::size_t>(i)], 0, l.hi[static_cast<std::size_t>(i)], 0);
        if (complemented) Complement(tmp, set);
        return;
    }
    Pieces pieces;
    LiteralPieces(OnLine(h, p, d), complemented, pieces);
    set.clear();
    for (int i = 0; i < pieces.n; ++i)
        set.Append(pieces.lo[i], Interval::kNoId, pieces.hi[i], Interval::kNoId);
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
    DeviceRay ray;
    if (h.w > 0) {
        ray.d = Dehomogenize(h) - p;
        ray.sMax = 1.0;
    } else {
        ray.d = h.w == 0 ? h.xyz() : h.xyz() - p * h.w;
    }
    ray.length = Length(ray.d);
    return ray;
}

ShadowTester::ShadowTester(const FlatScene& scene, bool spatialIndex,
                           std::shared_ptr<const WideNodeTrees> wide)
    : scene_(scene), wideTrees_(std::move(wide)) {
    std::vector<Box3> boxes;
    for (const FlatSolid& solid : scene.solids)
        boxes.push_back(scene.nodes[static_cast<std::size_t>(solid.root)].bounds);
    solids_ = BoxTree(boxes, spatialIndex);
    if (!wideTrees_) wideTrees_ = WideNodeTrees::Shared(scene, spatialIndex);
    wide_ = wideTrees_->trees.data();
    wideOf_ = wideTrees_->of.data();
    // The deepest node below a root (the root at depth 0), without recursion: a node's depth is
    // its parent's + 1, walked from every root.
    subtrahendOf_.assign(scene.bodies.size(), -1);
    leafOf_.assign(scene.bodies.size(), -1);
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        const FlatCsgNode& node = scene.nodes[n];
        if (node.isLeaf || node.op != scene::CsgOp::kDifference) continue;
        for (std::size_t j = 1; j < node.children.size(); ++j) {
            const FlatCsgNode& c = scene.nodes[static_cast<std::size_t>(node.children[j])];
            if (c.isLeaf && c.body >= 0 && static_cast<std::size_t>(c.body) < scene.bodies.size()) {
                subtrahendOf_[static_cast<std::size_t>(c.body)] = static_cast<std::int32_t>(n);
                leafOf_[static_cast<std::size_t>(c.body)] = node.children[j];
            }
        }
    }
    if (scene.nodes.size() <= kReachNodes) {
        leavesOf_.assign(scene.bodies.size(), 0);
        for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
            const FlatCsgNode& node = scene.nodes[n];
            if (node.isLeaf && node.body >= 0 &&
                static_cast<std::size_t>(node.body) < scene.bodies.size())
                leavesOf_[static_cast<std::size_t>(node.body)] |= std::uint64_t{1} << n;
        }
        // The leaves reached from a root through unions, intersections and differences' first
        // children only (a node reached by two paths counts when either is such a path).
        std::vector<std::int32_t> positive;
        for (const FlatSolid& solid : scene.solids) positive.push_back(solid.root);
        std::uint64_t seen = 0;
        while (!positive.empty()) {
            const auto n = static_cast<std::size_t>(positive.back());
            positive.pop_back();
            if (n >= scene.nodes.size() || (seen >> n & 1)) continue;
            seen |= std::uint64_t{1} << n;
            const FlatCsgNode& node = scene.nodes[n];
            if (node.isLeaf) {
                positiveLeaves_ |= std::uint64_t{1} << n;
            } else if (node.op == scene::CsgOp::kDifference) {
                if (!node.children.empty()) positive.push_back(node.children[0]);
            } else {
                for (int c : node.children) positive.push_back(c);
            }
        }
    }
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

void ShadowTester::Wide(const FlatCsgNode& node, std::int32_t wide, const Vec3& p, const Vec3& d,
                        double s0, double s1, std::vector<IntervalList*>& slots, std::size_t k,
                        bool anyHit, const Walk& walk) const {
    const std::size_t from = node.op == scene::CsgOp::kDifference ? 1 : 0;
    const bool union_ = node.op == scene::CsgOp::kUnion;
    Query(static_cast<std::size_t>(wide) + 1, walk.view, p, d, s0, s1, [&](std::int32_t i) {
        const int c = node.children[from + static_cast<std::size_t>(i)];
        if (!NodeHits(c, p, d, s0, s1, walk)) return false;
        Node(c, p, d, s0, s1, slots, k + 1, anyHit && union_, walk);
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

IntervalList ShadowTester::BodyOnSegment(int body, const Vec3& p, const Vec3& d, double s0,
                                         double s1, bool generic) const {
    std::vector<IntervalList> lists(5);
    std::vector<IntervalList*> slots;
    for (IntervalList& l : lists) slots.push_back(&l);
    if (generic)
        BodyGeneric(body, p, d, s0, s1, slots, 0);
    else
        Body(body, p, d, s0, s1, slots, 0);
    return *slots[0];
}

// The fold starts from the window (s0, s1) rather than the whole line: every node's set is then
// its exact set ∩ (s0, s1) (∩ distributes over ∪, ∩ and −), all that Blocked looks at, and a body
// the segment leaves at once (a surface facing the light) empties after a few literals, so a
// difference skips its subtrahends. Lists: a literal's set at k+1 (k+2 scratch), the fold at k+3.
void ShadowTester::BodyGeneric(int body, const Vec3& p, const Vec3& d, double s0, double s1,
                               std::vector<IntervalList*>& slots, std::size_t k) const {
    slots[k]->clear();
    slots[k]->Append(s0, Interval::kNoId, s1, Interval::kNoId);
    for (const FlatLiteral& l : scene_.bodies[static_cast<std::size_t>(body)].literals) {
        ++tRayLiterals;  // the shading budget's count (shade_budget.h)
        LiteralInto(scene_.halfSpaces[static_cast<std::size_t>(l.halfSpace)], l.complemented, p, d,
                    *slots[k + 1], *slots[k + 2]);
        Intersection(*slots[k], *slots[k + 1], *slots[k + 3]);
        std::swap(slots[k], slots[k + 3]);
        if (slots[k]->empty()) break;
    }
}

bool ShadowTester::OriginLiteralMeets(int body, int halfSpace, const Vec3& p, const Vec3& d,
                                      double s0, double s1) const {
    // The literal cut to [s0, s1] as Body's loop cuts (the same comparisons).
    for (const FlatLiteral& l : scene_.bodies[static_cast<std::size_t>(body)].literals) {
        if (l.halfSpace != halfSpace) continue;
        const FlatHalfSpace& h = scene_.halfSpaces[static_cast<std::size_t>(halfSpace)];
        if (h.IsQuartic()) return true;
        ++tRayLiterals;
        const LinePolynomial q = OnLine(h, p, d);
        double pieceLo, pieceHi;
        if (h.isPlane && PlanePiece(q, l.complemented, pieceLo, pieceHi)) {
            if (!(pieceLo < pieceHi)) return false;
            const double lo = pieceLo >= s0 ? pieceLo : s0;
            const double hi = s1 <= pieceHi ? s1 : pieceHi;
            return lo < hi;
        }
        Pieces set;
        LiteralPieces(q, l.complemented, set);
        bool meets = false;
        for (int j = 0; j < set.n; ++j) {
            const double lo = set.lo[j] >= s0 ? set.lo[j] : s0;
            const double hi = s1 <= set.hi[j] ? s1 : set.hi[j];
            meets |= lo < hi;
        }
        return meets;
    }
    return true;  // not a literal of the body: no answer from it
}

// BodyGeneric's fold while the set is one interval [lo, hi] (a convex body, and most others on a
// short segment): each literal's Pieces cut it by the rules of IntersectionOfOne (the later start,
// the earlier end; empty unless lo < hi), with no list made. A literal that splits it in two, or
// a quartic one, hands the set to the lists for the rest of the literals. The endpoints are those
// of BodyGeneric (the tests compare them); the ids are not kept (all kNoId: shadow rays ask only
// where the set is).
void ShadowTester::Body(int body, const Vec3& p, const Vec3& d, double s0, double s1,
                        std::vector<IntervalList*>& slots, std::size_t k, int first) const {
    const std::vector<FlatLiteral>& literals =
        scene_.bodies[static_cast<std::size_t>(body)].literals;
    if (first >= 0 && !OriginLiteralMeets(body, first, p, d, s0, s1)) {
        slots[k]->clear();  // empty there: the body is empty (file comment)
        return;
    }
    double lo = s0, hi = s1;
    std::size_t i = 0;
    bool lists = false;  // the set is in *slots[k] from literal i on
    for (; i < literals.size(); ++i) {
        const FlatHalfSpace& h = scene_.halfSpaces[static_cast<std::size_t>(literals[i].halfSpace)];
        if (h.IsQuartic()) {
            slots[k]->clear();
            slots[k]->Append(lo, Interval::kNoId, hi, Interval::kNoId);
            lists = true;
            break;
        }
        ++tRayLiterals;
        double pieceLo, pieceHi;
        if (h.isPlane && PlanePiece(OnLine(h, p, d), literals[i].complemented, pieceLo, pieceHi)) {
            // The one piece cut as below (set.n == 1), or empty (set.n == 0).
            if (!(pieceLo < pieceHi)) {
                hi = lo;
            } else {
                if (pieceLo >= lo) lo = pieceLo;
                if (!(hi <= pieceHi)) hi = pieceHi;
            }
            if (!(lo < hi)) break;
            continue;
        }
        Pieces set;
        LiteralPieces(OnLine(h, p, d), literals[i].complemented, set);
        if (set.n == 0) {
            hi = lo;  // empty
        } else if (set.n == 1) {
            if (set.lo[0] >= lo) lo = set.lo[0];
            if (!(hi <= set.hi[0])) hi = set.hi[0];
        } else {
            // [lo, hi] ∩ [a0, b0] and [lo, hi] ∩ [a1, b1], b0 < a1: separated pieces.
            const double l0 = set.lo[0] >= lo ? set.lo[0] : lo;
            const double h0 = hi <= set.hi[0] ? hi : set.hi[0];
            const double l1 = set.lo[1] >= lo ? set.lo[1] : lo;
            const double h1 = hi <= set.hi[1] ? hi : set.hi[1];
            const bool first = l0 < h0, second = l1 < h1;
            if (first && second) {
                slots[k]->clear();
                slots[k]->Append(l0, Interval::kNoId, h0, Interval::kNoId);
                slots[k]->Append(l1, Interval::kNoId, h1, Interval::kNoId);
                lists = true;
                ++i;
                break;
            }
            if (first) {
                lo = l0;
                hi = h0;
            } else if (second) {
                lo = l1;
                hi = h1;
            } else {
                hi = lo;
            }
        }
        if (!(lo < hi)) break;
    }
    if (!lists) {
        slots[k]->clear();
        slots[k]->Append(lo, Interval::kNoId, hi, Interval::kNoId);
        return;
    }
    for (; i < literals.size(); ++i) {  // BodyGeneric's loop from literal i
        ++tRayLiterals;
        LiteralInto(scene_.halfSpaces[static_cast<std::size_t>(literals[i].halfSpace)],
                    literals[i].complemented, p, d, *slots[k + 1], *slots[k + 2]);
        Intersection(*slots[k], *slots[k + 1], *slots[k + 3]);
        std::swap(slots[k], slots[k + 3]);
        if (slots[k]->empty()) break;
    }
}

double ShadowTester::PastOrigin(const Vec3& p, const Vec3& d, double s0, double s1,
                                std::vector<IntervalList*>& slots, std::size_t k,
                                const Walk& walk) const {
    // The body's set is the one the node's subtrahends' union or fold takes in (the same call),
    // so the node's set on (s0, t) is empty, and on (t, s1) every operand's and subtrahend's set
    // is the one made on (s0, s1) cut to (t, s1): the folds start from the window and cut it by
    // the same comparisons of the same roots (shadows.h). The answer on (s0, s1) is the same. A
    // leaf whose box the segment misses is not taken in (as there), whatever its literals say.
    const std::size_t b = static_cast<std::size_t>(walk.origin.body);
    if (!NodeHits(leafOf_[b], p, d, s0, s1, walk)) return s0;
    Body(walk.origin.body, p, d, s0, s1, slots, k + 1, walk.origin.halfSpace);
    const IntervalList& in = *slots[k + 1];
    if (in.empty() || !(in.begin()->lo <= s0)) return s0;
    return in.begin()->hi;
}

void ShadowTester::Node(int n, const Vec3& p, const Vec3& d, double s0, double s1,
                        std::vector<IntervalList*>& slots, std::size_t k, bool anyHit,
                        const Walk& walk) const {
    const FlatCsgNode& node = scene_.nodes[static_cast<std::size_t>(n)];
    if (node.isLeaf) {
        Body(node.body, p, d, s0, s1, slots, k,
             node.body == walk.origin.body ? walk.origin.halfSpace : -1);
        return;
    }
    if (walk.origin.body >= 0 &&
        subtrahendOf_[static_cast<std::size_t>(walk.origin.body)] == static_cast<std::int32_t>(n)) {
        s0 = PastOrigin(p, d, s0, s1, slots, k, walk);
        if (!(s0 < s1)) {
            slots[k]->clear();
            return;
        }
    }
    if (anyHit && node.op == scene::CsgOp::kDifference && node.children.size() >= 2) {
        const FlatCsgNode& minuend = scene_.nodes[static_cast<std::size_t>(node.children[0])];
        if (!minuend.isLeaf && minuend.op == scene::CsgOp::kUnion) {
            DistributedDifference(n, p, d, s0, s1, slots, k, walk);
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
            if (!NodeHits(c, p, d, s0, s1, walk)) return;
            Node(c, p, d, s0, s1, slots, k, false, walk);
            if (slots[k]->empty()) return;
        }
        Wide(node, wide, p, d, s0, s1, slots, k, anyHit, walk);
        return;
    }
    bool first = true;
    slots[k]->clear();
    for (int c : node.children) {
        // A child whose box the segment misses is ∅ on it (boxes are conservative), which is all
        // that matters here: the answer only looks at (s0, s1).
        const bool misses = !NodeHits(c, p, d, s0, s1, walk);
        if (first) {
            first = false;
            if (!misses) Node(c, p, d, s0, s1, slots, k, anyHit && union_, walk);
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
        Node(c, p, d, s0, s1, slots, k + 1, anyHit && union_, walk);
        Fold(node.op, slots, k);
        if (slots[k]->empty() ? !union_ : union_ && anyHit) return;
    }
}

void ShadowTester::DistributedDifference(int n, const Vec3& p, const Vec3& d, double s0, double s1,
                                         std::vector<IntervalList*>& slots, std::size_t k,
                                         const Walk& walk) const {
    const FlatCsgNode& node = scene_.nodes[static_cast<std::size_t>(n)];
    const int m = node.children[0];
    const FlatCsgNode& minuend = scene_.nodes[static_cast<std::size_t>(m)];
    slots[k]->clear();
    // Node n's box passed this test (every Node call follows a NodeHits of the same segment);
    // the minuend's box is usually the same box (a difference is bounded by its minuend), and
    // then so is the answer.
    const bool sameBox = node.bounds.lo == minuend.bounds.lo && node.bounds.hi == minuend.bounds.hi;
    if (!sameBox && !NodeHits(m, p, d, s0, s1, walk)) return;
    bool haveSubtrahends = false;
    // Operand c of the minuend's union: its set in slots[k + 1]; the subtrahends' union, made
    // the first time an operand meets the segment, in slots[k]; true (the difference's set, not
    // empty, left in slots[k]) when c − subtrahends meets the segment.
    auto operand = [&](int c) {
        if (!NodeHits(c, p, d, s0, s1, walk)) return false;
        Node(c, p, d, s0, s1, slots, k + 1, false, walk);
        if (slots[k + 1]->empty()) return false;
        if (!haveSubtrahends) {
            haveSubtrahends = true;
            auto subtrahend = [&](int b) {
                if (!NodeHits(b, p, d, s0, s1, walk)) return false;
                Node(b, p, d, s0, s1, slots, k + 2, false, walk);
                Union(*slots[k], *slots[k + 2], *slots[k + 3]);
                std::swap(slots[k], slots[k + 3]);
                return false;
            };
            const std::int32_t wide = wideOf_[static_cast<std::size_t>(n)];
            if (wide >= 0) {
                Query(static_cast<std::size_t>(wide) + 1, walk.view, p, d, s0, s1,
                      [&](std::int32_t i) {
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
        found = Query(
            static_cast<std::size_t>(wide) + 1, walk.view, p, d, s0, s1,
            [&](std::int32_t i) { return operand(minuend.children[static_cast<std::size_t>(i)]); });
    } else {
        for (int c : minuend.children)
            if ((found = operand(c))) break;
    }
    if (!found) slots[k]->clear();
}

int ShadowTester::AddDirection(const Vec3& d) {
    std::vector<BoxTree::HalfLineView> views;
    views.push_back(solids_.ViewAlong(d));
    for (const BoxTree& t : wideTrees_->trees) views.push_back(t.ViewAlong(d));
    views_.push_back(std::move(views));
    return static_cast<int>(views_.size()) - 1;
}

bool ShadowTester::NodeHits(int n, const Vec3& p, const Vec3& d, double s0, double s1,
                            const Walk& walk) const {
    // A node without its bit in the reach: no segment of the run meets its box (MayMeet).
    if ((walk.reach >> (static_cast<unsigned>(n) & 63) & 1) == 0) return false;
    // The slab test, not the view's looser one: a node the segment misses is never evaluated
    // (its literals could give a rounding-level sliver there). The view's test as a first filter
    // saved nothing measurable on the machined part (docs/performance.md).
    return HitsBox(scene_.nodes[static_cast<std::size_t>(n)].bounds, p, d, s0, s1);
}

std::uint64_t ShadowTester::MayMeet(const Vec3& lo, const Vec3& hi, const DeviceRay& ray) const {
    if (leavesOf_.empty() || !(ray.length > 0)) return kReachAll;
    // Blocked's earliest start: (1e-4 + 1024 · DepthRounding(z)) / |d| >= 1e-4 / |d| (a rounded
    // sum of 1e-4 and a non-negative number is at least 1e-4, and the quotient is monotone).
    const double s0 = 1e-4 / ray.length;
    std::uint64_t reach = 0;
    for (std::size_t n = 0; n < scene_.nodes.size(); ++n) {
        const FlatCsgNode& node = scene_.nodes[n];
        if (!BoxTree::SegmentsMayHitBox(node.bounds, lo, hi, ray.d, s0, ray.sMax)) continue;
        if (node.isLeaf && node.body >= 0 &&
            static_cast<std::size_t>(node.body) < scene_.bodies.size() &&
            BodyBehindAPlane(node.body, lo, hi, ray.d))
            continue;
        reach |= std::uint64_t{1} << n;
    }
    return reach;
}

bool ShadowTester::BodyBehindAPlane(int body, const Vec3& lo, const Vec3& hi, const Vec3& d) const {
    for (const FlatLiteral& l : scene_.bodies[static_cast<std::size_t>(body)].literals) {
        const FlatHalfSpace& h = scene_.halfSpaces[static_cast<std::size_t>(l.halfSpace)];
        if (!h.isPlane || h.IsQuartic()) continue;
        const Plane& pl = h.plane;
        // OnLine's coefficients: h (the same for every start, d being the run's) and c = P(p).
        // P's rounded value is monotone in each coordinate (a rounded product by a fixed
        // coefficient and a rounded sum are), so its least and greatest values over the starts
        // are those at two corners of the box, chosen by the coefficients' signs.
        const double lineH = OnLine(h, lo, d).h;
        const Vec3 low{pl.a >= 0 ? lo.x : hi.x, pl.b >= 0 ? lo.y : hi.y, pl.c >= 0 ? lo.z : hi.z};
        const Vec3 high{pl.a >= 0 ? hi.x : lo.x, pl.b >= 0 ? hi.y : lo.y, pl.c >= 0 ? hi.z : lo.z};
        const double cLo = pl.Evaluate(low), cHi = pl.Evaluate(high);
        // PlanePiece's range, so that it, not LiteralPieces, takes every start's polynomial.
        const double ah = std::fabs(lineH);
        if (!(ah >= 0x1p-200 && ah <= 0x1p200 && std::fabs(cLo) <= 0x1p200 &&
              std::fabs(cHi) <= 0x1p200))
            continue;
        // Its piece is (−∞, root], root = −c / 2h < 0 < s0: where the line leaves the set (h > 0
        // for the literal, h < 0 for its complement) from a start outside it (c > 0, c < 0).
        if (!l.complemented ? lineH > 0 && cLo > 0 : lineH < 0 && cHi < 0) return true;
    }
    return false;
}

bool ShadowTester::Blocked(const Vec3& p, const Vec3& d, double sMax) const {
    return Blocked(p, DeviceRay{d, sMax, Length(d)});
}

bool ShadowTester::Blocked(const Vec3& p, const DeviceRay& ray, const ShadowOrigin& origin,
                           std::uint64_t reach) const {
    const Vec3& d = ray.d;
    const double sMax = ray.sMax;
    const double len = ray.length;
    if (!(len > 0)) return false;
    // The segment starts past the surface p lies on: 1e-4 pixel, plus far more than the rounding
    // of p's depth to the Frame's float (frame.h; half an ulp, 1.5e-5 pixel at |z| = 256), so
    // that a point rounded into its own solid does not shadow itself unless the light grazes
    // the surface within about 0.06 degrees. The start is then 0.015 pixel out at |z| = 256.
    const double s0 = (1e-4 + 1024 * DepthRounding(p.z)) / len;
    // No body but the origin's may be met where it adds to a solid (Reach, shadows.h): where its
    // literal of the surface alone misses the segment, its set does, and so does every solid's.
    if (reach != kReachAll && origin.body >= 0 && origin.halfSpace >= 0 &&
        (reach & positiveLeaves_ & ~leavesOf_[static_cast<std::size_t>(origin.body)]) == 0 &&
        !OriginLiteralMeets(origin.body, origin.halfSpace, p, d, s0, sMax))
        return false;
    std::vector<IntervalList*>& slots =
        ThreadScratch(static_cast<std::size_t>(maxDepth_) + 6).slots;
    // The trees' views along d serve a half-line of their direction (AddDirection).
    Walk walk;
    walk.view = ray.view >= 0 && sMax == HUGE_VAL ? ray.view : -1;
    walk.origin = origin;
    walk.reach = reach;
    auto solidBlocks = [&](std::int32_t i) {
        const FlatSolid& solid = scene_.solids[static_cast<std::size_t>(i)];
        if (!NodeHits(solid.root, p, d, s0, sMax, walk)) return false;
        Node(solid.root, p, d, s0, sMax, slots, 0, true, walk);
        for (const Interval& in : *slots[0])
            if (in.hi > s0 && in.lo < sMax) return true;
        return false;
    };
    // One solid (one CSG object, the usual part): the tree of solids would only visit it, after
    // a test of its box no tighter than the root's own slab test; so that test alone.
    if (scene_.solids.size() == 1) return solidBlocks(0);
    return Query(0, walk.view, p, d, s0, sMax, solidBlocks);
}

}  // namespace quadrix
