// The format-neutral shape builders (ellipsoid.h, hexahedron.h, truncated_cone.h, torus.h,
// local_frame.h) against analytic facts: the textbook coefficients of a sphere, a cylinder and a
// cone in DESIGN.md's order, points just inside and just outside each shape, and exact boxes.
// Points are 1 % of the local size from the boundary, so every containment test is a strict one.
#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/import/shapes/ellipsoid.h"
#include "quadrix/import/shapes/hexahedron.h"
#include "quadrix/import/shapes/local_frame.h"
#include "quadrix/import/shapes/torus.h"
#include "quadrix/import/shapes/truncated_cone.h"

namespace quadrix::import {
namespace {

// Coefficients computed through a 4×4 inverse and two products: a few ulps of the largest.
constexpr double kCoefTol = 1e-14;

void ExpectQuadric(const ShapeHalfSpace& h, const std::array<double, 10>& want) {
    ASSERT_TRUE(h.IsQuadric());
    for (int i = 0; i < 10; ++i) EXPECT_NEAR(h.quadric.k[i], want[i], kCoefTol) << "k[" << i << "]";
}

void ExpectPlane(const ShapeHalfSpace& h, const Plane& want) {
    ASSERT_TRUE(h.isPlane);
    EXPECT_NEAR(h.plane.a, want.a, kCoefTol);
    EXPECT_NEAR(h.plane.b, want.b, kCoefTol);
    EXPECT_NEAR(h.plane.c, want.c, kCoefTol);
    EXPECT_NEAR(h.plane.d, want.d, kCoefTol);
}

void ExpectBox(const Box3& box, const Vec3& lo, const Vec3& hi, double tol) {
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(box.lo[i], lo[i], tol) << "lo[" << i << "]";
        EXPECT_NEAR(box.hi[i], hi[i], tol) << "hi[" << i << "]";
    }
}

TEST(ShapeBuilders, SphereHasTheTextbookQuadric) {
    // (x−1)² + (y−2)² + (z−3)² <= 4, divided by r² = 4 (powers of two: exact in binary).
    const ShapeResult s = SphereShape({1, 2, 3}, 2);
    ASSERT_TRUE(s.ok) << s.problem;
    ASSERT_EQ(s.shape.bodies.size(), 1u);
    ASSERT_EQ(s.shape.bodies[0].size(), 1u);
    ExpectQuadric(s.shape.bodies[0][0], {0.25, 0.25, 0.25, 0, 0, 0, -0.25, -0.5, -0.75, 2.5});
    EXPECT_TRUE(ShapeContains(s.shape, {1, 2, 3}));
    EXPECT_TRUE(ShapeContains(s.shape, {2.98, 2, 3}));
    EXPECT_FALSE(ShapeContains(s.shape, {3.02, 2, 3}));
    EXPECT_TRUE(ShapeContains(s.shape, {1, 2, 1.02}));
    EXPECT_FALSE(ShapeContains(s.shape, {1, 2, 0.98}));
    ExpectBox(ShapeBox(s.shape, Mat4::Identity()), {-1, 0, 1}, {3, 4, 5}, 0);
}

TEST(ShapeBuilders, EllipsoidWithObliqueSemiAxes) {
    // Semi-axes need not be perpendicular: the point V + α A + β B + γ C is inside iff
    // α² + β² + γ² <= 1.
    const Vec3 v{-1, 0.5, 2}, a{2, 1, 0}, b{0.5, 1, 0.3}, c{0, -0.2, 1.5};
    const ShapeResult s = EllipsoidShape(v, a, b, c);
    ASSERT_TRUE(s.ok) << s.problem;
    for (double t : {0.99, -0.99}) {
        EXPECT_TRUE(ShapeContains(s.shape, v + a * t));
        EXPECT_TRUE(ShapeContains(s.shape, v + b * t));
        EXPECT_TRUE(ShapeContains(s.shape, v + c * t));
        EXPECT_FALSE(ShapeContains(s.shape, v + a * (t * 1.02)));
        EXPECT_FALSE(ShapeContains(s.shape, v + c * (t * 1.02)));
    }
    // (0.5, 0.5, 0.7): |.|² = 0.99 inside; (0.5, 0.5, 0.72): 1.0184 outside.
    EXPECT_TRUE(ShapeContains(s.shape, v + a * 0.5 + b * 0.5 + c * 0.7));
    EXPECT_FALSE(ShapeContains(s.shape, v + a * 0.5 + b * 0.5 + c * 0.72));
    // Its one extent piece is the ellipsoid itself: the box's half width along x is
    // sqrt(ax² + bx² + cx²).
    const Box3 box = ShapeBox(s.shape, Mat4::Identity());
    EXPECT_NEAR(box.hi.x - v.x, std::sqrt(4 + 0.25), 1e-15);
    const ShapeResult flat = EllipsoidShape(v, a, a * 2, c);
    EXPECT_FALSE(flat.ok);
    EXPECT_EQ(flat.problem, "the semi-axes A, B, C are degenerate");
}

TEST(ShapeBuilders, BoxIsItsSixFacePlanes) {
    const Vec3 lo{-1, 2, 0.5}, hi{3, 2.5, 4};
    const ShapeResult s = BoxShape(lo, hi);
    ASSERT_TRUE(s.ok) << s.problem;
    ASSERT_EQ(s.shape.bodies.size(), 1u);
    const ShapeBody& body = s.shape.bodies[0];
    ASSERT_EQ(body.size(), 6u);
    // The faces 1234 (z = lo.z), 8765 (z = hi.z), 1485 (x = lo.x), 2673 (x = hi.x), 1562
    // (y = lo.y), 4378 (y = hi.y), each with its outward unit normal.
    ExpectPlane(body[0], {0, 0, -1, lo.z});
    ExpectPlane(body[1], {0, 0, 1, -hi.z});
    ExpectPlane(body[2], {-1, 0, 0, lo.x});
    ExpectPlane(body[3], {1, 0, 0, -hi.x});
    ExpectPlane(body[4], {0, -1, 0, lo.y});
    ExpectPlane(body[5], {0, 1, 0, -hi.y});
    const Vec3 mid = (lo + hi) * 0.5;
    EXPECT_TRUE(ShapeContains(s.shape, mid));
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 in = mid, out = mid;
        const double size = hi[axis] - lo[axis];
        in[axis] = hi[axis] - 0.01 * size;
        out[axis] = hi[axis] + 0.01 * size;
        EXPECT_TRUE(ShapeContains(s.shape, in)) << axis;
        EXPECT_FALSE(ShapeContains(s.shape, out)) << axis;
        in[axis] = lo[axis] + 0.01 * size;
        out[axis] = lo[axis] - 0.01 * size;
        EXPECT_TRUE(ShapeContains(s.shape, in)) << axis;
        EXPECT_FALSE(ShapeContains(s.shape, out)) << axis;
    }
    ExpectBox(ShapeBox(s.shape, Mat4::Identity()), lo, hi, 0);
}

TEST(ShapeBuilders, HexahedronWithRepeatedVerticesIsAWedgeOrATetrahedron) {
    // arb6 (a wedge): vertices 5 = 6 and 7 = 8 make the top an edge over x = 0; the top face
    // 8765 collapses and is dropped, the other five faces give five planes.
    const ShapeResult wedge =
        HexahedronShape({Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{2, 2, 0}, Vec3{0, 2, 0}, Vec3{0, 0, 2},
                         Vec3{0, 0, 2}, Vec3{0, 2, 2}, Vec3{0, 2, 2}});
    ASSERT_TRUE(wedge.ok) << wedge.problem;
    EXPECT_EQ(wedge.shape.bodies[0].size(), 5u);
    // Its slope x + z <= 2.
    EXPECT_TRUE(ShapeContains(wedge.shape, {0.99, 1, 0.99}));
    EXPECT_FALSE(ShapeContains(wedge.shape, {1.01, 1, 1.01}));
    // arb4 (a tetrahedron): vertices 1 2 3 1 5 5 5 5: x, y, z >= 0 and x + y + z <= 1.
    const ShapeResult tet =
        HexahedronShape({Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 0}, Vec3{0, 0, 1},
                         Vec3{0, 0, 1}, Vec3{0, 0, 1}, Vec3{0, 0, 1}});
    ASSERT_TRUE(tet.ok) << tet.problem;
    EXPECT_EQ(tet.shape.bodies[0].size(), 4u);
    EXPECT_TRUE(ShapeContains(tet.shape, {0.33, 0.33, 0.33}));
    EXPECT_FALSE(ShapeContains(tet.shape, {0.34, 0.34, 0.34}));
    EXPECT_FALSE(ShapeContains(tet.shape, {-0.01, 0.2, 0.2}));
    // Flat (top = base): refused.
    const ShapeResult flat =
        HexahedronShape({Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 0},
                         Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}});
    EXPECT_FALSE(flat.ok);
    EXPECT_EQ(flat.problem, "its vertices do not span a solid");
}

TEST(ShapeBuilders, TwistedHexahedronIsBoundedByTheBoxOfItsVertices) {
    // Vertex 3 lifted to (2, 2, 1) twists the base: its plane (through vertices 1, 2, 3) is
    // y − 2z <= 0, which vertex 4 = (0, 2, 0) violates. The face planes alone would reach beyond
    // the vertices; six box planes, x <= 2, −x <= 0, y <= 2, … keep the solid within them.
    const ShapeResult s =
        HexahedronShape({Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{2, 2, 1}, Vec3{0, 2, 0}, Vec3{0, 0, 2},
                         Vec3{2, 0, 2}, Vec3{2, 2, 2}, Vec3{0, 2, 2}});
    ASSERT_TRUE(s.ok) << s.problem;
    const ShapeBody& body = s.shape.bodies[0];
    ASSERT_EQ(body.size(), 12u);
    for (int axis = 0; axis < 3; ++axis) {
        Vec3 n;
        n[axis] = 1;
        ExpectPlane(body[6 + 2 * axis], {n.x, n.y, n.z, -2});
        ExpectPlane(body[7 + 2 * axis], {-n.x, -n.y, -n.z, 0});
    }
    ExpectBox(ShapeBox(s.shape, Mat4::Identity()), {0, 0, 0}, {2, 2, 2}, 0);
    EXPECT_TRUE(ShapeContains(s.shape, {1, 1, 1.5}));
    EXPECT_FALSE(ShapeContains(s.shape, {1, 1.5, 0.5}));  // below the lifted base: y − 2z > 0
    EXPECT_FALSE(ShapeContains(s.shape, {1, 1, 2.02}));
    // A convex box has no box planes.
    EXPECT_EQ(BoxShape({0, 0, 0}, {1, 1, 1}).shape.bodies[0].size(), 6u);
}

TEST(ShapeBuilders, CylinderAndConeHaveTheTextbookQuadrics) {
    // The circular cylinder of radius 2 along z over [0, 4]: x²/4 + y²/4 − 1 <= 0, caps −z/4 <= 0
    // and z/4 − 1 <= 0.
    const ConeShape cyl =
        TruncatedConeShape({0, 0, 0}, {0, 0, 4}, {2, 0, 0}, {0, 2, 0}, {2, 0, 0}, {0, 2, 0});
    ASSERT_TRUE(cyl.ok) << cyl.problem;
    EXPECT_FALSE(cyl.quartic);
    ASSERT_EQ(cyl.shape.bodies[0].size(), 3u);
    ExpectQuadric(cyl.shape.bodies[0][0], {0.25, 0.25, 0, 0, 0, 0, 0, 0, 0, -1});
    ExpectPlane(cyl.shape.bodies[0][1], {0, 0, -0.25, 0});
    ExpectPlane(cyl.shape.bodies[0][2], {0, 0, 0.25, -1});
    // Radii 2 at z = 0 and 1 at z = 4: m = −1/2, Q = <1/4, 1/4, −m²/16, 0, 0, 0, 0, 0, −m/4, −1>.
    const ConeShape cone =
        TruncatedConeShape({0, 0, 0}, {0, 0, 4}, {2, 0, 0}, {0, 2, 0}, {1, 0, 0}, {0, 1, 0});
    ASSERT_TRUE(cone.ok) << cone.problem;
    EXPECT_FALSE(cone.quartic);
    ExpectQuadric(cone.shape.bodies[0][0], {0.25, 0.25, -0.015625, 0, 0, 0, 0, 0, 0.125, -1});
    for (double z : {0.4, 2.0, 3.6}) {
        const double r = 2 - z / 4;
        EXPECT_TRUE(ShapeContains(cone.shape, {0.99 * r, 0, z})) << z;
        EXPECT_FALSE(ShapeContains(cone.shape, {1.01 * r, 0, z})) << z;
        EXPECT_TRUE(ShapeContains(cone.shape, {0, -0.99 * r, z})) << z;
    }
    EXPECT_FALSE(ShapeContains(cone.shape, {0, 0, -0.04}));
    EXPECT_FALSE(ShapeContains(cone.shape, {0, 0, 4.04}));
    // The two end circles are the extent: the box is [−2, 2]² × [0, 4].
    ExpectBox(ShapeBox(cone.shape, Mat4::Identity()), {-2, -2, 0}, {2, 2, 4}, 1e-15);
}

TEST(ShapeBuilders, ConeWithItsApexAtTheBase) {
    // OpenSCAD's cylinder(h = 3, r1 = 0, r2 = 1.5): the apex at the origin, radius z/2.
    const ConeShape s =
        TruncatedConeShape({0, 0, 0}, {0, 0, 3}, {0, 0, 0}, {0, 0, 0}, {1.5, 0, 0}, {0, 1.5, 0});
    ASSERT_TRUE(s.ok) << s.problem;
    for (double z : {0.3, 1.5, 2.7}) {
        EXPECT_TRUE(ShapeContains(s.shape, {0, 0.99 * z / 2, z})) << z;
        EXPECT_FALSE(ShapeContains(s.shape, {0, 1.01 * z / 2, z})) << z;
    }
    // The other nappe of the double cone, below the apex, is cut off by the cap.
    EXPECT_FALSE(ShapeContains(s.shape, {0, 0.1, -0.5}));
    ExpectBox(ShapeBox(s.shape, Mat4::Identity()), {-1.5, -1.5, 0}, {1.5, 1.5, 3}, 1e-15);
}

TEST(ShapeBuilders, ConeWithDissimilarEndsIsTheQuarticGeneralCone) {
    // Base semi-axes 2 (x) and 1 (y), top 1 and 1: |A|·|D| = 2 ≠ |B|·|C| = 1. Half-way up the
    // semi-axes are 1.5 and 1.
    const ConeShape s =
        TruncatedConeShape({0, 0, 0}, {0, 0, 4}, {2, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 1, 0});
    ASSERT_TRUE(s.ok) << s.problem;
    EXPECT_TRUE(s.quartic);
    ASSERT_EQ(s.shape.bodies[0].size(), 3u);  // the quartic and its two caps
    EXPECT_TRUE(s.shape.bodies[0][0].IsQuartic());
    EXPECT_TRUE(ShapeContains(s.shape, {1.485, 0, 2}));
    EXPECT_FALSE(ShapeContains(s.shape, {1.515, 0, 2}));
    EXPECT_TRUE(ShapeContains(s.shape, {0, 0.99, 2}));
    EXPECT_FALSE(ShapeContains(s.shape, {0, 1.01, 2}));
    // On the ellipse x²/1.5² + y²/1² = 1 at 45° in parameter: (1.5, 1)·cos 45°, scaled by 0.99
    // and 1.01.
    const double c = std::sqrt(0.5);
    EXPECT_TRUE(ShapeContains(s.shape, {0.99 * 1.5 * c, 0.99 * c, 2}));
    EXPECT_FALSE(ShapeContains(s.shape, {1.01 * 1.5 * c, 1.01 * c, 2}));
    EXPECT_FALSE(ShapeContains(s.shape, {0, 0, 4.04}));
    ExpectBox(ShapeBox(s.shape, Mat4::Identity()), {-2, -1, 0}, {2, 1, 4}, 1e-15);
}

TEST(ShapeBuilders, ConeRefusals) {
    const Vec3 x{1, 0, 0}, y{0, 1, 0};
    EXPECT_EQ(TruncatedConeShape({}, {}, x, y, x, y).problem, "the height vector H is zero");
    EXPECT_EQ(TruncatedConeShape({}, {0, 0, 1}, x, {}, {}, y).problem,
              "both end ellipses are degenerate");
    EXPECT_EQ(TruncatedConeShape({}, {0, 0, 1}, x, y, y, x).problem,
              "C must be parallel to A and D to B");
    EXPECT_EQ(TruncatedConeShape({}, {1, 1, 0}, x, y, x, y).problem, "A, B and H are coplanar");
    EXPECT_FALSE(SimilarConeBody({}, x, y, {1, 1, 0}, 1).has_value());
}

TEST(ShapeBuilders, TorusIsTheTextbookQuartic) {
    // F = (x² + y² + z² + R² − r²)² − 4R²(x² + y²): the builder's quartic is evaluated in its own
    // unit-sized frame, so it is a positive multiple of F (the same ratio everywhere).
    const double R = 3, r = 1;
    const ShapeResult s = TorusShape({0, 0, 0}, {0, 0, 2}, R, r);
    ASSERT_TRUE(s.ok) << s.problem;
    ASSERT_EQ(s.shape.bodies.size(), 1u);
    const ShapeHalfSpace& h = s.shape.bodies[0][0];
    ASSERT_TRUE(h.IsQuartic());
    auto f = [&](const Vec3& p) {
        const double rho2 = p.x * p.x + p.y * p.y, s2 = rho2 + p.z * p.z + R * R - r * r;
        return s2 * s2 - 4 * R * R * rho2;
    };
    const double ratio = h.Evaluate({3, 0, 0}) / f({3, 0, 0});
    EXPECT_GT(ratio, 0);
    for (const Vec3& p : {Vec3{0, 0, 0}, Vec3{1, 2, 0.5}, Vec3{-2.5, 1, -0.3}, Vec3{0, 5, 3}})
        EXPECT_NEAR(h.Evaluate(p) / f(p), ratio, 1e-12 * ratio) << p.x << " " << p.y;
    EXPECT_TRUE(ShapeContains(s.shape, {0, 3.99, 0}));
    EXPECT_FALSE(ShapeContains(s.shape, {0, 4.01, 0}));
    EXPECT_TRUE(ShapeContains(s.shape, {-2.01, 0, 0}));
    EXPECT_FALSE(ShapeContains(s.shape, {-1.99, 0, 0}));
    EXPECT_TRUE(ShapeContains(s.shape, {3, 0, 0.99}));
    EXPECT_FALSE(ShapeContains(s.shape, {3, 0, 1.01}));
    // The ring circle plus the tube's ball: [−4, 4]² × [−1, 1].
    ExpectBox(ShapeBox(s.shape, Mat4::Identity()), {-4, -4, -1}, {4, 4, 1}, 1e-15);
    EXPECT_FALSE(TorusShape({}, {0, 0, 1}, 1, 2).ok);  // the tube reaches the axis
}

TEST(ShapeBuilders, EllipticalTorusAboutATiltedAxis) {
    // Axis ŷ through (1, 2, 3); radius of revolution 5; meridian semi-axis 2 along the axis
    // (C = 2ŷ) and 1 across it.
    const Vec3 v{1, 2, 3};
    const ShapeResult s = EllipticalTorusShape(v, {0, 3, 0}, 5, {0, 2, 0}, 1);
    ASSERT_TRUE(s.ok) << s.problem;
    EXPECT_TRUE(ShapeContains(s.shape, v + Vec3{5, 1.98, 0}));
    EXPECT_FALSE(ShapeContains(s.shape, v + Vec3{5, 2.02, 0}));
    EXPECT_TRUE(ShapeContains(s.shape, v + Vec3{0, 0, 5.99}));
    EXPECT_FALSE(ShapeContains(s.shape, v + Vec3{0, 0, 6.01}));
    EXPECT_TRUE(ShapeContains(s.shape, v + Vec3{-4.01, 0, 0}));
    EXPECT_FALSE(ShapeContains(s.shape, v + Vec3{-3.99, 0, 0}));
    EXPECT_FALSE(ShapeContains(s.shape, v));
    // C along the axis: the containing sum is exact, [−6, 6] across the axis, [−2, 2] along it.
    ExpectBox(ShapeBox(s.shape, Mat4::Identity()), v + Vec3{-6, -2, -6}, v + Vec3{6, 2, 6}, 1e-14);
    EXPECT_FALSE(EllipticalTorusShape({}, {0, 0, 1}, 1, {0, 0, 3}, 1).ok);  // reaches the axis
}

TEST(ShapeBuilders, LocalFrameMapsTextbookFormsIntoShapeSpace) {
    // Frame O = (1, 1, 1), e1 = 2x̂, e2 = ŷ + x̂, e3 = 3ẑ: the local plane u1 − 1 <= 0 holds at
    // O + e1 (on it) and the local unit ball contains O + 0.99 e2.
    const Vec3 o{1, 1, 1}, e1{2, 0, 0}, e2{1, 1, 0}, e3{0, 0, 3};
    const LocalFrame f(o, e1, e2, e3);
    ASSERT_TRUE(f.ok());
    const ShapeHalfSpace p = f.Plane4(1, 0, 0, -1);
    EXPECT_NEAR(p.Evaluate(o + e1), 0, 1e-15);
    EXPECT_NEAR(p.Evaluate(o + e1 * 0.5 + e2 * 7 + e3 * -3), -0.5, 1e-14);
    const ShapeHalfSpace q = f.Quad(DiagonalQuadric(1, 1, 1, -1), true);
    EXPECT_TRUE(q.transparent);
    EXPECT_LT(q.Evaluate(o + e2 * 0.99), 0);
    EXPECT_GT(q.Evaluate(o + e2 * 1.01), 0);
    EXPECT_NEAR(q.Evaluate(o + e3), 0, 1e-15);
    EXPECT_FALSE(LocalFrame(o, e1, e1 * 2, e3).ok());
    for (const Vec3& axis : {Vec3{0, 0, 1}, Vec3{1, 0, 0}, Normalize(Vec3{0.6, -0.7, 0.2})}) {
        const Vec3 n = AnyPerpendicular(axis);
        EXPECT_NEAR(Dot(n, axis), 0, 1e-15);
        EXPECT_NEAR(Length(n), 1, 1e-15);
    }
}

// The extent a scene body keeps (BodyExtent): the pieces after the placement, only for a shape of
// one body whose pieces' hull has exactly its box (an ellipsoid, a cone, a convex hexahedron with
// planar faces) under an affine placement; none for a torus (a Minkowski sum), a twisted or
// nearly twisted hexahedron, or a perspective map.
TEST(ShapeBuilders, BodyExtentOnlyWhereThePiecesGiveTheExactBox) {
    const Mat4 place =
        (Transform::Translate({5, -3, 2}) * Transform::Rotate(0, 30) * Transform::Rotate(2, 50))
            .Matrix();
    const ShapeResult ell = EllipsoidShape({1, 2, 3}, {2, 0, 0}, {0, 1, 0}, {0, 0, 0.5});
    ASSERT_TRUE(ell.ok);
    const std::vector<ExtentPiece> e = BodyExtent(ell.shape, place);
    ASSERT_EQ(e.size(), 1u);
    EXPECT_EQ(e[0].c, place.MapPoint({1, 2, 3}));
    EXPECT_EQ(e[0].a, place.MapVector({2, 0, 0}));
    const ConeShape cyl =
        TruncatedConeShape({0, 0, 0}, {0, 0, 4}, {2, 0, 0}, {0, 2, 0}, {1, 0, 0}, {0, 1, 0});
    ASSERT_TRUE(cyl.ok);
    EXPECT_EQ(BodyExtent(cyl.shape, place).size(), 2u);  // the two end discs
    EXPECT_EQ(BodyExtent(BoxShape({0, 0, 0}, {1, 2, 3}).shape, place).size(), 8u);
    // Not exact: a torus's box is a sum of pieces.
    EXPECT_TRUE(BodyExtent(TorusShape({0, 0, 0}, {0, 0, 1}, 3, 1).shape, place).empty());
    // A base twisted by 0.0003, within kHexahedronTol: convex to the builder (no box planes),
    // but its corner is not where the vertex is.
    const ShapeResult nearlyTwisted =
        HexahedronShape({Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{2, 2, 0.0003}, Vec3{0, 2, 0},
                         Vec3{0, 0, 2}, Vec3{2, 0, 2}, Vec3{2, 2, 2}, Vec3{0, 2, 2}});
    ASSERT_TRUE(nearlyTwisted.ok);
    EXPECT_EQ(nearlyTwisted.shape.bodies[0].size(), 6u);
    EXPECT_TRUE(BodyExtent(nearlyTwisted.shape, place).empty());
    // Perspective: no extent.
    Mat4 perspective = place;
    perspective.m[3][2] = -0.01;
    EXPECT_TRUE(BodyExtent(ell.shape, perspective).empty());
}

}  // namespace
}  // namespace quadrix::import
