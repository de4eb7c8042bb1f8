// Conservative bounds of bodies and CSG trees; the method is described in bounds.h. The
// stages live in bounds_math.cpp (a), bounds_relaxation.cpp (b1) and bounds_search.cpp (b2).
#include "quadrix/flatten/bounds.h"

#include <cmath>

#include "quadrix/flatten/bounds_internal.h"

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

double HalfSpaceScale(const FlatHalfSpace& hs) {
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
    Box3 box = LiteralBox(hs, false);
    for (int i = 0; i < 3; ++i) {
        if (std::isfinite(box.lo[i])) s = std::fmax(s, std::fabs(box.lo[i]));
        if (std::isfinite(box.hi[i])) s = std::fmax(s, std::fabs(box.hi[i]));
    }
    return std::isfinite(s) ? s : 0.0;
}

Box3 IntersectionBounds(std::span<const BoundLiteral> literals, const BoundsOptions& options,
                        BoundsStats* stats) {
    if (stats) ++stats->bodies;
    std::vector<InsideFn> fns;
    std::vector<Box3> boxes;
    std::vector<Vec3> seeds;
    fns.reserve(literals.size());
    boxes.reserve(literals.size());
    Box3 b0 = Box3::Everything();
    for (const BoundLiteral& lit : literals) {
        fns.push_back(MakeInsideFn(*lit.halfSpace, lit.complemented));
        Vec3 centre;
        bool hasCentre = false;
        boxes.push_back(AnalyticBox(fns.back(), &centre, &hasCentre));
        if (hasCentre) seeds.push_back(centre);
        b0 = b0.Intersected(boxes.back());
    }
    if (b0.Empty()) return Box3{};

    // Drop literals that contain all of B0: they cannot shape the set inside B0.
    std::vector<InsideFn> shaping;
    int shapingIndex = -1;
    bool b0Finite = b0.Finite();
    double c[3], h[3];
    for (int j = 0; j < 3; ++j) {
        c[j] = 0.5 * b0.lo[j] + 0.5 * b0.hi[j];
        h[j] = 0.5 * b0.hi[j] - 0.5 * b0.lo[j];
    }
    for (std::size_t i = 0; i < fns.size(); ++i) {
        if (b0Finite) {
            const InsideFn& f = fns[i];
            Range r = RangeFromLocal(EvaluateLocal(f, c), f.a, f.lamMin, f.lamMax, h, nullptr);
            if (r.hi <= r.margin) continue;
        }
        shaping.push_back(fns[i]);
        shapingIndex = static_cast<int>(i);
    }
    if (shaping.empty()) {
        if (stats) ++stats->analyticOnly;
        return b0;
    }
    // One shaping quadric whose analytic bounds are B0's on every axis it bounds: within B0 the
    // set is its ellipse/ellipsoid section times B0's range on its free axes (AnalyticBox bounds a
    // quadric only when it is positive definite on the axes it depends on and free along the
    // others), so B0 is exact.
    if (shaping.size() == 1 && !shaping[0].isPlane) {
        const Box3& own = boxes[shapingIndex];
        bool exact = false;
        for (int i = 0; i < 3; ++i) {
            if (!(std::isfinite(own.lo[i]) && std::isfinite(own.hi[i]))) continue;
            exact = own.lo[i] == b0.lo[i] && own.hi[i] == b0.hi[i];
            if (!exact) break;
        }
        if (exact) {
            if (stats) ++stats->analyticOnly;
            return b0;
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
        relaxation = BoundByConvexRelaxation(relaxed, nappes, region, work, stats);
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

std::vector<Box3> TreeBounds(const FlatScene& scene, const std::vector<Box3>& bodyBoxes) {
    std::vector<Box3> out(scene.nodes.size());
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const FlatCsgNode& node = scene.nodes[i];
        if (node.isLeaf) {
            out[i] = bodyBoxes[node.body];
            continue;
        }
        Box3 box;
        switch (node.op) {
            case scene::CsgOp::kUnion:
                for (int c : node.children) box.Extend(out[c]);
                break;
            case scene::CsgOp::kIntersection:
                box = Box3::Everything();
                for (int c : node.children) box = box.Intersected(out[c]);
                if (node.children.empty()) box = Box3{};
                break;
            case scene::CsgOp::kDifference:
                if (!node.children.empty()) box = out[node.children[0]];
                break;
        }
        out[i] = box.Empty() ? Box3{} : box;  // one canonical empty box
    }
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
