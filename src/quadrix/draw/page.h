// A page to write: strokes of one or more drawings placed in page coordinates, plus the sheet's
// frame lines and texts (docs/drawings.md). Page units are device pixels for a single view
// (`unit` "px", 1 px written as 1 pt in PDF/EPS) or millimetres for a sheet (`unit` "mm").
// Line widths and dashes are in page units.
#pragma once

#include <string>
#include <vector>

#include "quadrix/draw/drawing.h"

namespace quadrix::draw {

struct LineStyle {
    double silhouette = 1.6;  // visible contour generators (outlines)
    double edge = 1.1;        // visible edges
    double hidden = 0.7;      // hidden lines (dashed)
    double dash = 5, gap = 3;
    double frame = 0.5;     // sheet border and title block
    double tangent = 0.45;  // visible tangent edges (Stroke::tangent), thinner than edges
};

struct PageText {
    double x = 0, y = 0;  // baseline start
    double size = 3;
    std::string text;
};

struct PageLine {
    Point2 a, b;
};

struct Page {
    double width = 0, height = 0;
    std::string unit = "px";
    std::vector<Stroke> strokes;
    std::vector<PageLine> frameLines;
    std::vector<PageText> texts;
    LineStyle style;
    std::string title;  // document title (SVG <title>, PDF metadata)
};

// A single-view page: the drawing in device pixels.
Page SingleViewPage(const Drawing& d, const std::string& title);

}  // namespace quadrix::draw
