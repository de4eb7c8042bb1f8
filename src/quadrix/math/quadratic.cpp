#include "quadrix/math/quadratic.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

namespace quadrix {
namespace {

// 2^e for e in [-1022, 1023], built from its bit pattern (exact, no libm call).
double Pow2(int e) { return std::bit_cast<double>(static_cast<std::uint64_t>(e + 1023) << 52); }

// floor(log2 |x|) for a finite, non-zero, normal x.
int Exponent(double x) {
    return static_cast<int>((std::bit_cast<std::uint64_t>(x) >> 52) & 0x7ff) - 1023;
}

}  // namespace

double DifferenceOfProducts(double a, double b, double c, double d) {
    // a·b − c·d = (p1 − p2) + (e1 − e2) exactly. With u = 2^-53 and S = |a b| + |c d|:
    // |e1 − e2| <= u S, so rounding the two differences and the final sum costs at most
    // 2u |result| + 2u² S, i.e. about 2 ulps unless the result is below u·S (cancellation of 16
    // digits), where the absolute error 2u²·S still holds.
    TwoProductResult x = TwoProduct(a, b);
    TwoProductResult y = TwoProduct(c, d);
    return (x.p - y.p) + (x.e - y.e);
}

namespace detail {

// The whole solver; SolveQuadratic (quadratic.h) answers the unscaled linear case inline.
QuadraticRoots SolveQuadraticGeneral(double a, double h, double c) {
    QuadraticRoots r;
    if (!std::isfinite(a) || !std::isfinite(h) || !std::isfinite(c)) return r;  // kNone

    // 1. Scale by a power of two so that max(|a|, |h|, |c|) lies in [1, 2): exact, roots unchanged.
    double m = std::fabs(a) > std::fabs(h) ? std::fabs(a) : std::fabs(h);
    if (std::fabs(c) > m) m = std::fabs(c);
    if (m == 0) {
        r.kind = RootKind::kAll;
        return r;
    }
    // The scaling only guards against overflow and underflow. With m in [2^-200, 2^200] the
    // products h², a·c (≤ 2^401) cannot overflow, every test below compares quantities scaled by
    // the same power of two, √ of the power-of-four factor of the discriminant is exact and the
    // roots are ratios in which the factor cancels; so skipping it changes no bit unless a
    // coefficient is so far below m (< 2^-400 or so) that its products are subnormal — and then
    // they are below the rounding of the others either way. The common case skips it.
    if (m >= 0x1p-200 && m <= 0x1p200) {
        // (no scaling)
    } else if (m < 0x1p-1000) {  // tiny or subnormal: bring into the normal range first (exact)
        a *= 0x1p600;
        h *= 0x1p600;
        c *= 0x1p600;
        m *= 0x1p600;
    }
    int e = m >= 0x1p-200 && m <= 0x1p200 ? 0 : Exponent(m);
    if (e != 0) {
        // Two steps keep each factor a normal double for any e in [-1022, 1023].
        double f1 = Pow2(-e / 2), f2 = Pow2(-e - (-e / 2));
        a = a * f1 * f2;
        h = h * f1 * f2;
        c = c * f1 * f2;
    }

    // 2. Linear or constant equation.
    if (a == 0) {
        if (h == 0) {
            r.kind = c == 0 ? RootKind::kAll : RootKind::kNone;
            return r;
        }
        r.kind = RootKind::kSingle;
        r.t0 = r.t1 = -c / (2.0 * h);  // 2.0 * h is exact
        return r;
    }

    // 3. Reduced discriminant: plain when the products do not cancel (error <= u|p1| + u|p2| +
    // u|Δ| <= 3u|Δ| under the test below), error-compensated otherwise.
    double p1 = h * h, p2 = a * c;
    double disc = p1 - p2;
    if (!(p1 + std::fabs(p2) <= 2.0 * std::fabs(disc))) disc = DifferenceOfProducts(h, h, a, c);
    if (disc < 0) return r;  // kNone
    if (disc == 0) {
        r.kind = RootKind::kDouble;
        r.t0 = r.t1 = -h / a;
        return r;
    }

    // 4. Stable roots. Error budget (u = 2^-53, κ = (h² + |a c|)/Δ): Δ has relative error
    // <= 3u (plain, κ <= 2) or 2u + 2u²κ (compensated), √Δ <= u + ½ that, q adds one rounding to
    // terms of one sign, and the final division one more: <= 4.5u + u²κ for each root.
    double s = std::sqrt(disc);
    double q = -(h + std::copysign(s, h));  // |q| >= s > 0
    double t0 = q / a, t1 = c / q;
    if (t1 < t0) std::swap(t0, t1);
    r.kind = RootKind::kTwo;
    r.t0 = t0;
    r.t1 = t1;
    return r;
}

}  // namespace detail

}  // namespace quadrix
