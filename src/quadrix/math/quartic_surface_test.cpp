#include "quadrix/math/quartic_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace quadrix {
namespace {

QuarticSurface Torus31() { return *QuarticSurface::Torus({0, 0, 0}, {0, 0, 1}, 3, 1); }

TEST(MathQuarticSurface, TorusAlongItsAxis) {
    const QuarticSurface t = Torus31();
    // Through the tube at ρ = 2.5: z = ±sqrt(1 − 0.25).
    QuarticLineSet s = t.OnLine({2.5, 0, 0, 1}, {0, 0, 1, 0});
    ASSERT_EQ(s.count, 1);
    EXPECT_NEAR(s.lo[0], -std::sqrt(0.75), 1e-14);
    EXPECT_NEAR(s.hi[0], std::sqrt(0.75), 1e-14);
    // Through the hole and outside.
    EXPECT_EQ(t.OnLine({0, 0, 0, 1}, {0, 0, 1, 0}).count, 0);
    EXPECT_EQ(t.OnLine({1.999, 0, 0, 1}, {0, 0, 1, 0}).count, 0);
    EXPECT_EQ(t.OnLine({4.001, 0, 0, 1}, {0, 0, 1, 0}).count, 0);
}

TEST(MathQuarticSurface, TorusAcrossBothTubes) {
    const QuarticSurface t = Torus31();
    QuarticLineSet s = t.OnLine({0, 0, 0, 1}, {1, 0, 0, 0});
    ASSERT_EQ(s.count, 2);
    EXPECT_NEAR(s.lo[0], -4, 1e-14);
    EXPECT_NEAR(s.hi[0], -2, 1e-14);
    EXPECT_NEAR(s.lo[1], 2, 1e-14);
    EXPECT_NEAR(s.hi[1], 4, 1e-14);
    // Oblique direction, scaled parameter: the same points.
    s = t.OnLine({-10, 0, 0, 1}, {2, 0, 0, 0});
    ASSERT_EQ(s.count, 2);
    EXPECT_NEAR(s.lo[0], 3, 1e-14);
    EXPECT_NEAR(s.hi[1], 7, 1e-14);
}

TEST(MathQuarticSurface, GrazingRaysOverTheTube) {
    const QuarticSurface t = Torus31();
    // Tangent to the top of the tube (z = 1): double roots, no point intervals.
    EXPECT_EQ(t.OnLine({0, 0, 1, 1}, {1, 0, 0, 0}).count, 0);
    EXPECT_EQ(t.OnLine({0, 0, 1 + 1e-9, 1}, {1, 0, 0, 0}).count, 0);
    // Just below: two tiny intervals of half-width sqrt(1 − z²) about x = ±3.
    const double z = 1 - 1e-6, w = std::sqrt(1 - z * z);
    QuarticLineSet s = t.OnLine({0, 0, z, 1}, {1, 0, 0, 0});
    ASSERT_EQ(s.count, 2);
    EXPECT_NEAR(s.lo[0], -3 - w, 1e-9);
    EXPECT_NEAR(s.hi[0], -3 + w, 1e-9);
    EXPECT_NEAR(s.lo[1], 3 - w, 1e-9);
    EXPECT_NEAR(s.hi[1], 3 + w, 1e-9);
    // Tangent to the outer equator along y at x = 4 and just inside it.
    EXPECT_EQ(t.OnLine({4, 0, 0, 1}, {0, 1, 0, 0}).count, 0);
    s = t.OnLine({4 - 1e-8, 0, 0, 1}, {0, 1, 0, 0});
    ASSERT_EQ(s.count, 1);
    EXPECT_NEAR(s.hi[0], std::sqrt(16 - (4 - 1e-8) * (4 - 1e-8)), 1e-8);
}

TEST(MathQuarticSurface, FarAndScaledLikeDeviceSpace) {
    // A torus of radius 50 px at depth 10⁶: the re-centred local frame keeps the roots exact.
    QuarticSurface t = Torus31();
    t.TransformBy(Transform::Translate({400, 300, 1e6}) * Transform::Scale({50, 50, 50}));
    QuarticLineSet s = t.OnLine({400 + 125, 300, 0, 1}, {0, 0, 1, 0});
    ASSERT_EQ(s.count, 1);
    EXPECT_NEAR(s.lo[0], 1e6 - 50 * std::sqrt(0.75), 1e-8);
    EXPECT_NEAR(s.hi[0], 1e6 + 50 * std::sqrt(0.75), 1e-8);
    // Gradient: the outward normal at the top of the tube points along +z.
    const Vec4 g = t.HomogeneousGradient({400 + 150, 300, 1e6 + 50});
    EXPECT_GT(g.z, 0);
    EXPECT_NEAR(g.x / g.z, 0, 1e-9);
    EXPECT_NEAR(g.y / g.z, 0, 1e-9);
    EXPECT_LT(t.Evaluate({400 + 150, 300, 1e6}), 0);
    EXPECT_GT(t.Evaluate({400, 300, 1e6}), 0);
}

TEST(MathQuarticSurface, ProjectiveMapKeepsTheLineParameter) {
    // Under a projective map N, the line N P0 + t N P1 meets N(torus) at the same t.
    const QuarticSurface t = Torus31();
    Mat4 n = Mat4::Identity();
    n(3, 2) = 0.05;  // w = 1 + z/20 (a perspective division)
    n(0, 3) = 7;
    const Transform map = *Transform::FromMatrix(n);
    QuarticSurface u = t;
    u.TransformBy(map);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> d(-4, 4);
    int hits = 0;
    for (int k = 0; k < 200; ++k) {
        const Vec4 p0{d(rng), d(rng), d(rng), 1}, p1{d(rng), d(rng), d(rng), 0};
        const QuarticLineSet a = t.OnLine(p0, p1);
        const QuarticLineSet b = u.OnLine(n * p0, n * p1);
        ASSERT_EQ(a.count, b.count);
        for (int i = 0; i < a.count; ++i) {
            EXPECT_NEAR(a.lo[static_cast<std::size_t>(i)], b.lo[static_cast<std::size_t>(i)], 1e-9);
            EXPECT_NEAR(a.hi[static_cast<std::size_t>(i)], b.hi[static_cast<std::size_t>(i)], 1e-9);
        }
        hits += a.count;
    }
    EXPECT_GT(hits, 20);
}

TEST(MathQuarticSurface, EllipticalTorusContainsItsEllipse) {
    // Ellipse centred at ρ = 5, semi-axis 2 tilted 30° from the radius, other semi-axis 1.
    const double c30 = std::cos(M_PI / 6), s30 = std::sin(M_PI / 6);
    const auto e =
        QuarticSurface::EllipticalTorus({0, 0, 0}, {0, 0, 2}, 5, {2 * c30, 0, 2 * s30}, 1);
    ASSERT_TRUE(e);
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-1.2, 1.2), phi(0, 2 * M_PI);
    for (int k = 0; k < 2000; ++k) {
        const double a = u(rng), b = u(rng), f = phi(rng);
        // Point at ellipse coordinates (a, b): inside iff a² + b² < 1.
        const double rho = 5 + 2 * a * c30 - b * s30, z = 2 * a * s30 + b * c30;
        const Vec3 p{rho * std::cos(f), rho * std::sin(f), z};
        const double q = a * a + b * b;
        if (std::fabs(q - 1) < 1e-6) continue;
        EXPECT_EQ(e->Evaluate(p) <= 0, q < 1) << a << " " << b;
    }
    std::string why;
    EXPECT_FALSE(QuarticSurface::EllipticalTorus({0, 0, 0}, {0, 0, 1}, 1.5, {2, 0, 0}, 1, &why));
    EXPECT_NE(why.find("axis"), std::string::npos);
    EXPECT_FALSE(QuarticSurface::Torus({0, 0, 0}, {0, 0, 1}, 1, 1, &why));
    EXPECT_FALSE(QuarticSurface::Torus({0, 0, 0}, {0, 0, 0}, 3, 1, &why));
}

TEST(MathQuarticSurface, GeneralConeSections) {
    // Base ellipse 4 × 1 at z = 0, top ellipse 1 × 3 at z = 10 (not similar: a quartic).
    const auto g = QuarticSurface::GeneralCone({0, 0, 0}, {0, 0, 10}, {4, 0, 0}, {0, 1, 0}, 1, 3);
    ASSERT_TRUE(g);
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(-5, 5), h(0, 1);
    for (int k = 0; k < 2000; ++k) {
        const double t = h(rng), x = u(rng), y = u(rng);
        const double a = 4 - 3 * t, b = 1 + 2 * t;
        const double q = x * x / (a * a) + y * y / (b * b);
        if (std::fabs(q - 1) < 1e-6) continue;
        EXPECT_EQ(g->Evaluate({x, y, 10 * t}) <= 0, q < 1);
    }
    // Along z through (0, 0): the whole slab (caps not included in the quartic itself).
    const QuarticLineSet s = g->OnLine({0, 0, -100, 1}, {0, 0, 1, 0});
    ASSERT_EQ(s.count, 1);
    EXPECT_LT(s.lo[0], 100);
    EXPECT_GT(s.hi[0], 110);
    const auto caps = g->GeneralConeCaps();
    EXPECT_NEAR(caps[0].z, -1, 1e-15);
    EXPECT_NEAR(caps[1].z, 1, 1e-15);
    EXPECT_NEAR(caps[1].w, -10, 1e-13);
    // Across at z = 5: x in ±2.5.
    const QuarticLineSet x = g->OnLine({-10, 0, 5, 1}, {1, 0, 0, 0});
    ASSERT_EQ(x.count, 1);
    EXPECT_NEAR(x.lo[0], 7.5, 1e-12);
    EXPECT_NEAR(x.hi[0], 12.5, 1e-12);
}

}  // namespace
}  // namespace quadrix
