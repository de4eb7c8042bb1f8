#include <fmt/format.h>

#include <cstdio>

#include "commands.h"
#include "quadrix/io/output_file.h"
#include "quadrix/io/pov_export.h"
#include "quadrix/io/writers.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix::cli {

void AddExportCommand(CLI::App& app, ExportArgs& args) {
    CLI::App* cmd = app.add_subcommand("export", "Write a scene in another renderer's format");
    cmd->add_option("scenes", args.scenes, "Scene files, read in order ('-' = standard input)")
        ->required();
    cmd->add_option("--to", args.to, "Target format")
        ->check(CLI::IsMember({"pov"}))
        ->capture_default_str();
    cmd->add_option("-o,--output", args.output, "Output file")->required();
    cmd->add_option("--size", args.size, "Image size WIDTHxHEIGHT the export is set up for")
        ->capture_default_str();
    cmd->add_flag("--mask", args.mask, "Unlit white solids on black (coverage masks)");
    cmd->add_flag("--shadows", args.shadows,
                  "Lights cast shadows (as quadrix render --shadows; default: shadowless)");
    // The same scene and view options as render (view_options.cpp).
    AddSceneViewOptions(*cmd, args, "Export");
    AddLimitOptions(*cmd, args);
}

int RunExport(const ExportArgs& args) {
    if (auto e = ApplyLimits(args); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    Diagnostics diags;
    PipelineOptions po;
    if (auto e = ParseSize(args.size, po.width, po.height); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    po.scenePaths = args.scenes;
    CameraRequest camera;
    if (auto e = SceneViewOptions(args, po, camera, diags); !e.empty()) {
        diags.Print(stderr);
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    std::vector<std::string> inputs = args.scenes;
    if (!args.rtView.empty()) inputs.push_back(args.rtView);
    if (auto e = CheckOutputPaths({args.output}, inputs); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 1;
    }
    RenderContext ctx;
    ViewRequest view = po.View();
    bool ok = ctx.Read(po.Input(), diags);
    if (ok && camera.Any()) ok = ApplyCamera(ctx, camera, view, diags);
    ok = ok && ctx.Flatten(view, diags);
    if (ok && !ctx.Flat().freeforms.empty())
        diags.Warning({},
                      fmt::format("{} freeform surface{} not exported (POV-Ray has no exact "
                                  "NURBS primitive)",
                                  ctx.Flat().freeforms.size(),
                                  ctx.Flat().freeforms.size() == 1 ? " is" : "s are"),
                      {}, "export");
    diags.Print(stderr);
    if (!ok || diags.HasErrors()) {
        std::fprintf(stderr, "quadrix: %d error%s; nothing written\n", diags.ErrorCount(),
                     diags.ErrorCount() == 1 ? "" : "s");
        return 1;
    }
    const FlatScene* flat = &ctx.Flat();
    PovExportOptions pov;
    pov.mask = args.mask;
    pov.shadows = args.shadows;
    if (auto e = WriteOutputFile(args.output, ExportPov(*flat, pov)); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 1;
    }
    return 0;
}

}  // namespace quadrix::cli
