#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include "commands.h"
#include "quadrix/batch/run.h"
#include "quadrix/engines/registry.h"
#include "quadrix/frame/memory_budget.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/io/output_file.h"
#include "quadrix/io/time_limit.h"
#include "quadrix/io/writers.h"
#include "quadrix/pipeline/camera.h"
#include "quadrix/pipeline/output.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/pipeline/stats_report.h"
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
        "render",
        "Render scene files to an image (.png, .ppm colour, .pgm gray, .exr with depth/normal/id "
        "layers, or .qxf frame dump)");
    cmd->add_option("scenes", args.scenes, "Scene files, read in order ('-' = standard input)")
        ->required();
    cmd->add_option("-o,--output", args.output,
                    "Output file; the format follows the extension ('-' = standard output, PNG "
                    "unless --format says otherwise)")
        ->required();
    cmd->add_option("--format", args.format,
                    "Output format, overriding the extension: png, ppm, pgm, pnm, exr or qxf")
        ->check(CLI::IsMember({"png", "ppm", "pgm", "pnm", "exr", "qxf"}));
    cmd->add_option("--size", args.size, "Image size WIDTHxHEIGHT in pixels")
        ->capture_default_str();
    cmd->add_option("--view", args.view, "Name of the view to use (default: the last one defined)");
    cmd->add_option("--engine", args.engine,
                    "Rendering engine (" + EngineList() +
                        "); what it cannot draw is drawn by raycast and composed by depth")
        ->capture_default_str();
    auto* fast =
        cmd->add_flag("--fast", args.fast, "Constant (flat) shading per surface, as UniQuadrix -f");
    cmd->add_flag("--phong", args.phong,
                  "Phong shading per pixel (diffuse + specular highlight; seed 000's post-shading "
                  "unit) instead of Lambert")
        ->excludes(fast);
    cmd->add_flag("--png16", args.png16, "16 bits per channel in PNG output (sRGB-encoded)");
    auto* shadows = cmd->add_flag(
        "--shadows", args.shadows,
        "Shadows from every light, by shadow rays through the CSG (parallel views; the default "
        "when the scene declares lights)");
    // Picture quality (docs/shading.md).
    cmd->add_flag("--no-shadows", args.noShadows, "No shadows, even when the scene has lights")
        ->excludes(shadows);
    cmd->add_option("--aa", args.aa,
                    "Anti-aliasing: samples per edge pixel, off|4|16|64 (default " +
                        std::to_string(kDefaultAaSamples) + "; interior pixels are not resampled)");
    cmd->add_option("--aa-filter", args.aaFilter, "Anti-aliasing filter: box|mitchell")
        ->check(CLI::IsMember({"box", "mitchell"}));
    cmd->add_flag("--edges", args.edges,
                  "Draw exact silhouette, intersection and crease lines, one pixel wide");
    cmd->add_option("--camera", args.camera,
                    "Look-at camera eye_x,eye_y,eye_z,center_x,center_y,center_z in the model's "
                    "coordinates (Z-up for BRL-CAD/OpenSCAD files), as OpenSCAD");
    cmd->add_option("--projection", args.projection, "With --camera: ortho|persp (default persp)");
    cmd->add_option("--fov", args.fov, "With --camera: vertical field of view in degrees (22.5)")
        ->expected(1);
    cmd->add_flag("--viewall", args.viewAll, "Fit the window to the whole scene");
    cmd->add_flag("--autocenter", args.autoCenter, "Centre the scene in the picture");
    cmd->add_flag("--stats", args.stats, "Print timings and engine counters to standard error");
    cmd->add_flag("--json", args.json,
                  "With --stats: the statistics as one JSON object on standard output");
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
                  "Refuse what cannot be drawn as asked: primitives that cannot be drawn "
                  "(torus, ...) even with --allow-missing, and solids the engine cannot draw "
                  "(instead of composing them from raycast)");
    cmd->add_flag("--allow-missing", args.allowMissing,
                  "Draw an imported model without the primitives that cannot be drawn (torus, "
                  "...): a warning and a count in --stats instead of an error");
    cmd->footer(EnginesHelp());
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
    AddAnimationOptions(*cmd, args);
}

std::string ParseAaSamples(const std::string& text, int& samples) {
    if (text == "default") {
        samples = kDefaultAaSamples;
        return {};
    }
    if (text == "off" || text == "0" || text == "1") {
        samples = 0;
        return {};
    }
    for (int n : {4, 16, 64})
        if (text == std::to_string(n)) {
            samples = n;
            return {};
        }
    return fmt::format("--aa: expected off, 4, 16 or 64, found '{}'", text);
}

namespace {
// Whether the scene declares a light that can cast a shadow (not the default rig: docs/shading.md).
bool DeclaresLights(const FlatScene& flat) {
    for (const scene::Light& l : flat.lights)
        if (!l.isRig && l.kind != scene::Light::Kind::kAmbient) return true;
    return false;
}

// The camera options → CameraRequest; an error message or empty.
std::string CameraOptions(const RenderArgs& args, CameraRequest& camera) {
    if (!args.camera.empty())
        if (auto e = ParseCamera(args.camera, camera); !e.empty()) return e;
    if (!args.projection.empty()) {
        if (args.camera.empty()) return "--projection needs --camera";
        if (auto e = ParseProjection(args.projection, camera); !e.empty()) return e;
    }
    if (!args.fov.empty()) camera.fovDegrees = args.fov[0];
    camera.viewAll = args.viewAll;
    camera.autoCenter = args.autoCenter;
    return {};
}

// The camera's view into `view` (after Read: the input format says which axis is up).
bool ApplyCamera(RenderContext& ctx, CameraRequest camera, ViewRequest& view, Diagnostics& diags) {
    camera.zUp = !ctx.Inputs().imports.empty();
    const std::optional<scene::View> own = ctx.Scene().ViewToUse(view.viewName);
    if (!own) return true;  // Flatten reports the unknown view
    std::string error;
    std::optional<scene::View> v = CameraView(camera, *own, error);
    if (!v) {
        diags.Error({}, error, {}, "command line");
        return false;
    }
    if (camera.autoCenter) {
        ViewRequest fit = view;
        fit.view = *v;
        fit.view->whh = fit.view->whw = std::nullopt;
        if (!ctx.Flatten(fit, diags)) return false;
        v = CentreOnScene(*v, ctx.Flat());
    }
    view.view = v;
    view.viewName.clear();
    return true;
}

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
// The end of a one-shot render whose outputs are all committed: the process exits here, so the
// destructors of the Frame (40 MB at 1280×720), the image, the scene and the thread pool do not
// run (5–6 ms of freeing, issue 24). Nothing is lost: the outputs are renamed into place and
// fsynced, no temporary file is pending (the signal-cleanup table is empty, so its handlers have
// nothing to do), and the standard streams are flushed here. Under AddressSanitizer the process
// returns normally, so that LeakSanitizer still checks the render path at exit.
#if defined(__SANITIZE_ADDRESS__)
#define QUADRIX_RENDER_FAST_EXIT 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define QUADRIX_RENDER_FAST_EXIT 0
#endif
#endif
#ifndef QUADRIX_RENDER_FAST_EXIT
#define QUADRIX_RENDER_FAST_EXIT 1
#endif
int FinishRender(const RenderArgs& args, int code) {
    // Not under an MPI launcher: MPI must be finalised at exit (batch/run.h).
    if (!QUADRIX_RENDER_FAST_EXIT || !args.exitWhenDone || PendingOutputFiles() != 0 ||
        batch::UnderMpiLauncher())
        return code;
    const bool flushed = std::fflush(stdout) == 0 && !std::ferror(stdout);
    std::fflush(stderr);
    ::_exit(flushed ? code : 1);
}
}  // namespace

int RunRender(const RenderArgs& args) {
    if (!args.maxMemory.empty()) {
        std::size_t bytes = 0;
        if (!ParseByteSize(args.maxMemory, bytes)) {
            std::fprintf(stderr,
                         "quadrix: error: --max-memory: expected a size of at least 1M such as "
                         "512M or 2G, found '%s'\n",
                         args.maxMemory.c_str());
            return 2;
        }
        SetMemoryBudget(bytes);
    }
    if (args.timeLimit != 0 && !SetTimeLimit(args.timeLimit)) {
        std::fprintf(stderr,
                     "quadrix: error: --time-limit: expected a positive number of "
                     "seconds\n");
        return 2;
    }
    int aaSamples = kDefaultAaSamples;
    if (auto e = ParseAaSamples(args.aa, aaSamples); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    Diagnostics diags;
    PipelineOptions po;
    if (auto e = ParseSize(args.size, po.width, po.height); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    OutputRequest outputs{args.output, args.dumpFrame, {}, args.format};
    outputs.png.bitDepth = args.png16 ? 16 : 8;
    if (args.output == "-" && args.stats && args.json) {
        std::fprintf(stderr,
                     "quadrix: error: --stats --json and -o - both write to standard "
                     "output; write the image to a file\n");
        return 2;
    }
    if (auto e = CheckOutputs(outputs); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    po.scenePaths = args.scenes;
    po.viewName = args.view;
    po.engine = args.engine;
    po.threads = args.threads;
    po.topObjects = args.top;
    po.strict = args.strict;
    po.allowMissing = args.allowMissing;
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
    // The engine and its options are checked before anything is read (a usage error).
    const EngineRequest engine = po.EngineRun();
    if (auto e = RenderContext::CheckEngine(engine); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }

    // The outputs against the inputs named on the command line (io/output_file.h); files read
    // later (`read`) are refused when the output is opened. (An animation's are frame patterns,
    // checked frame by frame when each is opened.)
    const bool animated = args.frames > 0 || args.turntable > 0 || !args.views.empty();
    std::vector<std::string> inputs = args.scenes;
    if (!args.rtView.empty()) inputs.push_back(args.rtView);
    if (auto e = animated
                     ? std::string()
                     : CheckOutputPaths(
                           {args.output, args.dumpFrame.empty() ? "-" : args.dumpFrame}, inputs);
        !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 1;
    }

    CameraRequest camera;
    if (auto e = CameraOptions(args, camera); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    if (camera.Any() && (po.rtView || po.azimuth || po.elevation)) {
        std::fprintf(stderr,
                     "quadrix: error: the camera options cannot be combined with "
                     "--az/--el or an rt view\n");
        return 2;
    }
    const bool animation = args.frames > 0 || args.turntable > 0 || !args.views.empty();
    if (animation && camera.Any()) {
        std::fprintf(stderr,
                     "quadrix: error: the camera options cannot be combined with "
                     "--frames, --turntable or --views (docs/batch.md)\n");
        return 2;
    }
    if (animation) {
        // Frames of an animation take the picture options as given (docs/batch.md): shadows and
        // anti-aliasing when asked for, not the single picture's defaults.
        ShadeOptions so;
        so.fast = args.fast;
        so.shadows = args.shadows;
        so.aaSamples = args.aa == "default" ? 0 : aaSamples;
        so.aaMitchell = args.aaFilter == "mitchell";
        so.edges = args.edges;
        if (args.phong) so.model = ShadingModel::kPhong;
        return RunAnimation(args, po, engine, so, outputs);
    }

    RenderContext ctx(args.threads);
    Frame frame;
    RenderReport report;
    ViewRequest view = po.View();
    bool writer = true;  // false on the MPI ranks of --sort-last other than rank 0
    bool ok = ctx.Read(po.Input(), diags);
    if (ok && camera.Any()) ok = ApplyCamera(ctx, camera, view, diags);
    ok = ok && ctx.Flatten(view, diags) &&
         RenderMaybeShared(args, ctx, engine, frame, report, diags, writer);
    diags.Print(stderr);
    if (!ok || diags.HasErrors()) {
        std::fprintf(stderr, "quadrix: %d error%s; no image written\n", diags.ErrorCount(),
                     diags.ErrorCount() == 1 ? "" : "s");
        return 1;
    }
    for (const std::string& w : report.stats.warnings)
        std::fprintf(stderr, "quadrix: warning: engine %s: %s\n", args.engine.c_str(), w.c_str());
    for (const std::string& n : report.notes)
        std::fprintf(stderr, "quadrix: note: %s\n", n.c_str());
    if (!writer) return 0;

    auto t0 = std::chrono::steady_clock::now();
    std::optional<Image> image;
    if (NeedsImage(outputs)) {
        ShadeOptions so;
        so.fast = args.fast;
        // The picture defaults (docs/shading.md): shadows where the scene declares lights, and
        // anti-aliasing, both only for scenes of at most kPictureDefaultBodies bodies (asked for
        // explicitly, they are still done).
        const bool small = ctx.Flat().bodies.size() <= kPictureDefaultBodies;
        const bool defaultShadows = !args.shadows && !args.noShadows && DeclaresLights(ctx.Flat());
        const bool defaultAa = args.aa == "default" && aaSamples > 1;
        if (!small && (defaultShadows || defaultAa))
            std::fprintf(
                stderr,
                "quadrix: note: %zu bodies: no default%s%s (--shadows, --aa N ask for "
                "them)\n",
                ctx.Flat().bodies.size(), defaultShadows ? " shadows" : "",
                defaultAa ? (defaultShadows ? " or anti-aliasing" : " anti-aliasing") : "");
        so.shadows = args.shadows || (defaultShadows && small);
        so.aaSamples = defaultAa && !small ? 0 : aaSamples;
        so.aaMitchell = args.aaFilter == "mitchell";
        so.edges = args.edges;
        if (args.phong) so.model = ShadingModel::kPhong;
        so.linear = outputs.png.bitDepth == 16;  // 8-bit files are encoded from the 8-bit pixels
        image = ctx.Shade(frame, so);
    }
    const std::string error = WriteOutputs(outputs, frame, image ? &*image : nullptr);
    const double writeSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!error.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", error.c_str());
        return 1;
    }
    if (args.stats) {
        const StatsInput in{&ctx, &report, &frame, writeSeconds};
        const std::string text = args.json ? FormatStatsJson(in) : FormatStatsText(in);
        std::fputs(text.c_str(), args.json ? stdout : stderr);
    }
    return FinishRender(args, 0);
}

}  // namespace quadrix::cli
