// Zeros and bounds of scalar Bézier polynomials by subdivision with convex-hull bounds
// (seed 002 §2: "the zero set of (Δ²₁₂(u) − δ²)" [Lane 81]).
//
// A scalar Bézier polynomial lies between its smallest and largest coefficient (the convex hull of
// its control polygon), and, by the variation-diminishing property (Descartes' rule of signs for
// the Bernstein basis, Lane & Riesenfeld 1981), it has at most V roots in the open interval, V the
// number of sign changes of its coefficients, and V minus the number of roots is even. Hence:
//   V = 0  → no root;   V = 1 → exactly one simple root, refined by bisection;
//   V >= 2 → subdivide at the midpoint and look again.
// Intervals narrower than the tolerance that still have V >= 2 are decided by the signs at their
// ends (an odd count gives one root at the middle, an even count none: a tangency or a pair of
// roots closer than the tolerance).
#pragma once

#include <optional>
#include <vector>

#include "quadrix/freeform/bezier_curve.h"

namespace quadrix::freeform {

struct RootOptions {
    // Absolute parameter tolerance of the returned roots.
    double tolerance = 1e-12;
    // More roots than this make the search give up (nullopt): a polynomial that hugs zero
    // (e.g. Δ² ≈ δ² along a whole stretch) would otherwise be cut into countless pieces.
    int maxRoots = 64;
};

// The parameters in the open interval (T0, T1) where the scalar curve f changes sign, sorted.
std::optional<std::vector<double>> SignChanges(const BezierCurve& f,
                                               const RootOptions& options = {});

// True when f(t) <= bound for every t of the interval, decided by subdivision down to `tolerance`
// (parameter width); an interval that cannot be decided at that width counts as "above" when the
// larger of its end values exceeds bound - false alarms are conservative for the callers.
bool AtMostEverywhere(const BezierCurve& f, double bound, double tolerance = 1e-9);

// Upper bound of max f over the interval, within `tolerance` of the true maximum (branch and bound
// on the control-point maxima).
double MaximumBound(const BezierCurve& f, double tolerance);

}  // namespace quadrix::freeform
