// Trimming candidate curves to the solids' boundary after CSG (docs/drawings.md).
//
// Breaks. Along a curve, whether it is an edge of the solid can only change where it crosses a
// third surface. For every other representative surface S whose box meets the curve's, the
// parameters where S(X(t)) = 0 are found: in closed form on lines (S is linear or quadratic in t:
// SolveQuadratic), elsewhere by sign changes over 96 samples of the parameter (every vertex of a
// polyline) refined by bisection to the last bit. Touching without crossing changes nothing, so
// missing a double root is harmless.
//
// Classification of each piece between breaks, at its midpoint p (exact point predicates on
// offset points, SceneProbe::Inside); a closed curve without breaks is kept only when its
// midpoint and one of its two golden-section points are on the boundary (its midpoint, t = π, is
// a point of symmetry, where it may touch a surface it does not cross: a tangency the breaks
// miss, which one sample would take for the whole curve):
//   - an edge of surfaces A and B: with gradients gA, gB at p, the four points p + d(sA, sB) with
//     gA·d = sA |gA| ε, gB·d = sB |gB| ε (d in the span of the gradients, sA, sB = ±1) sample the
//     four wedges around the curve. The curve is an edge when membership depends on both signs
//     (a convex or concave crease, or two solids meeting); when it depends on one sign only, the
//     boundary there is that surface's face and the other surface just passes through it; when
//     it is constant, the curve is inside or outside material. Surfaces meeting at less than
//     1e-4 rad (kTangentSin) are tangent there: see "tangent edges" below.
//     When a third surface contains the whole curve (a mitre: the bisecting plane and both
//     tubes share one ellipse), its breaks are skipped (its sign along the curve is rounding
//     noise) and the circle test of OnBoundary decides instead.
//   - a silhouette of quadric A: p ± ε gA/|gA| differ in membership.
// ε = 1e-7 times the image's larger side (device pixels): far above the rounding of p (1e-13 px)
// and far below any feature a drawing can show.
//
// Tangent edges (the smooth join of two faces: a box face tangent to a cylinder, a cylinder
// ending in a hemisphere of its radius). Where the curve's surfaces are tangent at p (their
// normals within 1e-4 rad), or the circle test finds one smooth sheet through p, membership is
// sampled again on a circle of radius δ = 1e-3 × the image's larger side in the curve's normal
// plane (about half a pixel: there the two tangent surfaces are apart by δ²/2 × the difference of
// their curvatures, far above rounding). When the boundary crosses that circle exactly twice,
// nearly opposite (within 0.1 rad), the two crossing points are assigned to the surface through
// p nearest to each (the curve's two surfaces and any third surface containing it); different
// surfaces on the two sides make p a TANGENT edge: the boundary passes from one face to the other
// without a crease. Several curves can carry the same tangent join (the slot's side meets its
// round bottom where the slot's floor plane passes too; the hemisphere's circle is both
// plane ∩ sphere and plane ∩ cylinder): one keeps it — the curve of the two faces' surfaces
// when one of them is a plane (the double line is extracted in closed form), else (two
// quadrics, whose tangent curve is not traced) a curve on the lower-numbered face's surface.
// Anything else (one face on both sides, a cusp where a cylinder rests on a plane) is no edge, as
// before.
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/draw/curve.h"
#include "quadrix/draw/curve_extraction.h"
#include "quadrix/draw/scene_probe.h"

namespace quadrix::draw {

struct CurvePiece {
    int curve = -1;
    double t0 = 0, t1 = 0;
    bool visible = true;
    bool tangent = false;  // a tangent edge (see above), not a crease
};

// What the point of a curve is (see the file comment).
enum class BoundaryKind : std::uint8_t { kNone, kEdge, kTangent };

// Sine of the angle between two normals below which the surfaces are tangent at a point.
inline constexpr double kTangentSin = 1e-4;

// Break parameters of `curve` against surface `s` within [t0, t1], sorted.
std::vector<double> CurveBreaks(const Curve3& curve, const FlatHalfSpace& s);

// Is the point at parameter t an edge (or silhouette) of the solids, and a crease or a tangent
// edge? (see the file comment). `shared`: the third surfaces that contain the whole curve; then
// the four wedges do not describe the neighbourhood and membership is sampled on a circle around
// the curve instead (48 directions, transitions bisected): a boundary that crosses the circle at
// two antipodal angles (within 1e-3 rad) is a smooth face (perhaps a tangent edge), anything else
// an edge.
BoundaryKind OnBoundary(const FlatScene& scene, const SceneProbe& probe, const Curve3& curve,
                        double t, double eps, const std::vector<int>& shared = {});

// The pieces of every curve on the boundary; tangent-edge pieces only with keepTangent (they
// cost the tangent test's circle either way, but no visibility work when left out).
std::vector<CurvePiece> TrimToBoundary(const FlatScene& scene, const Surfaces& surfaces,
                                       const SceneProbe& probe, const std::vector<Curve3>& curves,
                                       bool keepTangent = true);

}  // namespace quadrix::draw
