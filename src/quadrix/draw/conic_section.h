// The intersection of a plane with a quadric as exact parametric curves (docs/drawings.md).
//
// Method. Choose a point o on the plane (the foot of the box centre) and an orthonormal pair
// e1, e2 spanning it; with H = [e1 e2 o; 0 0 1] (4×3), the quadric restricted to the plane is the
// 2-D conic  q(s, t) = [s t 1] Hᵀ Q H [s t 1]ᵀ  (Q the symmetric 4×4 matrix of quadric.h). Its
// quadratic part is diagonalised by a rotation w1, w2 (eigenvalues λ1, λ2, |λ1| >= |λ2|), and in
// those axes q = λ1 σ² + λ2 ρ² + k after completing squares (the centre), or
// q = λ1 σ² + 2 β ρ + k when λ2 vanishes (parabolic). Then
//   λ1 λ2 > 0, −k/λ1 > 0 : ellipse, semi-axes sqrt(−k/λ1), sqrt(−k/λ2)
//   λ1 λ2 < 0, k ≠ 0     : hyperbola, two branches
//   λ1 λ2 < 0, k = 0     : two lines crossing at the centre (a plane through a cone's apex)
//   λ2 = 0, β ≠ 0        : parabola
//   λ2 = 0, β = 0        : two parallel lines (a plane parallel to a cylinder's axis), one double
//                          line when k = 0 (the plane is tangent to the cylinder), or none
//   λ1 = λ2 = 0          : the line 2 b·(s, t) + k = 0 (the quadric is linear on the plane)
// "Vanishes" is decided against the size of the terms over the box: |λ| R², |β| R, |k| are
// compared with 1e-10 times the largest of them (R = the box's half-diagonal). Unbounded curves
// get a parameter range that covers the box (lines are clipped to it exactly).
#pragma once

#include <vector>

#include "quadrix/draw/curve.h"
#include "quadrix/math/quadric.h"

namespace quadrix::draw {

// The curves of plane ∩ quadric inside `box` (a finite box). `tangent` is set when the
// intersection is a double line (plane tangent to the quadric along a line).
std::vector<Curve3> PlaneQuadricCurves(const Plane& plane, const Quadric& quadric, const Box3& box,
                                       bool* tangent = nullptr);

// The line where two planes meet, clipped to `box`; false when they are parallel or the line
// misses the box.
bool PlanePlaneLine(const Plane& p1, const Plane& p2, const Box3& box, Curve3& out);

// Clips the line o + t u, t in [t0, t1], to the box (slabs); false when nothing is left.
bool ClipLineToBox(const Vec3& o, const Vec3& u, const Box3& box, double& t0, double& t1);

}  // namespace quadrix::draw
