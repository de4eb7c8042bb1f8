// SVG output of a drawing page, written directly (not through Cairo) so that conics stay exact
// (docs/drawings.md "Exactness"): a whole ellipse is one <ellipse> element, an elliptical arc is a
// path of SVG `A` commands whose radii and rotation come from the singular value decomposition
// of its conjugate semi-diameters [U V] = R(φ) diag(rx, ±ry) R(θ) (closed form for 2×2); arcs of
// more than 0.9π are written as several `A` commands of at most 2π/3, since the large-arc flag
// is ill-conditioned near π. A parabolic arc is one quadratic Bézier `Q` (exact: the curve is a
// quadratic polynomial), a hyperbolic arc cubic Béziers `C` within Page::tolerance
// (page.h ConicToCubics). Numbers are written with 17 significant digits (round-trip exact).
// Cairo's SVG surface, by contrast, writes every arc as cubic Béziers.
//
// Hidden strokes are drawn first (class "hidden", dashed), then visible edges (class "tangent",
// thin, for tangent edges), then silhouettes.
#pragma once

#include <string>

#include "quadrix/draw/page.h"

namespace quadrix::draw {

struct EllipseAxes {
    double rx = 0, ry = 0;  // rx >= ry >= 0
    double rotation = 0;    // radians, of the rx axis from +x toward +y
    bool positive = true;   // increasing θ runs toward +y from +x (SVG sweep-flag 1)
};

// The axes of the ellipse c + U cos θ + V sin θ.
EllipseAxes AxesOf(const Point2& U, const Point2& V);

std::string SvgDocument(const Page& page);

// Writes atomically; returns an error message or empty.
std::string WriteSvg(const std::string& path, const Page& page);

}  // namespace quadrix::draw
