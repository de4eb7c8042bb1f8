// Tests of the conservative bounds (bounds.h): analytic boxes against exact extents, the
// branch-and-bound against analytic extents of capped/mitered cylinders and cones, rejection
// sampling (every sampled point of a body lies in its box), unbounded and empty sets, and the
// amount of work (counted, so the checks are deterministic; times are printed, not asserted).
#include "quadrix/flatten/bounds.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

namespace quadrix {
namespace {

FlatHalfSpace PlaneHs(const Plane& p) {
    FlatHalfSpace h;
    h.isPlane = true;
    h.plane = p;
    return h;
}

FlatHalfSpace QuadricHs(const Quadric& q) {
    FlatHalfSpace h;
    h.isPlane = false;
    h.quadric = q;
    return h;
}

// A rotation from a random unit quaternion (uniform over rotations), with its exact transpose as
// the inverse.
Transform RandomRotation(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0, 1);
    double w = n(rng), x = n(rng), y = n(rng), z = n(rng);
    double len = std::sqrt(w * w + x * x + y * y + z * z);
    w /= len, x /= len, y /= len, z /= len;
    Mat4 m = Mat4::Identity();
    m.m[0][0] = 1 - 2 * (y * y + z * z);
    m.m[0][1] = 2 * (x * y - w * z);
    m.m[0][2] = 2 * (x * z + w * y);
    m.m[1][0] = 2 * (x * y + w * z);
    m.m[1][1] = 1 - 2 * (x * x + z * z);
    m.m[1][2] = 2 * (y * z - w * x);
    m.m[2][0] = 2 * (x * z - w * y);
    m.m[2][1] = 2 * (y * z + w * x);
    m.m[2][2] = 1 - 2 * (x * x + y * y);
    return Transform(m, m.Transposed());
}

// Unit-radius ellipsoid x²/a² + y²/b² + z²/c² <= 1 in local coordinates.
Quadric Ellipsoid(double a, double b, double c) {
    return Quadric::FromCoefficients({1 / (a * a), 1 / (b * b), 1 / (c * c), 0, 0, 0, 0, 0, 0, -1});
}

// Exact box of worldFromLocal(ellipsoid a, b, c): centre t, half-extent_i = |row_i(R diag(a))|.
Box3 ExactEllipsoidBox(const Transform& worldFromLocal, double a, double b, double c) {
    const Mat4& m = worldFromLocal.Matrix();
    Box3 box;
    double s[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
        double e = 0;
        for (int j = 0; j < 3; ++j) e += (m.m[i][j] * s[j]) * (m.m[i][j] * s[j]);
        e = std::sqrt(e);
        box.lo[i] = m.m[i][3] - e;
        box.hi[i] = m.m[i][3] + e;
    }
    return box;
}

// Box of an ellipse P0 + U cosθ + V sinθ.
void ExtendByEllipse(Box3& box, const Vec3& p0, const Vec3& u, const Vec3& v) {
    for (int i = 0; i < 3; ++i) {
        double e = std::sqrt(u[i] * u[i] + v[i] * v[i]);
        box.lo[i] = std::fmin(box.lo[i], p0[i] - e);
        box.hi[i] = std::fmax(box.hi[i], p0[i] + e);
    }
}

struct Body {
    std::vector<FlatHalfSpace> hs;
    std::vector<bool> complemented;
    std::vector<BoundLiteral> Literals() const {
        std::vector<BoundLiteral> l;
        for (std::size_t i = 0; i < hs.size(); ++i) l.push_back({&hs[i], complemented[i]});
        return l;
    }
    bool Contains(const Vec3& p) const {
        for (std::size_t i = 0; i < hs.size(); ++i) {
            double v = hs[i].Evaluate(p);
            if (complemented[i] ? !(v > 0) : !(v <= 0)) return false;
        }
        return true;
    }
};

// Mitered pipe in local coordinates: radius r along z, cut by z <= top + sx x and
// z >= bottom + sy y; placed by worldFromLocal. Returns the exact box too (the extremes of a
// cylinder segment lie on its two cut ellipses, since it is ruled along its axis).
Body MiteredPipe(const Transform& worldFromLocal, double r, double top, double sx, double bottom,
                 double sy, Box3& exact) {
    Body b;
    Quadric cyl = Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -r * r});
    b.hs.push_back(QuadricHs(cyl.Transformed(worldFromLocal)));
    b.hs.push_back(PlaneHs(Plane{-sx, 0, 1, -top}.Transformed(worldFromLocal)));   // z-sx x-top<=0
    b.hs.push_back(PlaneHs(Plane{0, sy, -1, bottom}.Transformed(worldFromLocal)));  // z>=bottom+sy y
    b.complemented = {false, false, false};
    // Cut ellipses in local coordinates: (r cosθ, r sinθ, top + sx r cosθ).
    const Transform& t = worldFromLocal;
    Vec3 o = t.MapPoint({0, 0, top});
    Vec3 u = t.MapVector({r, 0, sx * r}), v = t.MapVector({0, r, 0});
    exact = Box3{};
    ExtendByEllipse(exact, o, u, v);
    o = t.MapPoint({0, 0, bottom});
    u = t.MapVector({r, 0, 0});
    v = t.MapVector({0, r, sy * r});
    ExtendByEllipse(exact, o, u, v);
    return b;
}

void ExpectConservativeAndTight(const Box3& got, const Box3& exact, double tol,
                                const char* what) {
    for (int i = 0; i < 3; ++i) {
        EXPECT_LE(got.lo[i], exact.lo[i]) << what << " axis " << i;
        EXPECT_GE(got.hi[i], exact.hi[i]) << what << " axis " << i;
        EXPECT_LE(exact.lo[i] - got.lo[i], tol) << what << " axis " << i;
        EXPECT_LE(got.hi[i] - exact.hi[i], tol) << what << " axis " << i;
    }
}

TEST(Bounds, RotatedEllipsoidsAreAnalyticAndExact) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> size(0.1, 5), pos(-20, 20), mag(-8, 8);
    for (int trial = 0; trial < 200; ++trial) {
        // Magnitudes 10^±8 (STYLE.md): the same shape scaled, to check the relative accuracy.
        double s = std::pow(10.0, mag(rng));
        double a = size(rng) * s, b = size(rng) * s, c = size(rng) * s;
        Transform t = Transform::Translate({pos(rng) * s, pos(rng) * s, pos(rng) * s}) *
                      RandomRotation(rng);
        FlatHalfSpace hs = QuadricHs(Ellipsoid(a, b, c).Transformed(t));
        BoundLiteral lit{&hs, false};
        BoundsStats stats;
        Box3 got = IntersectionBounds({&lit, 1}, {}, &stats);
        Box3 exact = ExactEllipsoidBox(t, a, b, c);
        // Relative 1e-7 of the size: the analytic formula is exact up to rounding in the
        // transformed coefficients (cond(A) up to 2500 here) plus a 1e-10 relative pad.
        ExpectConservativeAndTight(got, exact, 1e-7 * std::fmax(a, std::fmax(b, c)) * 20,
                                   "ellipsoid");
        EXPECT_EQ(stats.analyticOnly, 1);
        EXPECT_EQ(stats.boxesPopped, 0);
    }
}

TEST(Bounds, ComplementedSphereIsUnboundedAndSphereCanBeEmpty) {
    FlatHalfSpace s = QuadricHs(Ellipsoid(1, 1, 1));
    Box3 outside = LiteralBox(s, true);
    EXPECT_FALSE(outside.Finite());
    // x² + y² + z² + 1 <= 0 is empty.
    FlatHalfSpace none = QuadricHs(Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, 1}));
    EXPECT_TRUE(LiteralBox(none, false).Empty());
    BoundLiteral lit{&none, false};
    EXPECT_TRUE(IntersectionBounds({&lit, 1}).Empty());
}

TEST(Bounds, AxisCylinderCappedByAxisPlanesIsAnalytic) {
    // x² + y² <= 4 capped at 0 <= z <= 3: exact box without search.
    Body b;
    b.hs = {QuadricHs(Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -4})),
            PlaneHs({0, 0, 1, -3}), PlaneHs({0, 0, -1, 0})};
    b.complemented = {false, false, false};
    auto lits = b.Literals();
    BoundsStats stats;
    Box3 got = IntersectionBounds(lits, {}, &stats);
    ExpectConservativeAndTight(got, Box3{{-2, -2, 0}, {2, 2, 3}}, 1e-9, "cylinder");
    EXPECT_EQ(stats.analyticOnly, 1);
}

TEST(Bounds, UncappedCylinderIsUnboundedOnlyAlongItsAxis) {
    // Along z: bounded in x, y (analytically), unbounded in z.
    FlatHalfSpace cyl = QuadricHs(Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 1, 0, 0, 0}));
    BoundLiteral lit{&cyl, false};  // (x+1)² + y² <= 1
    Box3 got = IntersectionBounds({&lit, 1}, {});
    EXPECT_NEAR(got.lo.x, -2, 1e-9);
    EXPECT_NEAR(got.hi.x, 0, 1e-9);
    EXPECT_NEAR(got.lo.y, -1, 1e-9);
    EXPECT_NEAR(got.hi.y, 1, 1e-9);
    EXPECT_EQ(got.lo.z, -HUGE_VAL);
    EXPECT_EQ(got.hi.z, HUGE_VAL);
    // Oblique, in the xy plane: bounded in z only; found by the search.
    std::mt19937_64 rng(3);
    Transform t = Transform::Rotate(2, 30);
    FlatHalfSpace ob = QuadricHs(
        Quadric::FromCoefficients({0, 1, 1, 0, 0, 0, 0, 0, 0, -1}).Transformed(t));  // along x
    BoundLiteral lit2{&ob, false};
    BoundsOptions o;
    o.searchLimit = 1e6;
    Box3 g2 = IntersectionBounds({&lit2, 1}, o);
    EXPECT_EQ(g2.lo.x, -HUGE_VAL);
    EXPECT_EQ(g2.hi.x, HUGE_VAL);
    EXPECT_EQ(g2.lo.y, -HUGE_VAL);
    EXPECT_EQ(g2.hi.y, HUGE_VAL);
    EXPECT_LE(g2.lo.z, -1);
    EXPECT_GE(g2.hi.z, 1);
    EXPECT_LE(g2.hi.z, 1 + 2e-3);  // relTolerance 1e-3 of the inner box, which is huge here:
                                   // the z bound comes from the exclusion test, not the tolerance
}

TEST(Bounds, MiteredPipesAreConservativeAndTight) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1), r(0.2, 2);
    BoundsStats stats;
    double seconds = 0;
    const int kTrials = 100;
    for (int trial = 0; trial < kTrials; ++trial) {
        Transform t = Transform::Translate({5 * u(rng), 5 * u(rng), 5 * u(rng)}) *
                      RandomRotation(rng);
        Box3 exact;
        double radius = r(rng);
        Body b = MiteredPipe(t, radius, 2 + u(rng), 0.8 * u(rng), -2 + u(rng), 0.8 * u(rng),
                             exact);
        auto lits = b.Literals();
        auto t0 = std::chrono::steady_clock::now();
        Box3 got = IntersectionBounds(lits, {}, &stats);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        // relTolerance 1e-3 of the body's size (about 4-6 here) per side, with slack 2x.
        ExpectConservativeAndTight(got, exact, 2e-2, "mitered pipe");
    }
    std::printf("[ bounds ] mitered pipe: %.1f us/body, %.0f boxes popped/body, %lld budget hits\n",
                1e6 * seconds / kTrials, double(stats.boxesPopped) / kTrials,
                static_cast<long long>(stats.budgetExhausted));
    EXPECT_EQ(stats.budgetExhausted, 0);
}

}  // namespace
}  // namespace quadrix
