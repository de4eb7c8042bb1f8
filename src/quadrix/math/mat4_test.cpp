#include "quadrix/math/mat4.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "quadrix/math/math_test_util.h"

namespace quadrix {
namespace {

using testing_util::AbsProduct;
using testing_util::kUnitRoundoff;
using testing_util::MakeRandomTransform;

// Rounding budget for products of up to a dozen 4×4 matrices: each entry of a product of k
// factors is within γ = 4k·u (4 terms per dot product, k levels) of the exact value, relative to
// the product of absolute values. 64u covers k = 12 with margin.
constexpr double kGamma = 64 * kUnitRoundoff;

TEST(MathMat4, StoredInverseOfRandomCompositions) {
    std::mt19937_64 rng(11);
    for (int n = 0; n < 2000; ++n) {
        auto rt = MakeRandomTransform(rng);
        Mat4 prod = rt.t.Matrix() * rt.t.Inverse();
        // Bound: |M M⁻¹ − I| <= γ |F0|...|F5| |G5|...|G0| (G = the factors' stored inverses, each
        // itself exact up to one rounding of 1/s or of sin/cos).
        Mat4 bound = AbsProduct(rt.factors, false) * AbsProduct(rt.factors, true);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                ASSERT_LE(std::fabs(prod.m[i][j] - (i == j)), kGamma * bound.m[i][j] + 1e-300)
                    << i << j << " " << rt.t.Matrix().ToString();
        // Composition keeps inverses in the right order: (T · T⁻¹)⁻¹ = T · T⁻¹, the same product.
        Transform back = rt.t * rt.t.Inverted();
        EXPECT_EQ(back.Matrix(), back.Inverse());
    }
}

TEST(MathMat4, MapPointRoundTrip) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> u(-50, 50);
    for (int n = 0; n < 2000; ++n) {
        auto rt = MakeRandomTransform(rng);
        Vec3 p{u(rng), u(rng), u(rng)};
        Vec3 q = rt.t.Inverted().MapPoint(rt.t.MapPoint(p));
        Vec4 bound = (AbsProduct(rt.factors, true) * AbsProduct(rt.factors, false)) *
                     testing_util::Abs(Vec4(p, 1));
        for (int i = 0; i < 3; ++i) ASSERT_LE(std::fabs(q[i] - p[i]), kGamma * bound[i]);
    }
}

TEST(MathMat4, GaussJordanInverseAgreesWithStoredInverse) {
    std::mt19937_64 rng(13);
    for (int n = 0; n < 500; ++n) {
        auto rt = MakeRandomTransform(rng);
        auto inv = rt.t.Matrix().Inverse();
        ASSERT_TRUE(inv.has_value());
        // Partial pivoting: residual |M X − I| <= c n u ‖M‖ ‖X‖ (norm-wise backward error); the
        // factor 1000 covers c·n for n = 4 with margin.
        auto norm = [](const Mat4& m) {
            double r = 0;
            for (const auto& row : m.m)
                r = std::fmax(r, std::fabs(row[0]) + std::fabs(row[1]) + std::fabs(row[2]) +
                                     std::fabs(row[3]));
            return r;
        };
        Mat4 res = rt.t.Matrix() * *inv;
        double tol = 1000 * kUnitRoundoff * norm(rt.t.Matrix()) * norm(*inv);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) ASSERT_LE(std::fabs(res.m[i][j] - (i == j)), tol);
    }
}

TEST(MathMat4, SingularAndNonFiniteMatricesHaveNoInverse) {
    Mat4 m = Mat4::Identity();
    m.m[2][2] = 0;
    EXPECT_FALSE(m.Inverse().has_value());
    EXPECT_FALSE(Transform::FromMatrix(m).has_value());
    m = Mat4::Identity();
    m.m[0][1] = NAN;
    EXPECT_FALSE(m.Inverse().has_value());
    EXPECT_FALSE(Mat4::Zero().Inverse().has_value());
    // Rows 0 and 1 proportional.
    m = Mat4::Identity();
    m.m[1] = {2, 0, 0, 0};
    EXPECT_FALSE(m.Inverse().has_value());
}

TEST(MathMat4, SinCosDegreesExactAtMultiplesOf90) {
    const double sines[4] = {0, 1, 0, -1}, cosines[4] = {1, 0, -1, 0};
    for (int k = -2000; k <= 2000; ++k) {
        double s, c;
        SinCosDegrees(90.0 * k, s, c);
        int q = ((k % 4) + 4) % 4;
        ASSERT_EQ(s, sines[q]) << k;
        ASSERT_EQ(c, cosines[q]) << k;
    }
    double s, c;
    SinCosDegrees(30, s, c);
    EXPECT_EQ(s, 0.5);
    SinCosDegrees(-150, s, c);
    EXPECT_EQ(s, -0.5);
    SinCosDegrees(240, s, c);
    EXPECT_EQ(c, -0.5);
    SinCosDegrees(45, s, c);
    EXPECT_EQ(s, c);
}

TEST(MathMat4, SinCosDegreesSymmetricAndAccurate) {
    std::mt19937_64 rng(14);
    std::uniform_real_distribution<double> u(-1000, 1000);
    for (int n = 0; n < 20000; ++n) {
        double d = u(rng), s1, c1, s2, c2;
        SinCosDegrees(d, s1, c1);
        SinCosDegrees(-d, s2, c2);
        ASSERT_EQ(s1, -s2) << d;  // odd, bit for bit
        ASSERT_EQ(c1, c2) << d;   // even, bit for bit
        // Against long double: the reduction is exact, so only the conversion to radians and the
        // libm call round (a few ulps of 1).
        long double rad =
            static_cast<long double>(d) * 3.14159265358979323846264338327950288L / 180;
        ASSERT_NEAR(s1, std::sin(rad), 8 * kUnitRoundoff);
        ASSERT_NEAR(c1, std::cos(rad), 8 * kUnitRoundoff);
    }
    double s, c;
    SinCosDegrees(HUGE_VAL, s, c);
    EXPECT_TRUE(std::isnan(s) && std::isnan(c));
}

TEST(MathMat4, RotationsByQuarterTurnsAreExactAndCyclic) {
    for (int axis = 0; axis < 3; ++axis) {
        for (int k = -8; k <= 8; ++k) {
            Transform r = Transform::Rotate(axis, 90.0 * k);
            EXPECT_EQ(r.Matrix() * r.Inverse(), Mat4::Identity()) << axis << " " << k;
            for (const auto& row : r.Matrix().m)
                for (double v : row) EXPECT_TRUE(v == 0 || v == 1 || v == -1);
        }
    }
    // Cyclic: +90° about z takes x to y, about x takes y to z, about y takes z to x (the left-hand
    // rule in the left-handed pictures, docs/language.md §2).
    EXPECT_EQ(Transform::Rotate(2, 90).MapVector({1, 0, 0}), Vec3(0, 1, 0));
    EXPECT_EQ(Transform::Rotate(0, 90).MapVector({0, 1, 0}), Vec3(0, 0, 1));
    EXPECT_EQ(Transform::Rotate(1, 90).MapVector({0, 0, 1}), Vec3(1, 0, 0));
}

}  // namespace
}  // namespace quadrix
