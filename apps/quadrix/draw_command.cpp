// `quadrix draw`: exact hidden-line drawings (docs/drawings.md), one view or a sheet of views.
#include <fmt/format.h>

#include <cstdio>
#include <string>
#include <vector>

#include "commands.h"
#include "quadrix/draw/page_file.h"
#include "quadrix/draw/sheet.h"
#include "quadrix/frame/image_limits.h"
#include "quadrix/pipeline/drawing_output.h"
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

int Fail(Diagnostics& diags) {
    diags.Print(stderr);
    std::fprintf(stderr, "quadrix: %d error%s; nothing written\n", diags.ErrorCount(),
                 diags.ErrorCount() == 1 ? "" : "s");
    return 1;
}

void PrintStats(const std::string& view, const draw::DrawStats& s) {
    std::fprintf(stderr,
                 "draw %s: %d candidate curves (%d lines, %d conics, %d silhouettes, %d "
                 "quartic branches, %d tangent lines), %d boundary pieces (%d tangent edges), "
                 "%d strokes (%d coincident strokes dropped), %lld ray tests, %d visibility "
                 "changes, %.1f ms (curves %.1f, trim "
                 "%.1f, visibility %.1f, strokes %.1f)\n",
                 view.c_str(), s.candidates, s.lines, s.conics, s.silhouettes, s.quartics,
                 s.tangentPairs, s.pieces, s.tangentPieces, s.strokes, s.duplicates, s.rayTests,
                 s.visibilityChanges, s.seconds * 1e3, s.curveSeconds * 1e3, s.trimSeconds * 1e3,
                 s.visibilitySeconds * 1e3, s.strokeSeconds * 1e3);
}

draw::TangentEdges ParseTangentEdges(const std::string& s) {
    if (s == "off") return draw::TangentEdges::kOff;
    if (s == "on") return draw::TangentEdges::kOn;
    return draw::TangentEdges::kThin;
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
    cmd->add_option("--sheet", args.sheet,
                    "Sheet size for --views (default A4); without --views, the standard sheet "
                    "front,top,right,iso")
        ->check(CLI::IsMember({"A4", "A3", "letter", "a4", "a3", "Letter"}));
    cmd->add_option("--projection", args.projection,
                    "Arrangement of --views, first or third angle (default third)")
        ->check(CLI::IsMember({"first", "third"}));
    cmd->add_option("--scale", args.scale,
                    "Sheet scale A:B (1:2, 2:1) or a number (A:1), instead of the largest "
                    "standard scale that fits");
    cmd->add_option("--tolerance", args.tolerance,
                    "Largest distance of the Béziers written for conics that have no exact form "
                    "(px on a single view, default 0.05; mm on a sheet, default 0.01)");
    cmd->add_option("--hidden", args.hidden, "Hidden lines: dashed or off")
        ->check(CLI::IsMember({"dashed", "off"}))
        ->capture_default_str();
    cmd->add_option("--tangent-edges", args.tangentEdges,
                    "Tangent edges (smooth joins of two faces): thin lines, off, or on (drawn "
                    "as edges)")
        ->check(CLI::IsMember({"thin", "off", "on"}))
        ->capture_default_str();
    cmd->add_option("--section", args.section,
                    "Section plane \"A B C D\": keep A x + B y + C z + D <= 0, as quadrix "
                    "render --section");
    cmd->add_flag("--allow-missing", args.allowMissing,
                  "Draw without what the drawer cannot draw (freeform surfaces; imported "
                  "primitives that cannot be drawn): a warning instead of an error");
    cmd->add_flag("--stats", args.stats, "Print curve counts and times to standard error");
    AddLimitOptions(*cmd, args);
}

int RunDraw(const DrawArgs& args) {
    if (auto e = ApplyLimits(args); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
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
    std::vector<std::string> viewNames = SplitComma(args.views);
    // Sheet options without --views ask for a sheet: the standard four views (what a drawing
    // sheet shows), never silently a single view.
    const bool sheetOption = !args.sheet.empty() || !args.projection.empty() || !args.scale.empty();
    if (viewNames.empty() && sheetOption) {
        if (!args.view.empty()) {
            std::fprintf(stderr,
                         "quadrix: error: --sheet, --projection and --scale lay out a sheet of "
                         "standard views (--views); they cannot be combined with --view\n");
            return 2;
        }
        viewNames = {"front", "top", "right", "iso"};
    }
    if (!viewNames.empty() && !args.view.empty()) {
        std::fprintf(stderr, "quadrix: error: --view and --views cannot be combined\n");
        return 2;
    }
    double scale = 0;
    if (!args.scale.empty())
        if (auto e = draw::ParseScale(args.scale, scale); !e.empty()) {
            std::fprintf(stderr, "quadrix: error: --scale: %s\n", e.c_str());
            return 2;
        }
    double tolerance = viewNames.empty() ? 0.05 : 0.01;
    if (!args.tolerance.empty()) {
        std::size_t used = 0;
        double t = 0;
        try {
            t = std::stod(args.tolerance, &used);
        } catch (...) {
            used = 0;
        }
        if (used != args.tolerance.size() || !(t >= 1e-6 && t <= 100)) {
            std::fprintf(stderr,
                         "quadrix: error: --tolerance: '%s' is not a distance between 1e-6 and "
                         "100 (px on a single view, mm on a sheet)\n",
                         args.tolerance.c_str());
            return 2;
        }
        tolerance = t;
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
    // Stage 1 of the render context (pipeline/render_context.h); flattening, the refusal of
    // what cannot be drawn, drawing and writing are the path every front end shares
    // (pipeline/drawing_output.h).
    Diagnostics diags;
    RenderContext context(1);
    InputRequest input;
    input.paths = args.scenes;
    input.allowMissing = args.allowMissing;
    if (!context.Read(input, diags) || diags.HasErrors()) return Fail(diags);
    DrawingRequest request;
    request.view.width = width;
    request.view.height = height;
    request.view.viewName = args.view;
    request.view.section = section;
    request.sheetViews = viewNames;
    request.options.hidden = args.hidden != "off";
    request.options.tangentEdges = ParseTangentEdges(args.tangentEdges);
    request.allowMissing = args.allowMissing;
    // The model's file: the first (later ones are usually views or settings for it).
    request.title = args.scenes.empty() ? "" : args.scenes.front();
    draw::SheetSizeByName(args.sheet.empty() ? "A4" : args.sheet, request.sheet.size);
    request.sheet.firstAngle = args.projection == "first";
    request.sheet.fileName = request.title;
    request.sheet.scale = scale;
    request.sheet.tolerance = tolerance;
    request.tolerance = tolerance;
    DrawingReport report;
    if (!WriteDrawingFile(context, request, args.output, diags, &report)) return Fail(diags);
    if (args.stats) {
        for (const auto& [name, stats] : report.views) PrintStats(name, stats);
        if (!viewNames.empty())
            std::fprintf(stderr, "draw sheet: %zu views, scale %s, %.1f ms drawing\n",
                         viewNames.size(), report.scaleText.c_str(), report.seconds * 1e3);
    }
    diags.Print(stderr);
    return 0;
}

}  // namespace quadrix::cli
