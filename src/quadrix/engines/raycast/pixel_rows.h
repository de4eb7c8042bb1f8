// Where engine `raycast` writes pixels (step 6 of a render, raycast.cpp): a tile's staging copy
// (TileBuffer) of the Frame's arrays, in the Frame's own format (float depth, packed normal,
// frame.h: nothing reads a pixel back once its hit is resolved in double), addressed by pixel
// (x, y) relative to an origin. A tile writes its sub-tiles into the staging copy, which
// RenderTile then copies into the Frame row by row: runs of 256 pixels per array, where writing
// each 8×8 sub-tile into the Frame directly touched its rows eight pixels at a time (write misses
// the prefetchers cannot follow: about 20 cycles a pixel, against 6 for the runs).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "quadrix/engines/raycast/tiling.h"
#include "quadrix/frame/frame.h"

namespace quadrix::raycast {

// Pixel (x, y) is at Index(x, y) of each array: relative to the origin (x0, y0), `stride` pixels
// a row.
struct PixelRows {
    float* depth;
    PackedNormal* normal;
    std::int32_t* surface;
    std::int32_t* body;
    std::size_t stride;
    int x0, y0;

    std::size_t Index(int x, int y) const {
        return static_cast<std::size_t>(y - y0) * stride + static_cast<std::size_t>(x - x0);
    }
    void SetBackground(std::size_t k) const {
        depth[k] = HUGE_VALF;
        normal[k] = PackedNormal{};
        surface[k] = Frame::kNone;
        body[k] = Frame::kNone;
    }
    // Background on the pixel rectangle [x0, x1) × [y0, y1): array by array along each row
    // (contiguous stores the compiler turns into wide ones), not pixel by pixel.
    void FillBackground(int xa, int ya, int xb, int yb) const {
        const auto n = static_cast<std::size_t>(xb - xa);
        for (int j = ya; j < yb; ++j) {
            const std::size_t k = Index(xa, j);
            std::fill_n(depth + k, n, HUGE_VALF);
            std::fill_n(normal + k, n, PackedNormal{});
            std::fill_n(surface + k, n, Frame::kNone);
            std::fill_n(body + k, n, Frame::kNone);
        }
    }
};

// The staging copy of one tile's pixels (one per worker thread), and its copy into the Frame.
class TileBuffer {
  public:
    PixelRows Rows(int x0, int y0) {
        return {depth_.data(), normal_.data(), surface_.data(), body_.data(), kTileW, x0, y0};
    }
    void CopyTile(int x0, int y0, int x1, int y1, Frame& frame) const {
        const auto n = static_cast<std::ptrdiff_t>(x1 - x0);
        for (int j = y0; j < y1; ++j) {
            const auto from = static_cast<std::ptrdiff_t>(j - y0) * kTileW;
            const auto to = static_cast<std::ptrdiff_t>(frame.Index(x0, j));
            std::copy_n(depth_.begin() + from, n, frame.depth.begin() + to);
            std::copy_n(normal_.begin() + from, n, frame.normal.begin() + to);
            std::copy_n(surface_.begin() + from, n, frame.surface.begin() + to);
            std::copy_n(body_.begin() + from, n, frame.body.begin() + to);
        }
    }

  private:
    static constexpr std::size_t kTilePixels = static_cast<std::size_t>(kTileW) * kTileH;
    std::vector<float> depth_ = std::vector<float>(kTilePixels);
    std::vector<PackedNormal> normal_ = std::vector<PackedNormal>(kTilePixels);
    std::vector<std::int32_t> surface_ = std::vector<std::int32_t>(kTilePixels);
    std::vector<std::int32_t> body_ = std::vector<std::int32_t>(kTilePixels);
};

}  // namespace quadrix::raycast
