// Quadric–quadric curves traced with a bounded error (quartic_trace.h): points on both surfaces,
// one polyline per branch, chords within the tolerance of the true curve.
#include "quadrix/draw/quartic_trace.h"

#include <gtest/gtest.h>

#include <cmath>

namespace quadrix::draw {
namespace {

Quadric CylinderY(double cx, double cz, double r) {
    return Quadric::FromCoefficients({1, 0, 1, 0, 0, 0, -cx, 0, -cz, cx * cx + cz * cz - r * r});
}
Quadric Sphere(double r) { return Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, -r * r}); }

void ExpectOnBoth(const std::vector<Curve3>& curves, const Quadric& a, const Quadric& b) {
    for (const Curve3& c : curves)
        for (int i = 0; i <= 400; ++i) {
            const Vec3 p = c.At(c.t0 + (c.t1 - c.t0) * i / 400);
            EXPECT_NEAR(a.Evaluate(p) / Length(a.Gradient(p)), 0, 1e-9);
            EXPECT_NEAR(b.Evaluate(p) / Length(b.Gradient(p)), 0, 1e-9);
        }
}

TEST(QuarticTrace, ParallelCylindersMeetInTwoLines) {
    const Quadric a = CylinderY(0, 0, 2), b = CylinderY(2, 0, 2);
    const Box3 box{{-4, -10, -4}, {4, 10, 4}};
    auto curves = TraceQuadricQuadric(a, b, box);
    EXPECT_EQ(curves.size(), 2u);
    ExpectOnBoth(curves, a, b);
}

TEST(QuarticTrace, CylinderThroughASphereGivesTwoClosedLoopsWithinTolerance) {
    const Quadric s = Sphere(2), c = CylinderY(0.8, 0, std::sqrt(0.84));
    const Box3 box{{-3, -3, -3}, {3, 3, 3}};
    auto curves = TraceQuadricQuadric(s, c, box, 0.001);
    ASSERT_EQ(curves.size(), 2u);
    ExpectOnBoth(curves, s, c);
    for (const Curve3& k : curves) {
        EXPECT_LT(Length(k.points.front() - k.points.back()), 1e-9);  // closed
        // Chord midpoints (before projection) are within the tolerance of the curve.
        for (std::size_t i = 0; i + 1 < k.points.size(); ++i) {
            const Vec3 m = (k.points[i] + k.points[i + 1]) * 0.5;
            Vec3 q = m;
            ASSERT_TRUE(ProjectOntoBoth(s, c, q, 1e-12));
            EXPECT_LT(Length(q - m), 0.0015);
        }
    }
}

TEST(QuarticTrace, DisjointCoaxialCylindersGiveNothing) {
    const Box3 box{{-4, -10, -4}, {4, 10, 4}};
    EXPECT_TRUE(TraceQuadricQuadric(CylinderY(0, 0, 2), CylinderY(0, 0, 1), box).empty());
}

}  // namespace
}  // namespace quadrix::draw
