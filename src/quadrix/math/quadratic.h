// A numerically stable solver for real quadratic equations, and the error-free products it is
// built on.
//
// Form. We solve   a t² + 2 h t + c = 0   ("half-b" form, h = b/2). This is the form a quadric
// takes along a ray (DESIGN.md "Depth of a quadric at a pixel": Q = c z² + 2 b z + a, with the
// factor 2 of the UniQuadrix coefficients), and it saves the factors 2 and 4 of the textbook
// formula: the reduced discriminant is  Δ = h² − a c  and the roots are  (−h ± √Δ) / a.
//
// Method (the classical one, see e.g. pbrt-v4's Quadratic and Kahan, "On the Cost of
// Floating-Point Computation Without Extra-Precise Arithmetic", 2004):
//  1. The three coefficients are scaled by one power of two so that the largest has magnitude in
//     [1, 2). Scaling by 2^k changes no root and rounds nothing (unless a coefficient is more than
//     2^1000 times smaller than the largest, when it becomes subnormal), and afterwards no product
//     of two coefficients can overflow.
//  2. Δ = h·h − a·c. When the two products do not cancel much (|h²| + |a c| <= 2|Δ|, which
//     includes every a c <= 0) the plain difference is accurate to 3u relative (u = 2^-53).
//     Otherwise Δ is recomputed with Dekker's error-free products (Veltkamp splitting, no FMA, so
//     the result is identical on every machine whatever -ffp-contract says): both products are
//     exact as unevaluated sums p + e, and Δ = (p₁ − p₂) + (e₁ − e₂) is accurate to about 2u
//     relative even when h² and a c nearly cancel (near-tangent rays).
//  3. q = −(h + sign(h)·√Δ) adds two numbers of one sign, so it suffers no cancellation; the roots
//     are q/a and c/q (Vieta), each with a relative error of a few ulps.
//
// Degenerate cases are explicit results, never NaN: a = 0 is a linear equation (one root, none,
// or every t when the equation is 0 = 0), Δ = 0 exactly is a double root (tangency) and is flagged
// as such, Δ < 0 has no real root. Non-finite coefficients give kNone.
#pragma once

#include <cmath>
#include <cstdint>

namespace quadrix {

// An exact product: a·b = p + e exactly, p = fl(a·b), unless a·b overflows or e underflows
// (|a·b| below about 2^-969), or |a| or |b| exceeds 2^996 (the split would overflow).
struct TwoProductResult {
    double p = 0, e = 0;
};

// Dekker (1971) with Veltkamp's split: each factor is cut into two halves of at most 26
// significant bits, whose products are exact, and the rounding error of a·b is recovered from
// them. Written without std::fma so that it does not depend on hardware FMA (and the project
// builds with -ffp-contract=off, so the compiler may not fuse these operations either). Inline:
// it runs per pixel.
inline TwoProductResult TwoProduct(double a, double b) {
    constexpr double kSplitter = 134217729.0;  // 2^27 + 1
    double p = a * b;
    double ta = kSplitter * a, tb = kSplitter * b;
    double ah = ta - (ta - a), bh = tb - (tb - b);
    double al = a - ah, bl = b - bh;
    double e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return {p, e};
}

// a·b − c·d with an error of about 2 ulps of the result (no catastrophic cancellation), computed
// with TwoProduct; same range caveats as TwoProduct.
double DifferenceOfProducts(double a, double b, double c, double d);

enum class RootKind : std::uint8_t {
    kNone,    // no real root: Δ < 0, or a = h = 0 ≠ c, or a non-finite coefficient
    kSingle,  // a = 0, h ≠ 0: the one root of the linear equation 2 h t + c = 0, in t0 (= t1)
    kDouble,  // Δ = 0 exactly: one double root (tangency) in t0 = t1
    kTwo,     // Δ > 0: two distinct roots t0 < t1 (distinct in exact arithmetic; they may round
              // to the same double for a nearly tangent ray)
    kAll,     // a = h = c = 0: every t is a root
};

struct QuadraticRoots {
    RootKind kind = RootKind::kNone;
    double t0 = 0, t1 = 0;  // sorted, t0 <= t1; meaningful for kSingle, kDouble and kTwo

    // Number of distinct roots reported (0, 1 or 2; 0 for kAll).
    int Count() const {
        return kind == RootKind::kTwo ? 2
                                      : (kind == RootKind::kSingle || kind == RootKind::kDouble);
    }
};

// Real roots of a t² + 2 h t + c = 0 (see the file comment). Accuracy: for finite coefficients
// whose magnitudes lie within a factor 2^1000 of the largest, each reported root of the given
// (already rounded) coefficients has a relative error of at most about 5u + u²·(h² + |a c|)/Δ,
// u = 2^-53 (error analysis in quadratic.cpp; the second term only matters for rays within ~1e-16
// of tangency); roots overflow to ±inf only when their exact value is out of range.
//
// A linear equation whose coefficients need no scaling (a = 0, h ≠ 0, max(|h|, |c|) in
// [2^-200, 2^200], the range in which the solver scales nothing: quadratic.cpp) is solved inline,
// −c / (2h), the same root the solver gives; planes along rays are the common callers' case
// (shadow rays, the literal evaluators, trimming). Everything else, NaN included (it fails the
// comparisons), goes to the general solver.
namespace detail {
QuadraticRoots SolveQuadraticGeneral(double a, double h, double c);
}  // namespace detail

inline QuadraticRoots SolveQuadratic(double a, double h, double c) {
    const double ah = std::fabs(h), ac = std::fabs(c);
    if (a == 0 && h != 0 && ah <= 0x1p200 && ac <= 0x1p200 && (ah >= 0x1p-200 || ac >= 0x1p-200)) {
        QuadraticRoots r;
        r.kind = RootKind::kSingle;
        r.t0 = r.t1 = -c / (2.0 * h);  // 2.0 * h is exact
        return r;
    }
    return detail::SolveQuadraticGeneral(a, h, c);
}

}  // namespace quadrix
