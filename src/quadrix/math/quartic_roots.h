// Certified isolation of the real roots of a polynomial of degree <= 4 on an interval, and the
// set where it is <= 0 (the ray–quartic step of math/quartic_surface.h).
//
// Method: the derivative cascade. On [lo, hi] the roots of p''' (at most one, linear) split the
// interval into pieces where p'' is monotone; each piece whose ends differ in sign holds exactly
// one root of p'', found by safeguarded Newton–bisection on its bracket. Those roots split [lo, hi]
// into pieces where p' is monotone, whose roots (found likewise) split it into pieces where p
// itself is monotone: on each such piece p has a root iff its end values differ in sign, and then
// exactly one. So every root with a sign change is found, each to full precision inside a bracket
// that is never lost (no closed form, no Ferrari: no cancellation between resolvent roots), and a
// double root where p only touches 0 (a tangent ray) produces no sign change, hence no point
// interval in the set p <= 0 (regularised convention, math/interval_list.h). Values are taken
// with Horner's rule; a monotone piece whose end values are both <= 0 is inside entirely.
#pragma once

#include <array>

namespace quadrix {

// Σ c[i] s^i at s (Horner).
double EvalPoly4(const std::array<double, 5>& c, double s);

// The real roots of c where it changes sign in (lo, hi), ascending; returns their number (<= 4).
int SignChangeRoots(const std::array<double, 5>& c, double lo, double hi,
                    std::array<double, 4>& roots);

// The regular closed set {s ∈ [lo, hi] : c(s) <= 0} as at most 3 separated intervals (the ends
// lo, hi included when c <= 0 there); returns their number. For a quartic with positive leading
// behaviour at both ends (a bounded solid) at most 2.
int NonPositiveSet(const std::array<double, 5>& c, double lo, double hi,
                   std::array<double, 3>& setLo, std::array<double, 3>& setHi);

}  // namespace quadrix
