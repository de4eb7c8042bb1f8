#include "quadrix/eval/ray_literal.h"

#include <cmath>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "quadrix/math/quadratic.h"
#include "quadrix/util/cpu_features.h"

namespace quadrix::eval {

RayHalfSpace RayHalfSpace::From(const FlatHalfSpace& hs, const Vec3& p0) {
    RayHalfSpace r;
    r.isPlane = hs.isPlane;
    if (hs.IsQuartic()) {
        r.isPlane = false;
        r.quartic = hs.quartic;
        return r;
    }
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

// The set of a quartic on the ray through (x, y): at most two pieces with finite ends.
void QuarticSet(const QuarticSurface& q, double x, double y, std::int32_t id, RaySet& s) {
    const QuarticLineSet l = q.OnLine(Vec4{x, y, 0, 1}, Vec4{0, 0, 1, 0});
    for (int i = 0; i < l.count; ++i)
        Add(s, l.lo[static_cast<std::size_t>(i)], l.hi[static_cast<std::size_t>(i)], id);
}

// In place: the closure of the complement of a canonical set of at most two pieces (at most
// three: two only unless both pieces are finite, as a quartic's can be). The pieces are read field
// by field into scalars before any is written (a whole-struct copy of freshly stored pieces would
// stall on store-to-load forwarding, the hottest spot of a render before this was written so).
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
    if (hs.quartic) {
        ++counters.quartics;
        QuarticSet(*hs.quartic, x, y, id, inside);
    } else if (hs.isPlane) {
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
    if (hs.quartic) return QuadricOnRect::kUnknown;
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
    const double scale = H0 * H0 + ac * std::fabs(K0) +
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

namespace {

constexpr int kBatchMax = 64;

// One pixel of QuadricBatch the reference way. With `cut` (cut mode, see ray_literal.h) a set of
// two pieces p0 < p1 is taken in too: the running interval is clipped by each piece with the
// rules below (IntersectionOfOne's, which the scalar body evaluation's sweep follows); the first
// non-empty result is kept, and when both are non-empty the second one's start lowers the cut.
// Both empty is ∅ exactly only without a cut; with one it is "∅ below the cut" (lo >= hi).
void QuadricBatchPixel(const RayHalfSpace& hs, bool complemented, std::int32_t tag, int p,
                       const double* xs, const double* ys, double* lo, std::int64_t* loId,
                       double* hi, std::int64_t* hiId, std::uint8_t* flag, double* cut,
                       LiteralCounters& counters) {
    const RaySet s = LiteralOnRay(hs, complemented, xs[p], ys[p], tag, counters);
    if (s.count == 0) {
        flag[p] = kBatchDead;
        return;
    }
    if (s.count == 2 && !cut) {
        flag[p] = kBatchScalar;
        return;
    }
    // The running interval clipped by piece v (the rules of ray_literal.h), as a candidate.
    struct Candidate {
        double lo, hi;
        std::int64_t loId, hiId;
    };
    auto clip = [&](const Interval& v) {
        Candidate c{lo[p], hi[p], loId[p], hiId[p]};
        ClipOne(c, v);
        return c;
    };
    auto keep = [&](const Candidate& c) {
        lo[p] = c.lo;
        loId[p] = c.loId;
        hi[p] = c.hi;
        hiId[p] = c.hiId;
    };
    const Candidate first = clip(s.piece[0]);
    if (s.count == 1) {
        keep(first);
        return;
    }
    const Candidate second = clip(s.piece[1]);
    const bool firstNonEmpty = first.lo < first.hi, secondNonEmpty = second.lo < second.hi;
    if (firstNonEmpty) {
        keep(first);
        if (secondNonEmpty && second.lo < cut[p]) cut[p] = second.lo;
    } else if (secondNonEmpty) {
        keep(second);
    } else if (cut[p] == kInf) {
        flag[p] = kBatchDead;
    } else {
        keep(first);  // ∅ below the cut (first.lo >= first.hi)
    }
}

// The vectorised pass of QuadricBatch over n <= kBatchMax pixels: the live pixels whose literal
// set the common case decides get their result; the other live ones get need[p] = 1 (else 0).
// Returns the number of live pixels.
//
// The common case, followed step by step through LiteralOnRay, SolveQuadratic and QuadraticSet:
// h, k and c finite, max(|c|, |h|, |k|) in [2^-200, 2^200] (SolveQuadratic does not rescale),
// c ≠ 0 (not linear) and disc ≠ 0 (no double root); the discriminant is the plain one or the
// compensated one exactly as SolveQuadratic chooses (both are computed: the compensated one is
// what every pixel of a surface far from the re-centring point needs, e.g. a cylinder lying
// across the view, which has no centre and is re-centred on the image centre at depth 0).
// Then with the shifted roots a = z0 + t0, b = z0 + t1 (sorted roots of kTwo when disc > 0) let
// J = [a, b] when disc > 0 and a < b, else J = ∅. For c > 0 QuadraticSet's set is J (disc < 0
// forces k > 0: nothing); for c < 0 it is the closure of J's complement (two half-lines, or
// everything when the roots round together or disc < 0, which forces k < 0), i.e. Complement(J)
// piece for piece, ids included. Complementing twice gives J back, so the literal's set is J
// when (c > 0) != complemented and Complement(J) otherwise (kFlip):
//   !kFlip: J = [a, b] -> that piece (kNoId on an infinite end); J = ∅ -> dead;
//    kFlip: J = ∅ -> (−∞, ∞); J = [a, b] finite -> two pieces (scalar; in cut mode, need: the
//           scalar QuadricBatchPixel takes them in); an infinite end -> need.
// Every operation is the scalar one in the same order (IEEE +, −, ×, /, √, no contraction: the
// project builds with -ffp-contract=off and no fast-math), so the bits are the same; the √ is a
// separate pass with SSE2 intrinsics because std::sqrt's errno handling stops the vectoriser.
template <bool kFlip>
[[gnu::always_inline]] inline int QuadricBatchFastBody(
    const RayHalfSpace& hs, bool cutMode, std::int64_t tag, int n, const double* __restrict xs,
    const double* __restrict ys, double* __restrict lo, std::int64_t* __restrict loId,
    double* __restrict hi, std::int64_t* __restrict hiId, std::uint8_t* __restrict flag,
    double* __restrict cut, std::uint8_t* __restrict need) {
    const double c = hs.c, x0 = hs.x0, y0 = hs.y0, z0 = hs.z0, hx = hs.hx, hy = hs.hy, h0 = hs.h0,
                 axx = hs.axx, axy = hs.axy, ax = hs.ax, byy = hs.byy, by = hs.by, k0 = hs.k0;
    constexpr double kBig = 0x1p200, kSmall = 0x1p-200;
    // c's part of the common-case test (c finite and non-zero, |c| <= 2^200), and whether |c|
    // alone already reaches 2^-200.
    const bool cOk = std::fabs(c) <= kBig && c != 0;
    const bool cLarge = std::fabs(c) >= kSmall;
    double hv[kBatchMax], kv[kBatchMax], pv[kBatchMax], cv[kBatchMax], dv[kBatchMax], sv[kBatchMax];
    double av[kBatchMax], bv[kBatchMax];
    std::int64_t usePlain[kBatchMax], fast[kBatchMax], twov[kBatchMax];

    // 1. h, k and both discriminants; which pixels are in the common case (but for disc ≠ 0).
    // Both discriminants are stored and chosen in the next loop: a choice here would let the
    // compiler compute the compensated one conditionally, which -ftrapping-math forbids it to
    // if-convert, and the loop would not be vectorised.
    for (int p = 0; p < n; ++p) {
        const double dx = xs[p] - x0, dy = ys[p] - y0;
        const double h = hx * dx + hy * dy + h0;
        const double k = dx * (axx * dx + axy * dy + ax) + dy * (byy * dy + by) + k0;
        const double ah = std::fabs(h), ak = std::fabs(k);
        const double p1 = h * h, p2 = c * k;
        const double plain = p1 - p2;
        // DifferenceOfProducts(h, h, c, k), inline (same operands in the same order).
        const TwoProductResult e1 = TwoProduct(h, h), e2 = TwoProduct(c, k);
        hv[p] = h;
        kv[p] = k;
        pv[p] = plain;
        cv[p] = (e1.p - e2.p) + (e1.e - e2.e);
        usePlain[p] = p1 + std::fabs(p2) <= 2.0 * std::fabs(plain);
        fast[p] = cOk & (ah <= kBig) & (ak <= kBig) & (cLarge | (ah >= kSmall) | (ak >= kSmall));
    }

    // 2. The discriminant SolveQuadratic uses, and its square root (NaN where disc < 0, which
    // step 3 does not use).
    for (int p = 0; p < n; ++p) dv[p] = usePlain[p] ? pv[p] : cv[p];
    int i = 0;
#if defined(__SSE2__)
    for (; i + 2 <= n; i += 2) _mm_storeu_pd(sv + i, _mm_sqrt_pd(_mm_loadu_pd(dv + i)));
#endif
    for (; i < n; ++i) sv[i] = std::sqrt(dv[i]);

    // 3. Roots, the literal's set, and the merge into the batch.
    int live = 0;
    for (int p = 0; p < n; ++p) {
        const double h = hv[p], k = kv[p], s = sv[p];
        const double q = -(h + std::copysign(s, h));
        const double t0 = q / c, t1 = k / q;
        // Sorted, then shifted (QuadraticSet): the same as shifting both and then choosing,
        // which keeps every addition unconditional (a conditional one blocks if-conversion
        // under -ftrapping-math).
        const bool swap = t1 < t0;
        const double e0 = z0 + t0, e1 = z0 + t1;
        const double a = swap ? e1 : e0, b = swap ? e0 : e1;
        const bool j = (dv[p] > 0) & (a < b);
        const bool isLive = flag[p] == kBatchLive;
        const bool ok = isLive & (fast[p] != 0) & (dv[p] != 0);
        const bool aInf = std::fabs(a) == kInf, bInf = std::fabs(b) == kInf;
        bool piece, dead, scalar;
        double vlo, vhi;
        std::int64_t vloId, vhiId;
        if (kFlip) {
            piece = ok & !j;
            dead = false;
            scalar = !cutMode & ok & j & !aInf & !bInf;  // cut mode: below
            vlo = -kInf;
            vhi = kInf;
            vloId = vhiId = kNoId;
        } else {
            piece = ok & j;
            dead = ok & !j;
            scalar = false;
            vlo = a;
            vhi = b;
            vloId = aInf ? std::int64_t{kNoId} : tag;
            vhiId = bInf ? std::int64_t{kNoId} : tag;
        }
        const double curLo = lo[p], curHi = hi[p];
        const std::int64_t curLoId = loId[p], curHiId = hiId[p];
        const bool takeLo = piece & !(curLo > vlo), takeHi = piece & !(curHi <= vhi);
        double newLo = takeLo ? vlo : curLo, newHi = takeHi ? vhi : curHi;
        std::int64_t newLoId = takeLo ? vloId : curLoId, newHiId = takeHi ? vhiId : curHiId;
        // Cut mode, two finite pieces (−∞, a] and [b, ∞): step 4.
        const bool two = kFlip & cutMode & ok & j & !aInf & !bInf;
        av[p] = a;
        bv[p] = b;
        twov[p] = two;
        lo[p] = newLo;
        loId[p] = newLoId;
        hi[p] = newHi;
        hiId[p] = newHiId;
        flag[p] = dead ? std::uint8_t{kBatchDead} : scalar ? std::uint8_t{kBatchScalar} : flag[p];
        need[p] = isLive & !(piece | dead | scalar | two);
        live += isLive;
    }

    // 4. Cut mode, two finite pieces (−∞, a] and [b, ∞): QuadricBatchPixel's rules as selects.
    // The running interval clipped by each piece; the first non-empty one is kept, and the
    // second one's start lowers the cut when both are non-empty; both empty is dead only without
    // a cut. (A loop of its own: inside step 3 GCC no longer vectorises.)
    if (kFlip && cutMode) {
        for (int p = 0; p < n; ++p) {
            const bool two = twov[p] != 0;
            const double a = av[p], b = bv[p];
            const double curLo = lo[p], curHi = hi[p], curCut = cut[p];
            const std::int64_t curLoId = loId[p], curHiId = hiId[p];
            const bool l0Take = !(curLo > -kInf), h0Take = !(curHi <= a);
            const double l0 = l0Take ? -kInf : curLo, h0 = h0Take ? a : curHi;
            const std::int64_t l0Id = l0Take ? std::int64_t{kNoId} : curLoId;
            const std::int64_t h0Id = h0Take ? tag : curHiId;
            const bool l1Take = !(curLo > b), h1Take = !(curHi <= kInf);
            const double l1 = l1Take ? b : curLo, h1 = h1Take ? kInf : curHi;
            const std::int64_t l1Id = l1Take ? tag : curLoId;
            const std::int64_t h1Id = h1Take ? std::int64_t{kNoId} : curHiId;
            const bool first = l0 < h0, second = l1 < h1;
            const bool useSecond = !first & second;
            const double twoLo = useSecond ? l1 : l0, twoHi = useSecond ? h1 : h0;
            const std::int64_t twoLoId = useSecond ? l1Id : l0Id, twoHiId = useSecond ? h1Id : h0Id;
            lo[p] = two ? twoLo : curLo;
            loId[p] = two ? twoLoId : curLoId;
            hi[p] = two ? twoHi : curHi;
            hiId[p] = two ? twoHiId : curHiId;
            const bool dead = two & !first & !second & (curCut == kInf);
            flag[p] = dead ? std::uint8_t{kBatchDead} : flag[p];
            const bool lower = two & first & second & (l1 < curCut);
            cut[p] = lower ? l1 : curCut;
        }
    }
    return live;
}

// QuadricBatchFastBody built for AVX2 and for the baseline (util/cpu_features.h), from one
// parameter list.
#define QUADRIX_QUADRIC_BATCH_FAST(Name, Target)                                                  \
    template <bool kFlip>                                                                         \
    Target int Name(const RayHalfSpace& hs, bool cutMode, std::int64_t tag, int n,                \
                    const double* __restrict xs, const double* __restrict ys,                     \
                    double* __restrict lo, std::int64_t* __restrict loId, double* __restrict hi,  \
                    std::int64_t* __restrict hiId, std::uint8_t* __restrict flag,                 \
                    double* __restrict cut, std::uint8_t* __restrict need) {                      \
        return QuadricBatchFastBody<kFlip>(hs, cutMode, tag, n, xs, ys, lo, loId, hi, hiId, flag, \
                                           cut, need);                                            \
    }
QUADRIX_QUADRIC_BATCH_FAST(QuadricBatchFastAvx2, QUADRIX_AVX2)
QUADRIX_QUADRIC_BATCH_FAST(QuadricBatchFastBaseline, )
#undef QUADRIX_QUADRIC_BATCH_FAST
template <bool kFlip>
int QuadricBatchFast(const RayHalfSpace& hs, bool cutMode, std::int64_t tag, int n,
                     const double* __restrict xs, const double* __restrict ys,
                     double* __restrict lo, std::int64_t* __restrict loId, double* __restrict hi,
                     std::int64_t* __restrict hiId, std::uint8_t* __restrict flag,
                     double* __restrict cut, std::uint8_t* __restrict need) {
    return gCpuHasAvx2 ? QuadricBatchFastAvx2<kFlip>(hs, cutMode, tag, n, xs, ys, lo, loId, hi,
                                                     hiId, flag, cut, need)
                       : QuadricBatchFastBaseline<kFlip>(hs, cutMode, tag, n, xs, ys, lo, loId, hi,
                                                         hiId, flag, cut, need);
}

}  // namespace

void QuadricBatch(const RayHalfSpace& hs, bool complemented, std::int32_t tag, int n,
                  const double* xs, const double* ys, double* lo, std::int64_t* loId, double* hi,
                  std::int64_t* hiId, std::uint8_t* flag, LiteralCounters& counters, double* cut) {
    if (hs.quartic) {  // never batched: the scalar path evaluates it (up to three pieces)
        for (int p = 0; p < n; ++p)
            if (flag[p] == kBatchLive) flag[p] = kBatchScalar;
        return;
    }
    // A plane (not what this is for), or a c that leaves no pixel to the vectorised pass (c = 0:
    // a cylinder or paraboloid along the rays; non-finite; beyond 2^200): the plain loop.
    if (hs.isPlane || !(std::fabs(hs.c) <= 0x1p200 && hs.c != 0)) {
        for (int p = 0; p < n; ++p)
            if (flag[p] == kBatchLive)
                QuadricBatchPixel(hs, complemented, tag, p, xs, ys, lo, loId, hi, hiId, flag, cut,
                                  counters);
        return;
    }
    const bool flip = (hs.c > 0) == complemented;
    const bool cutMode = cut != nullptr;
    double noCut[kBatchMax];  // the fast pass's cut array outside cut mode (read, left as is)
    for (int base = 0; base < n; base += kBatchMax) {
        const int m = n - base < kBatchMax ? n - base : kBatchMax;
        std::uint8_t need[kBatchMax];
        double* const cuts = cutMode ? cut + base : noCut;
        if (!cutMode)
            for (int p = 0; p < m; ++p) noCut[p] = kInf;
        const int live = flip ? QuadricBatchFast<true>(hs, cutMode, tag, m, xs + base, ys + base,
                                                       lo + base, loId + base, hi + base,
                                                       hiId + base, flag + base, cuts, need)
                              : QuadricBatchFast<false>(hs, cutMode, tag, m, xs + base, ys + base,
                                                        lo + base, loId + base, hi + base,
                                                        hiId + base, flag + base, cuts, need);
        counters.quadrics += static_cast<std::uint64_t>(live);
        LiteralCounters unused;  // already counted
        for (int p = 0; p < m; ++p)
            if (need[p])
                QuadricBatchPixel(hs, complemented, tag, base + p, xs, ys, lo, loId, hi, hiId, flag,
                                  cut, unused);
    }
}

void LiteralSetOnRay(const RayHalfSpace& hs, bool complemented, double x, double y, std::int32_t id,
                     IntervalList& out, LiteralCounters& counters) {
    RaySet s = LiteralOnRay(hs, complemented, x, y, id, counters);
    out.clear();
    for (int i = 0; i < s.count; ++i)
        out.Append(s.piece[i].lo, s.piece[i].loId, s.piece[i].hi, s.piece[i].hiId);
}

}  // namespace quadrix::eval
