#include "quadrix/eval/ray_evaluator.h"

#include <cmath>
#include <utility>

#include "quadrix/math/quadratic.h"

namespace quadrix::eval {

RayEvaluator::RayEvaluator(const FlatScene& scene) : scene_(scene) {
    // The same re-centring points as raycast (its SceneTables::ReferencePoint), so the two
    // engines solve bit-identical quadratics.
    Vec3 anchor{std::round(0.5 * scene.width), std::round(0.5 * scene.height), 0};
    halfSpaces_.reserve(scene.halfSpaces.size());
    for (const FlatHalfSpace& hs : scene.halfSpaces) {
        Vec3 ref = !hs.IsQuadric() ? anchor : RayHalfSpace::Centre(hs.quadric).value_or(anchor);
        halfSpaces_.push_back(RayHalfSpace::From(hs, ref));
    }
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        bodyFirstTag_.push_back(static_cast<int>(tags_.size()));
        bool valid = true;
        for (const FlatLiteral& lit : scene.bodies[b].literals)
            valid = valid && lit.halfSpace >= 0 &&
                    static_cast<std::size_t>(lit.halfSpace) < scene.halfSpaces.size();
        if (!valid) continue;  // a body naming a missing half-space is empty (as in raycast)
        for (const FlatLiteral& lit : scene.bodies[b].literals) {
            const FlatHalfSpace& hs = scene.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
            tags_.push_back({lit.halfSpace, static_cast<int>(b), lit.complemented,
                             !hs.transparent && !hs.isClip});
        }
    }
    bodyFirstTag_.push_back(static_cast<int>(tags_.size()));
}

void RayEvaluator::BodySet(int body, double x, double y, IntervalList& out) {
    out.clear();
    int first = bodyFirstTag_[static_cast<std::size_t>(body)];
    int last = bodyFirstTag_[static_cast<std::size_t>(body) + 1];
    IntervalList lit, tmp;
    for (int t = first; t < last; ++t) {
        const Tag& tag = tags_[static_cast<std::size_t>(t)];
        RaySet s = LiteralOnRay(halfSpaces_[static_cast<std::size_t>(tag.halfSpace)],
                                tag.complemented, x, y, t, literalCounters_);
        if (s.count == 0) {
            out.clear();
            return;
        }
        if (t == first) {
            for (int i = 0; i < s.count; ++i)
                out.Append(s.piece[i].lo, s.piece[i].loId, s.piece[i].hi, s.piece[i].hiId);
        } else if (s.count == 1) {
            ClipTo(out, s.piece[0]);
        } else {
            lit.clear();
            for (int i = 0; i < s.count; ++i)
                lit.Append(s.piece[i].lo, s.piece[i].loId, s.piece[i].hi, s.piece[i].hiId);
            Intersection(out, lit, tmp);
            std::swap(out, tmp);
        }
        if (out.empty()) return;
    }
}

bool RayEvaluator::First(const IntervalList& l, Hit& hit) const {
    for (const Interval& v : l) {
        for (auto [t, id] : {std::pair{v.lo, v.loId}, std::pair{v.hi, v.hiId}}) {
            if (id >= 0 && std::isfinite(t) && tags_[static_cast<std::size_t>(id)].opaque) {
                hit.t = t;
                hit.halfSpace = tags_[static_cast<std::size_t>(id)].halfSpace;
                hit.body = tags_[static_cast<std::size_t>(id)].body;
                return true;
            }
        }
    }
    return false;
}

bool RayEvaluator::Body(int body, double x, double y, Hit& hit) {
    IntervalList l;
    BodySet(body, x, y, l);
    return First(l, hit);
}

bool RayEvaluator::Node(int node, double x, double y, Hit& hit) {
    IntervalList l;
    TreeSet(
        node, [&](int body, IntervalList& out) { BodySet(body, x, y, out); }, l);
    return First(l, hit);
}

int RayEvaluator::SheetOf(int halfSpace, double t, double x, double y) const {
    const RayHalfSpace& r = Ray(halfSpace);
    if (r.isPlane || r.quartic) return 0;
    const double dx = x - r.x0, dy = y - r.y0;
    QuadraticRoots roots =
        SolveQuadratic(r.c, r.hx * dx + r.hy * dy + r.h0,
                       dx * (r.axx * dx + r.axy * dy + r.ax) + dy * (r.byy * dy + r.by) + r.k0);
    return roots.kind == RootKind::kTwo &&
                   std::fabs(t - (r.z0 + roots.t1)) < std::fabs(t - (r.z0 + roots.t0))
               ? 1
               : 0;
}

}  // namespace quadrix::eval
