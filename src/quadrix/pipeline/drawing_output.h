// "Scene → drawing file" (docs/drawings.md): the one code path by which every front end writes an
// exact hidden-line drawing — `quadrix draw`, uq's `device svg:FILE` (pdf:, eps:) and the viewer's
// drawing key. Given a render context that has read its scene (stage 1, render_context.h):
//   1. flatten the view (stage 2; a view already flattened for the same request costs nothing),
//      or each standard view of a sheet in turn;
//   2. refuse what the drawer cannot draw (draw/undrawable.h): a quartic surface or a freeform
//      surface is an error unless `allowMissing` (then a warning, and the rest is drawn: the
//      solids without quartics);
//   3. draw (draw/drawing.h) and lay out the page: one view in device pixels, or the sheet
//      (draw/sheet.h);
//   4. write the file by its extension (draw/page_file.h), atomically.
// Every failure is an error in the diagnostics and leaves no file behind.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "quadrix/draw/drawing.h"
#include "quadrix/draw/sheet.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/scene/diagnostics.h"

namespace quadrix {

struct DrawingRequest {
    // The single view to draw: size, view name or view, section, lights (the same request as a
    // render of the view, so that the flat scene is shared). With `sheetViews`, only the
    // section is used: each standard view is flattened at 1000×1000.
    ViewRequest view;
    std::vector<std::string> sheetViews;  // standard views (draw/sheet.h) for one sheet, <= 4
    draw::SheetOptions sheet;             // paper, projection and title-block file name
    draw::DrawOptions options;
    double tolerance = 0.05;    // px: Bézier tolerance of a single view (a sheet: sheet.tolerance)
    bool allowMissing = false;  // leave freeform surfaces out (a warning) instead of an error
    std::string title;          // the page's title (a single view; a sheet uses sheet.fileName)
    SourceLoc loc;              // where an error writing the file is reported (uq's `show`)
};

struct DrawingReport {
    std::vector<std::pair<std::string, draw::DrawStats>> views;  // name and statistics per view
    std::string scaleText;                                       // a sheet's scale ("1:2")
    std::size_t strokes = 0;                                     // on the page
    double seconds = 0;                                          // drawing, all views
};

// Writes the drawing of `request` to `path` (.svg, .pdf, .eps/.ps, .png). False when something
// could not be read, flattened, drawn or written: the errors are in `diags` and no file is
// written. Warnings (freeform surfaces left out, an empty drawing) are added to `diags` too.
bool WriteDrawingFile(RenderContext& context, const DrawingRequest& request,
                      const std::string& path, Diagnostics& diags, DrawingReport* report = nullptr);

}  // namespace quadrix
