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
// offset points, SceneProbe::Inside); a closed curve without breaks is an edge only when its
// midpoint and one of its two golden-section points say so (its midpoint, t = π, is a point of
// symmetry, where it may touch a surface it does not cross: a tangency the breaks miss, which one
// sample would take for the whole curve):
//   - an edge of surfaces A and B: with gradients gA, gB at p, the four points p + d(sA, sB) with
//     gA·d = sA |gA| ε, gB·d = sB |gB| ε (d in the span of the gradients, sA, sB = ±1) sample the
//     four wedges around the curve. The curve is an edge when membership depends on both signs
//     (a convex or concave crease, or two solids meeting); when it depends on one sign only, the
//     boundary there is that surface's face and the other surface just passes through it; when
//     it is constant, the curve is inside or outside material. Surfaces meeting at less than
//     1e-4 rad are tangent there (a smooth join): not an edge.
//     When a third surface contains the whole curve (a mitre: the bisecting plane and both
//     tubes share one ellipse), its breaks are skipped (its sign along the curve is rounding
//     noise) and the circle test of OnBoundary decides instead.
//   - a silhouette of quadric A: p ± ε gA/|gA| differ in membership.
// ε = 1e-7 times the image's larger side (device pixels): far above the rounding of p (1e-13 px)
// and far below any feature a drawing can show.
#pragma once

#include <vector>

#include "quadrix/draw/curve.h"
#include "quadrix/draw/curve_extraction.h"
#include "quadrix/draw/scene_probe.h"

namespace quadrix::draw {

struct CurvePiece {
    int curve = -1;
    double t0 = 0, t1 = 0;
    bool visible = true;
};

// Break parameters of `curve` against surface `s` within [t0, t1], sorted.
std::vector<double> CurveBreaks(const Curve3& curve, const FlatHalfSpace& s);

// Is the point at parameter t an edge (or silhouette) of the solids? (see the file comment)
// `shared`: a third surface contains the whole curve; then the four wedges do not describe the
// neighbourhood and membership is sampled on a circle around the curve instead (48 directions,
// transitions bisected): a boundary that crosses the circle at two antipodal angles (within
// 1e-3 rad) is a smooth face, anything else an edge.
bool OnBoundary(const FlatScene& scene, const SceneProbe& probe, const Curve3& curve, double t,
                double eps, bool shared = false);

std::vector<CurvePiece> TrimToBoundary(const FlatScene& scene, const Surfaces& surfaces,
                                       const SceneProbe& probe, const std::vector<Curve3>& curves);

}  // namespace quadrix::draw
