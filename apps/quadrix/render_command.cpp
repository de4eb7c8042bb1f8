#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "commands.h"
#include "quadrix/engines/patch/phong.h"
#include "quadrix/frame/memory_budget.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/io/time_limit.h"
#include "quadrix/io/writers.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/shade/shader.h"

namespace quadrix::cli {

std::string ParseSize(const std::string& text, int& width, int& height) {
    long long w = 0, h = 0;
    char x = 0;
    char rest = 0;
    if (std::sscanf(text.c_str(), "%lld%c%lld%c", &w, &x, &h, &rest) != 3 || (x != 'x' && x != 'X'))
        return fmt::format("--size: expected WIDTHxHEIGHT (e.g. 640x480), found '{}'", text);
    if (auto e = CheckImageSize(w, h); !e.empty()) return "--size: " + e;
    width = static_cast<int>(w);
    height = static_cast<int>(h);
    return {};
}

void AddRenderCommand(CLI::App& app, RenderArgs& args) {
    CLI::App* cmd = app.add_subcommand(
        "render", "Render scene files to an image (.png, .pgm/.ppm, or .qxf frame dump)");
    cmd->add_option("scenes", args.scenes, "Scene files, read in order ('-' = standard input)")
        ->required();
    cmd->add_option("-o,--output", args.output, "Output file; the format follows the extension")
        ->required();
    cmd->add_option("--size", args.size, "Image size WIDTHxHEIGHT in pixels")
        ->capture_default_str();
    cmd->add_option("--view", args.view, "Name of the view to use (default: the last one defined)");
    cmd->add_option("--engine", args.engine, "Rendering engine")->capture_default_str();
    auto* fast =
        cmd->add_flag("--fast", args.fast, "Constant (flat) shading per surface, as UniQuadrix -f");
    cmd->add_flag("--phong", args.phong,
                  "Phong shading per pixel (diffuse + specular highlight; seed 000's post-shading "
                  "unit) instead of Lambert")
        ->excludes(fast);
    cmd->add_flag("--stats", args.stats, "Print timings and engine counters to standard error");
    cmd->add_option("--threads", args.threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024));
    cmd->add_option("--engine-opt", args.engineOptions,
                    "Engine-specific setting KEY=VALUE (repeatable; see docs/ for each engine)");
    cmd->add_option("--dump-frame", args.dumpFrame,
                    "Also write the Frame (depth, normal, ids) as a .qxf text dump");
    cmd->add_option("--top", args.top,
                    "Objects to draw from BRL-CAD/OpenSCAD files (repeatable or comma-separated; "
                    "default: every top-level object)")
        ->delimiter(',')
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmd->add_flag("--strict", args.strict,
                  "Primitives that cannot be drawn exactly (torus, ...) are an error");
    cmd->add_option("--az", args.az, "Azimuth in degrees (rt convention), orthographic fit")
        ->expected(1);
    cmd->add_option("--el", args.el, "Elevation in degrees (rt convention)")->expected(1);
    cmd->add_option("--viewsize", args.viewsize, "rt view size in mm (with --az/--el or --eye-pt)")
        ->expected(1);
    cmd->add_option("--eye-pt", args.eyePt, "rt eye point X Y Z in model mm")->expected(3);
    cmd->add_option("--viewrot", args.viewrot, "rt view rotation: 16 numbers, row-major")
        ->expected(16);
    cmd->add_option("--rt-view", args.rtView,
                    "File of rt view commands (viewsize; eye_pt; viewrot or orientation)");
    cmd->add_option("--max-memory", args.maxMemory,
                    "Memory budget, e.g. 2G or 512M: larger images are refused (docs/output.md)");
    cmd->add_option("--time-limit", args.timeLimit,
                    "Give up after this many seconds (exit 124, no output left)");
}

namespace {
// The rt-style view options → PipelineOptions; returns an error message or empty.
std::string RtViewOptions(const RenderArgs& args, PipelineOptions& po, Diagnostics& diags) {
    if (!args.az.empty()) po.azimuth = args.az[0];
    if (!args.el.empty()) po.elevation = args.el[0];
    if (!args.viewsize.empty()) {
        if (!(args.viewsize[0] > 0)) return "--viewsize must be positive";
        po.viewsize = args.viewsize[0];
    }
    bool explicitView = !args.eyePt.empty() || !args.viewrot.empty();
    if (explicitView) {
        if (args.eyePt.size() != 3 || args.viewrot.size() != 16 || !po.viewsize)
            return "an explicit rt view needs --viewsize, --eye-pt (3 numbers) and --viewrot (16)";
        import::RtView rt;
        rt.viewsize = *po.viewsize;
        rt.eye = {args.eyePt[0], args.eyePt[1], args.eyePt[2]};
        for (int k = 0; k < 16; ++k) rt.viewrot.m[k / 4][k % 4] = args.viewrot[k];
        po.rtView = rt;
    }
    if (!args.rtView.empty()) {
        std::string text;
        if (auto why = ReadBoundedFile(args.rtView, text); !why.empty())
            return fmt::format("--rt-view: cannot read '{}': {}", args.rtView, why);
        auto rt = import::ParseRtViewScript(text, args.rtView, diags);
        if (!rt) return "--rt-view: the view file has errors";
        po.rtView = *rt;
    }
    if ((po.rtView || po.azimuth || po.elevation) && !args.view.empty())
        return "--view cannot be combined with --az/--el or an rt view";
    return {};
}
}  // namespace

int RunRender(const RenderArgs& args) {
    if (!args.maxMemory.empty()) {
        std::size_t bytes = 0;
        if (!ParseByteSize(args.maxMemory, bytes)) {
            std::fprintf(stderr, "quadrix: error: --max-memory: expected a size of at least 1M "
                                 "such as 512M or 2G, found '%s'\n", args.maxMemory.c_str());
            return 2;
        }
        SetMemoryBudget(bytes);
    }
    if (args.timeLimit != 0 && !SetTimeLimit(args.timeLimit)) {
        std::fprintf(stderr, "quadrix: error: --time-limit: expected a positive number of "
                             "seconds\n");
        return 2;
    }
    Diagnostics diags;
    PipelineOptions po;
    if (auto e = ParseSize(args.size, po.width, po.height); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    ImageFormat format;
    if (!ImageFormatFromPath(args.output, format)) {
        std::fprintf(stderr,
                     "quadrix: error: cannot tell the image format of '%s' (use .png, .pgm, .ppm, "
                     ".pnm or .qxf)\n",
                     args.output.c_str());
        return 2;
    }
    po.scenePaths = args.scenes;
    po.viewName = args.view;
    po.engine = args.engine;
    po.threads = args.threads;
    po.topObjects = args.top;
    po.strict = args.strict;
    if (auto e = RtViewOptions(args, po, diags); !e.empty()) {
        diags.Print(stderr);
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    for (const std::string& kv : args.engineOptions) {
        auto eq = kv.find('=');
        if (eq == std::string::npos || eq == 0) {
            std::fprintf(stderr, "quadrix: error: --engine-opt: expected KEY=VALUE, found '%s'\n",
                         kv.c_str());
            return 2;
        }
        po.engineOptions[kv.substr(0, eq)] = kv.substr(eq + 1);
    }

    // Every output is checked before anything is read or drawn (io/output_file.h): none may be a
    // device, FIFO, directory or input, and a refused --dump-frame must not follow a written image.
    std::vector<std::string> outputs{args.output};
    if (!args.dumpFrame.empty()) outputs.push_back(args.dumpFrame);
    std::vector<std::string> inputs = args.scenes;
    if (!args.rtView.empty()) inputs.push_back(args.rtView);
    if (auto e = CheckOutputPaths(outputs, inputs); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 1;
    }

    PipelineResult result;
    bool ok = RunPipeline(po, result, diags);
    diags.Print(stderr);
    if (!ok || diags.HasErrors()) {
        std::fprintf(stderr, "quadrix: %d error%s; no image written\n", diags.ErrorCount(),
                     diags.ErrorCount() == 1 ? "" : "s");
        return 1;
    }

    for (const std::string& w : result.stats.warnings)
        std::fprintf(stderr, "quadrix: warning: engine %s: %s\n", args.engine.c_str(), w.c_str());

    auto t0 = std::chrono::steady_clock::now();
    ShadeOptions so;
    so.fast = args.fast;
    // Both outputs are written to temporary files, then renamed together (CommitAll).
    std::string error;
    OutputFile mainFile(args.output);
    std::optional<OutputFile> dumpFile;
    if (!args.dumpFrame.empty()) dumpFile.emplace(args.dumpFrame);
    if (format == ImageFormat::kFrameDump) {
        error = WriteFrameDump(mainFile, result.frame);
    } else {
        Image image = args.phong ? patch::PhongShade(result.frame, result.flat)
                                 : Shade(result.frame, result.flat, so);
        error = format == ImageFormat::kPng ? WritePng(mainFile, image) : WritePnm(mainFile, image);
    }
    if (error.empty() && dumpFile) error = WriteFrameDump(*dumpFile, result.frame);
    if (error.empty())
        error = dumpFile ? CommitAll({&mainFile, &*dumpFile}) : CommitAll({&mainFile});
    double writeSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!error.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", error.c_str());
        return 1;
    }
    if (args.stats) {
        std::fprintf(stderr,
                     "engine %s  %dx%d  solids %zu  bodies %zu  half-spaces %zu  covered %zu px\n"
                     "read %.3f s  flatten %.3f s  render %.3f s  shade+write %.3f s\n",
                     args.engine.c_str(), result.frame.width, result.frame.height,
                     result.flat.solids.size(), result.flat.bodies.size(),
                     result.flat.halfSpaces.size(), result.frame.CoveredCount(),
                     result.readSeconds, result.flattenSeconds, result.renderSeconds,
                     writeSeconds);
        for (const auto& [path, r] : result.inputs.imports)
            std::fprintf(stderr, "%s: %s, %d solids drawn; %s\n", path.c_str(), r.format.c_str(),
                         r.solids, r.CensusText().c_str());
        for (const auto& [name, value] : result.stats.counters)
            std::fprintf(stderr, "  %s: %.17g\n", name.c_str(), value);
        if (!result.stats.report.empty()) std::fprintf(stderr, "%s\n", result.stats.report.c_str());
    }
    return 0;
}

}  // namespace quadrix::cli
