// Bodies into patches (patch.h) and the paper's per-pixel polynomials (patch_polynomials.h).
#include "quadrix/engines/patch/patch.h"

#include <gtest/gtest.h>

#include <random>

#include "quadrix/engines/patch/patch_polynomials.h"
#include "quadrix/engines/patch/patch_test_util.h"

namespace quadrix::patch {
namespace {

using testing::SceneBuilder;
using testing::Sphere;
using testing::SphereBox;

TEST(PatchConvert, WindowIsThePixelsWhoseCentresLieInTheBox) {
    const Box3 box{{2.5, 3.4, 0}, {6.5, 3.6, 1}};
    const PixelWindow w = WindowOfBox(box, 10, 10);
    EXPECT_EQ(w.x0, 2);  // centre 2.5 is on the box's edge: included
    EXPECT_EQ(w.x1, 7);  // centre 6.5 included
    EXPECT_EQ(w.y0, 3);
    EXPECT_EQ(w.y1, 4);
    EXPECT_EQ(w.Pixels(), 5);
    EXPECT_TRUE(WindowOfBox({{3.6, 0, 0}, {4.4, 9, 1}}, 10, 10).Empty());  // between centres
    const PixelWindow all = WindowOfBox(Box3::Everything(), 8, 6);
    EXPECT_EQ(all.Pixels(), 48);
    EXPECT_TRUE(WindowOfBox(Box3{}, 8, 6).Empty());
    EXPECT_TRUE(WindowOfBox({{20, 20, 0}, {30, 30, 1}}, 8, 6).Empty());  // off the image
}

TEST(PatchConvert, QuadricWithTransparentAndComplementedPlanes) {
    SceneBuilder b(32, 32);
    const Vec3 c{16, 16, 50};
    const int q = b.AddQuadric(Sphere(c, 10));
    const int p = b.AddPlane({0, 0, 1, -50});  // z <= 50, complemented: z >= 50
    const int body = b.AddBody({{q, false}, {p, true}}, SphereBox(c, 10));
    const Conversion conv = ConvertBody(b.scene(), body, CapPolicy::kSkip);
    ASSERT_TRUE(conv.patch.has_value()) << RejectionName(conv.why);
    EXPECT_EQ(conv.patch->planeCount, 1);
    EXPECT_EQ(conv.patch->planes[0].plane, (Plane{0, 0, -1, 50}));  // negated
    EXPECT_EQ(conv.patch->surface, q);
    EXPECT_EQ(conv.patch->body, body);
    EXPECT_EQ(conv.patch->solid, b.scene().bodies[static_cast<std::size_t>(body)].solid);
    EXPECT_EQ(conv.patch->window.x0, 6);
    EXPECT_EQ(conv.patch->window.x1, 26);
}

TEST(PatchConvert, NegativeCIsNormalisedAndComplementedQuadricIsTheSameSurface) {
    SceneBuilder b(32, 32);
    Quadric q = Sphere({16, 16, 50}, 10);
    for (double& k : q.k) k = -k;  // the outside of the sphere: C < 0
    const int hq = b.AddQuadric(q);
    const int body = b.AddBody({{hq, true}}, SphereBox({16, 16, 50}, 10));
    const Conversion conv = ConvertBody(b.scene(), body, CapPolicy::kSkip);
    ASSERT_TRUE(conv.patch.has_value());
    EXPECT_GT(conv.patch->quadric.C(), 0);
    EXPECT_EQ(conv.patch->quadric, Sphere({16, 16, 50}, 10));
}

TEST(PatchConvert, RedundantPlanesAreDroppedToFitFour) {
    SceneBuilder b(32, 32);
    const Vec3 c{16, 16, 50};
    std::vector<FlatLiteral> lits{{b.AddQuadric(Sphere(c, 10)), false}};
    for (int k = 0; k < 4; ++k) lits.push_back({b.AddPlane({1, 0, 0, -16.0 - k}), false});
    // Two clipping planes far in front and behind: they do not meet the box.
    lits.push_back({b.AddPlane({0, 0, -1, 0}, true, true), false});     // z >= 0
    lits.push_back({b.AddPlane({0, 0, 1, -1000}, true, true), false});  // z <= 1000
    const int body = b.AddBody(lits, SphereBox(c, 10));
    const Conversion conv = ConvertBody(b.scene(), body, CapPolicy::kSkip);
    ASSERT_TRUE(conv.patch.has_value()) << RejectionName(conv.why);
    EXPECT_EQ(conv.planesDropped, 2);
    EXPECT_EQ(conv.patch->planeCount, 4);
}

TEST(PatchConvert, APlaneTouchingTheBoxIsNotRedundant) {
    // The box of a capped body ends exactly on its cap: the cap still cuts.
    SceneBuilder b(32, 32);
    const Vec3 c{16, 16, 50};
    const int body =
        b.AddBody({{b.AddQuadric(Sphere(c, 10)), false}, {b.AddPlane({1, 0, 0, -16}), false}},
                  {{6, 6, 40}, {16, 26, 60}});
    const Conversion conv = ConvertBody(b.scene(), body, CapPolicy::kSkip);
    ASSERT_TRUE(conv.patch.has_value());
    EXPECT_EQ(conv.patch->planeCount, 1);
}

TEST(PatchConvert, WhatCannotBeAPatchIsReportedNotDrawn) {
    SceneBuilder b(32, 32);
    const Vec3 c{16, 16, 50};
    const Box3 box = SphereBox(c, 10);
    const int q = b.AddQuadric(Sphere(c, 10));
    const int q2 = b.AddQuadric(Sphere(c + Vec3{3, 0, 0}, 10));
    const int opaque = b.AddPlane({1, 0, 0, -16}, false);
    std::vector<FlatLiteral> five{{q, false}};
    for (int k = 0; k < 5; ++k) five.push_back({b.AddPlane({1, 0.1 * k, 0, -16}), false});
    Quadric alongView;  // cylinder x² + y² = 25 along z: C = 0
    alongView.k = {1, 1, 0, 0, 0, 0, -16, -16, 0, 2 * 256 - 25};
    Quadric nan = Sphere(c, 10);
    nan.k[0] = std::nan("");

    auto why = [&](std::vector<FlatLiteral> lits, CapPolicy caps = CapPolicy::kSkip) {
        return ConvertBody(b.scene(), b.AddBody(lits, box), caps).why;
    };
    EXPECT_EQ(why({{b.AddPlane({1, 0, 0, -16}), false}}), Rejection::kNoQuadric);
    EXPECT_EQ(why({{q, false}, {q2, false}}), Rejection::kSeveralQuadrics);
    EXPECT_EQ(why(five), Rejection::kTooManyPlanes);
    EXPECT_EQ(why({{q, false}, {opaque, false}}), Rejection::kOpaquePlaneFace);
    EXPECT_EQ(why({{b.AddQuadric(alongView), false}}), Rejection::kViewAlongSurface);
    EXPECT_EQ(why({{b.AddQuadric(nan), false}}), Rejection::kNotFinite);
    EXPECT_EQ(why({{b.AddQuadric(Sphere(c, 10), true), false}}), Rejection::kInvisible);
    EXPECT_EQ(why({{99, false}}), Rejection::kMalformed);
    // caps=open draws the quadric with the opaque plane as a bound.
    const Conversion open =
        ConvertBody(b.scene(), b.AddBody({{q, false}, {opaque, false}}, box), CapPolicy::kOpen);
    ASSERT_TRUE(open.patch.has_value());
    EXPECT_TRUE(open.drawnOpen);
    // Degenerate planes: 0 <= 0 holds everywhere (dropped), 1 <= 0 nowhere (empty body).
    const Conversion everywhere =
        ConvertBody(b.scene(), b.AddBody({{q, false}, {b.AddPlane({0, 0, 0, 0}), false}}, box),
                    CapPolicy::kSkip);
    ASSERT_TRUE(everywhere.patch.has_value());
    EXPECT_EQ(everywhere.planesDropped, 1);
    EXPECT_EQ(why({{q, false}, {b.AddPlane({0, 0, 0, 1}), false}}), Rejection::kEmpty);
    // A body whose box is empty is empty.
    EXPECT_EQ(ConvertBody(b.scene(), b.AddBody({{q, false}}, Box3{}), CapPolicy::kSkip).why,
              Rejection::kEmpty);
}

TEST(PatchPolynomials, PaperFormulasAgreeWithTheQuadricAtRandomPoints) {
    // Eq. 1.3 (F1, F2), the plane depths and eq. 1.4 (normals), re-derived in patch_polynomials.h,
    // against direct evaluation: F1 ± sqrt(F2) are roots of Q along the ray, NX.. is ∇Q.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        QuadricPatch p;
        for (double& k : p.quadric.k) k = u(rng);
        if (p.quadric.C() < 0.1) p.quadric.k[2] = 0.1 + std::fabs(p.quadric.C());
        p.planeCount = 2;
        p.planes[0].plane = {u(rng), u(rng), u(rng), u(rng)};
        p.planes[1].plane = {u(rng), u(rng), 0, u(rng)};
        const PatchPolynomials poly = PolynomialsOf(p);
        const double x = 3 * u(rng), y = 3 * u(rng);
        const double f2 = poly.f2(x, y);
        // Tolerances: the coefficients are O(1/C²) <= 100 and x, y <= 3, so terms are below
        // about 1e4; 1e-9 relative to that.
        const double scale = 1e4;
        if (f2 > 1e-6) {
            for (double z : {poly.f1(x, y) - std::sqrt(f2), poly.f1(x, y) + std::sqrt(f2)})
                EXPECT_NEAR(p.quadric.Evaluate({x, y, z}), 0, 1e-9 * scale);
            const double z = poly.f1(x, y) + std::sqrt(f2);
            const Vec3 g = p.quadric.Gradient({x, y, z});
            EXPECT_NEAR(poly.nxBase(x, y) + poly.e * z, g.x, 1e-9 * scale);
            EXPECT_NEAR(poly.nyBase(x, y) + poly.f * z, g.y, 1e-9 * scale);
            EXPECT_NEAR(poly.nzBase(x, y) + poly.twoC * z, g.z, 1e-9 * scale);
        } else if (f2 < -1e-6) {
            // No root: Q has the sign of C everywhere on the ray.
            for (double z : {-5.0, 0.0, 5.0}) EXPECT_GT(p.quadric.Evaluate({x, y, z}), 0);
        }
        const Plane& pl = p.planes[0].plane;
        EXPECT_NEAR(pl.Evaluate({x, y, poly.zp[0](x, y)}), 0, 1e-9 * scale);
        EXPECT_EQ(poly.kind[1], PlaneKind::kPerpendicular);
        EXPECT_NEAR(poly.zp[1](x, y), -p.planes[1].plane.Evaluate({x, y, 0}), 1e-12);
    }
}

TEST(PatchPolynomials, RangeOnRectangleBracketsEverySample) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 100; ++trial) {
        const Quadratic2 q{u(rng), u(rng), u(rng), u(rng), u(rng), u(rng)};
        const Range r = RangeOnRectangle(q, -2, 3, -1, 2);
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for (int i = 0; i <= 100; ++i)
            for (int j = 0; j <= 100; ++j) {
                const double v = q(-2 + 5 * i / 100.0, -1 + 3 * j / 100.0);
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
        // The range is exact: it contains every sample and is within the grid's resolution of
        // them (the slope is at most about 10, the grid step 0.05: second order 1e-2 suffices).
        EXPECT_LE(r.lo, lo + 1e-12);
        EXPECT_GE(r.hi, hi - 1e-12);
        EXPECT_GT(r.lo, lo - 0.05);
        EXPECT_LT(r.hi, hi + 0.05);
    }
}

}  // namespace
}  // namespace quadrix::patch
