#include "quadrix/math/symmetric_eigen.h"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include "quadrix/util/cpu_features.h"

namespace quadrix {

namespace {

// After the sweeps: the Gershgorin radius left, and the diagonal sorted with its vectors.
void Conclude(const double m[3][3], const double v[3][3], double vals[3], double vecs[3][3],
              double& offDiagonal) {
    offDiagonal = 0;
    for (int i = 0; i < 3; ++i) {
        double radius = 0;
        for (int j = 0; j < 3; ++j)
            if (j != i) radius += std::fabs(m[i][j]);
        offDiagonal = std::fmax(offDiagonal, radius);
    }
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int x, int y) { return m[x][x] < m[y][y]; });
    for (int i = 0; i < 3; ++i) {
        vals[i] = m[order[i]][order[i]];
        for (int r = 0; r < 3; ++r) vecs[r][i] = v[r][order[i]];
    }
}

constexpr int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};  // the rotations of a sweep, in order

#if defined(__x86_64__) || defined(__i386__)
// (x, y) ← (c x − s y, s x + c y) in the lanes of `rot`: one pair of a rotation's update.
[[gnu::always_inline]] QUADRIX_AVX2 inline void Turn(__m256d c, __m256d s, __m256d rot, __m256d& x,
                                                     __m256d& y) {
    const __m256d nx = _mm256_sub_pd(_mm256_mul_pd(c, x), _mm256_mul_pd(s, y));
    const __m256d ny = _mm256_add_pd(_mm256_mul_pd(s, x), _mm256_mul_pd(c, y));
    x = _mm256_blendv_pd(x, nx, rot);
    y = _mm256_blendv_pd(y, ny, rot);
}

// SymmetricEigen's sweeps for four matrices (lanes past n hold zeros: no sweep, as for the zero
// matrix). Every operation is the scalar one on each lane; the selects keep a lane's entries
// where its own run would not have changed them.
QUADRIX_AVX2 void SweepsAvx2(int n, const double (*const a[])[3], SymmetricEigenResult out[]) {
    alignas(32) double lanes[3][3][kEigenLanes] = {};
    for (int l = 0; l < n; ++l)
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) lanes[i][j][l] = a[l][i][j];
    __m256d m[3][3], v[3][3];
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
    __m256d frob = zero;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            m[i][j] = _mm256_load_pd(lanes[i][j]);
            v[i][j] = i == j ? one : zero;
            frob = _mm256_add_pd(frob, _mm256_mul_pd(m[i][j], m[i][j]));
        }
    // Lanes still sweeping: `frob > 0` and no stop so far.
    __m256d active = _mm256_cmp_pd(frob, zero, _CMP_GT_OQ);
    const __m256d tiny = _mm256_mul_pd(_mm256_set1_pd(1e-34), frob);
    const __m256d signBit = _mm256_set1_pd(-0.0);
    const __m256d two = _mm256_set1_pd(2.0);
    for (int sweep = 0; sweep < 12; ++sweep) {
        __m256d off =
            _mm256_add_pd(_mm256_mul_pd(m[0][1], m[0][1]), _mm256_mul_pd(m[0][2], m[0][2]));
        off = _mm256_add_pd(off, _mm256_mul_pd(m[1][2], m[1][2]));
        active = _mm256_andnot_pd(_mm256_cmp_pd(off, tiny, _CMP_LE_OQ), active);
        if (_mm256_movemask_pd(active) == 0) break;
        for (const auto& pq : kPairs) {
            const int p = pq[0], q = pq[1];
            // `if (m[p][q] == 0) continue;` (a NaN rotates, as in the scalar code).
            const __m256d rot = _mm256_and_pd(active, _mm256_cmp_pd(m[p][q], zero, _CMP_NEQ_UQ));
            if (_mm256_movemask_pd(rot) == 0) continue;
            const __m256d theta =
                _mm256_div_pd(_mm256_sub_pd(m[q][q], m[p][p]), _mm256_mul_pd(two, m[p][q]));
            const __m256d sign =
                _mm256_blendv_pd(_mm256_set1_pd(-1.0), one, _mm256_cmp_pd(theta, zero, _CMP_GE_OQ));
            const __m256d absTheta = _mm256_andnot_pd(signBit, theta);
            const __m256d t = _mm256_div_pd(
                sign, _mm256_add_pd(absTheta, _mm256_sqrt_pd(_mm256_add_pd(
                                                  _mm256_mul_pd(theta, theta), one))));
            const __m256d c =
                _mm256_div_pd(one, _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(t, t), one)));
            const __m256d s = _mm256_mul_pd(t, c);
            for (int r = 0; r < 3; ++r) Turn(c, s, rot, m[r][p], m[r][q]);
            for (int r = 0; r < 3; ++r) Turn(c, s, rot, m[p][r], m[q][r]);
            for (int r = 0; r < 3; ++r) Turn(c, s, rot, v[r][p], v[r][q]);
        }
    }
    alignas(32) double vl[3][3][kEigenLanes];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            _mm256_store_pd(lanes[i][j], m[i][j]);
            _mm256_store_pd(vl[i][j], v[i][j]);
        }
    for (int l = 0; l < n; ++l) {
        double ml[3][3], vv[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                ml[i][j] = lanes[i][j][l];
                vv[i][j] = vl[i][j][l];
            }
        Conclude(ml, vv, out[l].vals, out[l].vecs, out[l].offDiagonal);
    }
}
#endif

}  // namespace

void SymmetricEigen(const double a[3][3], double vals[3], double vecs[3][3], double& offDiagonal) {
    double m[3][3], v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    double frob = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            m[i][j] = a[i][j];
            frob += m[i][j] * m[i][j];
        }
    for (int sweep = 0; sweep < 12 && frob > 0; ++sweep) {
        double off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
        if (off <= 1e-34 * frob) break;
        for (const auto& pq : kPairs) {
            const int p = pq[0], q = pq[1];
            if (m[p][q] == 0) continue;
            // Jacobi rotation annihilating m[p][q] (Golub & Van Loan, §8.5).
            double theta = (m[q][q] - m[p][p]) / (2 * m[p][q]);
            double t =
                (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
            double c = 1 / std::sqrt(t * t + 1), s = t * c;
            for (int r = 0; r < 3; ++r) {
                double mrp = m[r][p], mrq = m[r][q];
                m[r][p] = c * mrp - s * mrq;
                m[r][q] = s * mrp + c * mrq;
            }
            for (int r = 0; r < 3; ++r) {
                double mpr = m[p][r], mqr = m[q][r];
                m[p][r] = c * mpr - s * mqr;
                m[q][r] = s * mpr + c * mqr;
            }
            for (int r = 0; r < 3; ++r) {
                double vrp = v[r][p], vrq = v[r][q];
                v[r][p] = c * vrp - s * vrq;
                v[r][q] = s * vrp + c * vrq;
            }
        }
    }
    Conclude(m, v, vals, vecs, offDiagonal);
}

void SymmetricEigenLanes(int n, const double (*const a[])[3], SymmetricEigenResult out[]) {
    n = std::clamp(n, 0, kEigenLanes);
#if defined(__x86_64__) || defined(__i386__)
    if (gCpuHasAvx2 && n > 1) {
        SweepsAvx2(n, a, out);
        return;
    }
#endif
    for (int l = 0; l < n; ++l) SymmetricEigen(a[l], out[l].vals, out[l].vecs, out[l].offDiagonal);
}

}  // namespace quadrix
