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
    EXPECT_EQ(im.boxWidth, maxX + 1);  // the rectangle a window copies
    EXPECT_EQ(im.boxHeight, maxY + 1);
    int expectedInk = 0;
    for (char c : std::string("RAYCAST 12.5 MSH HELP")) expectedInk += Ink(c);
    EXPECT_EQ(ink, expectedInk);
    EXPECT_EQ(OverlayScale(720), 2);
    EXPECT_TRUE(DrawOverlay({}, 200, 100).Empty());
}

// The help line at a 320-pixel-wide window (53 columns at scale 1) is wrapped, not cut off: every
// row fits, every word is kept in order, and the box stays inside the window.
TEST(ViewerOverlay, LongLinesWrapToTheWindowsWidth) {
    const std::string help =
        "H help  X section  [ ] move it  C hatch  D drawing  V view  O overlay  Q quit";
    EXPECT_EQ(OverlayColumns(320, 240), 52);    // (320 - 3) / 6
    EXPECT_EQ(OverlayColumns(1280, 720), 106);  // (1280 - 6) / 12 at scale 2
    const std::vector<std::string> rows = WrapOverlayLines({"raycast", help}, 52);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0], "raycast");
    EXPECT_EQ(rows[1], "H help  X section  [ ] move it  C hatch  D drawing");
    EXPECT_EQ(rows[2], "  V view  O overlay  Q quit");
    auto words = [](const std::string& text) {
        std::vector<std::string> w;
        std::string cur;
        for (char c : text + " ")
            if (c == ' ') {
                if (!cur.empty()) w.push_back(cur);
                cur.clear();
            } else {
                cur += c;
            }
        return w;
    };
    for (int columns : {11, 13, 26, 40}) {  // a word and the indentation fit
        std::string joined;
        for (const std::string& r : WrapOverlayLines({help}, columns)) {
            EXPECT_LE(static_cast<int>(r.size()), columns) << r;
            joined += r + " ";
        }
        EXPECT_EQ(words(joined), words(help)) << columns;
    }
    // A word longer than a row is cut, not dropped.
    EXPECT_EQ(WrapOverlayLines({"abcdefgh"}, 5), (std::vector<std::string>{"abcde", "  fgh"}));
    // Drawn: the box is inside a 320×240 window, three rows tall.
    const OverlayImage im = DrawOverlay({"raycast", help}, 320, 240);
    int maxX = 0, maxY = 0;
    for (int y = 0; y < 240; ++y)
        for (int x = 0; x < 320; ++x)
            if (im.rgba[(y * 320 + x) * 4 + 3] == 255) {
                maxX = std::max(maxX, x);
                maxY = std::max(maxY, y);
            }
    EXPECT_EQ(maxX, 2 + 50 * 6 - 1 + 2 - 1);  // the longest row, 50 characters
    EXPECT_EQ(maxY, 2 + 3 * 10 - 3 + 2 - 1);
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
