#include "quadrix/math/symmetric_eigen.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace quadrix {
namespace {

// A = R diag(λ) Rᵀ for a random rotation R: the solver returns λ ascending, A v = λ v for each
// column, and the columns orthonormal.
TEST(SymmetricEigen, RecoversAKnownSpectrum) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        double lam[3] = {u(rng) * 10, u(rng), u(rng) * 1e-3};
        if (trial % 5 == 0) lam[1] = lam[0];  // a repeated eigenvalue
        // Rotation from a random unit quaternion.
        double q[4] = {u(rng), u(rng), u(rng), u(rng)};
        const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (double& c : q) c /= n;
        const double w = q[0], x = q[1], y = q[2], z = q[3];
        const double r[3][3] = {
            {1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
        double a[3][3] = {};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k) a[i][j] += r[i][k] * lam[k] * r[j][k];
        double vals[3], vecs[3][3], off = -1;
        SymmetricEigen(a, vals, vecs, off);
        double sorted[3] = {lam[0], lam[1], lam[2]};
        std::sort(sorted, sorted + 3);
        for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(vals[i], sorted[i], 1e-13) << trial;
            double residual = 0, norm = 0;
            for (int row = 0; row < 3; ++row) {
                double av = 0;
                for (int k = 0; k < 3; ++k) av += a[row][k] * vecs[k][i];
                residual = std::fmax(residual, std::fabs(av - vals[i] * vecs[row][i]));
                norm += vecs[row][i] * vecs[row][i];
            }
            EXPECT_LT(residual, 1e-13) << trial;
            EXPECT_NEAR(norm, 1, 1e-14) << trial;
        }
        EXPECT_GE(off, 0);
        EXPECT_LT(off, 1e-14);
    }
}

TEST(SymmetricEigen, ZeroAndDiagonalMatrices) {
    const double zero[3][3] = {};
    double vals[3], vecs[3][3], off = -1;
    SymmetricEigen(zero, vals, vecs, off);
    for (double v : vals) EXPECT_EQ(v, 0);
    EXPECT_EQ(off, 0);
    const double diag[3][3] = {{3, 0, 0}, {0, -2, 0}, {0, 0, 5}};
    SymmetricEigen(diag, vals, vecs, off);
    EXPECT_EQ(vals[0], -2);
    EXPECT_EQ(vals[1], 3);
    EXPECT_EQ(vals[2], 5);
    EXPECT_EQ(vecs[1][0], 1);  // the eigenvector of -2 is the y axis
}

}  // namespace
}  // namespace quadrix
