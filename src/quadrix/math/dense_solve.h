// Dense linear solves A x = b by Gaussian elimination with partial pivoting (Golub & Van Loan,
// §3.4): the one solver shared by the bounds (flatten/bounds_math.cpp: normal equations and a
// cone's apex; flatten/bounds_relaxation.cpp: barrier Newton steps and KKT polishing) and the
// scanline Resolver (three planes meeting, engines/scanline/coefficients.cpp §4.5.8).
//
// The arithmetic is fixed, so that every caller gets the same bits from the same system:
//   - column c's pivot is the first row i >= c with the largest |a_ic| (a later row replaces it
//     only when strictly larger); the pivot row is swapped with row c (matrix and b) when it is
//     another row;
//   - each row i > c is updated with f = a_ic / a_cc as a_ij -= f a_cj for j = c .. n-1, then
//     b_i -= f b_c;
//   - back substitution: x_i = (b_i − a_i,i+1 x_i+1 − ... − a_i,n-1 x_n-1) / a_ii, the products
//     subtracted in increasing j (BackOrder::kIncreasing), or in decreasing j
//     (BackOrder::kDecreasing: the order of the scanline Resolver's three-plane vertex, kept so
//     that its frames stay bit-identical; the two orders round differently in the last bits).
// (The build has no FMA contraction, STYLE.md, so inlining does not change the bits either.)
//
// Singularity test: the system is refused (false) when a pivot's magnitude is not above
// `minPivot` (NaN pivots included), a pivot is not finite, or a component of x is not finite.
// Callers choose the threshold: an absolute one for a scaled system, a share of the largest entry
// (ratio × MaxAbsEntry, taken before the solve), or 0 to refuse exact zeros only.
//
// The matrix and b are overwritten (the upper triangular factor and the transformed right-hand
// side); x is written from the last component down, and is partly written when the solve fails.
// Two forms: a fixed-size array double[N][N] solved on its leading n×n block (n <= N), and a
// dynamic n×n row-major matrix in a span.
#pragma once

#include <cassert>
#include <cmath>
#include <cstddef>
#include <span>
#include <utility>

namespace quadrix {

// The order in which back substitution subtracts the known components (header comment).
enum class BackOrder { kIncreasing, kDecreasing };

namespace dense_detail {

// The elimination of the header comment over a matrix read through `at(i, j)` (a double&).
template <class At>
bool Solve(int n, At at, double* b, double* x, double minPivot, BackOrder order) {
    for (int col = 0; col < n; ++col) {
        int piv = col;
        for (int i = col + 1; i < n; ++i)
            if (std::fabs(at(i, col)) > std::fabs(at(piv, col))) piv = i;
        const double p = at(piv, col);
        if (!(std::fabs(p) > minPivot) || !std::isfinite(p)) return false;
        if (piv != col) {
            for (int j = 0; j < n; ++j) std::swap(at(piv, j), at(col, j));
            std::swap(b[piv], b[col]);
        }
        for (int i = col + 1; i < n; ++i) {
            const double f = at(i, col) / at(col, col);
            for (int j = col; j < n; ++j) at(i, j) -= f * at(col, j);
            b[i] -= f * b[col];
        }
    }
    for (int i = n - 1; i >= 0; --i) {
        double s = b[i];
        if (order == BackOrder::kIncreasing) {
            for (int j = i + 1; j < n; ++j) s -= at(i, j) * x[j];
        } else {
            for (int j = n - 1; j > i; --j) s -= at(i, j) * x[j];
        }
        x[i] = s / at(i, i);
        if (!std::isfinite(x[i])) return false;
    }
    return true;
}

}  // namespace dense_detail

// Solves the leading n×n block of `a` (n <= N) with right-hand side b[0..n); false when refused
// (header comment). a and b are overwritten.
template <std::size_t N>
bool SolveDense(int n, double (&a)[N][N], double* b, double* x, double minPivot = 0,
                BackOrder order = BackOrder::kIncreasing) {
    assert(n >= 0 && static_cast<std::size_t>(n) <= N);
    return dense_detail::Solve(
        n, [&a](int i, int j) -> double& { return a[i][j]; }, b, x, minPivot, order);
}

// The dynamic form: `a` holds n×n entries row-major; b and x hold n entries.
inline bool SolveDense(int n, std::span<double> a, std::span<double> b, std::span<double> x,
                       double minPivot = 0, BackOrder order = BackOrder::kIncreasing) {
    assert(n >= 0 && a.size() >= static_cast<std::size_t>(n) * static_cast<std::size_t>(n) &&
           b.size() >= static_cast<std::size_t>(n) && x.size() >= static_cast<std::size_t>(n));
    double* m = a.data();
    const std::size_t stride = static_cast<std::size_t>(n);
    return dense_detail::Solve(
        n,
        [m, stride](int i, int j) -> double& {
            return m[static_cast<std::size_t>(i) * stride + static_cast<std::size_t>(j)];
        },
        b.data(), x.data(), minPivot, order);
}

// The largest |a_ij| of the leading n×n block (NaN entries are skipped, as std::fmax does), for
// a threshold relative to the matrix: SolveDense(n, a, b, x, ratio * MaxAbsEntry(n, a)).
template <std::size_t N>
double MaxAbsEntry(int n, const double (&a)[N][N]) {
    double big = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) big = std::fmax(big, std::fabs(a[i][j]));
    return big;
}

inline double MaxAbsEntry(int n, std::span<const double> a) {
    double big = 0;
    const std::size_t count = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    for (std::size_t k = 0; k < count; ++k) big = std::fmax(big, std::fabs(a[k]));
    return big;
}

}  // namespace quadrix
