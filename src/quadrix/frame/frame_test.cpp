#include "quadrix/frame/frame.h"

#include <gtest/gtest.h>

#include <cmath>

namespace quadrix {
namespace {

TEST(Frame, APixelIsSixteenBytes) {
    Frame f(4, 3);
    const std::size_t perPixel =
        sizeof(f.depth[0]) + sizeof(f.normal[0]) + sizeof(f.surface[0]) + sizeof(f.body[0]);
    EXPECT_EQ(perPixel, 16u);
    EXPECT_EQ(Frame::kBytesPerPixel, perPixel);
    EXPECT_EQ(f.depth.size(), 12u);
    EXPECT_EQ(f.normal.size(), 12u);
}

// The solid of a pixel is its body's, from the per-body table; the background, a sample of no
// body and a body the table does not know have none.
TEST(Frame, ThePixelsSolidIsItsBodysFromTheTable) {
    Frame f(4, 1);
    f.bodySolid = {2, 0, 5};
    f.Offer(0, 1.0, Vec3{0, 0, -1}, 10, 2);
    f.Offer(1, 1.0, Vec3{0, 0, -1}, 11, 0);
    f.Offer(2, 1.0, Vec3{0, 0, -1}, 12, Frame::kNone);  // a freeform surface: no body
    EXPECT_EQ(f.Solid(0), 5);
    EXPECT_EQ(f.Solid(1), 2);
    EXPECT_EQ(f.Solid(2), Frame::kNone);
    EXPECT_EQ(f.Solid(3), Frame::kNone);  // background
    f.bodySolid.resize(1);
    EXPECT_EQ(f.Solid(0), Frame::kNone);  // body 2 is past the table
}

// Nearer is decided on the depth as stored (a float): a sample that rounds to the stored depth
// ties, and the tie keeps the earlier one (composition is then the same however engines
// rounded).
TEST(Frame, OfferDecidesOnTheStoredFloat) {
    Frame f(1, 1);
    const double z = 100.0 + 1.0 / 3;
    f.Offer(0, z, Vec3{0, 0, -1}, 1, 1);
    EXPECT_EQ(f.depth[0], static_cast<float>(z));
    const double sameFloat = z + 1e-9;  // ≠ z, but the same float
    ASSERT_NE(sameFloat, z);
    ASSERT_EQ(static_cast<float>(sameFloat), static_cast<float>(z));
    EXPECT_FALSE(f.Nearer(0, z - 1e-9));
    f.Offer(0, z - 1e-9, Vec3{1, 0, 0}, 2, 2);
    EXPECT_EQ(f.surface[0], 1);  // a tie in float: the earlier sample stays
    const double below = std::nextafter(static_cast<float>(z), 0.0f);
    EXPECT_TRUE(f.Nearer(0, below));
    f.Offer(0, below, Vec3{1, 0, 0}, 2, 2);
    EXPECT_EQ(f.surface[0], 2);
    EXPECT_EQ(f.Normal(0), (Vec3{1, 0, 0}));
}

TEST(Frame, DepthRoundingBoundsTheStoredDepth) {
    for (double z : {0.1, 1.0 / 3, 255.999999, 256.0000001, 1e3 + 1.0 / 7, -777.123456789, 4e6}) {
        Frame f(1, 1);
        f.Offer(0, z, Vec3{0, 0, -1}, 0, 0);
        EXPECT_LE(std::fabs(f.depth[0] - z), DepthRounding(z)) << z;
        EXPECT_GT(DepthRounding(z), 0) << z;
        EXPECT_LT(DepthRounding(z), 1e-7 * std::fabs(z)) << z;  // 2^-24 relative at most
    }
}

// Half the distance to the next float up, at every binade and in the subnormals.
TEST(Frame, DepthRoundingIsHalfTheFloatsUlp) {
    for (double z : {1e-42, 1.17549435e-38, 1e-20, 0.75, 1.0, 1.5, 2.0, 255.9, 256.0, 3e5, 1e30,
                     -7.25, 3.4e38}) {
        const float f = std::fabs(static_cast<float>(z));
        const double half = 0.5 * (static_cast<double>(std::nextafter(f, HUGE_VALF)) - f);
        EXPECT_EQ(DepthRounding(z), half) << z;
    }
}

TEST(Frame, DepthRoundingOfTheBackgroundIsZero) {
    EXPECT_EQ(DepthRounding(HUGE_VAL), 0);
    EXPECT_EQ(DepthRounding(-HUGE_VAL), 0);
    EXPECT_EQ(DepthRounding(1e300), 0);  // beyond the largest float
}

TEST(Frame, ComposeMinKeepsTheNearerAndTheSolidsTable) {
    Frame a(2, 1), b(2, 1);
    b.bodySolid = {0, 1};
    a.Offer(0, 5, Vec3{0, 0, -1}, 1, 0);
    b.Offer(0, 6, Vec3{0, 0, -1}, 2, 1);
    b.Offer(1, 6, Vec3{0, 1, 0}, 2, 1);
    ComposeMin(a, b);
    EXPECT_EQ(a.surface[0], 1);
    EXPECT_EQ(a.surface[1], 2);
    EXPECT_EQ(a.normal[1], b.normal[1]);  // the packed bits, unchanged
    EXPECT_EQ(a.Solid(1), 1);
    EXPECT_EQ(a.Solid(0), 0);
}

}  // namespace
}  // namespace quadrix
