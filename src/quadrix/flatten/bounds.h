// Conservative axis-aligned bounds of bodies (intersections of half-space literals) and of CSG
// trees, in device space (or any space the half-spaces are expressed in).
//
// Notation: a literal is a half-space H with an optional complement. Its "inside function" f is
// f = P (plane) or f = Q (quadric) for H and f = -P / -Q for !H; the literal holds where f <= 0
// (the closure of the complement is used, which only ever enlarges the set: conservative).
// A quadric is f(p) = pᵀAp + 2bᵀp + k with A the upper-left 3×3 block of the UniQuadrix matrix
// (DESIGN.md "Coefficients"), b = (G H J) and k = K.
//
// A body's box is found in stages; each stage only ever shrinks a box that is already valid.
//  (a) Analytic boxes of single literals, intersected into B0 (bounds_math.cpp):
//      - an axis-aligned plane n_i x_i + d <= 0 bounds axis i by -d/n_i;
//      - a quadric whose A, restricted to the axes it depends on, is positive definite is an
//        ellipsoid (or an elliptic cylinder along the axes it ignores): centre c = -A⁻¹b and
//        half-extent_i = sqrt(R · (A⁻¹)_ii) with R = -f(c) = bᵀA⁻¹b - k (the set is
//        (p-c)ᵀA(p-c) <= R, whose support along e_i is sqrt(R e_iᵀA⁻¹e_i)); R < 0: empty.
//      Literals containing all of B0 are dropped; when a single ellipsoid (or axis cylinder) is
//      left, B0 is exact and we stop (10,000 spheres: ~5 ms).
//  (a') A body of planes only (at most 16): the box of its vertices, enumerated over triples of
//      its planes and the search region's faces (exact; bounds.cpp PolytopeBox).
//  (a'') A body of ONE convex quadric (positive semidefinite, or a nappe separated from its twin
//      by one of the planes) and at most 16 planes: capped and mitered cylinders and cones,
//      ellipsoids cut by planes (bounds_critical.cpp). The extremes of ±x, ±y, ±z over the body
//      are among finitely many critical points (three planes; a two-plane edge ∩ the quadric; the
//      critical points on a plane's conic and on the quadric: each a linear solve and one
//      quadratic); the best feasible one per side, with KKT multipliers fitted there, goes through
//      the weak-duality certificate of (b1) below, so the box is rigorous whatever the rounding
//      of the enumeration (a capped cylinder's search region is first cut to a ball proven to
//      hold it: the certificate's allowance for a cylinder's rounding-level negative eigenvalue
//      grows with the ball's radius squared). Declines (the next stages decide) when a certified
//      side is more than 1e-7 × (size + |coordinate|) from its candidate (1e-5 for a nappe), when
//      the body is unbounded or has no feasible candidate. ~10-20 µs a body, where (b1) takes
//      ~1 ms.
//  (b1) The convex relaxation (bounds_relaxation.cpp): planes, positive semidefinite quadrics
//      (ellipsoids, cylinders, paraboloids) and "nappes" (one nappe of a cone or the inside of one
//      sheet of a two-sheet hyperboloid: convex, and proven to contain the body by a separating
//      plane constraint or an LP), plus the search region's faces. For each of ±x, ±y, ±z a
//      log-barrier interior-point method finds the extreme point, Newton on the KKT system of the
//      active constraints polishes it, and Lagrangian weak duality certifies the bound:
//          e·x <= e·x - Σ λ_i f_i(x) - μ f_ball(x)  <=  L(x̂) + sup_d (r·d - dᵀMd),
//      for any λ >= 0, any x̂ (r = ∇L(x̂), M = Σλ_i A_i + μ I/R²), evaluated with rounding
//      allowances; a nappe enters as its supporting plane through the apex. Exact (to ~1e-9 of the
//      size) for convex bodies: capped and mitered cylinders, capped cones, tubes (whose
//      complemented inner literal is left out and checked at the extreme point). A quadric counts
//      as positive semidefinite when λmin(A) >= -1e-12 ‖A‖ (relative to A, not to the largest of
//      the ten coefficients: a cone far from the origin, whose normalised A is tiny, is not
//      convex). The relaxation's interior point must stay inside the certified box; when it does
//      not (rounding allowances overrun by a nearly singular A), the relaxation is discarded and
//      (b2) bounds every side. Measured
//      (bounds_test.cpp, -O3, one core of a loaded 2-core machine): ~150-250 µs per mitered pipe
//      or cone frustum.
//  (b2) Where (b1) cannot settle a side (a non-convex literal cuts off the relaxation's extreme
//      or bounds a side it leaves unbounded: hyperboloids of one sheet, complemented quadrics
//      reaching the outside), a best-first branch-and-bound per direction over boxes
//      (bounds_search.cpp). Each box (centre c, half-widths h) is tested against each literal with
//      the centred form, exact to second order for quadrics:
//          f(c + d) = f(c) + g·d + dᵀAd,  g = ∇f(c),  |d_i| <= h_i,
//      with g·d in ±Σ|g_i|h_i and dᵀAd bounded by the tighter of the entrywise and the Rayleigh
//      (eigenvalue) bounds, plus a rounding margin; a box is discarded only when some literal (or
//      a non-negative combination of the undecided ones, with weights making its gradient point
//      along the searched direction as KKT multipliers do) is certainly > 0. NaN or inf means
//      "unknown", never "outside". A box is halved across the axis of largest smear
//      (max |∂f/∂x_i| over the box × h_i, summed over the undecided literals, plus a bonus for the
//      searched axis): at a box centred on a hyperboloid's axis the gradient vanishes but the
//      smear does not. Boxes pop in order of their extreme coordinate, so the popped
//      face is always a valid bound; the search stops when the popped box lies inside the set
//      (exact), within relTolerance × (size of the certified inner box) of a point of the set,
//      or when the box budget is spent (still conservative). A capped one-sheet hyperboloid
//      takes a few milliseconds.
// A side beyond 1e-3 × searchLimit is reported unbounded (±inf): a set cut off only by the
// search box can leave it through another face, so its extent along an axis oblique to its
// recession direction is large but below the limit itself.
//
// Tree bounds: union → union of the children's boxes; intersection → intersection; difference →
// the minuend's. Solids' boxes are clipped to the image rectangle [0, width] × [0, height].
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/vec.h"

namespace quadrix {

struct LiteralCache;  // flatten/literal_cache.h

struct BoundsOptions {
    // The search region is |coordinate| <= searchLimit; a side beyond 1e-3 × searchLimit is
    // reported unbounded. The Flattener sets this to 1e6 × the scene's scale.
    double searchLimit = 1e12;
    // The branch-and-bound (stage (b2)) stops when the bound is within relTolerance × the size
    // of the part of the set found so far (a point-certified inner box).
    double relTolerance = 1e-3;
    // Boxes popped per direction before giving up (the bound returned is still conservative).
    int maxBoxesPerDirection = 4000;
    // Stage (a') for bodies of at most 16 planes: the box of the polytope's vertices (exact, far
    // cheaper than the relaxation); off only to compare the two in tests.
    bool polytopeVertices = true;
    // Stage (a'') for bodies of one convex quadric and at most 16 planes (bounds_critical.cpp);
    // off only to compare it with the relaxation in tests.
    bool criticalPoints = true;
    // Stage (a'') leaves out of its enumeration the faces of a capped cylinder's bootstrap box,
    // which lie apart from the body (bounds_critical.cpp); true only to check in tests that this
    // changes no box.
    bool criticalPointsOnApartFaces = false;
    // Stage (a) of the uncomplemented quadric literals, made once for the half-spaces these
    // bounds are taken over (flatten/literal_cache.h); null: each literal's is made as needed.
    // The boxes are the same bits either way.
    const LiteralCache* literals = nullptr;
};

struct BoundsStats {
    std::int64_t bodies = 0;              // bodies bounded
    std::int64_t analyticOnly = 0;        // bodies whose analytic box was exact (no search)
    std::int64_t convexSolves = 0;        // convex-relaxation extremes certified (one per side)
    std::int64_t boxesPopped = 0;         // branch-and-bound boxes popped, over all directions
    std::int64_t boxesTested = 0;         // boxes classified against literals
    std::int64_t budgetExhausted = 0;     // directions that stopped on the box budget
    std::int64_t criticalPointBoxes = 0;  // bodies bounded by stage (a'')
    std::int64_t neckWideBoxes = 0;       // of those, tight only within a nappe's neck allowance
};

struct BoundLiteral {
    const FlatHalfSpace* halfSpace = nullptr;
    bool complemented = false;
};

// The analytic box of one literal (stage (a)); Box3::Everything() when it has none, an empty box
// when the literal's set is provably empty.
Box3 LiteralBox(const FlatHalfSpace& halfSpace, bool complemented);

// A length characterising where a half-space lies (distance of a plane from the origin, size and
// position of a quadric); used by the Flattener to choose searchLimit. 0 when unknown.
// `literalBox` and `quadricExtent`, when given, are LiteralBox(halfSpace, false) and the
// quadric's extent already made from one inside function (LiteralCache::Entry).
double HalfSpaceScale(const FlatHalfSpace& halfSpace, const Box3* literalBox = nullptr,
                      const double* quadricExtent = nullptr);

// Conservative bounds of the intersection of the literals. Infinite coordinates mean unbounded
// on that side; an empty box means the set is provably empty.
Box3 IntersectionBounds(std::span<const BoundLiteral> literals, const BoundsOptions& options = {},
                        BoundsStats* stats = nullptr);

// IntersectionBounds of a FlatBody's literals.
Box3 BodyBounds(const FlatScene& scene, const FlatBody& body, const BoundsOptions& options = {},
                BoundsStats* stats = nullptr);

// Node bounds from per-body boxes (indexed like scene.bodies): union / intersection / minuend.
// Nodes must be stored children before parents (as the Flattener emits them).
std::vector<Box3> TreeBounds(const FlatScene& scene, const std::vector<Box3>& bodyBoxes);
// One node of TreeBounds: a leaf's box is `leafBody` (its body's), another node's combines its
// children's boxes in `nodeBoxes`. A node's box is thus a function of its subtree alone.
Box3 TreeNodeBounds(const FlatCsgNode& node, const Box3& leafBody,
                    const std::vector<Box3>& nodeBoxes);

// Fills body, node and solid bounds of a FlatScene; solids are clipped to the image in x and y.
void ComputeSceneBounds(FlatScene& scene, const BoundsOptions& options = {},
                        BoundsStats* stats = nullptr);

}  // namespace quadrix
