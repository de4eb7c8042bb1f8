// The pixels whose centres lie in a span of device x (or y), shared by the scanline engine's
// units and its row bodies so that both make exactly the same ranges.
#pragma once

#include <algorithm>
#include <cmath>

namespace quadrix::scanline {

// Inclusive pixel range [a, b] of the centres i + ½ inside [lo, hi], clipped to [0, n); a > b when
// no centre is inside. NaN bounds give the whole range.
inline void PixelRange(double lo, double hi, int n, int& a, int& b) {
    double fa = std::ceil(lo - 0.5), fb = std::floor(hi - 0.5);
    a = static_cast<int>(std::clamp(std::isnan(fa) ? 0.0 : fa, 0.0, static_cast<double>(n)));
    b = static_cast<int>(std::clamp(std::isnan(fb) ? n - 1.0 : fb, -1.0, n - 1.0));
}

}  // namespace quadrix::scanline
