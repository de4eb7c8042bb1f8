#include "quadrix/math/quadratic.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

namespace quadrix {
namespace {

constexpr double kU = 0x1p-53;         // unit roundoff of double
constexpr long double kUL = 0x1p-64L;  // unit roundoff of x87 long double (64-bit significand)

__extension__ typedef unsigned __int128 U128;

// |x| = m · 2^e with an odd integer m < 2^53 (x finite, non-zero).
void Decompose(double x, std::uint64_t& m, int& e) {
    int ex;
    double f = std::frexp(std::fabs(x), &ex);  // f in [0.5, 1)
    m = static_cast<std::uint64_t>(std::ldexp(f, 53));
    e = ex - 53;
    while ((m & 1) == 0) {  // odd significand: the exponent is then as large as possible
        m >>= 1;
        ++e;
    }
}

TEST(MathQuadratic, TwoProductIsExact) {
    // Oracle: the 106-bit integer product of the significands. a·b = p + e must hold exactly.
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> mant(1.0, 2.0);
    std::uniform_int_distribution<int> ex(-200, 200);
    for (int n = 0; n < 20000; ++n) {
        double a = std::ldexp(mant(rng), ex(rng)) * (n & 1 ? -1 : 1);
        double b = std::ldexp(mant(rng), ex(rng));
        TwoProductResult r = TwoProduct(a, b);
        std::uint64_t ma, mb, mp, me = 0;
        int ea, eb, ep, ee = 0;
        Decompose(a, ma, ea);
        Decompose(b, mb, eb);
        Decompose(r.p, mp, ep);
        if (r.e != 0) Decompose(r.e, me, ee);
        int base = ea + eb;  // the exact product is ma·mb·2^base; p and e are multiples of 2^base
        ASSERT_GE(ep, base);
        U128 exact = static_cast<U128>(ma) * mb;
        U128 pPart = static_cast<U128>(mp) << (ep - base);
        U128 ePart = 0;
        if (r.e != 0) {
            ASSERT_GE(ee, base);
            ePart = static_cast<U128>(me) << (ee - base);
        }
        // Signs: p has the sign of a·b; e may have either sign.
        bool eSameSign = (r.e > 0) == (r.p > 0);
        U128 sum = eSameSign ? pPart + ePart : pPart - ePart;
        ASSERT_TRUE(sum == exact) << a << " * " << b;
    }
}

TEST(MathQuadratic, DifferenceOfProductsRecoversCancelledDigits) {
    // h = 1 + 2^-30: h² − 1 = 2^-29 + 2^-60 exactly (representable). The naive fl(h·h) − 1 loses
    // the 2^-60 term.
    double h = 1.0 + 0x1p-30;
    EXPECT_EQ(DifferenceOfProducts(h, h, 1.0, 1.0), 0x1p-29 + 0x1p-60);
    EXPECT_EQ(h * h - 1.0, 0x1p-29);  // documents what the compensation buys
}

TEST(MathQuadratic, SmallIntegerRootsAreExact) {
    // (t − 3)(t − 5) = t² − 8t + 15: h = −4. Every step is exact for these small integers.
    QuadraticRoots r = SolveQuadratic(1, -4, 15);
    ASSERT_EQ(r.kind, RootKind::kTwo);
    EXPECT_EQ(r.t0, 3.0);
    EXPECT_EQ(r.t1, 5.0);
    EXPECT_EQ(r.Count(), 2);
    // (t + 7)(t − 2) · (−3): leading coefficient negative, roots still sorted.
    r = SolveQuadratic(-3, -7.5, 42);
    ASSERT_EQ(r.kind, RootKind::kTwo);
    EXPECT_EQ(r.t0, -7.0);
    EXPECT_EQ(r.t1, 2.0);
    // c = 0: roots 0 and −2h/a.
    r = SolveQuadratic(2, 3, 0);
    ASSERT_EQ(r.kind, RootKind::kTwo);
    EXPECT_EQ(r.t0, -3.0);
    EXPECT_EQ(r.t1, 0.0);
    // h = 0: ±√(−c/a).
    r = SolveQuadratic(1, 0, -16);
    ASSERT_EQ(r.kind, RootKind::kTwo);
    EXPECT_EQ(r.t0, -4.0);
    EXPECT_EQ(r.t1, 4.0);
}

TEST(MathQuadratic, LinearAndConstantCases) {
    QuadraticRoots r = SolveQuadratic(0, 2, -8);  // 4t − 8 = 0
    EXPECT_EQ(r.kind, RootKind::kSingle);
    EXPECT_EQ(r.t0, 2.0);
    EXPECT_EQ(r.t1, 2.0);
    EXPECT_EQ(r.Count(), 1);
    EXPECT_EQ(SolveQuadratic(0, 0, 0).kind, RootKind::kAll);
    EXPECT_EQ(SolveQuadratic(0, 0, 0).Count(), 0);
    EXPECT_EQ(SolveQuadratic(0, 0, 1).kind, RootKind::kNone);
    EXPECT_EQ(SolveQuadratic(0, 0, -1e-300).kind, RootKind::kNone);
    // Huge linear coefficients: the scaling keeps −c/(2h) finite.
    r = SolveQuadratic(0, 1e308, -1e308);
    EXPECT_EQ(r.kind, RootKind::kSingle);
    EXPECT_EQ(r.t0, 0.5);
}

TEST(MathQuadratic, DoubleRootsAreFlagged) {
    QuadraticRoots r = SolveQuadratic(1, -3, 9);  // (t − 3)²
    EXPECT_EQ(r.kind, RootKind::kDouble);
    EXPECT_EQ(r.t0, 3.0);
    EXPECT_EQ(r.t1, 3.0);
    EXPECT_EQ(r.Count(), 1);
    // Scaling the equation by 2^±900 changes nothing (products of these would over/underflow
    // without the scaling step).
    for (double s : {0x1p900, 0x1p-900, 0x1p-1060 /* subnormal */}) {
        r = SolveQuadratic(s, -3 * s, 9 * s);
        EXPECT_EQ(r.kind, RootKind::kDouble) << s;
        EXPECT_EQ(r.t0, 3.0) << s;
    }
    // −5 (t + 0.25)²: double root with a negative leading coefficient.
    r = SolveQuadratic(-5, -1.25, -0.3125);
    EXPECT_EQ(r.kind, RootKind::kDouble);
    EXPECT_EQ(r.t0, -0.25);
}

TEST(MathQuadratic, NoRealRootsAndNonFinite) {
    EXPECT_EQ(SolveQuadratic(1, 0, 1).kind, RootKind::kNone);
    EXPECT_EQ(SolveQuadratic(-1, 1, -1.0000001).kind, RootKind::kNone);
    EXPECT_EQ(SolveQuadratic(NAN, 0, 1).kind, RootKind::kNone);
    EXPECT_EQ(SolveQuadratic(1, HUGE_VAL, 1).kind, RootKind::kNone);
    // Just beyond tangency: h = 1 + 3·2^-28 has h² = 1 + 3·2^-27 + 9·2^-56, which rounds UP to
    // c = 1 + 3·2^-27 + 2^-52. The naive h·h − c is 0 (a false double root); the exact
    // discriminant is 9·2^-56 − 2^-52 = −7·2^-56 < 0.
    double h = 1.0 + 3 * 0x1p-28;
    double c = 1.0 + 3 * 0x1p-27 + 0x1p-52;
    ASSERT_EQ(h * h, c);
    EXPECT_EQ(DifferenceOfProducts(h, h, 1.0, c), -7 * 0x1p-56);
    EXPECT_EQ(SolveQuadratic(1, h, c).kind, RootKind::kNone);
}

TEST(MathQuadratic, HugeAndTinyCoefficientsDoNotOverflow) {
    // (t − 1)(t − 3) times 1e300: the naive discriminant h² would overflow to inf.
    for (double s : {1e300, -1e300, 1e-300, 5e-320 /* subnormal */}) {
        QuadraticRoots r = SolveQuadratic(s, -2 * s, 3 * s);
        ASSERT_EQ(r.kind, RootKind::kTwo) << s;
        // 3·s is rounded (relative u), which moves the roots by 1.5u·root; the solver adds at most
        // 5u·root (header): 8u and 24u absolute cover both.
        EXPECT_NEAR(r.t0, 1.0, 8 * kU) << s;
        EXPECT_NEAR(r.t1, 3.0, 24 * kU) << s;
    }
    // Widely separated roots 1e-150 and 1e150 with a = 1: h² = 1e300 and ac = 1 are fine, but the
    // small root must come from c/q, not from (−h + √Δ)/a (which would cancel to 0).
    QuadraticRoots r = SolveQuadratic(1, -0.5 * (1e150 + 1e-150), 1.0);
    ASSERT_EQ(r.kind, RootKind::kTwo);
    EXPECT_NEAR(r.t0 / 1e-150, 1.0, 8 * kU);
    EXPECT_NEAR(r.t1 / 1e150, 1.0, 8 * kU);
}

// The same algorithm in x87 extended precision without compensation: an independent oracle whose
// own error is bounded by u_L·(κ + 1) in Δ (κ = (h² + |a c|)/Δ), hence ½ u_L (κ + 1) + 3 u_L in a
// root.
struct Oracle {
    long double t0, t1, kappa;
    bool twoRoots;
};
Oracle SolveLong(double a, double h, double c) {
    long double A = a, H = h, C = c;
    long double disc = H * H - A * C;
    Oracle o{0, 0, 0, disc > 0};
    if (!o.twoRoots) return o;
    o.kappa = (H * H + std::fabs(A * C)) / disc;
    long double s = std::sqrt(disc);
    long double q = -(H + (H < 0 ? -s : s));
    o.t0 = q / A;
    o.t1 = C / q;
    if (o.t1 < o.t0) std::swap(o.t0, o.t1);
    return o;
}

TEST(MathQuadratic, RandomRootsMatchLongDoubleOracle) {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> logMag(-8, 8), unit(0, 1);
    std::uniform_real_distribution<double> logScale(-250, 250);
    int compared = 0;
    for (int n = 0; n < 200000; ++n) {
        // Roots over magnitudes 1e±8 with random signs; every fourth pair nearly coincides so that
        // the cancellation in Δ is exercised. Coefficients are scaled by 1e±250 so that the naive
        // h² or a·c would overflow or underflow.
        double r0 = std::pow(10.0, logMag(rng)) * (unit(rng) < 0.5 ? -1 : 1);
        double r1 = (n % 4 == 0) ? r0 * (1 + std::pow(10.0, -logMag(rng) * 0.75 - 6))
                                 : std::pow(10.0, logMag(rng)) * (unit(rng) < 0.5 ? -1 : 1);
        double a = std::pow(10.0, logScale(rng)) * (unit(rng) < 0.5 ? -1 : 1);
        double h = -0.5 * a * (r0 + r1);
        double c = a * r0 * r1;
        Oracle o = SolveLong(a, h, c);
        QuadraticRoots r = SolveQuadratic(a, h, c);
        // The oracle is trusted about the sign of Δ when its own error u_L(κ+1) is small.
        if (o.kappa * kUL > 0.01 || !o.twoRoots) continue;
        ASSERT_EQ(r.kind, RootKind::kTwo) << a << " " << h << " " << c;
        // Our bound (header): 5u + u²κ. The oracle's: ½u_L(κ+1) + 3u_L. Factor 2 of slack for the
        // second-order terms dropped in both analyses.
        long double tol = 2 * (5 * kU + kU * kU * o.kappa + 0.5L * kUL * (o.kappa + 1) + 3 * kUL);
        EXPECT_LE(std::fabs(r.t0 - o.t0), tol * std::fabs(o.t0)) << a << " " << h << " " << c;
        EXPECT_LE(std::fabs(r.t1 - o.t1), tol * std::fabs(o.t1)) << a << " " << h << " " << c;
        ++compared;
    }
    EXPECT_GT(compared, 180000);  // the skip above must stay rare
}

TEST(MathQuadratic, RandomLinearEquations) {
    // a = 0: the root −c/(2h) is one correctly rounded division (relative error <= u).
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> logMag(-8, 8);
    for (int n = 0; n < 10000; ++n) {
        double h = std::pow(10.0, logMag(rng)), c = -std::pow(10.0, logMag(rng));
        QuadraticRoots r = SolveQuadratic(0, h, c);
        ASSERT_EQ(r.kind, RootKind::kSingle);
        long double exact = -static_cast<long double>(c) / (2.0L * h);
        EXPECT_LE(std::fabs(r.t0 - exact), kU * exact * 1.01L);
    }
}

// The inline linear case (quadratic.h) gives what the general solver gives, bit for bit, on
// both sides of its range [2^-200, 2^200]: coefficients from 2^-1074 to 2^1023, zeros, infinities
// and NaN. Fails when the inline root is rounded otherwise (e.g. −c · (0.5 / h)) or when its range
// test admits a case the solver scales.
TEST(MathQuadratic, InlineLinearCaseIsTheGeneralSolvers) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> exponent(-1074, 1023);
    std::uniform_int_distribution<int> near(-260, 260);
    const double specials[] = {0.0,          -0.0,
                               HUGE_VAL,     -HUGE_VAL,
                               std::nan(""), 0x1p-200,
                               0x1p200,      0x1.fffffffffffffp199,
                               0x1p-201,     0x1.0000000000001p200};
    std::size_t inlined = 0;
    for (int n = 0; n < 400000; ++n) {
        auto pick = [&](int k) {
            if (k % 13 == 0) return specials[(n / 13 + k) % 10];
            return u(rng) * std::ldexp(1.0, k % 2 ? exponent(rng) : near(rng));
        };
        const double h = pick(n), c = pick(n + 5);
        const QuadraticRoots got = SolveQuadratic(0, h, c);
        const QuadraticRoots want = detail::SolveQuadraticGeneral(0, h, c);
        ASSERT_EQ(got.kind, want.kind) << h << " " << c;
        if (got.kind == RootKind::kSingle || got.kind == RootKind::kDouble) {
            ASSERT_EQ(std::bit_cast<std::uint64_t>(got.t0), std::bit_cast<std::uint64_t>(want.t0))
                << h << " " << c;
            ASSERT_EQ(std::bit_cast<std::uint64_t>(got.t1), std::bit_cast<std::uint64_t>(want.t1))
                << h << " " << c;
        }
        const double ah = std::fabs(h), ac = std::fabs(c);
        inlined += h != 0 && ah <= 0x1p200 && ac <= 0x1p200 && (ah >= 0x1p-200 || ac >= 0x1p-200);
    }
    EXPECT_GT(inlined, 100000u);  // both paths are exercised
    EXPECT_LT(inlined, 300000u);
}

}  // namespace
}  // namespace quadrix
