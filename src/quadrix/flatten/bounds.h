// Conservative axis-aligned bounds of bodies (intersections of half-space literals) and of CSG
// trees, in device space (or any space the half-spaces are expressed in).
//
// Notation: a literal is a half-space H with an optional complement. Its "inside function" f is
// f = P (plane) or f = Q (quadric) for H and f = -P / -Q for !H; the literal holds where f <= 0
// (the closure of the complement is used, which only ever enlarges the set: conservative).
// A quadric is f(p) = pᵀAp + 2bᵀp + k with A the upper-left 3×3 block of the UniQuadrix matrix
// (DESIGN.md "Coefficients"), b = (G H J) and k = K.
//
// A body's box is found in two stages.
//  (a) Analytic boxes of single literals, intersected into B0:
//      - an axis-aligned plane n_i x_i + d <= 0 bounds axis i by -d/n_i;
//      - a quadric whose A, restricted to the axes it depends on, is positive definite is an
//        ellipsoid (or an elliptic cylinder along the axes it ignores): centre c = -A⁻¹b and
//        half-extent_i = sqrt(R · (A⁻¹)_ii) with R = bᵀA⁻¹b - k (the set is (p-c)ᵀA(p-c) <= R;
//        the extent along e_i is the support function sqrt(R e_iᵀA⁻¹e_i)). R < 0: empty.
//  (b) Where B0 is still infinite, or where more than one literal shapes the body (so B0 may be
//      loose), a best-first branch-and-bound per direction (±x, ±y, ±z) over boxes.
//      Each box (centre c, half-widths h) is tested against each literal with the centred form,
//      exact to second order for quadrics:
//          f(c + d) = f(c) + g·d + dᵀAd,  g = ∇f(c),  |d_i| <= h_i,
//          g·d      ∈ ±Σ|g_i| h_i,
//          dᵀAd     ∈ [max(λmin⁻|h|², -hᵀ|A|h off the PSD diagonal ...), ...]
//      (both the Rayleigh bound λmin|d|² <= dᵀAd <= λmax|d|² and the entrywise bound are valid,
//      the tighter one is used; for convex quadrics λmin >= 0 so the lower bound is f(c) - Σ|g_i|h_i,
//      independent of the box's size along directions where g vanishes). A rounding margin relative
//      to the magnitudes of the terms is added. A box is discarded only when some literal's lower
//      bound is certainly > 0; NaN or inf in a bound means "unknown", never "outside".
//      Boxes are popped in order of their extreme coordinate in the searched direction, so the
//      popped box's face is always a valid (conservative) bound. The search stops when
//        - the popped box is entirely inside the set (the bound is then attained, exact), or
//        - the bound is within relTolerance × (size of the inner box) of a point certified to be
//          in the set, the inner box being the box of all such points found so far, or
//        - the box budget is spent (the bound is still conservative, only looser).
//      Boxes are split in two across the axis that contributes most to the undecided literals'
//      slack (normalised per literal), with a bias toward the searched axis, which is what narrows
//      the bound; thin slabs are fine where the gradient is along the searched axis (the typical
//      case near an extreme point of a smooth surface).
//      A set that reaches the search limit (BoundsOptions::searchLimit, set from the scene scale)
//      on a side is reported unbounded there (±inf).
//
// Tree bounds: union → union of the children's boxes; intersection → intersection; difference →
// the minuend's. Solids' boxes are clipped to the image rectangle [0, width] × [0, height].
//
// Speed (measured in bounds_test.cpp, Release, one core): spheres and ellipsoids take the
// analytic path (about a microsecond each); a capped or mitered oblique cylinder takes a few hundred
// boxes per direction.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/vec.h"

namespace quadrix {

struct BoundsOptions {
    // A set reaching |coordinate| >= searchLimit is reported unbounded on that side. The
    // Flattener sets this to 1e6 × the scene's scale.
    double searchLimit = 1e12;
    // The branch-and-bound stops when the bound is within relTolerance × the size of the part of
    // the set found so far (a point-certified inner box).
    double relTolerance = 1e-3;
    // Boxes popped per direction before giving up (the bound returned is still conservative).
    int maxBoxesPerDirection = 4000;
};

struct BoundsStats {
    std::int64_t bodies = 0;           // bodies bounded
    std::int64_t analyticOnly = 0;     // bodies whose analytic box was exact (no search)
    std::int64_t convexSolves = 0;     // convex-relaxation extremes certified (one per side)
    std::int64_t boxesPopped = 0;      // branch-and-bound boxes popped, over all directions
    std::int64_t boxesTested = 0;      // boxes classified against literals
    std::int64_t budgetExhausted = 0;  // directions that stopped on the box budget
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
double HalfSpaceScale(const FlatHalfSpace& halfSpace);

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

// Fills body, node and solid bounds of a FlatScene; solids are clipped to the image in x and y.
void ComputeSceneBounds(FlatScene& scene, const BoundsOptions& options = {},
                        BoundsStats* stats = nullptr);

}  // namespace quadrix
