// `quadrix draw`: exact hidden-line drawings (docs/drawings.md), one view or a sheet of views.
#include <fmt/format.h>

#include <cstdio>

#include "commands.h"
#include "quadrix/draw/drawing.h"
#include "quadrix/draw/page_file.h"
#include "quadrix/draw/sheet.h"
#include "quadrix/draw/undrawable.h"
#include "quadrix/frame/image_limits.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/pipeline/section_plane.h"

namespace quadrix::cli {

namespace {

std::vector<std::string> SplitComma(const std::string& s) {
    std::vector<std::string> out;
    std::string cur;
    for (char c : s) {
        if (c == ',') {
            if (!cur.empty()) out.push_back(cur);
            cur.clear();
        } else if (c != ' ') {
            cur += c;
        }
    }
    if (!cur.empty()) out.push_back(cur);
    return out;
}

double PixelsPerUnit(const FlatScene& flat) {
    const Mat4& m = flat.projection.deviceFromWorld.Matrix();
    return std::sqrt(m(0, 0) * m(0, 0) + m(1, 0) * m(1, 0) + m(2, 0) * m(2, 0));
}

int Fail(Diagnostics& diags) {
    diags.Print(stderr);
    std::fprintf(stderr, "quadrix: %d error%s; nothing written\n", diags.ErrorCount(),
                 diags.ErrorCount() == 1 ? "" : "s");
    return 1;
}

void PrintStats(const std::string& view, const draw::DrawStats& s) {
    std::fprintf(stderr,
                 "draw %s: %d candidate curves (%d lines, %d conics, %d silhouettes, %d "
                 "quartic branches; %d tangent pairs skipped), %d boundary pieces, %d strokes, "
                 "%lld ray tests, %d visibility changes, %.1f ms (curves %.1f, trim %.1f, "
                 "visibility %.1f, strokes %.1f)\n",
                 view.c_str(), s.candidates, s.lines, s.conics, s.silhouettes, s.quartics,
                 s.tangentPairs, s.pieces, s.strokes, s.rayTests, s.visibilityChanges,
                 s.seconds * 1e3, s.curveSeconds * 1e3, s.trimSeconds * 1e3,
                 s.visibilitySeconds * 1e3, s.strokeSeconds * 1e3);
}

}  // namespace

void AddDrawCommand(CLI::App& app, DrawArgs& args) {
    CLI::App* cmd = app.add_subcommand(
        "draw", "Exact hidden-line drawing (SVG with exact arcs, PDF, EPS) of a scene");
    cmd->add_option("scenes", args.scenes, "Scene files, read in order ('-' = standard input)")
        ->required();
    cmd->add_option("-o,--output", args.output,
                    "Output file: .svg, .pdf, .eps (or .png, a raster preview)")
        ->required();
    cmd->add_option("--size", args.size, "Device size WIDTHxHEIGHT of a single view (px)")
        ->capture_default_str();
    cmd->add_option("--view", args.view, "Name of the scene's view (default: the last defined)");
    cmd->add_option("--views", args.views,
                    "Standard views on one sheet, e.g. front,top,right,iso (also left, back, "
                    "bottom)");
    cmd->add_option("--sheet", args.sheet, "Sheet size for --views")
        ->check(CLI::IsMember({"A4", "A3", "letter", "a4", "a3", "Letter"}))
        ->capture_default_str();
    cmd->add_option("--projection", args.projection, "Arrangement of --views")
        ->check(CLI::IsMember({"first", "third"}))
        ->capture_default_str();
    cmd->add_option("--hidden", args.hidden, "Hidden lines: dashed or off")
        ->check(CLI::IsMember({"dashed", "off"}))
        ->capture_default_str();
    cmd->add_option("--section", args.section,
                    "Section plane \"A B C D\": keep A x + B y + C z + D <= 0, as quadrix "
                    "render --section");
    cmd->add_flag("--allow-missing", args.allowMissing,
                  "Draw without what the drawer cannot draw (freeform surfaces; imported "
                  "primitives that cannot be drawn): a warning instead of an error");
    cmd->add_flag("--stats", args.stats, "Print curve counts and times to standard error");
}

int RunDraw(const DrawArgs& args) {
    if (!draw::IsPageFileName(args.output)) {
        std::fprintf(stderr,
                     "quadrix: error: %s: the output must end in .svg, .pdf, .eps or .png\n",
                     args.output.c_str());
        return 2;
    }
    int width = 0, height = 0;
    if (auto e = ParseSize(args.size, width, height); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    if (auto e = CheckImageSize(width, height); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: --size: %s\n", e.c_str());
        return 2;
    }
    const std::vector<std::string> viewNames = SplitComma(args.views);
    if (!viewNames.empty() && !args.view.empty()) {
        std::fprintf(stderr, "quadrix: error: --view and --views cannot be combined\n");
        return 2;
    }
    if (viewNames.size() > 4) {
        std::fprintf(stderr, "quadrix: error: --views takes at most four views\n");
        return 2;
    }
    for (const std::string& v : viewNames) {
        scene::View sv;
        if (!draw::StandardView(v, sv)) {
            std::fprintf(stderr,
                         "quadrix: error: unknown view '%s' in --views (front, top, right, left, "
                         "back, bottom, iso)\n",
                         v.c_str());
            return 2;
        }
    }
    std::optional<Plane> section;
    if (!args.section.empty()) {
        Plane p;
        if (auto e = ParseSectionPlane(args.section, p); !e.empty()) {
            std::fprintf(stderr, "quadrix: error: --section: %s\n", e.c_str());
            return 2;
        }
        section = p;
    }
    // Stages 1 and 2 of the render context (pipeline/render_context.h); the drawer takes the
    // flat scene where an engine would.
    Diagnostics diags;
    RenderContext context(1);
    InputRequest input;
    input.paths = args.scenes;
    input.allowMissing = args.allowMissing;
    if (!context.Read(input, diags) || diags.HasErrors()) return Fail(diags);
    ViewRequest request;
    request.width = width;
    request.height = height;
    request.viewName = args.view;
    request.section = section;
    if (viewNames.empty() && (!context.Flatten(request, diags) || diags.HasErrors()))
        return Fail(diags);
    // The drawer handles planes and quadrics: a quartic (torus, elliptical torus, general cone)
    // is refused by name, and a freeform surface too unless --allow-missing (draw/undrawable.h),
    // rather than drawn wrong or left out.
    if (viewNames.empty() && !draw::CheckDrawable(context.Flat(), args.allowMissing, diags))
        return Fail(diags);
    draw::DrawOptions dopt;
    dopt.hidden = args.hidden != "off";
    // The model's file: the first (later ones are usually views or settings for it).
    const std::string title = args.scenes.empty() ? "" : args.scenes.front();
    draw::Page page;
    if (viewNames.empty()) {
        draw::Drawing d = draw::MakeDrawing(context.Flat(), dopt);
        if (args.stats) PrintStats(context.Flat().viewName, d.stats);
        page = draw::SingleViewPage(d, title);
    } else {
        std::vector<draw::SheetView> views;
        double total = 0;
        for (const std::string& name : viewNames) {
            scene::View sv;
            draw::StandardView(name, sv);
            sv.id = "draw#" + sv.id;
            context.Scene().views.push_back(sv);
            context.SceneChanged();
            ViewRequest vr;
            vr.width = 1000;
            vr.height = 1000;
            vr.viewName = sv.id;
            vr.section = section;
            const bool ok = context.Flatten(vr, diags);
            context.Scene().views.pop_back();
            context.SceneChanged();
            if (!ok || diags.HasErrors()) return Fail(diags);
            // Every view flattens the same solids: one check (and one warning) is enough.
            if (views.empty() && !draw::CheckDrawable(context.Flat(), args.allowMissing, diags))
                return Fail(diags);
            draw::SheetView v;
            v.name = name;
            v.drawing = draw::MakeDrawing(context.Flat(), dopt);
            v.pixelsPerUnit = PixelsPerUnit(context.Flat());
            total += v.drawing.stats.seconds;
            if (args.stats) PrintStats(name, v.drawing.stats);
            views.push_back(std::move(v));
        }
        draw::SheetOptions so;
        draw::SheetSizeByName(args.sheet, so.size);
        so.firstAngle = args.projection == "first";
        so.fileName = title;
        std::string scaleText;
        page = draw::LayoutSheet(std::move(views), so, &scaleText);
        if (args.stats)
            std::fprintf(stderr, "draw sheet: %zu views, scale %s, %.1f ms drawing\n",
                         viewNames.size(), scaleText.c_str(), total * 1e3);
    }
    if (page.strokes.empty())
        diags.Warning({}, "the drawing is empty: no edge or outline of the solids lies in the view",
                      {}, "draw");
    diags.Print(stderr);
    const std::string err = draw::WritePageFile(args.output, page);
    if (!err.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", err.c_str());
        return 1;
    }
    return 0;
}

}  // namespace quadrix::cli
