// `quadrix compare`: the one frame comparison (frame/compare.h) from the command line.
//
//   quadrix compare A.qxf B.qxf [--diff diff.png]           two Frame dumps, B the reference
//   quadrix compare --engines a,b SCENE... [--size WxH] [--view NAME] [--diff diff.png]
//                                                           two engines on one flattened scene,
//                                                           b the reference (default raycast)
// Prints the comparison; exit 0 when the frames agree (no off-edge coverage or surface
// difference and every same-surface depth within --tolerance), 1 when they differ or an input
// cannot be read, 2 for a usage error.
#include <fmt/format.h>

#include <cstdio>
#include <string>

#include "commands.h"
#include "quadrix/frame/compare.h"
#include "quadrix/io/writers.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix::cli {

void AddCompareCommand(CLI::App& app, CompareArgs& args) {
    CLI::App* cmd = app.add_subcommand(
        "compare", "Compare two Frames (.qxf dumps, or two engines on one scene) pixel by pixel");
    cmd->add_option("inputs", args.inputs,
                    "Two .qxf Frame dumps (A, then the reference B), or with --engines the scene "
                    "files")
        ->required();
    cmd->add_option("--engines", args.engines,
                    "ENGINE_A,ENGINE_B: render the scene with both (B is the reference; default "
                    "raycast)");
    cmd->add_option("--size", args.size, "Image size WIDTHxHEIGHT (with --engines)")
        ->capture_default_str();
    cmd->add_option("--view", args.view, "View to use (with --engines)");
    cmd->add_option("--diff", args.diff, "Write a diff image (.png/.ppm) of the comparison");
    cmd->add_option("--tolerance", args.tolerance,
                    "Largest same-surface depth difference that agrees (device z units)")
        ->capture_default_str();
    AddLimitOptions(*cmd, args);
}

namespace {

// Exit status: 0 rendered, 1 scene error, 2 usage error (bad size, unknown engine; docs/cli.md).
int RenderWithEngines(const CompareArgs& args, Frame& a, Frame& b, std::string& names) {
    std::string first = args.engines, second = "raycast";
    if (auto comma = args.engines.find(','); comma != std::string::npos) {
        first = args.engines.substr(0, comma);
        second = args.engines.substr(comma + 1);
    }
    names = first + " vs " + second;
    ViewRequest view;
    if (auto e = ParseSize(args.size, view.width, view.height); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    view.viewName = args.view;
    EngineRequest ra, rb;
    ra.engine = first;
    rb.engine = second;
    for (const EngineRequest* r : {&ra, &rb})
        if (auto e = RenderContext::CheckEngine(*r); !e.empty()) {
            std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
            return 2;
        }
    RenderContext ctx;
    Diagnostics diags;
    InputRequest in;
    in.paths = args.inputs;
    RenderReport report;
    const bool ok = ctx.Read(in, diags) && ctx.Flatten(view, diags) &&
                    ctx.Render(ra, a, report, diags) && ctx.Render(rb, b, report, diags);
    diags.Print(stderr);
    return ok && !diags.HasErrors() ? 0 : 1;
}

}  // namespace

int RunCompare(const CompareArgs& args) {
    if (auto e = ApplyLimits(args); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    Frame a, b;
    std::string names;
    if (!args.engines.empty()) {
        if (int code = RenderWithEngines(args, a, b, names); code != 0) return code;
    } else {
        if (args.inputs.size() != 2) {
            std::fprintf(stderr, "quadrix: error: compare takes two .qxf files (or --engines)\n");
            return 2;
        }
        for (int k = 0; k < 2; ++k)
            // Through the bounded reader, the size checked against the image limits and the
            // memory budget before the Frame is made; errors are positioned (FILE:LINE:COL).
            if (auto e = ReadFrameDump(args.inputs[k], k == 0 ? a : b); !e.empty()) {
                std::fprintf(stderr, "%s%s\n", e.rfind("error: ", 0) == 0 ? "quadrix: " : "",
                             e.c_str());
                return 1;
            }
        names = args.inputs[0] + " vs " + args.inputs[1];
    }
    CompareOptions options;
    options.depthTolerance = args.tolerance;
    const FrameComparison cmp = CompareFrames(a, b, options);
    std::printf("%s\n%s", names.c_str(), cmp.Summary().c_str());
    if (!args.diff.empty()) {
        const Image diff = FrameDiffImage(a, b, options);
        ImageFormat format;
        std::string e;
        if (!ImageFormatFromPath(args.diff, format) || format == ImageFormat::kFrameDump ||
            format == ImageFormat::kExr)
            e = fmt::format("--diff: '{}' is not a .png or .ppm file", args.diff);
        else
            e = format == ImageFormat::kPng ? WritePng(args.diff, diff) : WritePnm(args.diff, diff);
        if (!e.empty()) {
            std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
            return 1;
        }
    }
    const bool agree =
        !cmp.sizeMismatch && cmp.offEdgeDifferences == 0 && cmp.depthOverTolerance == 0;
    std::printf("%s\n", agree ? "frames agree" : "frames differ");
    return agree ? 0 : 1;
}

}  // namespace quadrix::cli
