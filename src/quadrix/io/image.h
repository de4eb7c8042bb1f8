// An image in LINEAR light, gray (1 channel) or RGB (3 channels), rows top to bottom.
//
// `pixels` holds 8-bit linear intensities (value/255): what the devices, the terminal and the
// tests read. Its storage is the Frame's (frame/frame.h FrameAllocator): from 2 MiB on, mapped on
// its own in 2 MiB pages, so a fresh process faults a 1280×720 RGB image in with 2 page faults
// instead of 675 (12 ms on this project's virtual machines, docs/performance.md "Output"). The
// shader also fills `linear` with the same values unquantised (floats in [0, 1]), so that the
// writers can encode the picture to sRGB 8 or 16 bits without banding in the darks (io/writers.h);
// an image made by hand may leave it empty.
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/frame/frame.h"

namespace quadrix {

struct Image {
    int width = 0, height = 0;
    int channels = 1;                 // 1 = gray, 3 = RGB
    FrameArray<std::uint8_t> pixels;  // row-major, channels interleaved
    std::vector<float> linear;        // empty, or the same layout as pixels, in [0, 1]

    Image() = default;
    Image(int w, int h, int c)
        : width(w),
          height(h),
          channels(c),
          pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) *
                     static_cast<std::size_t>(c),
                 0) {}
    std::uint8_t* At(int x, int y) {
        return &pixels[(static_cast<std::size_t>(y) * width + x) * channels];
    }
    const std::uint8_t* At(int x, int y) const {
        return &pixels[(static_cast<std::size_t>(y) * width + x) * channels];
    }
};

}  // namespace quadrix
