// The torus and the elliptical torus as exact Shapes (shape.h): BRL-CAD's tor and eto,
// OpenSCAD's rotate_extrude of a circle (a circle turned into an ellipse by its transforms gives
// the elliptical torus).
//
// Maths (math/quartic_surface.h has the surfaces): in a frame whose z axis is the axis of
// revolution, ρ = sqrt(x² + y²), the meridian ellipse g(ρ, z) <= 0 turned about the axis is the
// quartic F = E² − ρ² O² <= 0 with g = E + ρ O split into its even and odd parts in ρ. For the
// torus of ring radius R and tube radius r (0 < r < R) about the z axis through the origin,
//     F = (x² + y² + z² + R² − r²)² − 4 R² (x² + y²) <= 0.
// The elliptical torus: centre V, axis N, radius of revolution r, meridian ellipse with the
// semi-axis vector C (in the plane of N and a radius) and the other semi-axis of length r_d,
// centred at distance r from the axis; the ellipse must not reach the axis.
// One body of one quartic literal.
// Extent. A torus is not the convex hull of ellipsoids but a Minkowski sum: its ring circle
// {V, R e1, R e2} plus the ball of radius r (shape.h extentSums), exact. The elliptical torus: its
// circle of radius r plus the cylinder (a disc of the meridian ellipse's radial half extent ⊕ a
// segment of its axial half extent along N) that holds the meridian ellipse: a containing sum.
#pragma once

#include "quadrix/import/shapes/shape.h"
#include "quadrix/math/vec.h"

namespace quadrix::import {

// Torus about `axis` (any non-zero length) through `centre`, ring radius R, tube radius r.
ShapeResult TorusShape(const Vec3& centre, const Vec3& axis, double R, double r);

// Elliptical torus (BRL-CAD eto's parameters V, N, r, C, r_d).
ShapeResult EllipticalTorusShape(const Vec3& centre, const Vec3& axis, double r, const Vec3& c,
                                 double rd);

}  // namespace quadrix::import
