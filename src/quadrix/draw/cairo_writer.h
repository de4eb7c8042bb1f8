// PDF, EPS and PNG previews output of a drawing page through Cairo (docs/drawings.md).
//
// Elliptical arcs are drawn as cairo_arc on the unit circle under the affine map [U V] + c, so
// Cairo approximates them by cubic Béziers within its tolerance (0.1 device units by default,
// set here to 0.001 pt, i.e. 0.35 µm on paper); the stroke is applied after restoring the
// identity matrix so the pen stays round. PDF and PostScript have no exact elliptical arc, so
// this is the best their formats allow; the SVG writer (svg_writer.h) keeps arcs exact.
// Files are written to a temporary name and renamed (no half-written output).
#pragma once

#include <string>

#include "quadrix/draw/page.h"

namespace quadrix::draw {

// kPng is a raster preview (1 page unit = 1 pixel for single views, 4 px per mm for sheets).
enum class CairoFormat { kPdf, kEps, kPng };

// Returns an error message or empty.
std::string WriteCairo(const std::string& path, const Page& page, CairoFormat format);

}  // namespace quadrix::draw
