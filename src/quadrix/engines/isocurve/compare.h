// Item 5 of issue 6 / Figures 1–2 of seed 002: adaptive isocurves against uniformly spaced
// isocurves and against a polygon mesh of the same tolerance, measured on the same image.
//
// For each method: primitives (curves or triangles), total world length of the curves, pixels
// drawn (Σ over primitives of the pixels each touched), distinct pixels, pixels drawn more than
// once (redundancy), and, against a reference render, holes (pixels the reference covers and the
// method misses) and extra pixels (the converse: the thick curves overhang the outline by up to
// half their width). The reference is a mesh at 1/20 pixel tolerance scan-converted at pixel
// centres: it differs from the exact outline by less than that.
#pragma once

#include <string>
#include <vector>

#include "quadrix/engines/isocurve/render.h"

namespace quadrix::isocurve {

struct MethodRow {
    std::string method;
    long long primitives = 0;
    double length = 0;  // curves only
    long long pixelsDrawn = 0, distinctPixels = 0, multiplyDrawn = 0;
    long long holes = 0, extra = 0;
    double extractSeconds = 0, drawSeconds = 0;
    double Redundancy() const {
        return distinctPixels ? static_cast<double>(pixelsDrawn) / distinctPixels : 0.0;
    }
};

struct Comparison {
    double delta = 0;
    double thickness = 0;
    long long referencePixels = 0;
    std::vector<MethodRow> rows;  // adaptive, uniform, polygons
    std::string Format() const;
};

// Pixel mask of the reference render (1 where some surface covers the pixel centre).
std::vector<std::uint8_t> ReferenceMask(const std::vector<FreeformDrawable>& drawables,
                                        const Projection& projection, int width, int height);

// Runs the three methods on fresh Frames of the given size; `options` sets δ (or the spacing),
// thickness, direction and levels as for RenderFreeform.
Comparison CompareCoverage(const std::vector<FreeformDrawable>& drawables,
                           const Projection& projection, const IsocurveOptions& options, int width,
                           int height);

}  // namespace quadrix::isocurve
