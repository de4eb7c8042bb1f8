// Every branch of the bounding-plane algorithm (seed 000 §1.3.2), its logic form (§1.5.5) and the
// selection of Z' and ZOUT; the same branches through the whole float evaluation of a patch.
#include "quadrix/engines/patch/bounding_plane.h"

#include <gtest/gtest.h>

#include <random>

#include "quadrix/engines/patch/float_engine.h"
#include "quadrix/engines/patch/patch_test_util.h"

namespace quadrix::patch {
namespace {

// Roots used below: ZF = 10, ZB = 20.
constexpr double kZf = 10, kZb = 20;

DepthFlags Cut(PlaneKind kind, double zp) {
    DepthFlags f;
    CutByPlane(kind, zp, kZf, kZb, f);
    return f;
}

TEST(PatchBoundingPlane, FrontPlaneBetweenRootsCutsTheFrontSheetOnly) {
    const DepthFlags f = Cut(PlaneKind::kFront, 15);  // keeps z >= 15
    EXPECT_FALSE(f.ef);
    EXPECT_TRUE(f.eb);
    EXPECT_EQ(SelectSheet(f, false), Sheet::kBack);
}

TEST(PatchBoundingPlane, FrontPlaneBehindBothRootsCutsBoth) {
    const DepthFlags f = Cut(PlaneKind::kFront, 25);
    EXPECT_FALSE(f.ef);
    EXPECT_FALSE(f.eb);
    EXPECT_EQ(SelectSheet(f, false), Sheet::kNone);
}

TEST(PatchBoundingPlane, FrontPlaneBeforeBothRootsKeepsBoth) {
    const DepthFlags f = Cut(PlaneKind::kFront, 5);
    EXPECT_TRUE(f.ef);
    EXPECT_TRUE(f.eb);
    EXPECT_EQ(SelectSheet(f, false), Sheet::kFront);
}

TEST(PatchBoundingPlane, BackPlaneBetweenRootsCutsTheBackSheetOnly) {
    const DepthFlags f = Cut(PlaneKind::kBack, 15);  // keeps z <= 15
    EXPECT_TRUE(f.ef);
    EXPECT_FALSE(f.eb);
    EXPECT_EQ(SelectSheet(f, false), Sheet::kFront);
}

TEST(PatchBoundingPlane, BackPlaneBeforeBothRootsCutsBoth) {
    const DepthFlags f = Cut(PlaneKind::kBack, 5);
    EXPECT_FALSE(f.ef);
    EXPECT_FALSE(f.eb);
    EXPECT_EQ(SelectSheet(f, false), Sheet::kNone);
}

TEST(PatchBoundingPlane, BackPlaneBehindBothRootsKeepsBoth) {
    const DepthFlags f = Cut(PlaneKind::kBack, 25);
    EXPECT_TRUE(f.ef);
    EXPECT_TRUE(f.eb);
}

TEST(PatchBoundingPlane, PerpendicularPlaneCutsByTheSignOfZp) {
    // CP = 0: ZP holds -(A x + B y + D); the kept side is ZP >= 0, whatever the depths.
    DepthFlags out = Cut(PlaneKind::kPerpendicular, -0.5);
    EXPECT_FALSE(out.ef);
    EXPECT_FALSE(out.eb);
    DepthFlags in = Cut(PlaneKind::kPerpendicular, 0.5);
    EXPECT_TRUE(in.ef);
    EXPECT_TRUE(in.eb);
    DepthFlags on = Cut(PlaneKind::kPerpendicular, 0);  // closed half-space
    EXPECT_TRUE(on.ef);
    EXPECT_TRUE(on.eb);
    EXPECT_EQ(KindOfPlane(0.0), PlaneKind::kPerpendicular);
    EXPECT_EQ(KindOfPlane(-1e-300), PlaneKind::kFront);
    EXPECT_EQ(KindOfPlane(1e-300), PlaneKind::kBack);
}

TEST(PatchBoundingPlane, BothSheetsCutByTwoPlanes) {
    // A slab 12 <= z <= 18 strictly between the roots: neither root is kept.
    DepthFlags f;
    CutByPlane(PlaneKind::kFront, 12, kZf, kZb, f);
    CutByPlane(PlaneKind::kBack, 18, kZf, kZb, f);
    EXPECT_FALSE(f.ef);
    EXPECT_FALSE(f.eb);
    EXPECT_EQ(SelectSheet(f, false), Sheet::kNone);
}

TEST(PatchBoundingPlane, FlagsOnlyEverFall) {
    // A plane that keeps a root never re-enables it (the flags are ANDed).
    DepthFlags f;
    CutByPlane(PlaneKind::kFront, 15, kZf, kZb, f);
    CutByPlane(PlaneKind::kBack, 25, kZf, kZb, f);
    EXPECT_FALSE(f.ef);
    EXPECT_TRUE(f.eb);
}

TEST(PatchBoundingPlane, F2NegativeMeansNoSurface) {
    EXPECT_EQ(SelectSheet({true, true}, true), Sheet::kNone);
    EXPECT_TRUE(ZoutIsZmax({true, true}, true));
    EXPECT_TRUE(ZoutIsZmax({false, false}, false));
    EXPECT_FALSE(ZoutIsZmax({false, true}, false));
    EXPECT_FALSE(ZoutIsZmax({true, false}, false));
}

TEST(PatchBoundingPlane, RootsOnAPlaneAreKept) {
    // §1.3.2 compares strictly: the half-spaces are closed.
    EXPECT_TRUE(Cut(PlaneKind::kFront, kZf).ef);
    EXPECT_TRUE(Cut(PlaneKind::kFront, kZb).eb);
    EXPECT_TRUE(Cut(PlaneKind::kBack, kZb).eb);
    EXPECT_TRUE(Cut(PlaneKind::kBack, kZf).ef);
}

PlaneSignals Signals(PlaneKind kind, double zp, double zf, double zb) {
    PlaneSignals s;
    s.perpendicular = kind == PlaneKind::kPerpendicular;
    s.sgnCp = kind == PlaneKind::kFront;
    s.sgnZp = zp < 0;
    s.sgnZpMinusZf = zp - zf < 0;
    s.sgnZpMinusZb = zp - zb < 0;
    return s;
}

TEST(PatchBoundingPlane, LogicEquationsMatchTheAlgorithm) {
    // Fig. 1.8's logic and §1.3.2 agree whenever no difference is zero (the tie rule differs,
    // bounding_plane.h). Every ordering of ZP against ZF <= ZB, every kind and sign of ZP.
    const double zps[] = {-30, -5, 5, 15, 25};
    const double roots[][2] = {{10, 20}, {-20, -10}, {-10, 10}, {10, 10}};
    for (const auto& rt : roots)
        for (double zp : zps)
            for (PlaneKind kind :
                 {PlaneKind::kFront, PlaneKind::kBack, PlaneKind::kPerpendicular}) {
                DepthFlags algo;
                CutByPlane(kind, zp, rt[0], rt[1], algo);
                const CutSignals cut = CuttingPlaneLogic(Signals(kind, zp, rt[0], rt[1]));
                EXPECT_EQ(!cut.cutF, algo.ef) << "zp " << zp << " kind " << int(kind);
                EXPECT_EQ(!cut.cutB, algo.eb) << "zp " << zp << " kind " << int(kind);
            }
}

// The logic equations exactly as printed in §1.5.5 (both flags of a back plane on
// sgn(ZP - ZB) = 1).
CutSignals PrintedLogic(const PlaneSignals& s) {
    const bool slanted = !s.perpendicular;
    const bool both = (s.perpendicular && s.sgnZp) || (slanted && s.sgnCp && !s.sgnZpMinusZb) ||
                      (slanted && !s.sgnCp && s.sgnZpMinusZb);
    return {both || (slanted && s.sgnCp && !s.sgnZpMinusZf),
            both || (slanted && !s.sgnCp && s.sgnZpMinusZb)};
}

TEST(PatchBoundingPlane, PublishedBackPlaneEquationNeedsTheCorrection) {
    // A back plane between the roots must keep ZF (§1.3.2); the printed equation removes it.
    const PlaneSignals between = Signals(PlaneKind::kBack, 15, kZf, kZb);
    EXPECT_TRUE(Cut(PlaneKind::kBack, 15).ef);
    EXPECT_TRUE(PrintedLogic(between).cutF);
    EXPECT_FALSE(CuttingPlaneLogic(between).cutF);
    EXPECT_TRUE(CuttingPlaneLogic(between).cutB);
    // In front of both roots the two versions agree: everything is cut.
    const PlaneSignals before = Signals(PlaneKind::kBack, 5, kZf, kZb);
    EXPECT_TRUE(PrintedLogic(before).cutF && PrintedLogic(before).cutB);
    EXPECT_TRUE(CuttingPlaneLogic(before).cutF && CuttingPlaneLogic(before).cutB);
}

TEST(PatchBoundingPlane, HardwareTieRuleCutsAtZeroDifference) {
    // sgn(0) = 0 ("positive"): a front plane through ZF disables it in the hardware.
    const CutSignals c = CuttingPlaneLogic(Signals(PlaneKind::kFront, kZf, kZf, kZb));
    EXPECT_TRUE(c.cutF);
    EXPECT_FALSE(c.cutB);
}

// The same branches through the whole float computation: a sphere of radius 10 centred at
// (16, 16, 50) in a 32 × 32 image; at the centre pixel's ray x = y = 16.5 the roots are
// 50 ∓ sqrt(100 - 0.5).
class PatchBoundingPlaneSphere : public ::testing::Test {
  protected:
    testing::SceneBuilder builder{32, 32};
    const Vec3 centre{16, 16, 50};
    const double zf = 50 - std::sqrt(99.5), zb = 50 + std::sqrt(99.5);

    QuadricPatch Patch(const std::vector<Plane>& planes) {
        QuadricPatch p;
        p.quadric = testing::Sphere(centre, 10);
        p.planeCount = static_cast<int>(planes.size());
        for (std::size_t k = 0; k < planes.size(); ++k) p.planes[k].plane = planes[k];
        p.window = {0, 0, 32, 32};
        return p;
    }
};

TEST_F(PatchBoundingPlaneSphere, NoPlaneShowsTheFrontSheetFacingTheViewer) {
    const FloatPixel px = EvaluatePixelFloat(Patch({}), 16.5, 16.5);
    EXPECT_EQ(px.sheet, Sheet::kFront);
    EXPECT_NEAR(px.zout, zf, 1e-12);  // a few ulps of 50
    EXPECT_NEAR(px.f1, 50, 1e-12);
    EXPECT_NEAR(px.f2, 99.5, 1e-12);
    EXPECT_LT(px.gradient.z, 0);
}

TEST_F(PatchBoundingPlaneSphere, FrontPlaneShowsTheInsideWithNegatedNormal) {
    // -z + 50 <= 0 keeps z >= 50 (CP = -1): the front cap is removed, we see the back sheet from
    // inside, and the normal is negated to face us.
    const FloatPixel px = EvaluatePixelFloat(Patch({{0, 0, -1, 50}}), 16.5, 16.5);
    EXPECT_FALSE(px.flags.ef);
    EXPECT_TRUE(px.flags.eb);
    EXPECT_EQ(px.sheet, Sheet::kBack);
    EXPECT_NEAR(px.zout, zb, 1e-12);
    EXPECT_LT(px.gradient.z, 0);
    // The outward gradient of (x²+y²+z²)/100 - 1 at ZB, 2(ZB - 50)/100, points away from the
    // viewer (+z); negated. Tolerance: a few ulps of the terms (about 1).
    EXPECT_NEAR(px.gradient.z, -2 * (zb - 50) / 100, 1e-12);
}

TEST_F(PatchBoundingPlaneSphere, BackPlaneKeepsTheFrontSheet) {
    const FloatPixel px = EvaluatePixelFloat(Patch({{0, 0, 1, -50}}), 16.5, 16.5);
    EXPECT_TRUE(px.flags.ef);
    EXPECT_FALSE(px.flags.eb);
    EXPECT_EQ(px.sheet, Sheet::kFront);
}

TEST_F(PatchBoundingPlaneSphere, PerpendicularPlaneCutsHalfTheImage) {
    const QuadricPatch p = Patch({{1, 0, 0, -16}});  // keeps x <= 16
    EXPECT_EQ(EvaluatePixelFloat(p, 15.5, 16.5).sheet, Sheet::kFront);
    EXPECT_EQ(EvaluatePixelFloat(p, 16.5, 16.5).sheet, Sheet::kNone);
    EXPECT_NEAR(EvaluatePixelFloat(p, 16.5, 16.5).zp[0], -0.5, 1e-15);
}

TEST_F(PatchBoundingPlaneSphere, SlabBetweenTheRootsLeavesNothing) {
    const FloatPixel px = EvaluatePixelFloat(Patch({{0, 0, -1, 45}, {0, 0, 1, -55}}), 16.5, 16.5);
    EXPECT_FALSE(px.flags.ef);
    EXPECT_FALSE(px.flags.eb);
    EXPECT_EQ(px.sheet, Sheet::kNone);
}

TEST_F(PatchBoundingPlaneSphere, OutsideTheSilhouetteF2IsNegative) {
    const FloatPixel px = EvaluatePixelFloat(Patch({}), 30.5, 30.5);
    EXPECT_LT(px.f2, 0);
    EXPECT_EQ(px.sheet, Sheet::kNone);
}

}  // namespace
}  // namespace quadrix::patch
