// Adaptive isocurve extraction (seed 002 §2, Algorithm 1) and, for comparison, uniformly spaced
// isocurves at the same tolerance.
//
// Algorithm 1 as implemented (iso_family.h has the notation; parameters are those of the oriented
// surface, v fixed, t running):
//
//   AdapIsoCurve(S, δ): emit the boundary curves v0 and v1 over the whole running domain, then
//   Aux(v0, v1, [t0, t1]).
//
//   Aux(v1, v2, [a, b]), a pair of adjacent (sub-)isocurves C1 = S(·, v1), C2 = S(·, v2):
//     F(t) = Δ²₁₂(t) − δ² on [a, b], computed symbolically as scalar Bézier pieces:
//        polynomial S:  F = (C1 − C2)·(C1 − C2) − δ²           (degree 2p)
//        rational S:    F = |P1 w2 − P2 w1|² − δ² (w1 w2)²     (degree 4p)
//      (the second is Δ² − δ² times (w1 w2)² > 0: same sign, same zeros, still a polynomial).
//     - all Bézier coefficients of F <= 0 → Δ <= δ on [a, b]: the pair is covered (a "strip").
//     - all coefficients > 0 → Δ > δ everywhere: insert the middle isocurve.
//     - otherwise find the sign changes of F (roots.h, convex-hull subdivision), split [a, b]
//       there, and decide each piece by the sign of F at its middle (no sign change inside).
//   Middle(v1, v2, [a, b]): emit C12 = S(·, (v1 + v2)/2) on [a, b] and recurse on (v1, v12) and
//   (v12, v2) over [a, b]. Fixed values are therefore dyadic: v0 + k (v1 − v0) / 2^level (with
//   baseCount N: v0 + k (v1 − v0) / (N 2^level)).
//
// End conditions, made explicit (the paper leaves them to [Elber 92a]):
//   1. A piece between two crossings is decided by one evaluation, never by re-running the hull
//      test: at a crossing F = 0 exactly, so the strict tests "< δ²" / "> δ²" of the paper would
//      recurse forever on the pieces' end points.
//   2. Crossings closer than `parameterTolerance` (relative to the running domain) to a or b are
//      ignored, and pieces narrower than that are counted as covered ("slivers": F vanishes at both
//      ends of such a piece, so Δ exceeds δ there by a negligible amount).
//   3. If F has more than RootOptions::maxRoots sign changes (it hugs zero along a stretch), the
//      whole pair is treated as "Δ > δ" and refined: conservative.
//   4. Pairs wider than 2^-minLevel of the fixed domain are refined unconditionally: on a closed
//      surface the two boundary curves coincide (Δ ≡ 0), and in general a pair far apart can have
//      a small chord while the surface between them bulges. minLevel = 2 starts from 5 curves.
//   5. A pair at `maxLevel`, or met when the surface already has `maxCurves` curves, is not
//      refined further and is counted as unresolved (a δ absurdly small for the surface).
//   6. Middle curves of one fixed value that meet end to end are merged into one curve.
//   7. A rational surface whose weight function cannot be proven positive (Surface::
//      WeightPositive) reaches infinity: it gets no curves and one unresolved count. A pair whose F
//      has non-finite coefficients (overflow) is not refined and is counted as unresolved.
//
// Coverage (Definition 1 of the seed): every strip is a parameter rectangle [v1, v2] × [a, b]
// bounded by two emitted curves with Δ ≤ δ along it; the strips tile the domain.
#pragma once

#include <string>
#include <vector>

#include "quadrix/engines/isocurve/iso_family.h"
#include "quadrix/freeform/surface.h"

namespace quadrix::isocurve {

enum class Direction { kConstV, kConstU, kAuto };

struct Isocurve {
    Constant constant = Constant::kV;
    double fixed = 0;       // value of the constant parameter (dyadic)
    double t0 = 0, t1 = 1;  // range of the running parameter
    int level = 0;          // 0 for boundary curves, k for fixed = v0 + (2i+1)(v1 − v0)/2^k
};

// A covered pair: adjacent curves at fixedLo < fixedHi, both present on [t0, t1], with
// Δ ≤ δ along it (unless `resolved` is false: the pair reached maxLevel).
struct CoveredStrip {
    double fixedLo = 0, fixedHi = 0;
    double t0 = 0, t1 = 0;
    bool resolved = true;
};

struct ExtractOptions {
    Direction direction = Direction::kAuto;
    int minLevel = 2;
    int maxLevel = 24;
    int maxCurves = 1 << 18;  // per surface and direction
    // Curves to start from: 1 = the two boundary curves (Algorithm 1); N > 1 = N + 1 uniformly
    // spaced curves, each interval then refined dyadically; 0 = automatic, N in [4, 8) with
    // N·2^L the uniform count at this δ, so that the finest adaptive spacing is the uniform one
    // instead of up to twice as fine (a Quadrix extension, docs/isocurve.md).
    int baseCount = 1;
    double parameterTolerance = 1e-9;  // relative to the running domain
    bool keepStrips = false;           // fill Extraction::strips (tests, coverage checks)
};

struct ExtractStats {
    int curves = 0;        // after merging
    int pairs = 0;         // Aux calls
    int rootSearches = 0;  // pairs whose F changed sign (subdivided at crossings)
    int crossings = 0;     // parameters where Δ = δ, summed over pairs
    int slivers = 0;
    int unresolved = 0;
    int deepestLevel = 0;
    double length = 0;  // total world length of the curves
    double seconds = 0;
};

struct Extraction {
    Constant constant = Constant::kV;
    double delta = 0;
    int baseCount = 1;  // the N actually used (ExtractOptions::baseCount)
    std::vector<Isocurve> curves;
    std::vector<CoveredStrip> strips;  // oriented parameters, when keepStrips
    ExtractStats stats;
};

Extraction ExtractAdaptive(const freeform::Surface& surface, double delta,
                           const ExtractOptions& options = {});

// Full-length curves at fixed = v0 + k (v1 − v0)/n, k = 0..n, with the smallest n (searched by
// doubling, then bisection) for which every pair has Δ ≤ δ along the whole running domain, and
// n >= 2^minLevel: Shantz and Lien's uniform spacing at the same tolerance (seed 002 §1).
Extraction ExtractUniform(const freeform::Surface& surface, double delta,
                          const ExtractOptions& options = {});

// World length of one curve of a family.
double CurveLength(IsoFamily& family, const Isocurve& curve);

// Δ²(t) − δ² of two curve pieces over the same interval (see the file comment).
freeform::BezierCurve IsoDistanceExcess(const freeform::BezierCurve& c1,
                                        const freeform::BezierCurve& c2, double delta2);

}  // namespace quadrix::isocurve
