// Quartic half-spaces: the torus, the elliptical torus (BRL-CAD `eto`) and the general truncated
// cone (BRL-CAD `tgc` whose end ellipses are not similar), issue 20. They take part in CSG exactly
// like planes and quadrics (math/plane_or_quadric.h): a surface F = 0 whose inside is F <= 0.
//
// Representation. A generic device-space quartic has 35 coefficients and, for a torus of radius 1
// at depth 1000, terms of size 1e12 that cancel to 1: useless. A QuarticSurface therefore keeps
//   - its kind and shape parameters in a LOCAL frame where the body is centred and of size ~1, and
//   - the projective map `localFromSpace` from the containing space (object, world or device) to
//     that frame (a Transform: matrix and inverse, mat4.h).
// Mapping the surface by a point map x' = M x only composes localFromSpace with M⁻¹ (TransformBy),
// so every evaluation happens in re-centred, unit-sized local coordinates whatever the space.
//
// Local functions, in homogeneous local coordinates (X, Y, Z, W) (F is homogeneous of degree 4,
// F(λ·P) = λ⁴ F(P): its sign, hence inside/outside, does not depend on the representative):
//  - kRevolvedEllipse (torus and elliptical torus): the axis is local Z through the origin, the
//    meridian ellipse in the half-plane (ρ, z), ρ = sqrt(X² + Y²) >= 0, is g(ρ, z) <= 0 with
//        g = a ρ² + 2 b ρ z + c z² + d ρ + e z + f      (a, c > 0, ac > b²: an ellipse)
//    Writing g = E + ρ O with E = a ρ² + c z² + e z + f (even in ρ) and O = 2 b z + d, the surface
//    of revolution is g(ρ, z) g(−ρ, z) = 0:
//        F = E² − (X² + Y²) O²,   E = a (X² + Y²) + c Z² + e Z W + f W²,   O = 2 b Z + d W.
//    When the ellipse does not reach the axis, g(−ρ, z) > 0 for ρ >= 0, so F <= 0 exactly inside.
//    A torus (major R, minor r) is g = (ρ − R)² + z² − r²: F = (ρ² + z² + R² − r²)² − 4R²ρ².
//  - kGeneralCone (tgc): local (X, Y, T) with space point p = V + X·Â + Y·B̂ + T·H (Â, B̂ unit,
//    H the height vector, not necessarily perpendicular to them), semi-axes α(T) = α0 + α1 T and
//    β(T) = β0 + β1 T (homogeneous: α = α0 W + α1 T):
//        F = X² β² + Y² α² − α² β²   (<= 0: X²/α² + Y²/β² <= 1 where α, β ≠ 0).
//    Local X and Y are divided by the largest semi-axis so that they are ~1 as T is.
//
// Clip box. Each surface has a box in local coordinates (LocalBox) and the half-space is defined as
// {F <= 0} ∩ box: the inside never extends beyond it. For the revolved ellipse the box contains
// the whole solid, so this is just F <= 0. For the general cone the box is the slab
// T ∈ [−kConeSlabMargin, 1 + kConeSlabMargin] (and |X| <= max α, |Y| <= max β): the quartic is a
// double cone beyond an apex and unbounded, so the cone is meant to be capped by the separate
// plane literals T >= 0 and T <= 1 (GeneralConeCaps). The margin makes the caps, not the box,
// bound the capped body, so cap pixels are drawn by the cap planes with their exact normals.
//
// Along a line. The ray or shadow ray P(t) = P0 + t·P1 (homogeneous points of the containing
// space: P0 = (x, y, 0, 1), P1 = (0, 0, 1, 0) for the raycast engine's device rays, parallel and
// perspective alike; any direction for shadow rays) maps to L0 + t·L1 in local coordinates and F
// becomes a quartic in t. OnLine clips the line to the box (six linear constraints and W > 0,
// exact in t), re-parametrises t = tm + h s so that the box interval is s ∈ [−1, 1] (the body's
// depth range, so the coefficients are O(1) and well conditioned), expands F(L0' + s L1') and
// isolates its roots on [−1, 1] (math/quartic_roots.h: certified derivative cascade). The set
// F <= 0 comes out as at most two intervals (four roots), in the regularised convention of
// math/interval_list.h: a tangent (double-root) contact gives no point interval.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/math/mat4.h"
#include "quadrix/math/vec.h"

namespace quadrix {

// Up to two closed intervals [lo, hi] of the line parameter where F <= 0 (sorted, separated).
struct QuarticLineSet {
    std::array<double, 2> lo{}, hi{};
    int count = 0;
};

struct QuarticSurface {
    enum class Kind { kTorus, kEllipticalTorus, kGeneralCone };
    static constexpr double kConeSlabMargin = 1.0 / 64;

    Kind kind = Kind::kTorus;
    // Shape parameters as given (containing-space units), for export and diagnostics:
    //  kTorus:           p[0] = R (major), p[1] = r (minor)
    //  kEllipticalTorus: p[0] = r (radius of revolution), p[1] = |C| (semi-axis), p[2] = d
    //                    (the other semi-axis), p[3], p[4] = C's components along the radius and
    //                    the axis (cρ, cz)
    //  kGeneralCone:     p[0..3] = |A|, |B|, |C|, |D|
    std::array<double, 5> p{};
    // Local evaluation coefficients (see the file comment):
    //  revolved ellipse: k = {a, b, c, d, e, f}
    //  general cone:     k = {α0, α1, β0, β1}
    std::array<double, 6> k{};
    Box3 localBox;             // the clip box (local coordinates)
    Transform localFromSpace;  // containing space → local frame (projective in device space)

    // --- Constructors (containing-space units; nullopt with `why` set for bad parameters) ---
    // A torus about `axis` (any non-zero length) through `center`: 0 < r < R.
    static std::optional<QuarticSurface> Torus(const Vec3& center, const Vec3& axis, double R,
                                               double r, std::string* why = nullptr);
    // BRL-CAD eto: centre V, axis N, radius of revolution r, ellipse semi-axis vector C (in the
    // plane of N and a radius; its length and tilt), other semi-axis length d (perpendicular to C
    // in the meridian plane). The ellipse must not reach the axis.
    static std::optional<QuarticSurface> EllipticalTorus(const Vec3& V, const Vec3& N, double r,
                                                         const Vec3& C, double d,
                                                         std::string* why = nullptr);
    // BRL-CAD tgc: base V, height H, base semi-axes A ⊥ B (both ⊥ to nothing else required),
    // top semi-axes C ∥ A and D ∥ B given by their lengths c, d (>= 0, not both ends degenerate).
    // The cone must be capped: GeneralConeCaps gives the planes T >= 0 and T <= 1.
    static std::optional<QuarticSurface> GeneralCone(const Vec3& V, const Vec3& H, const Vec3& A,
                                                     const Vec3& B, double c, double d,
                                                     std::string* why = nullptr);
    // The caps of a general cone in the containing space, as plane coefficients <A B C D>
    // (inside <= 0): [0] is −T <= 0 (the base), [1] is T − 1 <= 0 (the top).
    std::array<Vec4, 2> GeneralConeCaps() const;

    // --- Evaluation in the containing space ---
    // F at a point (w = 1): <= 0 inside. Outside the clip box: a positive value.
    double Evaluate(const Vec3& p) const;
    // The homogeneous gradient (covector) of F∘localFromSpace at p; its xyz is the outward normal
    // direction in the containing space (up to a positive factor), mapped like a plane.
    Vec4 HomogeneousGradient(const Vec3& p) const;
    // The same surface after the point map x' = M x: localFromSpace ← localFromSpace · t⁻¹.
    void TransformBy(const Transform& t);
    bool AllFinite() const;

    // The set of t where P0 + t P1 is inside (F <= 0 within the clip box), `P0`, `P1` homogeneous
    // containing-space points. Always finite endpoints (the box bounds the set).
    QuarticLineSet OnLine(const Vec4& P0, const Vec4& P1) const;
    // The coefficients c[0..4] of F(L0 + s L1) = Σ c_i s^i for local homogeneous L0, L1.
    std::array<double, 5> LocalLinePolynomial(const Vec4& L0, const Vec4& L1) const;
    // F in local homogeneous coordinates (no clip box).
    double LocalF(const Vec4& L) const;

    // A conservative containing-space box of the inside (the local box's 8 corners mapped; the
    // whole space when the map is projective and the box reaches the vanishing plane).
    Box3 SpaceBounds() const;
    // The planes (<A B C D>, inside <= 0) of the clip box in the containing space, 6 faces and,
    // for a projective localFromSpace, W > 0: their intersection contains the inside (a convex
    // superset, used by flatten/bounds).
    std::vector<Vec4> SpaceBoxPlanes() const;

    // "torus", "elliptical torus", "general cone": for messages naming the primitive.
    std::string_view KindName() const;
};

}  // namespace quadrix
