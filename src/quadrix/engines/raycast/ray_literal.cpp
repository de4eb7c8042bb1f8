#include "quadrix/engines/raycast/ray_literal.h"

#include <cmath>

#include "quadrix/math/quadratic.h"

namespace quadrix::raycast {

RayHalfSpace RayHalfSpace::From(const FlatHalfSpace& hs, const Vec3& p0) {
    RayHalfSpace r;
    r.isPlane = hs.isPlane;
    if (hs.isPlane) {
        r.c = hs.plane.c;
        r.px = hs.plane.a;
        r.py = hs.plane.b;
        r.pd = hs.plane.d;
        return r;
    }
    const Quadric& q = hs.quadric;
    // b' = A p0 + b and K' = Q(p0) = p0ᵀ A p0 + 2 bᵀ p0 + K = p0ᵀ (b' + b) + K.
    double g = q.A() * p0.x + q.D() * p0.y + q.F() * p0.z + q.G();
    double h = q.D() * p0.x + q.B() * p0.y + q.E() * p0.z + q.H();
    double j = q.F() * p0.x + q.E() * p0.y + q.C() * p0.z + q.J();
    double k = p0.x * (g + q.G()) + p0.y * (h + q.H()) + p0.z * (j + q.J()) + q.K();
    r.c = q.C();
    r.x0 = p0.x;
    r.y0 = p0.y;
    r.z0 = p0.z;
    r.hx = q.F();
    r.hy = q.E();
    r.h0 = j;
    r.axx = q.A();
    r.axy = 2.0 * q.D();
    r.ax = 2.0 * g;
    r.byy = q.B();
    r.by = 2.0 * h;
    r.k0 = k;
    return r;
}

std::optional<Vec3> RayHalfSpace::Centre(const Quadric& q) {
    if (!q.AllFinite()) return std::nullopt;
    const double a = q.A(), b = q.B(), c = q.C(), d = q.D(), e = q.E(), f = q.F();
    // Adjugate of the symmetric [[a d f] [d b e] [f e c]].
    double c00 = b * c - e * e, c01 = f * e - d * c, c02 = d * e - b * f;
    double c11 = a * c - f * f, c12 = d * f - a * e, c22 = a * b - d * d;
    double det = a * c00 + d * c01 + f * c02;
    double scale = std::fmax(
        std::fmax(std::fabs(a), std::fabs(b)),
        std::fmax(std::fabs(c), std::fmax(std::fabs(d), std::fmax(std::fabs(e), std::fabs(f)))));
    // Well enough conditioned (|det| is a product of three eigenvalues): otherwise a cylinder or
    // paraboloid, whose "centre" is a line or does not exist.
    if (!(std::fabs(det) > 1e-9 * scale * scale * scale)) return std::nullopt;
    const double g = q.G(), h = q.H(), j = q.J();
    Vec3 p{-(c00 * g + c01 * h + c02 * j) / det, -(c01 * g + c11 * h + c12 * j) / det,
           -(c02 * g + c12 * h + c22 * j) / det};
    if (!IsFinite(p) || std::fabs(p.x) > 1e12 || std::fabs(p.y) > 1e12 || std::fabs(p.z) > 1e12)
        return std::nullopt;
    return Vec3{std::round(p.x), std::round(p.y), std::round(p.z)};
}

namespace {

constexpr double kInf = HUGE_VAL;
constexpr std::int32_t kNoId = Interval::kNoId;

// Adds [lo, hi] unless it is a point or empty (the regularised convention); ids of infinite ends
// are kNoId.
void Add(RaySet& s, double lo, double hi, std::int32_t id) {
    if (!(lo < hi)) return;
    s.piece[s.count++] = {lo, hi, std::isinf(lo) ? kNoId : id, std::isinf(hi) ? kNoId : id};
}

// The set where  c t + e <= 0  (a plane, or a quadric that is linear along this ray).
void LinearSet(double c, double e, std::int32_t id, RaySet& s) {
    if (c == 0) {
        if (e <= 0) Add(s, -kInf, kInf, id);  // the plane contains or misses the ray
        return;
    }
    double r = -e / c;  // may overflow to ±inf when c is tiny: then the set is all or nothing
    if (c > 0) {
        Add(s, -kInf, r, id);
    } else {
        Add(s, r, kInf, id);
    }
}

// The set where  a t² + 2 h t + k <= 0, shifted by z0.
void QuadraticSet(double a, double h, double k, double z0, std::int32_t id, RaySet& s) {
    QuadraticRoots roots = SolveQuadratic(a, h, k);
    double t0 = z0 + roots.t0, t1 = z0 + roots.t1;
    switch (roots.kind) {
        case RootKind::kAll:  // Q vanishes identically on the ray: Q <= 0 holds everywhere
            Add(s, -kInf, kInf, id);
            return;
        case RootKind::kNone:
            // No sign change, so Q has the sign of Q(0) = k (for a quadratic, h² − a k < 0 forces
            // a and k to share their sign; for a constant, Q = k).
            if (k < 0) Add(s, -kInf, kInf, id);
            return;
        case RootKind::kSingle:  // linear along the ray (a = 0 after scaling): 2 h t + k <= 0
            if (h > 0) {
                Add(s, -kInf, t0, id);
            } else {
                Add(s, t0, kInf, id);
            }
            return;
        case RootKind::kDouble:
            // a (t − r)² <= 0: only the touching point when a > 0 (regularised away), everything
            // when a < 0 (the ray grazes the surface from inside).
            if (a < 0) Add(s, -kInf, kInf, id);
            return;
        case RootKind::kTwo:
            if (a > 0) {
                Add(s, t0, t1, id);
            } else if (t0 < t1) {
                Add(s, -kInf, t0, id);
                Add(s, t1, kInf, id);
            } else {  // the roots rounded to one double: the two pieces touch
                Add(s, -kInf, kInf, id);
            }
            return;
    }
}

// In place: the closure of the complement of a canonical set of at most two pieces (again at
// most two). The pieces are read field by field into scalars before any is written (a whole-struct
// copy of freshly stored pieces would stall on store-to-load forwarding, the hottest spot of a
// render before this was written so).
void Complement(RaySet& s) {
    const int n = s.count;
    const double lo0 = s.piece[0].lo, hi0 = s.piece[0].hi, lo1 = s.piece[1].lo;
    const std::int32_t loId0 = s.piece[0].loId, hiId0 = s.piece[0].hiId, loId1 = s.piece[1].loId;
    const double lastHi = n == 0 ? -kInf : s.piece[n - 1].hi;
    const std::int32_t lastHiId = n == 0 ? kNoId : s.piece[n - 1].hiId;
    s.count = 0;
    if (n == 0) {
        s.piece[s.count++] = {-kInf, kInf, kNoId, kNoId};
        return;
    }
    if (-kInf < lo0) s.piece[s.count++] = {-kInf, lo0, kNoId, loId0};
    if (n == 2 && hi0 < lo1) s.piece[s.count++] = {hi0, lo1, hiId0, loId1};
    if (lastHi < kInf) s.piece[s.count++] = {lastHi, kInf, lastHiId, kNoId};
}

}  // namespace

RaySet LiteralOnRay(const RayHalfSpace& hs, bool complemented, double x, double y, std::int32_t id,
                    LiteralCounters& counters) {
    RaySet inside;
    if (hs.isPlane) {
        ++counters.planes;
        double e = hs.px * x + hs.py * y + hs.pd;
        if (!std::isfinite(e) || !std::isfinite(hs.c)) return inside;  // empty both ways
        LinearSet(hs.c, e, id, inside);
    } else {
        ++counters.quadrics;
        double dx = x - hs.x0, dy = y - hs.y0;
        double h = hs.hx * dx + hs.hy * dy + hs.h0;
        double k = dx * (hs.axx * dx + hs.axy * dy + hs.ax) + dy * (hs.byy * dy + hs.by) + hs.k0;
        if (!std::isfinite(h) || !std::isfinite(k) || !std::isfinite(hs.c)) return inside;
        QuadraticSet(hs.c, h, k, hs.z0, id, inside);
    }
    if (complemented) Complement(inside);
    return inside;  // named return value: constructed in the caller's slot, not copied
}

QuadricOnRect ClassifyQuadric(const RayHalfSpace& hs, double x0, double x1, double y0, double y1) {
    const double c = hs.c;
    if (!std::isfinite(c) || c == 0) return QuadricOnRect::kUnknown;
    const double hu = 0.5 * (x1 - x0), hv = 0.5 * (y1 - y0);
    const double X0 = 0.5 * (x0 + x1) - hs.x0, Y0 = 0.5 * (y0 + y1) - hs.y0;
    const double H0 = hs.hx * X0 + hs.hy * Y0 + hs.h0;
    const double K0 = X0 * (hs.axx * X0 + hs.axy * Y0 + hs.ax) + Y0 * (hs.byy * Y0 + hs.by) + hs.k0;
    const double Ku = 2 * hs.axx * X0 + hs.axy * Y0 + hs.ax;
    const double Kv = hs.axy * X0 + 2 * hs.byy * Y0 + hs.by;
    const double d0 = H0 * H0 - c * K0;
    const double bu = 2 * H0 * hs.hx - c * Ku, bv = 2 * H0 * hs.hy - c * Kv;
    const double auu = hs.hx * hs.hx - c * hs.axx, auv = 2 * hs.hx * hs.hy - c * hs.axy;
    const double avv = hs.hy * hs.hy - c * hs.byy;
    const double bound = d0 + std::fabs(bu) * hu + std::fabs(bv) * hv +
                         std::fmax(auu, 0.0) * hu * hu + std::fabs(auv) * hu * hv +
                         std::fmax(avv, 0.0) * hv * hv;
    const double ac = std::fabs(c);
    const double scale =
        H0 * H0 + ac * std::fabs(K0) +
        (2 * std::fabs(H0 * hs.hx) + ac * std::fabs(Ku)) * hu +
        (2 * std::fabs(H0 * hs.hy) + ac * std::fabs(Kv)) * hv +
        (hs.hx * hs.hx + ac * std::fabs(hs.axx)) * hu * hu +
        (2 * std::fabs(hs.hx * hs.hy) + ac * std::fabs(hs.axy)) * hu * hv +
        (hs.hy * hs.hy + ac * std::fabs(hs.byy)) * hv * hv +
        ac * (std::fabs(X0 * hs.ax) + std::fabs(Y0 * hs.by) + std::fabs(hs.k0) +
              std::fabs(hs.axx) * X0 * X0 + std::fabs(hs.axy * X0 * Y0) +
              std::fabs(hs.byy) * Y0 * Y0);
    if (!std::isfinite(bound) || !std::isfinite(scale)) return QuadricOnRect::kUnknown;
    if (!(bound < -1e-8 * scale)) return QuadricOnRect::kUnknown;
    return c < 0 ? QuadricOnRect::kInsideEverywhere : QuadricOnRect::kOutsideEverywhere;
}

void LiteralSetOnRay(const RayHalfSpace& hs, bool complemented, double x, double y, std::int32_t id,
                     IntervalList& out, LiteralCounters& counters) {
    RaySet s = LiteralOnRay(hs, complemented, x, y, id, counters);
    out.clear();
    for (int i = 0; i < s.count; ++i)
        out.Append(s.piece[i].lo, s.piece[i].loId, s.piece[i].hi, s.piece[i].hiId);
}

}  // namespace quadrix::raycast
