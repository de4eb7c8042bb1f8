// Checks of Definition 1 of seed 002 ("a valid coverage with respect to δ"): every surface point
// lies within δ of some isocurve, and adjacent isocurves are never farther apart than δ.
//
// Both work on the strips of an extraction (ExtractOptions::keepStrips): a random point S(t, v)
// lies in a strip [fixedLo, fixedHi] × [t0, t1]; its distance to the coverage is at most its
// distance to the two curves bounding that strip, measured first at the same running parameter
// (|S(t, v) − S(t, fixedLo)|, cheap) and, when that is not below δ, as the true distance to the two
// curves (a 1-D minimisation over the running parameter).
#pragma once

#include <cstdint>

#include "quadrix/engines/isocurve/extraction.h"
#include "quadrix/freeform/surface.h"

namespace quadrix::isocurve {

struct CoverageReport {
    int samples = 0;
    int uncovered = 0;        // points farther than δ from both bounding curves
    int outsideStrips = 0;    // points in no strip (a hole in parameter space)
    int inSeveralStrips = 0;  // points inside more than one strip (overlap; edges excluded)
    double maxDistance = 0;   // largest distance bound found, world units
    double meanDistance = 0;
};

CoverageReport CheckCoverage(const freeform::Surface& surface, const Extraction& extraction,
                             int samples, std::uint64_t seed);

// max over strips of max_t Δ(t) / δ, sampled at `perStrip` points of each resolved strip plus its
// ends (Δ from independent evaluations of the surface, not from the symbolic Δ²).
double MaxAdjacentRatio(const freeform::Surface& surface, const Extraction& extraction,
                        int perStrip);

// Sum of the parameter areas of the strips divided by the area of the domain (1 when the strips
// tile it).
double StripAreaRatio(const freeform::Surface& surface, const Extraction& extraction);

}  // namespace quadrix::isocurve
