// The sRGB transfer function (IEC 61966-2-1): Quadrix shades in linear light and encodes the
// picture with it on output; CSS/SVG, OpenSCAD and BRL-CAD colors are sRGB-encoded and are
// decoded with its inverse on input.
//
//   encode:  c <= 0.0031308 ? 12.92 c : 1.055 c^(1/2.4) - 0.055
//   decode:  s <= 0.04045   ? s / 12.92 : ((s + 0.055) / 1.055)^2.4
//
// The two thresholds are the standard's (they meet at the same point to 1e-7), both maps are
// monotonic on [0, 1] and fix 0 and 1; values outside [0, 1] are clamped first.
#pragma once

#include <algorithm>
#include <cmath>

namespace quadrix {

inline double SrgbFromLinear(double c) {
    if (!(c > 0)) return 0;  // also NaN
    if (c >= 1) return 1;
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

inline double LinearFromSrgb(double s) {
    if (!(s > 0)) return 0;
    if (s >= 1) return 1;
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

}  // namespace quadrix
