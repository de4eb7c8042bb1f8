#include "quadrix/viewer/overlay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

namespace quadrix::viewer {
namespace {

// The number of set pixels of a glyph.
int Ink(char c) {
    int n = 0;
    const std::uint8_t* rows = GlyphRows(c);
    for (int r = 0; r < kGlyphHeight; ++r)
        for (int b = 0; b < kGlyphWidth; ++b) n += (rows[r] >> b) & 1;
    return n;
}

TEST(ViewerOverlay, EveryPrintableCharacterHasAGlyphAndLowerCaseIsUpperCase) {
    EXPECT_EQ(Ink(' '), 0);
    std::set<std::vector<std::uint8_t>> distinct;
    for (char c = '!'; c <= '~'; ++c) {
        EXPECT_GT(Ink(c), 0) << c;
        const std::uint8_t* rows = GlyphRows(c);
        for (int r = 0; r < kGlyphHeight; ++r) EXPECT_LT(rows[r], 1 << kGlyphWidth) << c;
        if (c >= 'a' && c <= 'z') {
            const std::uint8_t* upper = GlyphRows(static_cast<char>(c - 'a' + 'A'));
            EXPECT_TRUE(std::equal(rows, rows + kGlyphHeight, upper)) << c;
        } else {
            distinct.insert(std::vector<std::uint8_t>(rows, rows + kGlyphHeight));
        }
    }
    EXPECT_EQ(distinct.size(), 94u - 26u);  // no two glyphs alike
    EXPECT_EQ(GlyphRows('\x01'), GlyphRows('?'));
}

TEST(ViewerOverlay, OpaqueBoxAtTheTopLeftTransparentElsewhere) {
    const OverlayImage im = DrawOverlay({"RAYCAST 12.5 MS", "H HELP"}, 200, 100);
    ASSERT_EQ(im.rgba.size(), 200u * 100 * 4);
    int opaque = 0, ink = 0;
    int maxX = 0, maxY = 0;
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 200; ++x) {
            const std::uint8_t* p = &im.rgba[(y * 200 + x) * 4];
            ASSERT_TRUE(p[3] == 0 || p[3] == 255);  // never blended
            if (p[3] == 255) {
                ++opaque;
                maxX = std::max(maxX, x);
                maxY = std::max(maxY, y);
                ink += p[0] > 128;
            }
        }
    // Scale 1 below 480 rows: 15 characters of 6 px less one, plus 2 px of padding each side.
    EXPECT_EQ(maxX, 2 + 15 * 6 - 1 + 2 - 1);
    EXPECT_EQ(maxY, 2 + 2 * 10 - 3 + 2 - 1);
    EXPECT_EQ(opaque, (maxX + 1) * (maxY + 1));
    int expectedInk = 0;
    for (char c : std::string("RAYCAST 12.5 MSH HELP")) expectedInk += Ink(c);
    EXPECT_EQ(ink, expectedInk);
    EXPECT_EQ(OverlayScale(720), 2);
    EXPECT_TRUE(DrawOverlay({}, 200, 100).Empty());
}

TEST(ViewerOverlay, CompositeReplacesOnlyTheOpaquePixels) {
    const OverlayImage im = DrawOverlay({"X"}, 20, 12);
    std::vector<std::uint8_t> rgb(20 * 12 * 3, 77);
    CompositeOverlay(im, rgb);
    for (int i = 0; i < 20 * 12; ++i) {
        const bool opaque = im.rgba[4 * i + 3] == 255;
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(rgb[3 * i + k], opaque ? im.rgba[4 * i + k] : 77) << i;
    }
}

}  // namespace
}  // namespace quadrix::viewer
