// The intersection curve of two quadrics (a space quartic), traced with a bounded error
// (docs/drawings.md). Closed forms exist only in special cases, so the curve is followed
// numerically, as a polyline whose chords stay within `chordTolerance` (device pixels) of it:
//  1. Seeds: the box is cut by 24 planes across each axis (three families, so that a curve
//     parallel to one family — the lines where parallel cylinders meet — is met by another);
//     on each plane the first
//     quadric's section is a conic in closed form (conic_section.h); where the second quadric
//     changes sign along it (64 samples per conic, then bisection to machine precision) the
//     section meets the curve.
//  2. Tracing from each seed in both directions: the tangent is ∇A × ∇B; a predictor step along
//     it is pulled back onto both surfaces by Newton's method on (A, B) with the minimum-norm
//     correction in the span of the two gradients. The step h keeps the turning of the tangent
//     θ between points below 8·tol/h (the sagitta of an arc of chord h turning by θ is ≈ hθ/8), so
//     the chord error is below `chordTolerance` wherever the curvature is resolved.
//  3. A branch ends where it leaves the box, closes on itself, or reaches a singular point
//     (∇A ∥ ∇B: tangent surfaces, a curve's node) — the tracer stops there and the rest of the
//     branch is traced from another seed. Seeds within 2 steps of a traced polyline are skipped.
#pragma once

#include <vector>

#include "quadrix/draw/curve.h"
#include "quadrix/math/quadric.h"

namespace quadrix::draw {

std::vector<Curve3> TraceQuadricQuadric(const Quadric& a, const Quadric& b, const Box3& box,
                                        double chordTolerance = 0.01);

}  // namespace quadrix::draw
