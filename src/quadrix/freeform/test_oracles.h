// Independent oracles for the freeform tests (header-only, used by *_test.cpp only): direct
// Bernstein sums, the Cox–de Boor recursion, finite differences. None of them shares code with
// the de Casteljau / de Boor implementations under test.
#pragma once

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "quadrix/math/vec.h"

namespace quadrix::freeform::testing {

inline double BinomialOracle(int n, int k) {
    double r = 1;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
}

// B_i^n(s) by its definition.
inline double BernsteinOracle(int n, int i, double s) {
    return BinomialOracle(n, i) * std::pow(s, i) * std::pow(1 - s, n - i);
}

// Cox–de Boor recursion for N_{i,p}(t) on a knot vector (0/0 := 0), with the right end of the
// domain [t_p, t_n] included in the last non-empty span.
inline double CoxDeBoor(const std::vector<double>& k, int i, int p, double t, double domainEnd) {
    if (p == 0) {
        // At the end of the domain take the limit from the left: the span (k_i, k_{i+1}] ∋ t.
        if (t == domainEnd) return k[i] < t && t <= k[i + 1] ? 1 : 0;
        return k[i] <= t && t < k[i + 1] ? 1 : 0;
    }
    double a = 0, b = 0;
    if (k[i + p] > k[i]) a = (t - k[i]) / (k[i + p] - k[i]) * CoxDeBoor(k, i, p - 1, t, domainEnd);
    if (k[i + p + 1] > k[i + 1])
        b = (k[i + p + 1] - t) / (k[i + p + 1] - k[i + 1]) *
            CoxDeBoor(k, i + 1, p - 1, t, domainEnd);
    return a + b;
}

// Fourth-order central difference of a vector-valued function of one variable.
inline std::vector<double> FiniteDifference(const std::function<std::vector<double>(double)>& f,
                                            double t, double h) {
    std::vector<double> a = f(t - 2 * h), b = f(t - h), c = f(t + h), d = f(t + 2 * h);
    std::vector<double> r(a.size());
    for (std::size_t k = 0; k < a.size(); ++k)
        r[k] = (a[k] - 8 * b[k] + 8 * c[k] - d[k]) / (12 * h);
    return r;
}

inline double MaxAbsDiff(const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (std::size_t k = 0; k < a.size(); ++k) m = std::fmax(m, std::fabs(a[k] - b[k]));
    return m;
}

inline double MaxAbs(const std::vector<double>& a) {
    double m = 0;
    for (double x : a) m = std::fmax(m, std::fabs(x));
    return m;
}

inline std::vector<double> RandomVector(std::mt19937_64& rng, std::size_t n, double lo = -1,
                                        double hi = 1) {
    std::uniform_real_distribution<double> d(lo, hi);
    std::vector<double> v(n);
    for (double& x : v) x = d(rng);
    return v;
}

inline double Uniform(std::mt19937_64& rng, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

}  // namespace quadrix::freeform::testing
