#include "quadrix/viewer/edges.h"

#include <gtest/gtest.h>

namespace quadrix::viewer {
namespace {

TEST(ViewerEdges, LinesWhereTheSurfaceIdChanges) {
    // An 8×6 frame: background, surface 0 in the box x 2..5, y 1..4, surface 1 in its right half.
    Frame f(8, 6);
    for (int y = 1; y <= 4; ++y)
        for (int x = 2; x <= 5; ++x) f.surface[y * 8 + x] = x >= 4 ? 1 : 0;
    Image im(8, 6, 3);
    std::fill(im.pixels.begin(), im.pixels.end(), 200);
    const int n = DrawEdges(f, im);
    auto dark = [&](int x, int y) { return im.pixels[(y * 8 + x) * 3] == 0; };
    // Left of the box's left side, above its top, and at the 0|1 change; the box's right and
    // bottom rows (their neighbour is the background).
    EXPECT_TRUE(dark(1, 2));
    EXPECT_TRUE(dark(3, 0));
    EXPECT_TRUE(dark(3, 2));
    EXPECT_TRUE(dark(5, 2));
    EXPECT_TRUE(dark(2, 4));
    EXPECT_FALSE(dark(2, 2));  // inside surface 0
    EXPECT_FALSE(dark(4, 2));  // inside surface 1, left neighbour differs but is not looked at
    EXPECT_FALSE(dark(0, 5));  // background
    int counted = 0;
    for (int i = 0; i < 48; ++i) counted += im.pixels[i * 3] == 0;
    EXPECT_EQ(n, counted);
    Image wrong(4, 4, 1);
    EXPECT_EQ(DrawEdges(f, wrong), 0);
}

}  // namespace
}  // namespace quadrix::viewer
