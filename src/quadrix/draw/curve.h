// The curves of a hidden-line drawing (docs/drawings.md), in DEVICE space (flat_scene.h: x
// column, y row, rays along +z). A drawing's line is the orthographic image (x, y) of a 3-D curve
// lying on one or two surfaces of the scene:
//   - an EDGE lies on two surfaces (plane–plane line, plane–quadric conic, quadric–quadric curve);
//   - a SILHOUETTE (contour generator) lies on one quadric and on its limb plane
//     F x + E y + C z + J = 0, the points where the quadric's normal is perpendicular to the rays
//     (seed 001 (4.11); scanline/coefficients.h LimbPlane).
// Conics are kept in closed form so that they can be written exactly (an orthographic image of an
// ellipse is an ellipse: SVG's elliptical arc):
//   kLine       X(t) = o + t u
//   kEllipse    X(t) = o + u cos t + v sin t,  t in [0, 2π] (a closed curve; pieces may wrap)
//   kHyperbola  X(t) = o + u cosh t + v sinh t (one branch)
//   kParabola   X(t) = o + u t + v t²
//   kPolyline   X(t) = points[i] + (t − i)(points[i+1] − points[i]), t in [0, n − 1]
//               (quadric–quadric curves, traced with a bounded error; see quartic_trace.h),
//               then pulled back onto both quadrics (`onA`, `onB`) by Newton's method, so that
//               every point the drawer tests lies on the true curve, not on a chord
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/math/quadric.h"
#include "quadrix/math/vec.h"

namespace quadrix::draw {

enum class CurveKind : std::uint8_t { kLine, kEllipse, kHyperbola, kParabola, kPolyline };
enum class CurveRole : std::uint8_t { kEdge, kSilhouette };

struct Curve3 {
    CurveKind kind = CurveKind::kLine;
    CurveRole role = CurveRole::kEdge;
    int surfaceA = -1, surfaceB = -1;  // FlatScene half-spaces; B = −1 for a silhouette
    Vec3 o, u, v;
    std::vector<Vec3> points;  // kPolyline
    bool project = false;      // kPolyline: At() projects onto onA ∩ onB
    Quadric onA, onB;
    double t0 = 0, t1 = 0;  // parameter domain

    Vec3 At(double t) const;
    // dX/dt.
    Vec3 Derivative(double t) const;
    bool Closed() const { return kind == CurveKind::kEllipse; }
};

const char* ToString(CurveKind k);

// Length of the orthographic image (x, y) of c on [t0, t1] (device pixels), from 64 chords.
double ProjectedLength(const Curve3& c, double t0, double t1);

// Pieces shorter than this in projection (device pixels) are below any drawing's resolution:
// gaps that short between kept pieces are closed, and visibility slivers that short join their
// neighbours (they come from tolerances at vertices and tangent points, not from the geometry).
inline constexpr double kSliver = 0.01;

// Newton projection of p onto a = b = 0 with minimum-norm steps in the span of the gradients;
// false when it does not converge to `tol` (device units) in 30 steps (p is then unchanged only
// in the sense that the caller should not trust it).
bool ProjectOntoBoth(const Quadric& a, const Quadric& b, Vec3& p, double tol);

}  // namespace quadrix::draw
