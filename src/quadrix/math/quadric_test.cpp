#include "quadrix/math/quadric.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "quadrix/math/math_test_util.h"

namespace quadrix {
namespace {

using testing_util::Abs;
using testing_util::AbsProduct;
using testing_util::kUnitRoundoff;
using testing_util::MakeRandomTransform;

// Rounding budget (see mat4_test.cpp): products of up to a dozen matrices plus the evaluation,
// relative to the same expression evaluated on absolute values.
constexpr double kGamma = 128 * kUnitRoundoff;

Quadric RandomQuadric(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    Quadric q;
    for (double& k : q.k) k = u(rng);
    return q;
}

// vᵀ |Q| v for a non-negative homogeneous v: the magnitude bounding the rounding of xᵀQx.
double AbsForm(const Quadric& q, const Vec4& v) {
    Mat4 a = Abs(q.Matrix());
    return Dot(v, a * v);
}

TEST(MathQuadric, TransformedQuadricHasTheSameValueAtMappedPoints) {
    // Q'(M x) = Q(x) for affine M (x' = M x, Q' = M⁻ᵀ Q M⁻¹), up to rounding bounded by
    // γ vᵀ|Q|v with v = |M⁻¹| |M| |x̃| (every product that forms Q', M x and the evaluation).
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> u(-20, 20);
    int signChecked = 0;
    for (int n = 0; n < 3000; ++n) {
        auto rt = MakeRandomTransform(rng);
        Quadric q = RandomQuadric(rng);
        Quadric qt = q.Transformed(rt.t);
        const Mat4 amp = AbsProduct(rt.factors, true) * AbsProduct(rt.factors, false);
        for (int m = 0; m < 10; ++m) {
            Vec3 x{u(rng), u(rng), u(rng)};
            double before = q.Evaluate(x);
            double after = qt.Evaluate(rt.t.MapPoint(x));
            Vec4 v = amp * Abs(Vec4(x, 1));
            double tol = kGamma * AbsForm(q, v);
            ASSERT_LE(std::fabs(after - before), tol) << before << " vs " << after;
            if (std::fabs(before) > tol) {
                ASSERT_EQ(before < 0, after < 0);  // the HSI keeps its sign: inside stays inside
                ++signChecked;
            }
        }
    }
    EXPECT_GT(signChecked, 20000);  // the tolerance must not make the sign test vacuous
}

TEST(MathQuadric, TransformedPlaneHasTheSameValueAtMappedPoints) {
    std::mt19937_64 rng(22);
    std::uniform_real_distribution<double> u(-20, 20), c(-1, 1);
    int signChecked = 0;
    for (int n = 0; n < 3000; ++n) {
        auto rt = MakeRandomTransform(rng);
        Plane p{c(rng), c(rng), c(rng), 10 * c(rng)};
        Plane pt = p.Transformed(rt.t);
        const Mat4 amp = AbsProduct(rt.factors, true) * AbsProduct(rt.factors, false);
        for (int m = 0; m < 10; ++m) {
            Vec3 x{u(rng), u(rng), u(rng)};
            double before = p.Evaluate(x), after = pt.Evaluate(rt.t.MapPoint(x));
            Vec4 v = amp * Abs(Vec4(x, 1));
            double tol = kGamma * Dot(Abs(p.AsVec4()), v);
            ASSERT_LE(std::fabs(after - before), tol);
            if (std::fabs(before) > tol) {
                ASSERT_EQ(before < 0, after < 0);
                ++signChecked;
            }
        }
    }
    EXPECT_GT(signChecked, 20000);
}

TEST(MathQuadric, ProjectiveMapsKeepTheSignOfTheHsi) {
    // A perspective-like M (last row not (0 0 0 1)) maps x̃ to (X, w); then Q'(X/w) = Q(x)/w² and
    // p'(X/w) = p(x)/w: the sign of the HSI is kept wherever w > 0 (in front of the eye).
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(-5, 5), c(-1, 1);
    int checked = 0;
    for (int n = 0; n < 2000; ++n) {
        auto rt = MakeRandomTransform(rng, 3);
        Mat4 persp = Mat4::Identity();
        persp.m[3] = {0.05 * c(rng), 0.05 * c(rng), 0.1, 1};  // w = 1 + 0.1 z + …
        Mat4 m = persp * rt.t.Matrix();
        auto t = Transform::FromMatrix(m);
        ASSERT_TRUE(t.has_value());
        Quadric q = RandomQuadric(rng);
        Quadric qt = q.Transformed(*t);
        Plane p{c(rng), c(rng), c(rng), c(rng)};
        Plane pt = p.Transformed(*t);
        for (int k = 0; k < 10; ++k) {
            Vec3 x{u(rng), u(rng), u(rng)};
            Vec4 h = m * Vec4(x, 1);
            if (h.w < 0.1) continue;
            Vec3 xp = Dehomogenize(h);
            // Tolerances: as in the affine tests with v = |M⁻¹||M||x̃|, times 1000 because M⁻¹ now
            // comes from Gauss-Jordan elimination (residual <= ~1000 u ‖M‖‖M⁻¹‖, mat4_test.cpp).
            Vec4 v = (Abs(t->Inverse()) * Abs(m)) * Abs(Vec4(x, 1));
            double tq = 1000 * kGamma * AbsForm(q, v);
            double tp = 1000 * kGamma * Dot(Abs(p.AsVec4()), v);
            double vq = q.Evaluate(x), vp = p.Evaluate(x);
            if (std::fabs(vq) > tq) {
                ASSERT_EQ(vq < 0, qt.Evaluate(xp) < 0);
            }
            if (std::fabs(vp) > tp) {
                ASSERT_EQ(vp < 0, pt.Evaluate(xp) < 0);
            }
            EXPECT_NEAR(qt.Evaluate(xp) * h.w * h.w, vq, tq);
            ++checked;
        }
    }
    EXPECT_GT(checked, 10000);
}

TEST(MathQuadric, EvaluateMatchesMatrixFormAndGradient) {
    std::mt19937_64 rng(24);
    std::uniform_real_distribution<double> u(-3, 3);
    for (int n = 0; n < 1000; ++n) {
        Quadric q = RandomQuadric(rng);
        Vec3 x{u(rng), u(rng), u(rng)};
        Vec4 h(x, 1);
        double form = Dot(h, q.Matrix() * h);
        double tol = 16 * kUnitRoundoff * AbsForm(q, Abs(h));
        EXPECT_NEAR(q.Evaluate(x), form, tol);
        EXPECT_EQ(Quadric::FromMatrix(q.Matrix()), q);
        // ∇Q = 2 (Q x̃)_xyz; compare with central differences (Q is quadratic, so the central
        // difference is exact up to rounding of about u·|Q|/step).
        Vec3 g = q.Gradient(x);
        const double step = 1e-3;
        for (int i = 0; i < 3; ++i) {
            Vec3 a = x, b = x;
            a[i] += step;
            b[i] -= step;
            double fd = (q.Evaluate(a) - q.Evaluate(b)) / (2 * step);
            EXPECT_NEAR(g[i], fd, 1e-9);
        }
        EXPECT_EQ(q.HomogeneousGradient(x).xyz() * 2.0, g);
    }
}

TEST(MathQuadric, PlaneProductIsTheProductOfThePlanes) {
    std::mt19937_64 rng(25);
    std::uniform_real_distribution<double> u(-3, 3);
    for (int n = 0; n < 1000; ++n) {
        Plane p1{u(rng), u(rng), u(rng), u(rng)}, p2{u(rng), u(rng), u(rng), u(rng)};
        Quadric q = Quadric::FromPlaneProduct(p1, p2);
        Vec3 x{u(rng), u(rng), u(rng)};
        double mag =
            Dot(Abs(p1.AsVec4()), Abs(Vec4(x, 1))) * Dot(Abs(p2.AsVec4()), Abs(Vec4(x, 1)));
        EXPECT_NEAR(q.Evaluate(x), p1.Evaluate(x) * p2.Evaluate(x), 32 * kUnitRoundoff * mag);
    }
    EXPECT_TRUE(Quadric::FromPlaneProduct({0, 0, 0, 1}, {0, 0, 0, 1}).IsDegenerateToLinear());
}

}  // namespace
}  // namespace quadrix
