// Conservative bounds of bodies and CSG trees; the method is described in bounds.h. The
// stages live in bounds_math.cpp (a), bounds_critical.cpp (a''), bounds_relaxation.cpp (b1) and
// bounds_search.cpp (b2).
#include "quadrix/flatten/bounds.h"

#include <cmath>
#include <optional>

#include "quadrix/flatten/bottom_up.h"
#include "quadrix/flatten/bounds_internal.h"
#include "quadrix/flatten/literal_cache.h"
#include "quadrix/math/symmetric_eigen.h"

namespace quadrix {

using namespace bounds_detail;

namespace {
double FrobeniusNorm(const double a[3][3]) {
    double s = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s += a[i][j] * a[i][j];
    return std::sqrt(s);
}
}  // namespace

Box3 LiteralBox(const FlatHalfSpace& halfSpace, bool complemented) {
    Vec3 centre;
    bool hasCentre;
    return AnalyticBox(MakeInsideFn(halfSpace, complemented), &centre, &hasCentre);
}

double HalfSpaceScale(const FlatHalfSpace& hs, const Box3* literalBox,
                      const double* quadricExtent) {
    if (hs.IsQuartic()) {  // the largest coordinate of its box
        const Box3 box = hs.quartic->SpaceBounds();
        double s = 0;
        for (int i = 0; i < 3; ++i)
            if (std::isfinite(box.lo[i]) && std::isfinite(box.hi[i]))
                s = std::fmax(s, std::fmax(std::fabs(box.lo[i]), std::fabs(box.hi[i])));
        return s;
    }
    if (hs.isPlane) {
        double n = Length(hs.plane.Normal());
        double s = n > 0 ? std::fabs(hs.plane.d) / n : 0.0;
        return std::isfinite(s) ? s : 0.0;
    }
    // Largest of |b|/|A| (about the distance of the centre), sqrt(|k|/|A|) (about a radius) and
    // the coordinates of the analytic box.
    const Quadric& q = hs.quadric;
    double aMax = 0;
    for (int i = 0; i < 6; ++i) aMax = std::fmax(aMax, std::fabs(q.k[i]));
    double bMax = std::fmax(std::fabs(q.G()), std::fmax(std::fabs(q.H()), std::fabs(q.J())));
    double s = 0;
    if (aMax > 0)
        s = std::fmax(bMax / aMax, std::sqrt(std::fabs(q.K()) / aMax));
    else if (bMax > 0)
        s = std::fabs(q.K()) / bMax;
    // An ellipsoid too ill-conditioned for the analytic box (LiteralBox declines it): its extent
    // |c| + sqrt(R / λmin), c = -A⁻¹b the centre, R = -f(c) (QuadricExtent). A ball scaled by 1e6
    // along x has λmin 1e-12 of the others and a scale of 1 from the largest coefficients, so its
    // 1e6 extent passed 1e-3 × the search limit and was called unbounded. Eigenvalues below 1e-14
    // of the largest are rounding noise (a rotated cylinder; an ellipsoid that elongated is a
    // cylinder to double precision anyway) and are left out. Both come from one inside function
    // and its eigen-decomposition (or from the LiteralCache, which made the same).
    Box3 box;
    double extent = 0;
    if (literalBox && quadricExtent) {
        box = *literalBox;
        extent = *quadricExtent;
    } else {
        InsideEigen eigen;
        const InsideFn f = MakeInsideFn(hs, false, &eigen);
        extent = QuadricExtent(f, eigen);
        Vec3 centre;
        bool hasCentre;
        box = literalBox ? *literalBox : AnalyticBox(f, &centre, &hasCentre);
    }
    if (aMax > 0) s = std::fmax(s, extent);
    for (int i = 0; i < 3; ++i) {
        if (std::isfinite(box.lo[i])) s = std::fmax(s, std::fabs(box.lo[i]));
        if (std::isfinite(box.hi[i])) s = std::fmax(s, std::fabs(box.hi[i]));
    }
    return std::isfinite(s) ? s : 0.0;
}

namespace {

// Stage (a'), bodies of planes only (arbs, prisms, the convex cells of imported meshes): the box
// of a bounded polytope is that of its vertices, the points where three of its planes meet and
// no plane is violated. B0's faces are constraints too (axis-aligned literals were folded into
// B0 and dropped from `shaping`); where B0 is unbounded, the faces of the search region keep the
// enumeration finite, and a feasible vertex on one of them means the polytope is unbounded:
// nullopt, the relaxation decides (it reports unbounded sides). Coefficients are normalised
// (max-abs 1); a triple whose determinant is below 1e-6 of the product of the normals' lengths
// gives an ill-conditioned vertex: skipped when it is clearly infeasible (two faces parallel up
// to rounding meet far away) or involves a search-region face (for a bounded polytope no point of
// those faces is feasible), else not trusted: nullopt. The box is widened by 1e-9 of its
// coordinates and size (rounding allowance). About 30 µs for 6 planes, where the relaxation takes
// ~0.5 ms.
std::optional<Box3> PolytopeBox(const std::vector<InsideFn>& shaping, const Box3& b0,
                                const BoundsOptions& options) {
    constexpr std::size_t kMaxPlanes = 16;
    if (shaping.empty() || shaping.size() > kMaxPlanes) return std::nullopt;
    struct P {
        Vec3 n;
        double k;
        bool artificial;
    };
    std::vector<P> planes;
    for (const InsideFn& f : shaping) {
        if (!f.isPlane) return std::nullopt;
        planes.push_back({{2 * f.b[0], 2 * f.b[1], 2 * f.b[2]}, f.k, false});
    }
    const double limit = options.searchLimit;
    for (int i = 0; i < 3; ++i) {
        Vec3 e;
        e[i] = 1;
        const bool hiReal = b0.hi[i]<limit, loReal = b0.lo[i]> - limit;
        planes.push_back({e, -(hiReal ? b0.hi[i] : limit), !hiReal});
        planes.push_back({-e, loReal ? b0.lo[i] : -limit, !loReal});
    }
    Box3 box;
    const std::size_t m = planes.size();
    for (std::size_t i = 0; i < m; ++i)
        for (std::size_t j = i + 1; j < m; ++j)
            for (std::size_t k = j + 1; k < m; ++k) {
                const P &pa = planes[i], &pb = planes[j], &pc = planes[k];
                const bool artificial = pa.artificial || pb.artificial || pc.artificial;
                const Vec3 &a = pa.n, &b = pb.n, &c = pc.n;
                const Vec3 bc = Cross(b, c), ca = Cross(c, a), ab = Cross(a, b);
                const double det = Dot(a, bc);
                const double scale = Length(a) * Length(b) * Length(c);
                if (det == 0) continue;  // exactly parallel: no vertex here
                const bool illConditioned = !(std::fabs(det) >= 1e-6 * scale);
                if (illConditioned && artificial) continue;
                const Vec3 x = (bc * -pa.k + ca * -pb.k + ab * -pc.k) / det;
                if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z))) {
                    if (illConditioned) continue;  // parallel planes up to rounding
                    return std::nullopt;
                }
                // An ill-conditioned triple (two faces parallel up to rounding, such as the
                // opposite faces of a box) usually meets far outside: it is skipped when it is
                // clearly infeasible, and only a nearly feasible one (a sliver) is left to the
                // relaxation.
                const double rel = illConditioned ? 1e-6 : 1e-9;
                bool in = true;
                for (const P& q : planes) {
                    const double v = Dot(q.n, x) + q.k;
                    const double tol =
                        rel * (std::fabs(q.k) +
                               Length(q.n) * (std::fabs(x.x) + std::fabs(x.y) + std::fabs(x.z)));
                    if (!(v <= tol)) {
                        in = false;
                        break;
                    }
                }
                if (!in) continue;
                if (illConditioned) return std::nullopt;
                if (artificial) return std::nullopt;  // unbounded
                box.Extend(x);
            }
    if (box.Empty()) return std::nullopt;  // empty or degenerate: let the relaxation say so
    for (int i = 0; i < 3; ++i) {
        const double size = box.hi[i] - box.lo[i];
        box.lo[i] -= 1e-9 * (std::fabs(box.lo[i]) + size);
        box.hi[i] += 1e-9 * (std::fabs(box.hi[i]) + size);
    }
    return box;
}

// Stage (a) of one literal: its inside function and analytic box, with the box's centre when it
// has one; from the literal cache when it holds them (literal_cache.h: the same values).
struct LiteralStageA {
    InsideFn f;
    Box3 box;
    Vec3 centre;
    bool hasCentre = false;
};
LiteralStageA StageA(const BoundLiteral& lit, const BoundsOptions& options) {
    if (options.literals && !lit.complemented)
        if (const LiteralCache::Entry* e = options.literals->Find(lit.halfSpace))
            return {e->fn, e->box, e->centre, e->hasCentre};
    LiteralStageA a;
    a.f = MakeInsideFn(*lit.halfSpace, lit.complemented);
    a.box = AnalyticBox(a.f, &a.centre, &a.hasCentre);
    return a;
}

// True when the literal provably holds on all of the finite box b0 (centre c, half-sizes h):
// it cannot shape the set inside b0.
bool HoldsOnAll(const InsideFn& f, const double c[3], const double h[3]) {
    const Range r = RangeFromLocal(EvaluateLocal(f, c), f.a, f.lamMin, f.lamMax, h, nullptr);
    return r.hi <= r.margin;
}

void CentreAndHalf(const Box3& b, double c[3], double h[3]) {
    for (int j = 0; j < 3; ++j) {
        c[j] = 0.5 * b.lo[j] + 0.5 * b.hi[j];
        h[j] = 0.5 * b.hi[j] - 0.5 * b.lo[j];
    }
}

// One shaping quadric whose analytic box `own` is B0's on every axis it bounds: within B0 the
// set is its ellipse/ellipsoid section times B0's range on its free axes (AnalyticBox bounds a
// quadric only when it is positive definite on the axes it depends on and free along the
// others), so B0 is exact.
bool OwnBoxIsB0(const Box3& own, const Box3& b0) {
    bool exact = false;
    for (int i = 0; i < 3; ++i) {
        if (!(std::isfinite(own.lo[i]) && std::isfinite(own.hi[i]))) continue;
        exact = own.lo[i] == b0.lo[i] && own.hi[i] == b0.hi[i];
        if (!exact) break;
    }
    return exact;
}

}  // namespace

Box3 IntersectionBounds(std::span<const BoundLiteral> literals, const BoundsOptions& options,
                        BoundsStats* stats) {
    // Quartic literals (math/quartic_surface.h) enter as convex supersets: an uncomplemented one
    // as the planes of its clip box (and its mapped box), a complemented one not at all (its set
    // is unbounded; leaving a literal out only enlarges the box).
    bool anyQuartic = false;
    for (const BoundLiteral& lit : literals) anyQuartic |= lit.halfSpace->IsQuartic();
    if (anyQuartic) {
        std::vector<FlatHalfSpace> planes;
        planes.reserve(7 * literals.size());  // no reallocation: `kept` points into it
        std::vector<BoundLiteral> kept;
        Box3 quarticBox = Box3::Everything();
        for (const BoundLiteral& lit : literals) {
            if (!lit.halfSpace->IsQuartic()) {
                kept.push_back(lit);
                continue;
            }
            if (lit.complemented) continue;
            const QuarticSurface& q = *lit.halfSpace->quartic;
            quarticBox = quarticBox.Intersected(q.SpaceBounds());
            for (const Vec4& p : q.SpaceBoxPlanes()) {
                FlatHalfSpace h;
                h.isPlane = true;
                h.plane = Plane::FromVec4(p);
                planes.push_back(std::move(h));
                kept.push_back({&planes.back(), false});
            }
        }
        const Box3 b = IntersectionBounds(kept, options, stats);
        return b.Empty() ? b : b.Intersected(quarticBox);
    }
    if (literals.size() == 1) {
        // One literal (a sphere, an ellipsoid): the steps below up to the analytic stage's
        // answer, without their lists (four allocations a body, most of the cost of bounding
        // 100,000 spheres); when that stage does not decide, the general path starts over.
        const LiteralStageA a = StageA(literals[0], options);
        const Box3 b0 = Box3::Everything().Intersected(a.box);
        if (b0.Empty()) {
            if (stats) ++stats->bodies;
            return Box3{};
        }
        bool decided = false;
        if (b0.Finite()) {
            double c[3], h[3];
            CentreAndHalf(b0, c, h);
            decided = HoldsOnAll(a.f, c, h);  // no shaping literal
        }
        if (!decided && !a.f.isPlane) decided = OwnBoxIsB0(a.box, b0);
        if (decided) {
            if (stats) {
                ++stats->bodies;
                ++stats->analyticOnly;
            }
            return b0;
        }
    }
    if (stats) ++stats->bodies;
    std::vector<InsideFn> fns;
    std::vector<Box3> boxes;
    std::vector<Vec3> seeds;
    fns.reserve(literals.size());
    boxes.reserve(literals.size());
    Box3 b0 = Box3::Everything();
    for (const BoundLiteral& lit : literals) {
        const LiteralStageA a = StageA(lit, options);
        fns.push_back(a.f);
        boxes.push_back(a.box);
        if (a.hasCentre) seeds.push_back(a.centre);
        b0 = b0.Intersected(boxes.back());
    }
    if (b0.Empty()) return Box3{};

    // Drop literals that contain all of B0: they cannot shape the set inside B0.
    std::vector<InsideFn> shaping;
    int shapingIndex = -1;
    bool b0Finite = b0.Finite();
    double c[3], h[3];
    CentreAndHalf(b0, c, h);
    for (std::size_t i = 0; i < fns.size(); ++i) {
        if (b0Finite && HoldsOnAll(fns[i], c, h)) continue;
        shaping.push_back(fns[i]);
        shapingIndex = static_cast<int>(i);
    }
    if (shaping.empty()) {
        if (stats) ++stats->analyticOnly;
        return b0;
    }
    // One shaping quadric whose analytic box is B0 (OwnBoxIsB0): B0 is exact.
    if (shaping.size() == 1 && !shaping[0].isPlane) {
        if (OwnBoxIsB0(boxes[static_cast<std::size_t>(shapingIndex)], b0)) {
            if (stats) ++stats->analyticOnly;
            return b0;
        }
    }
    if (options.polytopeVertices)
        if (auto box = PolytopeBox(shaping, b0, options)) {
            if (stats) ++stats->analyticOnly;
            return *box;
        }
    if (options.criticalPoints) {
        bool neckWide = false;
        if (auto box = CriticalPointBox(shaping, b0, options, &neckWide)) {
            if (stats) {
                ++stats->criticalPointBoxes;
                stats->neckWideBoxes += neckWide;
            }
            return *box;
        }
    }
    Box3 work = b0;
    // Literal classes: planes and positive semidefinite quadrics (convex), nappes (convex
    // components), the rest (non-convex: left to the branch-and-bound).
    std::vector<const InsideFn*> relaxed;
    std::vector<Nappe> nappes;
    std::vector<bool> isNappe;
    bool hasOther = false;
    for (const InsideFn& f : shaping) {
        // Positive semidefinite up to rounding, relative to ‖A‖: the coefficients are normalised
        // by the largest of all ten, so a quadric far from the origin has a tiny A, and a cone
        // with a distant apex a small but genuine negative eigenvalue.
        if (f.isPlane || f.lamMin >= -1e-12 * FrobeniusNorm(f.a)) {
            relaxed.push_back(&f);
            nappes.push_back(Nappe{});
            continue;
        }
        Nappe n = DetectNappe(f);
        if (n.ok) {
            relaxed.push_back(&f);
            nappes.push_back(n);
        } else {
            hasOther = true;
        }
    }
    const double limit = options.searchLimit;
    const double threshold = 1e-3 * limit;  // beyond this a side counts as unbounded
    RelaxationOutcome relaxation;
    Box3 region = work.Intersected(Box3{{-limit, -limit, -limit}, {limit, limit, limit}});
    if (!relaxed.empty() && !region.Empty()) {
        relaxation = relaxed.size() > kWorkingSetThreshold
                         ? BoundByWorkingSetRelaxation(relaxed, nappes, region, work, stats)
                         : BoundByConvexRelaxation(relaxed, nappes, region, work, stats);
        if (relaxation.empty) return Box3{};
    }
    bool hasNonConvex = hasOther;
    if (!relaxation.usedNappes)
        for (const Nappe& n : nappes) hasNonConvex |= n.ok;
    // Sides the relaxation has not settled: it failed there, or a literal it left out could
    // cut off its extreme or bound a side it leaves unbounded.
    bool sides[6];
    bool anySide = false;
    for (int side = 0; side < 6; ++side) {
        int axis = side / 2;
        bool high = side % 2 == 1;
        double v = high ? work.hi[axis] : -work.lo[axis];
        bool have = relaxation.haveExtreme[side];
        bool settled = have && !hasNonConvex;
        if (have && hasNonConvex && v <= threshold) {
            const Vec3& e = relaxation.extremes[side];
            double p[3] = {e.x, e.y, e.z};
            settled = true;
            for (const InsideFn& f : shaping) {
                Local l = EvaluateLocal(f, p);
                if (l.v > 1e-9 * (l.mag + 1e-300)) settled = false;
            }
        }
        sides[side] = !settled;
        anySide |= sides[side];
    }
    if (anySide) {
        if (b0Finite) seeds.push_back(b0.Center());
        for (int side = 0; side < 6; ++side)
            if (relaxation.haveExtreme[side]) seeds.push_back(relaxation.extremes[side]);
        if (!RefineByBranchAndBound(std::move(shaping), seeds, sides, options, stats, work))
            return Box3{};
    }
    for (int i = 0; i < 3; ++i) {
        if (work.lo[i] < -threshold) work.lo[i] = -kInf;
        if (work.hi[i] > threshold) work.hi[i] = kInf;
    }
    return work.Empty() ? Box3{} : work;
}

Box3 BodyBounds(const FlatScene& scene, const FlatBody& body, const BoundsOptions& options,
                BoundsStats* stats) {
    std::vector<BoundLiteral> lits;
    lits.reserve(body.literals.size());
    for (const FlatLiteral& l : body.literals)
        lits.push_back({&scene.halfSpaces[l.halfSpace], l.complemented});
    return IntersectionBounds(lits, options, stats);
}

Box3 TreeNodeBounds(const FlatCsgNode& node, const Box3& leafBody,
                    const std::vector<Box3>& nodeBoxes) {
    if (node.isLeaf) return leafBody;
    Box3 box;
    switch (node.op) {
        case scene::CsgOp::kUnion:
            for (int c : node.children) box.Extend(nodeBoxes[c]);
            break;
        case scene::CsgOp::kIntersection:
            box = Box3::Everything();
            for (int c : node.children) box = box.Intersected(nodeBoxes[c]);
            if (node.children.empty()) box = Box3{};
            break;
        case scene::CsgOp::kDifference:
            if (!node.children.empty()) box = nodeBoxes[node.children[0]];
            break;
    }
    return box.Empty() ? Box3{} : box;  // one canonical empty box
}

std::vector<Box3> TreeBounds(const FlatScene& scene, const std::vector<Box3>& bodyBoxes) {
    std::vector<Box3> out(scene.nodes.size());
    BottomUp(scene, [&](std::size_t i) {
        const FlatCsgNode& node = scene.nodes[i];
        out[i] = TreeNodeBounds(node, node.isLeaf ? bodyBoxes[node.body] : Box3{}, out);
    });
    return out;
}

void ComputeSceneBounds(FlatScene& scene, const BoundsOptions& options, BoundsStats* stats) {
    std::vector<Box3> bodyBoxes(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        bodyBoxes[i] = BodyBounds(scene, scene.bodies[i], options, stats);
        scene.bodies[i].bounds = bodyBoxes[i];
    }
    std::vector<Box3> nodeBoxes = TreeBounds(scene, bodyBoxes);
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) scene.nodes[i].bounds = nodeBoxes[i];
    Box3 image{{0, 0, -kInf},
               {static_cast<double>(scene.width), static_cast<double>(scene.height), kInf}};
    for (FlatSolid& s : scene.solids) {
        Box3 b = s.root >= 0 ? nodeBoxes[s.root] : Box3{};
        b = b.Intersected(image);
        s.bounds = b.Empty() ? Box3{} : b;
    }
}

}  // namespace quadrix
