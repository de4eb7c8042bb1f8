#include "quadrix/frame/frame.h"

#include <gtest/gtest.h>
#include <sys/mman.h>

#include <cerrno>
#include <cmath>
#include <cstring>

namespace quadrix {
namespace {

// Whether the page at p is mapped (msync fails with ENOMEM where nothing is).
bool Mapped(const void* p) {
    return msync(const_cast<void*>(p), 4096, MS_ASYNC) == 0 || errno != ENOMEM;
}

constexpr std::size_t kMiB = std::size_t{1} << 20;

// A freed mapping serves the next allocation of its length with the pages it had (written
// before: the same bytes are there), a shorter one with its start (the rest unmapped), and an
// exact length is preferred to a longer one.
TEST(FrameMemory, FreedMappingsServeLaterAllocations) {
    ReleaseKeptFrameBytes();
    auto* a = static_cast<unsigned char*>(AllocateFrameBytes(25 * kMiB));  // 26 MiB mapped
    std::memset(a, 0x5a, 25 * kMiB);
    FreeFrameBytes(a, 25 * kMiB);
    auto* b = static_cast<unsigned char*>(AllocateFrameBytes(26 * kMiB));
    EXPECT_EQ(b, a);
    EXPECT_EQ(b[25 * kMiB - 1], 0x5a) << "the same pages";
    FreeFrameBytes(b, 26 * kMiB);
    // 4 MiB taken from the 26 MiB one: its start, and the other 22 MiB unmapped.
    auto* c = static_cast<unsigned char*>(AllocateFrameBytes(3 * kMiB));
    EXPECT_EQ(c, a);
    EXPECT_EQ(c[0], 0x5a);
    EXPECT_TRUE(Mapped(c + 4 * kMiB - 4096));
    EXPECT_FALSE(Mapped(c + 4 * kMiB));
    EXPECT_FALSE(Mapped(c + 26 * kMiB - 4096));
    // Two freed mappings, 4 and 8 MiB: a 4 MiB request takes the 4 MiB one, then 8 the other.
    auto* d = static_cast<unsigned char*>(AllocateFrameBytes(8 * kMiB));
    FreeFrameBytes(d, 8 * kMiB);
    FreeFrameBytes(c, 4 * kMiB);
    EXPECT_EQ(AllocateFrameBytes(4 * kMiB), c);
    EXPECT_EQ(AllocateFrameBytes(8 * kMiB), d);
    FreeFrameBytes(c, 4 * kMiB);
    FreeFrameBytes(d, 8 * kMiB);
    ReleaseKeptFrameBytes();
    EXPECT_FALSE(Mapped(c));
    EXPECT_FALSE(Mapped(d));
}

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
