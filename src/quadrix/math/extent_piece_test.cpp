#include "quadrix/math/extent_piece.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace quadrix {
namespace {

// A disc of radius r about the axis n has the half widths r·sqrt(1 − n_i²) (n unit): checked for
// random rotations and translations of the disc {0, r e_x, r e_y} against that formula, and
// against points sampled on its rim, none outside the box and some within 1e-6 r of each side.
TEST(MathExtentPiece, ADiscsBoxUnderRotationsIsExact) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(-180, 180), shift(-50, 50);
    const double r = 3;
    const ExtentPiece disc{{0, 0, 0}, {r, 0, 0}, {0, r, 0}, {0, 0, 0}};
    for (int trial = 0; trial < 50; ++trial) {
        const Transform t = Transform::Translate({shift(rng), shift(rng), shift(rng)}) *
                            Transform::Rotate(0, angle(rng)) * Transform::Rotate(1, angle(rng)) *
                            Transform::Rotate(2, angle(rng));
        ASSERT_TRUE(IsAffine(t.Matrix()));
        const Box3 box = PieceBox(disc, t.Matrix());
        const Vec3 n = Normalize(t.MapVector({0, 0, 1}));
        const Vec3 c = t.MapPoint({0, 0, 0});
        for (int i = 0; i < 3; ++i) {
            const double half = r * std::sqrt(std::fmax(0.0, 1 - n[i] * n[i]));
            EXPECT_NEAR(box.lo[i], c[i] - half, 1e-12 * 60) << trial;
            EXPECT_NEAR(box.hi[i], c[i] + half, 1e-12 * 60) << trial;
        }
        Box3 rim;
        for (int k = 0; k < 20000; ++k) {
            const double phi = 2 * M_PI * k / 20000;
            rim.Extend(t.MapPoint({r * std::cos(phi), r * std::sin(phi), 0}));
        }
        for (int i = 0; i < 3; ++i) {
            EXPECT_LE(box.lo[i], rim.lo[i] + 1e-12) << trial;
            EXPECT_GE(box.hi[i], rim.hi[i] - 1e-12) << trial;
            EXPECT_LT(rim.lo[i] - box.lo[i], 1e-6 * r) << trial;
            EXPECT_LT(box.hi[i] - rim.hi[i], 1e-6 * r) << trial;
        }
        // Mapping the piece and taking its box is the same as the box after the map.
        const Box3 again = PieceBox(MappedPiece(disc, t.Matrix()));
        EXPECT_EQ(again.lo, box.lo);
        EXPECT_EQ(again.hi, box.hi);
    }
}

// For an affine map the piece's image is what Mat4::MapPoint and MapVector give, value for value
// (the importers' boxes and the walk's agree); for a projective one MappedPiece falls back to them.
TEST(MathExtentPiece, MappedPieceIsMapPointAndMapVector) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-100, 100);
    for (int trial = 0; trial < 200; ++trial) {
        Mat4 m;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) m.m[i][j] = u(rng);
        m.m[3][0] = m.m[3][1] = m.m[3][2] = 0;
        m.m[3][3] = 1;
        if (trial % 2) m.m[3][2] = 0.01 * u(rng);  // projective
        const ExtentPiece p{{u(rng), u(rng), u(rng)},
                            {u(rng), u(rng), u(rng)},
                            {u(rng), u(rng), u(rng)},
                            trial % 3 ? Vec3{u(rng), u(rng), u(rng)} : Vec3{}};
        const ExtentPiece q = MappedPiece(p, m);
        EXPECT_EQ(q.c, m.MapPoint(p.c)) << trial;
        EXPECT_EQ(q.a, m.MapVector(p.a)) << trial;
        EXPECT_EQ(q.b, m.MapVector(p.b)) << trial;
        EXPECT_EQ(q.d, m.MapVector(p.d)) << trial;
        const ExtentPiece point{p.c, {}, {}, {}};
        EXPECT_EQ(MappedPiece(point, m).c, m.MapPoint(p.c)) << trial;
        // The hull's box without the mapped pieces: the same values.
        Box3 expect = PieceBox(p, m);
        expect.Extend(PieceBox(point, m));
        const Box3 got = PiecesBox({p, point}, m);
        EXPECT_EQ(got.lo, expect.lo) << trial;
        EXPECT_EQ(got.hi, expect.hi) << trial;
    }
}

// An ellipsoid's box is its centre ± the lengths of the rows of its semi-axis matrix; a point
// piece's box is the point.
TEST(MathExtentPiece, EllipsoidAndPointBoxes) {
    const ExtentPiece ell{{1, 2, 3}, {2, 0, 0}, {0, 3, 4}, {0, -4, 3}};
    const Box3 b = PieceBox(ell);
    EXPECT_EQ(b.lo, (Vec3{-1, -3, -2}));
    EXPECT_EQ(b.hi, (Vec3{3, 7, 8}));
    const ExtentPiece point{{1, -2, 5}, {}, {}, {}};
    EXPECT_EQ(PieceBox(point).lo, (Vec3{1, -2, 5}));
    EXPECT_EQ(PieceBox(point).hi, (Vec3{1, -2, 5}));
}

// Only a last row of exactly 0 0 0 1 is affine: a perspective map is not (its boxes are not the
// pieces' images).
TEST(MathExtentPiece, IsAffineOnlyForTheLastRowZeroZeroZeroOne) {
    Mat4 m = Mat4::Identity();
    EXPECT_TRUE(IsAffine(m));
    m.m[3][2] = -0.1;
    EXPECT_FALSE(IsAffine(m));
    m = Mat4::Identity();
    m.m[3][3] = 2;
    EXPECT_FALSE(IsAffine(m));
}

}  // namespace
}  // namespace quadrix
