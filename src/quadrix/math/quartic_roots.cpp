// Derivative-cascade root isolation (quartic_roots.h).
#include "quadrix/math/quartic_roots.h"

#include <cmath>

namespace quadrix {
namespace {

// p of degree <= 4 with its derivative, on coefficients c[0..n].
struct Poly {
    std::array<double, 5> c{};
    int n = 0;
    double Eval(double s) const {
        double v = c[static_cast<std::size_t>(n)];
        for (int i = n - 1; i >= 0; --i) v = v * s + c[static_cast<std::size_t>(i)];
        return v;
    }
    Poly Derivative() const {
        Poly d;
        d.n = n > 0 ? n - 1 : 0;
        for (int i = 1; i <= n; ++i)
            d.c[static_cast<std::size_t>(i - 1)] = i * c[static_cast<std::size_t>(i)];
        return d;
    }
};

bool Negative(double v) { return v < 0; }

// The root of p in the bracket [a, b] where p(a) and p(b) have opposite signs (neither 0):
// Newton steps kept inside the bracket, a bisection whenever Newton leaves it or its step is not
// below half the step before the last one (the safeguard of Numerical Recipes' rtsafe), until a
// Newton step inside the bracket is below ~4 ulps, the bracket cannot shrink (adjacent doubles)
// or p vanishes. (The safeguard was once "the bracket did not halve": Newton approaching a root
// from one side moves one end only, so every other step was a bisection and a root took about
// 50 of them, three quarters of a quartic scene's time.)
double RefineRoot(const Poly& p, const Poly& dp, double a, double b, double fa) {
    const bool aNeg = Negative(fa);
    double x = 0.5 * (a + b);
    double step = b - a, stepBefore = b - a;  // the last two steps' lengths (the bracket's first)
    for (int iter = 0; iter < 200; ++iter) {
        const double fx = p.Eval(x);
        if (fx == 0 || !std::isfinite(fx)) return x;
        if (Negative(fx) == aNeg)
            a = x;
        else
            b = x;
        const double mid = 0.5 * (a + b);
        if (!(a < mid && mid < b)) break;  // a and b adjacent: the root is known to 1 ulp
        const double d = dp.Eval(x);
        double next = (d != 0 && std::isfinite(d)) ? x - fx / d : mid;
        // Converged: a Newton step inside the bracket below ~4 ulps (quadratic convergence, so
        // the root is known to full precision without bisecting the far end down to it).
        if (next > a && next < b && std::fabs(next - x) <= 1e-15 * (1 + std::fabs(x))) return next;
        if (!(next > a && next < b) || std::fabs(next - x) > 0.5 * stepBefore) next = mid;
        stepBefore = step;
        step = std::fabs(next - x);
        if (next == x) break;
        x = next;
    }
    // The better of the bracket's ends.
    return std::fabs(p.Eval(a)) <= std::fabs(p.Eval(b)) ? a : b;
}

// The points of (lo, hi) where p changes sign, ascending, by the cascade; returns their count.
int CascadeRoots(const Poly& p, double lo, double hi, std::array<double, 4>& out) {
    if (p.n <= 0) return 0;
    if (p.n == 1) {
        if (p.c[1] == 0) return 0;
        const double r = -p.c[0] / p.c[1];
        if (!(r > lo && r < hi)) return 0;
        out[0] = r;
        return 1;
    }
    const Poly dp = p.Derivative();
    std::array<double, 4> crit{};
    const int nc = CascadeRoots(dp, lo, hi, crit);
    // Pieces [lo, crit0], [crit0, crit1], …, [crit_last, hi]: p is monotone on each.
    int count = 0;
    double u = lo, fu = p.Eval(lo);
    for (int k = 0; k <= nc; ++k) {
        const double v = k < nc ? crit[static_cast<std::size_t>(k)] : hi;
        const double fv = p.Eval(v);
        if (fu != 0 && fv != 0 && Negative(fu) != Negative(fv) && count < 4)
            out[static_cast<std::size_t>(count++)] = RefineRoot(p, dp, u, v, fu);
        else if (fv == 0 && k < nc && count < 4) {
            // A root exactly at a critical point: a sign change only if the neighbours differ;
            // NonPositiveSet handles the sets, here it counts as a root when p changes sign.
            const double w = k + 1 < nc ? crit[static_cast<std::size_t>(k + 1)] : hi;
            const double fw = p.Eval(w);
            if (fu != 0 && fw != 0 && Negative(fu) != Negative(fw))
                out[static_cast<std::size_t>(count++)] = v;
        }
        u = v;
        fu = fv;
    }
    return count;
}

Poly Trimmed(const std::array<double, 5>& c) {
    Poly p;
    p.c = c;
    p.n = 4;
    while (p.n > 0 && p.c[static_cast<std::size_t>(p.n)] == 0) --p.n;
    return p;
}

}  // namespace

double EvalPoly4(const std::array<double, 5>& c, double s) {
    return (((c[4] * s + c[3]) * s + c[2]) * s + c[1]) * s + c[0];
}

int SignChangeRoots(const std::array<double, 5>& c, double lo, double hi,
                    std::array<double, 4>& roots) {
    if (!(lo < hi)) return 0;
    return CascadeRoots(Trimmed(c), lo, hi, roots);
}

int NonPositiveSet(const std::array<double, 5>& c, double lo, double hi,
                   std::array<double, 3>& setLo, std::array<double, 3>& setHi) {
    if (!(lo < hi)) return 0;
    const Poly p = Trimmed(c);
    const Poly dp = p.Derivative();
    std::array<double, 4> crit{};
    const int nc = p.n >= 2 ? CascadeRoots(dp, lo, hi, crit) : 0;
    int count = 0;
    auto append = [&](double a, double b) {
        if (!(a < b)) return;  // a point (tangency) or nothing: not part of a regular set
        if (count > 0 && a <= setHi[static_cast<std::size_t>(count - 1)]) {
            setHi[static_cast<std::size_t>(count - 1)] = b;  // touching pieces merge
            return;
        }
        if (count == 3) {  // cannot happen for degree <= 4 (rounding guard): keep it conservative
            setHi[2] = b;
            return;
        }
        setLo[static_cast<std::size_t>(count)] = a;
        setHi[static_cast<std::size_t>(count)] = b;
        ++count;
    };
    double u = lo, fu = p.Eval(lo);
    for (int k = 0; k <= nc; ++k) {
        const double v = k < nc ? crit[static_cast<std::size_t>(k)] : hi;
        const double fv = p.Eval(v);
        if (!std::isfinite(fu) || !std::isfinite(fv)) {
            // Overflow: nothing is known on this piece; leave it out (as ray_literal does).
        } else if (fu <= 0 && fv <= 0) {
            append(u, v);
        } else if (fu > 0 && fv > 0) {
            // outside
        } else if (fu == 0 || fv == 0) {
            // One end is a root and the other end is outside: only that point.
        } else {
            const double r = RefineRoot(p, p.n >= 1 ? dp : p, u, v, fu);
            if (fu < 0)
                append(u, r);
            else
                append(r, v);
        }
        u = v;
        fu = fv;
    }
    return count;
}

}  // namespace quadrix
