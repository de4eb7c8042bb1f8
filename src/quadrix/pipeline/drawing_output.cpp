#include "quadrix/pipeline/drawing_output.h"

#include <cmath>

#include "quadrix/draw/page_file.h"
#include "quadrix/draw/undrawable.h"

namespace quadrix {

namespace {

double PixelsPerUnit(const FlatScene& flat) {
    const Mat4& m = flat.projection.deviceFromWorld.Matrix();
    return std::sqrt(m(0, 0) * m(0, 0) + m(1, 0) * m(1, 0) + m(2, 0) * m(2, 0));
}

// Stage 2 for one standard view of a sheet: the view is added to the scene under a name no
// scene can use ("draw#front"), flattened and taken out again.
bool FlattenStandardView(RenderContext& context, const std::string& name, const ViewRequest& base,
                         Diagnostics& diags) {
    scene::View sv;
    if (!draw::StandardView(name, sv)) {
        diags.Error({}, "unknown standard view '" + name + "'", {}, "draw");
        return false;
    }
    sv.id = "draw#" + sv.id;
    context.Scene().views.push_back(sv);
    context.SceneChanged();
    ViewRequest vr;
    vr.width = 1000;
    vr.height = 1000;
    vr.viewName = sv.id;
    vr.section = base.section;
    const bool ok = context.Flatten(vr, diags);
    context.Scene().views.pop_back();
    context.SceneChanged();
    return ok && !diags.HasErrors();
}

}  // namespace

bool WriteDrawingFile(RenderContext& context, const DrawingRequest& request,
                      const std::string& path, Diagnostics& diags, DrawingReport* report) {
    DrawingReport local;
    DrawingReport& rep = report ? *report : local;
    rep = DrawingReport{};
    if (diags.HasErrors()) return false;
    draw::Page page;
    if (request.sheetViews.empty()) {
        if (!context.Flatten(request.view, diags) || diags.HasErrors()) return false;
        if (!draw::CheckDrawable(context.Flat(), request.allowMissing, diags, &context.Scene()))
            return false;
        const draw::Drawing d =
            draw::MakeDrawing(draw::DrawableSubset(context.Flat()), request.options);
        rep.views.emplace_back(context.Flat().viewName, d.stats);
        rep.seconds += d.stats.seconds;
        page = draw::SingleViewPage(d, request.title, request.tolerance);
    } else {
        std::vector<draw::SheetView> views;
        for (const std::string& name : request.sheetViews) {
            if (!FlattenStandardView(context, name, request.view, diags)) return false;
            // Every view flattens the same solids: one check (and one warning) is enough.
            if (views.empty() &&
                !draw::CheckDrawable(context.Flat(), request.allowMissing, diags, &context.Scene()))
                return false;
            draw::SheetView v;
            v.name = name;
            v.drawing = draw::MakeDrawing(draw::DrawableSubset(context.Flat()), request.options);
            v.pixelsPerUnit = PixelsPerUnit(context.Flat());
            rep.views.emplace_back(name, v.drawing.stats);
            rep.seconds += v.drawing.stats.seconds;
            views.push_back(std::move(v));
        }
        std::string overflow;
        page = draw::LayoutSheet(std::move(views), request.sheet, &rep.scaleText, &overflow);
        if (!overflow.empty()) diags.Warning({}, overflow, {}, "draw");
    }
    rep.strokes = page.strokes.size();
    if (page.strokes.empty())
        diags.Warning({}, "the drawing is empty: no edge or outline of the solids lies in the view",
                      {}, "draw");
    const std::string err = draw::WritePageFile(path, page);
    if (!err.empty()) {
        diags.Error(request.loc, err, {}, "draw");
        return false;
    }
    return true;
}

}  // namespace quadrix
