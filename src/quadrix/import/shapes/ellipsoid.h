// The ellipsoid and the sphere as exact Shapes (shape.h): BRL-CAD's ell and sph, OpenSCAD's
// sphere (scaled into an ellipsoid by its transforms), the ends of BRL-CAD's part.
//
// Maths. The ellipsoid with centre V and semi-axis vectors A, B, C (any three independent vectors;
// they need not be perpendicular, the solid is then still an ellipsoid) is the unit ball of the
// local frame (V; A, B, C) of local_frame.h:
//     u1² + u2² + u3² − 1 <= 0,   Q_loc = diag(1, 1, 1, −1),   Q = Lᵀ Q_loc L in shape space.
// For the sphere of radius r about c (A, B, C = r times the unit axes), u = (P − c)/r and
//     Q = <1/r², 1/r², 1/r², 0, 0, 0, −cx/r², −cy/r², −cz/r², (|c|² − r²)/r²>
// in DESIGN.md's order <A B C D E F G H J K>, the factor 2 on the linear terms included.
// One body of one quadric. Extent: the ellipsoid itself, the piece {V, A, B, C}, whose box under
// any affine map is exact. Refused when A, B, C are dependent (a flat or degenerate ellipsoid).
#pragma once

#include "quadrix/import/shapes/shape.h"
#include "quadrix/math/vec.h"

namespace quadrix::import {

ShapeResult EllipsoidShape(const Vec3& centre, const Vec3& a, const Vec3& b, const Vec3& c);

// The sphere of radius r about `centre`: EllipsoidShape(centre, r x̂, r ŷ, r ẑ).
ShapeResult SphereShape(const Vec3& centre, double r);

}  // namespace quadrix::import
