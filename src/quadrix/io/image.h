// An 8-bit image, gray (1 channel) or RGB (3 channels), rows top to bottom.
#pragma once

#include <cstdint>
#include <vector>

namespace quadrix {

struct Image {
    int width = 0, height = 0;
    int channels = 1;  // 1 = gray, 3 = RGB
    std::vector<std::uint8_t> pixels;  // row-major, channels interleaved

    Image() = default;
    Image(int w, int h, int c)
        : width(w), height(h), channels(c),
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
