// The viewer's in-window overlay (issue 18 §6): frame time, engine, resolution and a one-line
// help, drawn into the window's picture (not only its title bar) with a 5×7 bitmap font of our
// own (font.cpp: printable ASCII, lower case drawn as capitals), each glyph pixel a scale×scale
// square (2 from 480 window rows up, else 1).
//
// The overlay is an RGBA picture of the window's size: an opaque dark box behind the text, white
// glyphs, and every other pixel fully transparent. Only alpha 0 or 255, never in between: the
// window shows exactly the frame's pixels outside the box and the overlay's inside it, so a
// screenshot can be checked against (frame, overlay) exactly, and the frame itself — what
// `screenshot` saves — never contains the overlay.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace quadrix::viewer {

struct OverlayImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  // width·height·4, rows top to bottom
    // The opaque box at the top-left corner (clipped to the image): every pixel inside is
    // opaque, every pixel outside transparent, so a window need only copy this rectangle.
    int boxWidth = 0, boxHeight = 0;
    bool Empty() const { return rgba.empty(); }
};

constexpr int kGlyphWidth = 5, kGlyphHeight = 7;
// Rows of a printable ASCII character's glyph, bit 4 the leftmost column; other bytes draw '?'.
const std::uint8_t* GlyphRows(char c);
int OverlayScale(int windowHeight);

// How many characters a row of the overlay holds in a window `width` pixels wide (at least 1).
int OverlayColumns(int width, int height);
// `lines` broken into rows of at most `columns` characters: at the last space that fits (the
// spaces at the break are dropped; a continuation row starts with two spaces), a word longer
// than a row is cut. Nothing is lost: a narrow window gets more rows, not cut-off text.
std::vector<std::string> WrapOverlayLines(const std::vector<std::string>& lines, int columns);

// The lines at the window's top-left corner, wrapped to the window's width (WrapOverlayLines),
// rows below the window clipped.
OverlayImage DrawOverlay(const std::vector<std::string>& lines, int width, int height);
// The overlay over 8-bit RGB pixels of its size (what the window shows): opaque pixels replace.
void CompositeOverlay(const OverlayImage& overlay, std::vector<std::uint8_t>& rgb);

}  // namespace quadrix::viewer
