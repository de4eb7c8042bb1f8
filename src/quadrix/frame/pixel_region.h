// A pixel region of a Frame: the part of one picture an engine is asked to draw (issue 22,
// sort-first distributed rendering, batch/sort_first.h). A region is a list of rectangles of
// pixels [x0, x1) × [y0, y1) in Frame coordinates (x right, y down, as Frame::Index); the picture
// keeps its full size and its view, so every pixel of the region is computed with the same
// device coordinates, hence the same arithmetic, as in a render of the whole picture — which is
// what makes a picture assembled from the regions of several processes identical, bit for bit,
// to the picture of one.
//
// Contract (engines/engine.h, pipeline/render_context.h): a render with a region leaves every
// pixel outside it as background (CropToRegion); an engine may skip the work outside it (raycast
// skips its tiles there) or draw everything and be cropped (the others).
#pragma once

#include <vector>

#include "quadrix/frame/frame.h"

namespace quadrix {

struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) × [y0, y1)
    bool Empty() const { return x1 <= x0 || y1 <= y0; }
    bool Intersects(int xa, int ya, int xb, int yb) const {
        return x0 < xb && xa < x1 && y0 < yb && ya < y1;
    }
};

struct PixelRegion {
    std::vector<PixelRect> rects;

    // Whether the rectangle [xa, xb) × [ya, yb) meets the region.
    bool Intersects(int xa, int ya, int xb, int yb) const;
    bool Contains(int x, int y) const;
    // The number of pixels of the region inside a width × height picture (rects do not overlap
    // in the regions made here; overlapping ones are counted twice).
    long long Pixels(int width, int height) const;
};

// Full-width bands of `bandRows` rows dealt round-robin: band b (rows [b·bandRows,
// (b+1)·bandRows)) to part b mod parts. Interleaved bands share the rows of a picture evenly
// among the parts even when the part of interest is in its middle.
PixelRegion InterleavedBands(int width, int height, int part, int parts, int bandRows);

// Sets every pixel of `frame` outside `region` to background.
void CropToRegion(Frame& frame, const PixelRegion& region);

// Copies the pixels of `region` from `from` into `into` (Frames of the same size).
void CopyRegion(Frame& into, const Frame& from, const PixelRegion& region);

// ComposeMin (frame.h) on the pixels of `region` only (Frames of the same size).
void ComposeMinInRegion(Frame& into, const Frame& other, const PixelRegion& region);

}  // namespace quadrix
