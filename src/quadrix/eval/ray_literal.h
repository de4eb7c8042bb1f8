// The set of ray parameters where one half-space literal holds (DESIGN.md "Engines in more
// detail", raycast).
//
// A pixel's ray is x(t) = (x, y, t) in device space (x = i + ½, y = j + ½, t = device z, growing
// away from the viewer). Along it
//   plane   <A B C D>:  P(t) = C t + (A x + B y + D)
//   quadric <A … K>:    Q(t) = C t² + 2 (F x + E y + J) t + (A x² + B y² + 2D xy + 2G x + 2H y + K)
// (UniQuadrix coefficient order with the factor 2 on cross and linear terms, quadric.h), i.e. the
// "c z² + 2 b z + a" of DESIGN.md; the quadratic is solved by SolveQuadratic (math/quadratic.h).
//
// The literal H holds where P or Q <= 0, which on a ray is an interval, the complement of one
// (double cones, two-sheet hyperboloids, a cylinder seen sideways from outside …), everything or
// nothing. The complemented literal !H is the closure of the complement. Sets follow the
// regularised convention of math/interval_list.h: a ray that only touches a surface (a tangent ray,
// a ray through a cone's apex) gets no degenerate point interval, and a plane containing the ray
// (C = 0 and A x + B y + D = 0) holds along all of it while its complement holds nowhere.
// Non-finite coefficients along the ray (NaN, or overflow far from the origin) give the empty set
// for both H and !H: the body that uses the literal is not drawn there.
//
// Quartics (math/quartic_surface.h: torus, elliptical torus, general cone): the set comes from
// QuarticSurface::OnLine on the homogeneous device line (x, y, 0, 1) + t (0, 0, 1, 0), clipped to
// the surface's box and solved by the certified root isolation of math/quartic_roots.h: at most
// two pieces for H, three for !H (a ray through both tubes of a torus). No batch or tile proof
// applies to them (body_batch.cpp sends their pixels to the scalar path, tile_reduction.cpp never
// classifies them), so every quartic literal is evaluated by LiteralOnRay.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/interval_list.h"

namespace quadrix::eval {

// A half-space's coefficients regrouped for evaluation along rays parallel to z.
//
// Quadrics are re-centred (STYLE.md "re-centre before solving") on a reference point p0, the
// quadric's centre rounded to integers when it has one (see Centre): Q(p0 + d) = dᵀA d +
// 2 (A p0 + b)ᵀ d + Q(p0), so along the ray t = z0 + t'
//   Q = C t'² + 2 (F x' + E y' + J') t' + (x' (A x' + 2D y' + 2G') + y' (B y' + 2H') + K'),
//   x' = x − x0, y' = y − y0, (G' H' J') = A p0 + b, K' = Q(p0).
// Without it, a sphere of radius r at depth z solves h² − a c with h² ≈ a c ≈ z² ≫ r²: the
// discriminant is a difference of nearly equal numbers for every pixel (slow compensated path of
// SolveQuadratic, and per-pixel rounding noise of u·z² in c); re-centred, h ≈ 0 and the plain
// discriminant is exact to 3u. The rounding of K' (about u·|p0|²·|A|, once per surface) is of the
// size the coefficients already carry.
struct RayHalfSpace {
    bool isPlane = true;
    // Set for a quartic (then isPlane is false and the quadric fields are unused).
    std::shared_ptr<const QuarticSurface> quartic;
    bool IsQuadric() const { return !isPlane && !quartic; }
    // Plane: P = c t + (px x + py y + pd), not re-centred (no cancellation to avoid).
    // Quadric: as above, with c = C.
    double c = 0;
    double x0 = 0, y0 = 0, z0 = 0;                             // quadric reference point p0
    double hx = 0, hy = 0, h0 = 0;                             // F, E, J'
    double axx = 0, axy = 0, ax = 0, byy = 0, by = 0, k0 = 0;  // A, 2D, 2G', B, 2H', K'
    double px = 0, py = 0, pd = 0;

    // `reference` is p0 for a quadric (ignored for a plane); integers keep the shift exact.
    static RayHalfSpace From(const FlatHalfSpace& hs, const Vec3& reference = {});

    // The centre −A⁻¹b of a quadric whose quadratic part A (3×3) is safely invertible (spheres,
    // ellipsoids, cones, hyperboloids), rounded to integers; nullopt for cylinders, paraboloids,
    // degenerate or non-finite quadrics and centres beyond 1e12.
    static std::optional<Vec3> Centre(const Quadric& q);
};

// What evaluating a literal cost (for RenderStats).
struct LiteralCounters {
    std::uint64_t planes = 0;
    std::uint64_t quadrics = 0;
    std::uint64_t quartics = 0;
};

// A literal's set on one ray: at most two pieces for planes and quadrics, three for a
// complemented quartic; canonical (see interval_list.h).
struct RaySet {
    Interval piece[3];
    int count = 0;
};

// The set of t where the literal holds on the ray through (x, y); finite endpoints carry `id`,
// infinite ones Interval::kNoId.
RaySet LiteralOnRay(const RayHalfSpace& hs, bool complemented, double x, double y, std::int32_t id,
                    LiteralCounters& counters);

// What a quadric literal does on every ray of a rectangle of pixel centres, when that can be
// proved: along the ray, Q(t) = c t² + 2 h t + k (ray_literal.h) with h linear and k quadratic in
// the pixel position, so its discriminant D = h² − c k is a quadratic polynomial in (x, y).
// Expanded about the rectangle's centre, D = d0 + bu u + bv v + auu u² + auv u v + avv v² for
// |u| <= hu, |v| <= hv, and d0 + |bu| hu + |bv| hv + max(auu, 0) hu² + |auv| hu hv +
// max(avv, 0) hv² bounds it from above. Below −1e-8 times the sum of the magnitudes of the
// terms (rounding of this bound and of the per-pixel h, k and D is some 1e-15 of that), no ray
// meets the surface and Q keeps the sign of c on all of it: SolveQuadratic finds no root at
// any pixel, so the set is everything (c < 0) or nothing (c > 0). Only for c ≠ 0.
enum class QuadricOnRect { kUnknown, kInsideEverywhere, kOutsideEverywhere };
// `x0..x1 × y0..y1` is the rectangle of pixel centres.
QuadricOnRect ClassifyQuadric(const RayHalfSpace& hs, double x0, double x1, double y0, double y1);

// Per-pixel states of a body batch.
enum : std::uint8_t { kBatchLive = 0, kBatchDead = 1, kBatchScalar = 2 };
// For each pixel p < n with flag[p] == kBatchLive:
//    S = LiteralOnRay(hs, complemented, xs[p], ys[p], tag, ...)
//  - S.count == 0 -> flag[p] = kBatchDead;
//  - S.count == 2 -> flag[p] = kBatchScalar;
//  - S.count == 1 -> clip by its piece v with exactly these rules:
//        if (!(lo[p] > v.lo)) { lo[p] = v.lo; loId[p] = v.loId; }
//        if (!(hi[p] <= v.hi)) { hi[p] = v.hi; hiId[p] = v.hiId; }
// Pixels whose flag is not kBatchLive are left untouched (all arrays). A quartic marks every live
// pixel kBatchScalar.
// counters.quadrics += number of live pixels.
//
// Bit-identical to that loop for every input: a vectorised pass does the common case (c ≠ 0, no
// rescaling in SolveQuadratic, discriminant ≠ 0) with the same operations in the same order, and
// the pixels it leaves (c = 0, tangent rays, non-finite or extreme coefficients, …) go through
// LiteralOnRay itself. The output arrays must not overlap each other or xs, ys. Meant for
// quadrics (for a plane it is just the loop above).
//
// Cut mode (`cut` not null; cut[p] = +inf at the start of a body): the running [lo, hi] of a pixel
// is then the *first interval* of the body's set so far, exact on t < cut[p] (ids included), and
// a literal set of two pieces p0 < p1 is taken in instead of marking the pixel kBatchScalar: the
// running interval clipped by p0 (the rules above) if that is not empty, and then, when the one
// clipped by p1 is not empty either, cut[p] lowered to its start; else the one clipped by p1.
// Both empty is kBatchDead only while cut[p] is +inf (with a cut, the set beyond it may remain:
// lo >= hi then means "∅ below the cut"). Set operations are pointwise in t and the pieces of a
// body's list are separated, so the first interval and everything below the cut are those of the
// scalar body evaluation (trace.cpp, Tracer::EvaluateBodyLists), bit for bit.
void QuadricBatch(const RayHalfSpace& hs, bool complemented, std::int32_t tag, int n,
                  const double* xs, const double* ys, double* lo, std::int64_t* loId, double* hi,
                  std::int64_t* hiId, std::uint8_t* flag, LiteralCounters& counters,
                  double* cut = nullptr);

// The same as an IntervalList (for tests and callers that want a list).
void LiteralSetOnRay(const RayHalfSpace& hs, bool complemented, double x, double y, std::int32_t id,
                     IntervalList& out, LiteralCounters& counters);

}  // namespace quadrix::eval
