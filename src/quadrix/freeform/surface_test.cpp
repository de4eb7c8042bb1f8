#include "quadrix/freeform/surface.h"

#include <gtest/gtest.h>

#include <random>

#include "quadrix/freeform/test_oracles.h"

namespace quadrix::freeform {
namespace {

using testing::Uniform;

Surface RandomBicubic(std::mt19937_64& rng) {
    std::vector<Vec3> p;
    for (int k = 0; k < 16; ++k)
        p.push_back(
            {Uniform(rng, -1, 1) + (k % 4), Uniform(rng, -1, 1) + (k / 4), Uniform(rng, -1, 1)});
    return Surface::FromBezier(BezierSurface::FromPoints(3, 3, p), "r");
}

TEST(FreeformSurface, AffineAndProjectiveImagesAreExact) {
    std::mt19937_64 rng(41);
    Surface s = RandomBicubic(rng);
    Transform affine =
        Transform::Translate({1, 2, 3}) * Transform::Rotate(1, 30) * Transform::Scale({2, 1, 0.5});
    Mat4 proj = Mat4::Identity();
    proj(3, 2) = 0.2;  // w = 1 + 0.2 z: a perspective division
    proj(3, 3) = 2;
    Surface a = s.Transformed(affine.Matrix());
    Surface p = s.Transformed(proj);
    EXPECT_FALSE(a.Rational());
    EXPECT_TRUE(p.Rational());
    for (int k = 0; k < 50; ++k) {
        double u = Uniform(rng, 0, 1), v = Uniform(rng, 0, 1);
        Vec3 x = s.Point(u, v);
        // O(5) coordinates through a 4×4 product: 1e-13.
        EXPECT_LT(Length(a.Point(u, v) - affine.MapPoint(x)), 1e-13);
        EXPECT_LT(Length(p.Point(u, v) - proj.MapPoint(x)), 1e-13);
        // Normals are covectors: an affine map sends N to (A⁻ᵀ N) up to a positive factor
        // det A for proper maps.
        Vec3 n = s.NormalField(u, v), m = a.NormalField(u, v);
        const Mat4& inv = affine.Inverse();
        Vec3 expect{inv(0, 0) * n.x + inv(1, 0) * n.y + inv(2, 0) * n.z,
                    inv(0, 1) * n.x + inv(1, 1) * n.y + inv(2, 1) * n.z,
                    inv(0, 2) * n.x + inv(1, 2) * n.y + inv(2, 2) * n.z};
        EXPECT_NEAR(Dot(Normalize(m), Normalize(expect)), 1, 1e-12);
    }
}

TEST(FreeformSurface, TransposeSwapsParametersAndFlipsTheNormal) {
    std::mt19937_64 rng(42);
    Surface s = RandomBicubic(rng);
    Surface t = s.Transposed();
    for (int k = 0; k < 20; ++k) {
        double u = Uniform(rng, 0, 1), v = Uniform(rng, 0, 1);
        EXPECT_LT(Length(t.Point(v, u) - s.Point(u, v)), 1e-14);
        EXPECT_LT(Length(t.NormalField(v, u) + s.NormalField(u, v)), 1e-12);
    }
}

TEST(FreeformSurface, LimitNormalAtACollapsedEdge) {
    // A cone-like patch: the edge v = 0 collapsed to the apex (0, 0, 1) over a circle-ish base.
    std::vector<Vec3> p;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            double r = j / 3.0;
            p.push_back({r * (1 - i / 3.0), r * (i / 3.0), 1 - r});
        }
    Surface s = Surface::FromBezier(BezierSurface::FromPoints(3, 3, p));
    EXPECT_EQ(Length(s.NormalField(0.5, 0)), 0);
    std::optional<Vec3> n = s.UnitNormal(0.5, 0);
    ASSERT_TRUE(n.has_value());
    // The limit along v → 0 of the normal at u = 0.5: compare with a point very close to the apex.
    Vec3 near = Normalize(s.NormalField(0.5, 1e-6));
    EXPECT_NEAR(Dot(*n, near), 1, 1e-6);
    // Degenerate everywhere (all control points equal): no direction.
    Surface dot = Surface::FromBezier(
        BezierSurface::FromPoints(1, 1, {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}}));
    EXPECT_FALSE(dot.UnitNormal(0.3, 0.3).has_value());
}

TEST(FreeformSurface, BoundsWithPointsAtInfinity) {
    // A half circle as a rational quadratic with a middle weight of 0 (the control point is a
    // direction), swept along z: the Euclidean hull of the control points does not exist.
    std::vector<double> c;
    for (int j = 0; j < 2; ++j) {
        double z = j;
        double pts[3][4] = {{1, 0, z, 1}, {0, 1, 0, 0}, {-1, 0, z, 1}};
        for (auto& q : pts) c.insert(c.end(), {q[0], q[1], q[2], q[3]});
    }
    Surface s = Surface::FromBezier(BezierSurface(4, 2, 1, c));
    EXPECT_EQ(s.MinWeight(), 0);
    Box3 b = s.Bounds();
    ASSERT_TRUE(b.Finite());
    for (int k = 0; k <= 20; ++k) {
        Vec3 q = s.Point(k / 20.0, 0.5);
        EXPECT_NEAR(Length(Vec3{q.x, q.y, 0}), 1, 1e-14);  // w = (1−t)² + t² > 0: a half circle
        EXPECT_GE(q.y, b.lo.y);
        EXPECT_LE(q.y, b.hi.y);
    }
    EXPECT_LE(b.hi.y, 1.5);  // the hull after subdivision hugs the circle
}

}  // namespace
}  // namespace quadrix::freeform
