// The truncated general cone as an exact Shape (shape.h): BRL-CAD's tgc (and rcc, trc, rec,
// which are tgcs), OpenSCAD's cylinder and cone and the linear_extrude of a circle, the frustum
// of BRL-CAD's part.
//
// Parameters. Base ellipse at V with semi-axis vectors A, B; top ellipse at V + H with semi-axis
// vectors C ∥ A and D ∥ B in the same sense (FORMAT.md §6.1). H need not be perpendicular to A
// and B. A zero A or B (or C or D) is an apex: that end is degenerate; both may not be.
//
// Maths, similar ends (|A|·|D| = |B|·|C|, within librt's relative 1e-4): the solid is
//     P = V + s H + α A + β B,   α² + β² <= (1 + (k − 1) s)²,   0 <= s <= 1,   k = |C|/|A|,
// a quadric capped by two planes. In the local frame (V; A, B, H) of local_frame.h, with
// m = k − 1, the quadric is α² + β² − (1 + m s)² <= 0:
//     Q_loc = [[1 0 0 0] [0 1 0 0] [0 0 −m² −m] [0 0 −m −1]],
// the caps −s <= 0 and s − 1 <= 0: an elliptic cylinder when k = 1, a cone (apex at
// s = 1/(1 − k)) otherwise. An apex at the base (A or B zero) is described from the top end
// (V + H, −H, C, D) so that k stays finite. For the right circular cone of radii r1 at z = 0 and
// r2 at z = h about the z axis (α = x/r1, β = y/r1, s = z/h):
//     Q = <1/r1², 1/r1², −m²/h², 0, 0, 0, 0, 0, −m/h, −1>,   caps <0, 0, −1/h, 0>, <0, 0, 1/h, −1>,
// with m = r2/r1 − 1 (the cylinder: m = 0, Q = <1/r², 1/r², 0, …, 0, −1>).
// Maths, general ends: the quartic general cone of math/quartic_surface.h,
//     F = X² β(T)² + Y² α(T)² − α(T)² β(T)² <= 0 with α, β linear in T,
// capped by its planes T >= 0 and T <= 1 (QuarticSurface::GeneralConeCaps); `quartic` is set.
// Extent: the two end ellipses {V, A, B}, {V + H, k A, k B} (the general cone: C and D along Â,
// B̂), exact under any affine map (the solid is their convex hull).
#pragma once

#include <optional>

#include "quadrix/import/shapes/shape.h"
#include "quadrix/math/vec.h"

namespace quadrix::import {

// Relative tolerance of librt's quadric-tgc test |A|·|D| = |B|·|C| (FORMAT.md §6.1 quotes
// NEAR_EQUAL(..., 0.0001)), applied relative to the products so that it is unit-free.
inline constexpr double kSimilarEndsTol = 1e-4;

struct ConeShape : ShapeResult {
    bool quartic = false;  // the ends are not similar: the general (quartic) cone was built
};

ConeShape TruncatedConeShape(const Vec3& v, const Vec3& h, const Vec3& a, const Vec3& b,
                             const Vec3& c, const Vec3& d);

// The body of the similar-ended cone above from the base (v; a, b), the height vector h and the
// ratio k of the top semi-axes to the base's: the quadric and its two caps. nullopt when a, b, h
// are coplanar. (BRL-CAD's part uses it for the frustum between its spheres.)
std::optional<ShapeBody> SimilarConeBody(const Vec3& v, const Vec3& a, const Vec3& b, const Vec3& h,
                                         double k);

}  // namespace quadrix::import
