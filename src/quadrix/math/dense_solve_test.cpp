#include "quadrix/math/dense_solve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace quadrix {
namespace {

// A system with a zero in the first pivot position and an exact solution: partial pivoting must
// swap rows, and every step is exact in binary arithmetic.
TEST(DenseSolve, SolvesAKnownSystemThatNeedsPivoting) {
    double a[3][3] = {{0, 2, 1}, {1, 1, 1}, {2, 1, 0}};
    const double want[3] = {1, -2, 3};  // a · want = (-1, 2, 0)
    double b[3] = {-1, 2, 0}, x[3];
    ASSERT_TRUE(SolveDense(3, a, b, x));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(x[i], want[i]) << i;
}

// A larger array solved on its leading block: the entries outside it are not read.
TEST(DenseSolve, SolvesTheLeadingBlockOfALargerArray) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double a[4][4] = {
        {4, 1, nan, nan}, {2, 3, nan, nan}, {nan, nan, nan, nan}, {nan, nan, nan, nan}};
    double b[4] = {6, 8, nan, nan}, x[4] = {0, 0, 0, 0};
    ASSERT_TRUE(SolveDense(2, a, b, x));
    EXPECT_DOUBLE_EQ(x[0], 1);
    EXPECT_DOUBLE_EQ(x[1], 2);
}

// Random well-conditioned systems (diagonally dominant) of sizes 1 to 12 with a known solution:
// the residual is at the rounding level, and the fixed and dynamic forms give the same bits.
TEST(DenseSolve, FixedAndDynamicFormsAgreeBitForBit) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int n = 1; n <= 12; ++n) {
        for (int trial = 0; trial < 20; ++trial) {
            double fixed[12][12] = {}, fb[12], fx[12];
            std::vector<double> dyn(static_cast<std::size_t>(n * n)), db(n), dx(n), want(n);
            for (int i = 0; i < n; ++i) want[i] = 10 * u(rng);
            for (int i = 0; i < n; ++i) {
                double row = 0;
                for (int j = 0; j < n; ++j) {
                    fixed[i][j] = u(rng);
                    row += std::fabs(fixed[i][j]);
                }
                fixed[i][i] += std::copysign(row, fixed[i][i]);
                fb[i] = 0;
                for (int j = 0; j < n; ++j) fb[i] += fixed[i][j] * want[j];
                for (int j = 0; j < n; ++j) dyn[static_cast<std::size_t>(i * n + j)] = fixed[i][j];
                db[i] = fb[i];
            }
            ASSERT_TRUE(SolveDense(n, fixed, fb, fx)) << n;
            ASSERT_TRUE(SolveDense(n, dyn, db, dx)) << n;
            for (int i = 0; i < n; ++i) {
                EXPECT_EQ(fx[i], dx[i]) << n << " " << i;
                EXPECT_NEAR(fx[i], want[i], 1e-12 * n * 10) << n << " " << i;
            }
        }
    }
}

// The fixed order of operations (header comment), spelled out for a 3×3 system whose first
// column needs its last row as pivot: the solver's bits are the ones of that hand elimination.
TEST(DenseSolve, FollowsTheDocumentedOrderOfOperations) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        double a[3][3], b[3];
        for (int i = 0; i < 3; ++i) {
            b[i] = u(rng);
            for (int j = 0; j < 3; ++j) a[i][j] = u(rng);
        }
        a[2][0] = 2 + u(rng);  // the largest in column 0: rows 0 and 2 swap
        double m[3][3], r[3];
        for (int i = 0; i < 3; ++i) {
            r[i] = b[i];
            for (int j = 0; j < 3; ++j) m[i][j] = a[i][j];
        }
        for (int j = 0; j < 3; ++j) std::swap(m[0][j], m[2][j]);
        std::swap(r[0], r[2]);
        for (int i = 1; i < 3; ++i) {
            const double f = m[i][0] / m[0][0];
            for (int j = 0; j < 3; ++j) m[i][j] -= f * m[0][j];
            r[i] -= f * r[0];
        }
        if (std::fabs(m[2][1]) > std::fabs(m[1][1])) {
            for (int j = 0; j < 3; ++j) std::swap(m[1][j], m[2][j]);
            std::swap(r[1], r[2]);
        }
        const double f = m[2][1] / m[1][1];
        for (int j = 1; j < 3; ++j) m[2][j] -= f * m[1][j];
        r[2] -= f * r[1];
        const double z = r[2] / m[2][2];
        const double y = (r[1] - m[1][2] * z) / m[1][1];
        const double x = (r[0] - m[0][1] * y - m[0][2] * z) / m[0][0];
        const double xDecreasing = (r[0] - m[0][2] * z - m[0][1] * y) / m[0][0];
        double a2[3][3], b2[3];
        for (int i = 0; i < 3; ++i) {
            b2[i] = b[i];
            for (int j = 0; j < 3; ++j) a2[i][j] = a[i][j];
        }
        double got[3], gotDecreasing[3];
        ASSERT_TRUE(SolveDense(3, a, b, got));
        EXPECT_EQ(got[0], x);
        EXPECT_EQ(got[1], y);
        EXPECT_EQ(got[2], z);
        ASSERT_TRUE(SolveDense(3, a2, b2, gotDecreasing, 0, BackOrder::kDecreasing));
        EXPECT_EQ(gotDecreasing[0], xDecreasing);
        EXPECT_EQ(gotDecreasing[1], y);
        EXPECT_EQ(gotDecreasing[2], z);
    }
}

// Exactly singular systems are refused with any threshold, zero included.
TEST(DenseSolve, RefusesSingularSystems) {
    double parallel[3][3] = {{1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
    double b[3] = {1, 5, 0}, x[3];
    EXPECT_FALSE(SolveDense(3, parallel, b, x));
    double zero[2][2] = {};
    double bz[2] = {0, 0};
    EXPECT_FALSE(SolveDense(2, zero, bz, x));
    // Rank 2: the third row is the sum of the first two.
    double rank2[3][3] = {{1, 2, 3}, {4, 5, 6}, {5, 7, 9}};
    double b2[3] = {1, 1, 2};
    EXPECT_FALSE(SolveDense(3, rank2, b2, x, 1e-12 * MaxAbsEntry(3, rank2)));
}

// A nearly singular system (two rows differ by eps): its last pivot is about eps. A relative
// threshold above it refuses the system; below it, the solve goes through and is accurate to
// the system's condition.
TEST(DenseSolve, NearlySingularSystemsFollowTheThreshold) {
    for (double eps : {1e-6, 1e-10, 1e-14}) {
        auto make = [eps](double(&a)[2][2], double(&b)[2]) {
            a[0][0] = 1;
            a[0][1] = 1;
            a[1][0] = 1;
            a[1][1] = 1 + eps;
            b[0] = 2;
            b[1] = 2 + eps;  // solution (1, 1)
        };
        double a[2][2], b[2], x[2];
        make(a, b);
        EXPECT_FALSE(SolveDense(2, a, b, x, 10 * eps * MaxAbsEntry(2, a))) << eps;
        make(a, b);
        ASSERT_TRUE(SolveDense(2, a, b, x, 0.1 * eps * MaxAbsEntry(2, a))) << eps;
        EXPECT_NEAR(x[0], 1, 1e-15 / eps) << eps;
        EXPECT_NEAR(x[1], 1, 1e-15 / eps) << eps;
    }
    // An absolute threshold: a scaled-down system is refused, the same system scaled up is not.
    double small[2][2] = {{1e-13, 0}, {0, 1e-13}}, big[2][2] = {{1, 0}, {0, 1}};
    double bs[2] = {1e-13, 1e-13}, bb[2] = {1, 1}, x[2];
    EXPECT_FALSE(SolveDense(2, small, bs, x, 1e-12));
    EXPECT_TRUE(SolveDense(2, big, bb, x, 1e-12));
}

// Non-finite entries or solutions are refused: an infinite pivot, a NaN pivot, and a finite
// system whose solution overflows.
TEST(DenseSolve, RefusesNonFiniteValues) {
    const double inf = std::numeric_limits<double>::infinity();
    double x[2];
    double withInf[2][2] = {{inf, 0}, {0, 1}};
    double b1[2] = {1, 1};
    EXPECT_FALSE(SolveDense(2, withInf, b1, x));
    double withNan[2][2] = {{std::nan(""), 1}, {0, 1}};
    double b2[2] = {1, 1};
    EXPECT_FALSE(SolveDense(2, withNan, b2, x));
    double tiny[2][2] = {{1e-300, 0}, {0, 1}};
    double b3[2] = {1e300, 1};
    EXPECT_FALSE(SolveDense(2, tiny, b3, x));
    std::vector<double> dyn = {1e-300, 0, 0, 1}, bd = {1e300, 1}, xd(2);
    EXPECT_FALSE(SolveDense(2, dyn, bd, xd));
}

TEST(DenseSolve, MaxAbsEntryReadsTheLeadingBlock) {
    const double a[3][3] = {{1, -7, 100}, {2, 3, 100}, {100, 100, 100}};
    EXPECT_EQ(MaxAbsEntry(2, a), 7);
    EXPECT_EQ(MaxAbsEntry(3, a), 100);
    const std::vector<double> d = {1, -9, 2, 3};
    EXPECT_EQ(MaxAbsEntry(2, d), 9);
}

}  // namespace
}  // namespace quadrix
