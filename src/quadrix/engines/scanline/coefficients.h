// The Resolver's tools (seed 001 §4.5): coefficients of intersection lines, intersection conics,
// limb planes and limb conics, i-vertex equations, and the zero tests of §4.5.13 with estimated
// worst-case errors.
//
// Frame: device space (DESIGN.md): x = column, y = row, rays along +z, z grows away from the
// viewer. Planes <A B C D> and quadrics <A … K> in UniQuadrix order (quadric.h; the cross and
// linear terms carry a factor 2). 2-D shapes live in the view plane (x, y):
//   line   (4.2)  L(x, y) = a x + b y + c
//   conic  (4.3)  C(x, y) = a x² + b y² + c xy + d x + e y + f      (no factors 2 here)
//   quadratic (4.1) R(t) = a t² + b t + c
//
// Every formula below was re-derived (the OCR of the seed damaged some) and is unit-tested
// numerically in coefficients_test.cpp: each shape is checked to vanish on points constructed
// independently (points of both surfaces, of the limb, of the line).
#pragma once

#include <optional>
#include <vector>

#include "quadrix/math/quadric.h"
#include "quadrix/math/vec.h"

namespace quadrix::scanline {

struct Line2 {
    double a = 0, b = 0, c = 0;
    double Evaluate(double x, double y) const { return a * x + b * y + c; }
    // Sum of the magnitudes of the terms: the scale the rounding error of Evaluate is relative to.
    double TermScale(double x, double y) const {
        return std::fabs(a * x) + std::fabs(b * y) + std::fabs(c);
    }
};

struct Conic2 {
    double a = 0, b = 0, c = 0, d = 0, e = 0, f = 0;
    double Evaluate(double x, double y) const {
        return a * x * x + b * y * y + c * x * y + d * x + e * y + f;
    }
};

struct Quadratic1 {
    double a = 0, b = 0, c = 0;  // a t² + b t + c
    double Evaluate(double t) const { return (a * t + b) * t + c; }
};

// (4.7) The projection on the view plane of the line where two planes meet: z eliminated.
// Degenerate (a = b = 0) when the planes are parallel.
Line2 LineOfPlanes(const Plane& p1, const Plane& p2);

// (4.8) The projection of a plane–quadric intersection: z = −(A_p x + B_p y + D_p)/C_p put into
// Q, times C_p²/2 (the paper's scaling). Valid for any plane with C_p ≠ 0; for C_p = 0 it
// degenerates to (C_q/2)·(trace line)², i.e. the trace line counted twice.
Conic2 ConicOfPlaneQuadric(const Plane& p, const Quadric& q);

// (4.11) The limb plane n_z = F x + E y + C z + J = 0 (points where the normal (4.10) is parallel
// to the view plane).
Plane LimbPlane(const Quadric& q);

// (4.12) The limb conic: (4.8) applied to the limb plane, divided by C_q (so it is defined by the
// quadric alone; C_q ≠ 0 is the caller's responsibility).
Conic2 LimbConic(const Quadric& q);

// (4.14) UniQuadrix's existence test for the limb: C_q > 0 (the half-space does not contain the z
// axis at infinity). Used for the show-face choice of §4.4; the renderer draws limbs of any
// quadric with C_q ≠ 0 (a spherical hole, C_q < 0, has a silhouette too).
bool LimbExists(const Quadric& q);

// §4.5.8 The point where three planes meet, by Gauss elimination with partial pivoting
// (math/dense_solve.h); nullopt when the system is singular (pivot below the zero test's error
// estimate).
std::optional<Vec3> IntersectThreePlanes(const Plane& p1, const Plane& p2, const Plane& p3);

// (4.15) y eliminated from line and conic: a quadratic in x (use when |b_l| > |a_l|).
Quadratic1 LineConicInX(const Line2& l, const Conic2& c);
// (4.16) x eliminated: a quadratic in y (use when |a_l| >= |b_l|).
Quadratic1 LineConicInY(const Line2& l, const Conic2& c);

// (4.17) The conic at fixed y as a quadratic in x; (4.18) at fixed x as a quadratic in y.
Quadratic1 ConicAtY(const Conic2& c, double y);
Quadratic1 ConicAtX(const Conic2& c, double x);
// (4.20) The discriminant of (4.17) as a quadratic in y: its roots are the VEXTRM rows.
Quadratic1 VextrmQuadratic(const Conic2& c);
// (4.21) The discriminant of (4.18) as a quadratic in x: its roots are the HEXTRM columns.
Quadratic1 HextrmQuadratic(const Conic2& c);
// (4.22) 2 a x + c y + d = 0: splits the conic into legs single-valued in x (the insert line;
// it passes through the VEXTRMs). (4.23) 2 b y + c x + e = 0: through the HEXTRMs.
Line2 InsertLine(const Conic2& c);
Line2 HextrmLine(const Conic2& c);

// ---- Zero tests (§4.5.13). Each compares a number with E, its estimated worst-case error. ----

// Unit roundoff of double.
inline constexpr double kUnit = 1.1102230246251565e-16;

// (1) Is the plane perpendicular to the view plane? |C| within the rounding the view and device
// transforms leave on a coefficient of that size: a few ulps of |A| + |B| + |C| per matrix
// product (two products, 4 terms each): E = 64 u (|A| + |B| + |C|).
bool PlaneIsEdgeOn(const Plane& p);

// (2) Is the quadric a cylinder perpendicular to the view plane (Q independent of z)? The z terms
// (C, E, F, J), weighted by the extent `length` of the scene (pixels), against the other terms
// at that extent: |C|L² + 2|E|L² + 2|F|L² + 2|J|L <= 64 u (|A|L² + |B|L² + 2|D|L² + 2|G|L +
// 2|H|L + |K|).
bool QuadricIsViewCylinder(const Quadric& q, double length);

// (3) Roots of a quadratic whose coefficients carry a relative error `relError` (an estimate of
// the rounding of the formula that produced them). The discriminant b² − 4ac has the error
// E = (2 relError + 4u)(b² + 4|ac|); |disc| <= E is a double root.
struct Roots1 {
    enum Kind { kNone, kDouble, kTwo, kLinear } kind = kNone;
    double r0 = 0, r1 = 0;  // sorted; r0 = r1 for kDouble and kLinear
};
Roots1 SolveQuadratic1(const Quadratic1& q, double relError);

// (4) Does a point satisfy a half-space inequality? The value is within the rounding of its own
// evaluation (8u times the sum of the magnitudes of its terms) plus the effect of an error
// `pointError` (device units) in the point's coordinates (|gradient| · pointError).
bool SatisfiesPlane(const Plane& p, const Vec3& x, double pointError);
bool SatisfiesQuadric(const Quadric& q, const Vec3& x, double pointError);
// The same tests, returning the value and E for callers that want the margin.
double PlaneErrorEstimate(const Plane& p, const Vec3& x, double pointError);
double QuadricErrorEstimate(const Quadric& q, const Vec3& x, double pointError);

// (5) Do two i-vertices coincide? Their distance in the view plane against the error of points
// computed by the formulas above (relative 1e-9 of their magnitude plus 1e-9 pixel).
bool VerticesCoincide(double x1, double y1, double x2, double y2);

// §4.5.9 The points where a line and a conic meet in the view plane (two, or none for double or
// imaginary roots as §4.5.10 asks: a tangent touch creates no i-vertex).
std::vector<Vec3> LineConicIntersections(const Line2& l, const Conic2& c);

}  // namespace quadrix::scanline
