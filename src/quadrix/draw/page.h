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
    // Largest distance (page units) allowed between a conic arc and the cubic Béziers written
    // for it where the format has no exact form (hyperbolic arcs in SVG; every conic in PDF/EPS,
    // through Cairo): `quadrix draw --tolerance`, default 0.05 px on a single view and 0.01 mm
    // on a sheet. Parabolic arcs are exact quadratic Béziers in SVG and elliptical arcs exact
    // `A` commands, whatever the tolerance.
    double tolerance = 0.05;
};

// A cubic Bézier chain for a conic arc: p0 then three points (two controls and the end) per
// piece, with at most `tolerance` between each piece and the arc (checked at 16 points per
// piece; pieces are halved until they pass). Ends and tangents are the arc's exactly.
std::vector<Point2> ConicToCubics(const Stroke& s, double tolerance);

// A single-view page: the drawing in device pixels.
Page SingleViewPage(const Drawing& d, const std::string& title, double tolerance = 0.05);

}  // namespace quadrix::draw
