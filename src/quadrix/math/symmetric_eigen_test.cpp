#include "quadrix/math/symmetric_eigen.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "quadrix/util/cpu_features.h"

namespace quadrix {
namespace {

// a = R diag(λ) Rᵀ for R the rotation of a random unit quaternion.
void WithSpectrum(const double lam[3], std::mt19937& rng, double a[3][3]) {
    std::uniform_real_distribution<double> u(-1, 1);
    double q[4] = {u(rng), u(rng), u(rng), u(rng)};
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (double& c : q) c /= n;
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            a[i][j] = 0;
            for (int k = 0; k < 3; ++k) a[i][j] += r[i][k] * lam[k] * r[j][k];
        }
}

// A = R diag(λ) Rᵀ for a random rotation R: the solver returns λ ascending, A v = λ v for each
// column, and the columns orthonormal.
TEST(SymmetricEigen, RecoversAKnownSpectrum) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        double lam[3] = {u(rng) * 10, u(rng), u(rng) * 1e-3};
        if (trial % 5 == 0) lam[1] = lam[0];  // a repeated eigenvalue
        double a[3][3];
        WithSpectrum(lam, rng, a);
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

// Matrices of every kind the lanes must follow: a random spectrum under a random rotation (some
// with repeated or zero eigenvalues), random symmetric entries over 40 orders of magnitude,
// matrices with some off-diagonal entries 0 (rotations skipped), diagonal and zero ones (no
// sweep), and entries that are infinite or NaN.
std::vector<std::array<double, 9>> EigenCases() {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<std::array<double, 9>> cases;
    for (int trial = 0; trial < 4000; ++trial) {
        double a[3][3] = {};
        const int kind = trial % 8;
        if (kind < 3) {
            double lam[3] = {u(rng) * 10, u(rng), u(rng) * 1e-3};
            if (kind == 1) lam[1] = lam[0];
            if (kind == 2) lam[2] = 0;
            WithSpectrum(lam, rng, a);
        } else {
            const double scale = std::pow(10.0, std::floor(u(rng) * 20));
            for (int i = 0; i < 3; ++i)
                for (int j = i; j < 3; ++j) a[i][j] = a[j][i] = u(rng) * scale;
            if (kind == 4) a[0][1] = a[1][0] = 0;
            if (kind == 5) a[0][2] = a[2][0] = a[1][2] = a[2][1] = 0;
            if (kind == 6) a[0][1] = a[1][0] = a[0][2] = a[2][0] = a[1][2] = a[2][1] = 0;
            if (kind == 7 && trial % 16 == 7) {
                const double special[] = {std::numeric_limits<double>::infinity(),
                                          std::numeric_limits<double>::quiet_NaN(), 0.0, -0.0,
                                          std::numeric_limits<double>::denorm_min()};
                const int i = trial / 16 % 3, j = trial / 48 % 3;
                a[i][j] = a[j][i] = special[trial / 144 % 5];
            }
            if (kind == 7 && trial % 32 == 15)
                for (auto& row : a)
                    for (double& e : row) e = 0;
        }
        std::array<double, 9> flat{};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) flat[static_cast<std::size_t>(3 * i + j)] = a[i][j];
        cases.push_back(flat);
    }
    return cases;
}

// Every lane of SymmetricEigenLanes is SymmetricEigen's result bit for bit, whatever the other
// lanes hold (they stop sweeping at other times) and for 1 to 4 lanes.
TEST(SymmetricEigen, LanesAreTheScalarResultsBitForBit) {
    std::printf("(lanes: %s)\n", gCpuHasAvx2 ? "AVX2" : "one matrix at a time");
    const std::vector<std::array<double, 9>> cases = EigenCases();
    auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
    int compared = 0;
    for (std::size_t start = 0; start + kEigenLanes <= cases.size(); start += 3) {
        const int n = 1 + static_cast<int>(start / 3 % kEigenLanes);
        const double(*a[kEigenLanes])[3];
        for (int l = 0; l < n; ++l)
            a[l] = reinterpret_cast<const double(*)[3]>(cases[start + std::size_t(l)].data());
        SymmetricEigenResult lanes[kEigenLanes];
        SymmetricEigenLanes(n, a, lanes);
        for (int l = 0; l < n; ++l) {
            double vals[3], vecs[3][3], off;
            SymmetricEigen(a[l], vals, vecs, off);
            bool equal = same(off, lanes[l].offDiagonal);
            for (int i = 0; i < 3; ++i) {
                equal = equal && same(vals[i], lanes[l].vals[i]);
                for (int j = 0; j < 3; ++j) equal = equal && same(vecs[i][j], lanes[l].vecs[i][j]);
            }
            ASSERT_TRUE(equal) << "case " << start + std::size_t(l) << " in a batch of " << n;
            ++compared;
        }
    }
    EXPECT_GT(compared, 3000);
}

}  // namespace
}  // namespace quadrix
