#include "quadrix/engines/raycast/ray_literal.h"

#include <cmath>

#include "quadrix/math/quadratic.h"

namespace quadrix::raycast {

RayHalfSpace RayHalfSpace::From(const FlatHalfSpace& hs) {
    RayHalfSpace r;
    r.isPlane = hs.isPlane;
    if (hs.isPlane) {
        r.c = hs.plane.c;
        r.px = hs.plane.a;
        r.py = hs.plane.b;
        r.pd = hs.plane.d;
    } else {
        const Quadric& q = hs.quadric;
        r.c = q.C();
        r.hx = q.F();
        r.hy = q.E();
        r.h0 = q.J();
        r.axx = q.A();
        r.axy = 2.0 * q.D();
        r.ax = 2.0 * q.G();
        r.byy = q.B();
        r.by = 2.0 * q.H();
        r.k0 = q.K();
    }
    return r;
}

namespace {

constexpr double kInf = HUGE_VAL;
constexpr std::int32_t kNoId = Interval::kNoId;

// The set where  c t + e <= 0  (a plane, or a quadric that is linear along this ray).
void LinearSet(double c, double e, std::int32_t id, IntervalList& out) {
    if (c == 0) {
        if (e <= 0) out.Append(-kInf, kNoId, kInf, kNoId);  // the plane contains or misses the ray
        return;
    }
    double r = -e / c;  // may overflow to ±inf when c is tiny: then the set is all or nothing
    if (c > 0) {
        out.Append(-kInf, kNoId, r, std::isinf(r) ? kNoId : id);
    } else {
        out.Append(r, std::isinf(r) ? kNoId : id, kInf, kNoId);
    }
}

// The set where  a t² + 2 h t + k <= 0.
void QuadraticSet(double a, double h, double k, std::int32_t id, IntervalList& out) {
    QuadraticRoots roots = SolveQuadratic(a, h, k);
    auto idOf = [id](double t) { return std::isinf(t) ? kNoId : id; };
    switch (roots.kind) {
        case RootKind::kAll:  // Q vanishes identically on the ray: Q <= 0 holds everywhere
            out.Append(-kInf, kNoId, kInf, kNoId);
            return;
        case RootKind::kNone:
            // No sign change, so Q has the sign of Q(0) = k (for a quadratic, h² − a k < 0 forces
            // a and k to share their sign; for a constant, Q = k).
            if (k < 0) out.Append(-kInf, kNoId, kInf, kNoId);
            return;
        case RootKind::kSingle:  // linear along the ray (a = 0 after scaling): 2 h t + k <= 0
            if (h > 0) {
                out.Append(-kInf, kNoId, roots.t0, idOf(roots.t0));
            } else {
                out.Append(roots.t0, idOf(roots.t0), kInf, kNoId);
            }
            return;
        case RootKind::kDouble:
            // a (t − r)² <= 0: only the touching point when a > 0 (regularised away), everything
            // when a < 0 (the ray grazes the surface from inside).
            if (a < 0) out.Append(-kInf, kNoId, kInf, kNoId);
            return;
        case RootKind::kTwo:
            if (a > 0) {
                out.Append(roots.t0, idOf(roots.t0), roots.t1, idOf(roots.t1));
            } else {
                // Two pieces; Append merges them if the roots rounded to the same double.
                out.Append(-kInf, kNoId, roots.t0, idOf(roots.t0));
                out.Append(roots.t1, idOf(roots.t1), kInf, kNoId);
            }
            return;
    }
}

}  // namespace

void LiteralSetOnRay(const RayHalfSpace& hs, bool complemented, double x, double y,
                     std::int32_t id, IntervalList& out, LiteralCounters& counters) {
    out.clear();
    IntervalList inside;
    IntervalList& target = complemented ? inside : out;
    if (hs.isPlane) {
        ++counters.planes;
        double e = hs.px * x + hs.py * y + hs.pd;
        if (!std::isfinite(e) || !std::isfinite(hs.c)) return;
        LinearSet(hs.c, e, id, target);
    } else {
        ++counters.quadrics;
        double h = hs.hx * x + hs.hy * y + hs.h0;
        double k = x * (hs.axx * x + hs.axy * y + hs.ax) + y * (hs.byy * y + hs.by) + hs.k0;
        if (!std::isfinite(h) || !std::isfinite(k) || !std::isfinite(hs.c)) return;
        QuadraticSet(hs.c, h, k, id, target);
    }
    if (complemented) Complement(inside, out);
}

}  // namespace quadrix::raycast
