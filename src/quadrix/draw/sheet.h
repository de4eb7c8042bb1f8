// A drawing sheet (docs/drawings.md): several orthographic views of one scene at one scale on a
// paper size, in first- or third-angle arrangement, with a border and a small title block.
//
// Views (world coordinates, y up, the part's front facing −z as the language's default view
// looks along +z):
//   front  dop 0 0 −1, vup +y      top  dop 0 1 0, vup +z      right  dop 1 0 0, vup +y
//   iso    dop 1 1 −1, vup +y      (dop points toward the viewer, docs/language.md §3.8)
// Layout: the sheet inside a 10 mm border is a 2 × 2 grid above the title block. Third angle
// (ASME): top above front, right view to the right of front, iso top right. First angle (ISO):
// front top right, top view below it, right view to its left, iso bottom left. The scale is the
// largest standard ratio (…, 2:1, 1:1, 1:2, 1:2.5, 1:5, 1:10, …) at which every view fits 85 %
// of its cell; each view is scaled exactly from its device pixels (a similarity), so its arcs
// stay exact.
#pragma once

#include <string>
#include <vector>

#include "quadrix/draw/drawing.h"
#include "quadrix/draw/page.h"
#include "quadrix/scene/scene.h"

namespace quadrix::draw {

struct SheetSize {
    std::string name;
    double width = 0, height = 0;  // mm, landscape
};

// "A4", "A3", "letter" (case-insensitive); false when unknown.
bool SheetSizeByName(const std::string& name, SheetSize& out);

// The view of a standard name (front, top, right, left, bottom, back, iso); false when unknown.
bool StandardView(const std::string& name, scene::View& out);

struct SheetView {
    std::string name;
    Drawing drawing;           // device pixels
    double pixelsPerUnit = 1;  // device pixels per world unit of that view
};

struct SheetOptions {
    SheetSize size{"A4", 297, 210};
    bool firstAngle = false;
    std::string fileName;  // shown in the title block
    // The scale, millimetres of paper per world unit (0.5 is 1:2); 0 = the largest standard
    // scale at which every view fits (above). A given scale is used as it is, even when views
    // then overflow their cells (LayoutSheet says so in `overflow`).
    double scale = 0;
    double tolerance = 0.01;  // mm: Page::tolerance
};

// Parses a scale "A:B" (A mm of paper for B world units) or a positive number (A:1): "1:2",
// "2:1", "0.5". Returns an error message, or empty with `out` set.
std::string ParseScale(const std::string& text, double& out);

// The ratio written in the title block: "1:2", "2:1", "1:1", "1:2.5".
std::string ScaleText(double scale);

// Lays out the views (at most four, in the order front, top, right, iso of the layout above;
// names not in the layout fill the free cells). Returns the page in millimetres; `scaleText` is
// set to the ratio written in the title block ("1:2"); `overflow` (when given) is set when a
// view does not fit its cell at options.scale, with the largest standard scale that would.
Page LayoutSheet(std::vector<SheetView> views, const SheetOptions& options,
                 std::string* scaleText = nullptr, std::string* overflow = nullptr);

}  // namespace quadrix::draw
