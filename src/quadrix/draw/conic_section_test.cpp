// Plane–quadric sections in closed form (conic_section.h): every kind, checked by putting points
// of each curve back into both equations.
#include "quadrix/draw/conic_section.h"

#include <gtest/gtest.h>

#include <cmath>

namespace quadrix::draw {
namespace {

Box3 BigBox() { return {{-100, -100, -100}, {100, 100, 100}}; }

// Largest |plane| and |quadric| (relative to the gradient size) over 200 points of each curve.
void ExpectOnBoth(const std::vector<Curve3>& curves, const Plane& p, const Quadric& q) {
    for (const Curve3& c : curves)
        for (int i = 0; i <= 200; ++i) {
            const Vec3 x = c.At(c.t0 + (c.t1 - c.t0) * i / 200);
            // Distances to the surfaces: value / |gradient|, to 1e-9 of the box size.
            EXPECT_NEAR(p.Evaluate(x) / Length(p.Normal()), 0, 1e-9 * 100) << ToString(c.kind);
            const double g = Length(q.Gradient(x));
            if (g > 1e-6) {
                EXPECT_NEAR(q.Evaluate(x) / g, 0, 1e-9 * 100) << ToString(c.kind);
            }
        }
}

// x² + z² <= r² (a cylinder along y).
Quadric CylinderY(double r) {
    return Quadric::FromCoefficients({1, 0, 1, 0, 0, 0, 0, 0, 0, -r * r});
}

TEST(ConicSection, ObliqueCutOfACylinderIsOneEllipse) {
    const Plane p{0.3, 1, 0.2, -5};
    const Quadric q = CylinderY(3);
    auto curves = PlaneQuadricCurves(p, q, BigBox());
    ASSERT_EQ(curves.size(), 1u);
    EXPECT_EQ(curves[0].kind, CurveKind::kEllipse);
    // The minor semi-axis of an oblique section of a cylinder is its radius.
    EXPECT_NEAR(std::fmin(Length(curves[0].u), Length(curves[0].v)), 3.0, 1e-12);
    ExpectOnBoth(curves, p, q);
}

TEST(ConicSection, CapOfACylinderIsACircleOfExactRadius) {
    const Plane p{0, 1, 0, -7};
    auto curves = PlaneQuadricCurves(p, CylinderY(2.5), BigBox());
    ASSERT_EQ(curves.size(), 1u);
    EXPECT_NEAR(Length(curves[0].u), 2.5, 2.5e-14);
    EXPECT_NEAR(Length(curves[0].v), 2.5, 2.5e-14);
}

TEST(ConicSection, PlaneParallelToTheAxisGivesTwoLinesOrATangentLine) {
    const Quadric q = CylinderY(2);
    auto two = PlaneQuadricCurves(Plane{1, 0, 0, -1}, q, BigBox());
    ASSERT_EQ(two.size(), 2u);
    for (const Curve3& c : two) EXPECT_EQ(c.kind, CurveKind::kLine);
    ExpectOnBoth(two, Plane{1, 0, 0, -1}, q);
    bool tangent = false;
    auto one = PlaneQuadricCurves(Plane{1, 0, 0, -2}, q, BigBox(), &tangent);
    EXPECT_TRUE(tangent);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_NEAR(one[0].o.x, 2, 1e-12);
    EXPECT_TRUE(PlaneQuadricCurves(Plane{1, 0, 0, -3}, q, BigBox()).empty());
}

TEST(ConicSection, ConeSectionsThroughAndAwayFromTheApex) {
    // x² + z² − y² <= 0: a double cone along y with its apex at the origin.
    const Quadric cone = Quadric::FromCoefficients({1, -1, 1, 0, 0, 0, 0, 0, 0, 0});
    const Plane throughApex{1, 0, 0, 0};  // x = 0: the lines z = ±y
    auto lines = PlaneQuadricCurves(throughApex, cone, BigBox());
    ASSERT_EQ(lines.size(), 2u);
    ExpectOnBoth(lines, throughApex, cone);
    const Plane steep{1, 0, 0, -3};  // x = 3: a hyperbola y² − z² = 9, two branches
    auto hyp = PlaneQuadricCurves(steep, cone, BigBox());
    ASSERT_EQ(hyp.size(), 2u);
    EXPECT_EQ(hyp[0].kind, CurveKind::kHyperbola);
    ExpectOnBoth(hyp, steep, cone);
    const Plane parallel{1, -1, 0, -2};  // parallel to a ruling: a parabola
    auto par = PlaneQuadricCurves(parallel, cone, BigBox());
    ASSERT_EQ(par.size(), 1u);
    EXPECT_EQ(par[0].kind, CurveKind::kParabola);
    ExpectOnBoth(par, parallel, cone);
    EXPECT_TRUE(PlaneQuadricCurves(Plane{0, 1, 0, 0}, cone, BigBox()).empty());  // the apex only
}

TEST(ConicSection, PlanePlaneLineIsClippedToTheBox) {
    Curve3 line;
    ASSERT_TRUE(PlanePlaneLine(Plane{1, 0, 0, -1}, Plane{0, 1, 0, -2}, BigBox(), line));
    EXPECT_NEAR(line.At(line.t0).x, 1, 1e-12);
    EXPECT_NEAR(line.At(line.t1).y, 2, 1e-12);
    EXPECT_NEAR(std::fabs(line.At(line.t1).z - line.At(line.t0).z), 200, 1e-9);
    EXPECT_FALSE(PlanePlaneLine(Plane{1, 0, 0, -1}, Plane{2, 0, 0, 5}, BigBox(), line));
}

}  // namespace
}  // namespace quadrix::draw
