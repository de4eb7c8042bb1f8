#include "quadrix/viewer/edges.h"

namespace quadrix::viewer {

int DrawEdges(const Frame& frame, Image& image) {
    if (image.width != frame.width || image.height != frame.height) return 0;
    const int w = frame.width, h = frame.height, c = image.channels;
    const bool linear = image.linear.size() == image.pixels.size();
    int count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            const auto id = frame.surface[i];
            const bool edge = (x + 1 < w && frame.surface[i + 1] != id) ||
                              (y + 1 < h && frame.surface[i + w] != id);
            if (!edge) continue;
            ++count;
            for (int k = 0; k < c; ++k) {
                image.pixels[i * c + k] = 0;
                if (linear) image.linear[i * c + k] = 0;
            }
        }
    return count;
}

}  // namespace quadrix::viewer
