#include "quadrix/frame/compare.h"

#include <gtest/gtest.h>

#include <cmath>

namespace quadrix {
namespace {

// A 8×8 reference: surface 1 (body 1) on the left half at depth x, surface 2 (body 2) on the
// right half at depth 10 + x; the top row is background.
Frame Reference() {
    Frame f(8, 8);
    for (int y = 1; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const std::int32_t s = x < 4 ? 1 : 2;
            f.Offer(f.Index(x, y), x < 4 ? x : 10 + x, Vec3{0, 0, -1}, s, s);
        }
    return f;
}

TEST(FrameCompare, IdenticalFramesAgreeEverywhere) {
    const Frame ref = Reference();
    const FrameComparison c = CompareFrames(ref, ref);
    EXPECT_EQ(c.coveredBoth, 56u);
    EXPECT_EQ(c.sameSurface, 56u);
    EXPECT_EQ(c.sameSolid, 56u);
    EXPECT_EQ(c.SurfaceMismatches(), 0u);
    EXPECT_EQ(c.offEdgeDifferences, 0u);
    EXPECT_EQ(c.sameSurfaceOtherBody, 0u);
    EXPECT_EQ(c.maxDepthError, 0);
    EXPECT_EQ(c.referenceDepthRange, 17 - 0);  // depths 0 .. 3 and 14 .. 17
    EXPECT_EQ(FirstBitDifference(ref, ref), "");
}

// Each kind of difference lands in its own counter: a pixel uncovered away from any edge
// (coverage, off edge), a pixel of the other surface on the seam (on edge), a pixel of the same
// surface from another body, and a depth error.
TEST(FrameCompare, CountsEachKindOfDifference) {
    const Frame ref = Reference();
    Frame a = ref;
    a.SetBackground(a.Index(1, 5));  // off edge: coverage
    a.surface[a.Index(3, 4)] = 2;    // on the seam between the halves
    a.body[a.Index(6, 6)] = 7;       // same surface, another body
    a.depth[a.Index(5, 3)] += 0.25;  // same surface, depth error
    a.normal[a.Index(5, 3)] = Vec3{0, 1, -1};
    CompareOptions options;
    options.depthTolerance = 0.1;
    const FrameComparison c = CompareFrames(a, ref, options);
    EXPECT_EQ(c.onlyReference, 1u);
    EXPECT_EQ(c.onlyA, 0u);
    EXPECT_EQ(c.surfaceDiffers, 1u);
    EXPECT_EQ(c.SurfaceMismatches(), 2u);
    EXPECT_EQ(c.offEdgeDifferences, 1u);
    EXPECT_EQ(c.offEdgeCoverageDifferences, 1u);
    EXPECT_EQ(c.sameSurfaceOtherBody, 1u);
    EXPECT_EQ(c.sameSurface, 54u);
    EXPECT_EQ(c.depthOverTolerance, 1u);
    EXPECT_EQ(c.maxDepthError, 0.25);
    // 45 degrees, up to the packing of both normals (frame/packed_normal.h).
    EXPECT_NEAR(c.maxNormalErrorDegrees, 45, 2 * PackedNormal::kMaxError * 180 / M_PI);
    EXPECT_NE(c.firstDifference.find("pixel (1, 5)"), std::string::npos) << c.firstDifference;

    // A pixel of another surface inside a half (off edge): counted off edge, but not as coverage.
    Frame b = ref;
    b.surface[b.Index(1, 5)] = 2;
    const FrameComparison d = CompareFrames(b, ref);
    EXPECT_EQ(d.offEdgeDifferences, 1u);
    EXPECT_EQ(d.offEdgeCoverageDifferences, 0u);
}

TEST(FrameCompare, DepthRangeNeedsTwoDepths) {
    Frame one(2, 1);
    one.Offer(0, 5, Vec3{0, 0, -1}, 0, 0);
    EXPECT_EQ(CompareFrames(one, one).referenceDepthRange, 0);
    EXPECT_TRUE(CompareFrames(Frame(3, 3), one).sizeMismatch);
}

}  // namespace
}  // namespace quadrix
