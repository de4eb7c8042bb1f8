#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

#include "commands.h"
#include "quadrix/batch/run.h"
#include "quadrix/engines/registry.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/io/output_file.h"
#include "quadrix/io/phase_times.h"
#include "quadrix/io/writers.h"
#include "quadrix/pipeline/camera.h"
#include "quadrix/pipeline/output.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/pipeline/section_plane.h"
#include "quadrix/pipeline/stats_report.h"
#include "quadrix/shade/shader.h"
#include "quadrix/util/heap_huge_pages.h"

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
    cmd->add_option("--section", args.section,
                    "Section plane \"A B C D\" (world coordinates): keep the part where "
                    "A x + B y + C z + D <= 0 and draw the cut faces (docs/viewer.md)");
    cmd->add_flag("--hatch", args.hatch,
                  "With --section: hatch the cut faces with 45-degree lines fixed to the plane, "
                  "alternating direction from solid to solid (docs/viewer.md)");
    cmd->add_flag("--stats", args.stats, "Print timings and engine counters to standard error");
    cmd->add_flag("--json", args.json,
                  "With --stats: the statistics as one JSON object on standard output");
    cmd->add_option("--threads", args.threads,
                    "Worker threads (0 = all cores, or inline for a picture of at most 128x128 "
                    "pixels of a small scene; 1 = inline, without oneTBB)")
        ->check(CLI::Range(0, 1024));
    cmd->add_option("--engine-opt", args.engineOptions,
                    "Engine-specific setting KEY=VALUE (repeatable; see docs/ for each engine)");
    cmd->add_option("--dump-frame", args.dumpFrame,
                    "Also write the Frame (depth, normal, ids) as a .qxf text dump");
    cmd->add_flag("--strict", args.strict,
                  "Refuse what cannot be drawn as asked: primitives that cannot be drawn "
                  "(superell, dsp, ebm, nmg, ...) even with --allow-missing, and solids the engine "
                  "cannot draw "
                  "(instead of composing them from raycast)");
    AddSceneViewOptions(*cmd, args, "Draw");
    cmd->footer(EnginesHelp());
    AddLimitOptions(*cmd, args);
    AddAnimationOptions(*cmd, args);
}

namespace {
// Which picture options the command line leaves to the defaults.
PictureDefaults PictureRequest(const RenderArgs& args) {
    PictureDefaults d;
    d.shadows = !args.shadows && !args.noShadows;
    d.antialiasing = args.aa == "default";
    return d;
}

// The end of a one-shot render whose outputs are all committed: the process exits here, so the
// destructors of the Frame (40 MB at 1280×720), the image, the scene and the thread pool do not
// run (5–6 ms of freeing, issue 24). Nothing is lost: the outputs are renamed into place (and
// fsynced with QUADRIX_FSYNC=1), no temporary file is pending (the signal-cleanup table is
// empty, so its handlers have nothing to do), and the standard streams are flushed here. Under
// AddressSanitizer the process returns normally, so that LeakSanitizer still checks the render path
// at exit.
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
    MarkPhase("exit");  // the benchmark's phase table (io/phase_times.h); nothing unless asked
    PrintPhaseTimes();
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
    MarkPhase("start");
    if (auto e = ApplyLimits(args); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
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
    OutputRequest outputs;
    outputs.image = args.output;
    outputs.dumpFrame = args.dumpFrame;
    outputs.format = args.format;
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
    po.engine = args.engine;
    po.threads = args.threads;
    po.strict = args.strict;
    if (!args.section.empty()) {
        Plane section;
        if (auto e = ParseSectionPlane(args.section, section); !e.empty()) {
            std::fprintf(stderr, "quadrix: error: --section: %s\n", e.c_str());
            return 2;
        }
        po.section = section;
    }
    // The animation-only options on a still picture would be silently ignored (issue 22).
    if (args.frames == 0 && args.turntable == 0 && args.views.empty()) {
        if (!args.frameRange.empty()) {
            std::fprintf(stderr,
                         "quadrix: error: --frame-range: there is no animation to take frames "
                         "from (give --frames, --turntable or --views)\n");
            return 2;
        }
        if (args.resume) {
            std::fprintf(stderr,
                         "quadrix: error: --resume: a still picture has no frames to skip; it "
                         "applies to --frames, --turntable or --views (batch jobs resume by "
                         "default)\n");
            return 2;
        }
    }
    if (args.hatch && args.section.empty()) {
        std::fprintf(stderr,
                     "quadrix: error: --hatch: there is no section to hatch (give --section)\n");
        return 2;
    }
    CameraRequest camera;
    if (auto e = SceneViewOptions(args, po, camera, diags); !e.empty()) {
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

    const bool animation = args.frames > 0 || args.turntable > 0 || !args.views.empty();
    if (animation && camera.Any()) {
        std::fprintf(stderr,
                     "quadrix: error: the camera options cannot be combined with "
                     "--frames, --turntable or --views (docs/batch.md)\n");
        return 2;
    }
    if (animation) {
        // Frames of an animation get the picture defaults of a single picture (docs/batch.md),
        // applied frame by frame by the batch module; --no-shadows and --aa off turn them off.
        ShadeOptions so;
        so.fast = args.fast;
        so.shadows = args.shadows;
        so.aaSamples = args.aa == "default" ? 0 : aaSamples;
        so.linear = NeedsLinear(outputs);
        so.aaMitchell = args.aaFilter == "mitchell";
        so.edges = args.edges;
        so.hatch = args.hatch;
        if (args.phong) so.model = ShadingModel::kPhong;
        return RunAnimation(args, po, engine, so, PictureRequest(args), outputs);
    }

    // One picture: the threads share the heap in huge pages (util/heap_huge_pages.h; an
    // animation's frames keep the threads' own arenas).
    ShareTheHeapWithLaterThreads();
    RenderContext ctx(args.threads);
    ctx.NameHalfSpaces(false);  // a picture, and messages about solids and bodies
    Frame frame;
    RenderReport report;
    ViewRequest view = po.View();
    bool writer = true;  // false on the MPI ranks of --sort-last other than rank 0
    bool ok = ctx.Read(po.Input(), diags);
    MarkPhase("read");
    if (ok && camera.Any()) ok = ApplyCamera(ctx, camera, view, diags);
    ok = ok && ctx.Flatten(view, diags);
    MarkPhase("flatten");
    ShadeOptions so;
    std::string defaultsNote;
    if (ok) {
        so.fast = args.fast;
        // The picture defaults (shade/picture_defaults.h, docs/shading.md): shadows where the
        // scene declares lights, and anti-aliasing, for scenes of at most kPictureDefaultBodies
        // bodies.
        so.shadows = args.shadows;
        so.aaSamples = args.aa == "default" ? 0 : aaSamples;
        defaultsNote = ApplyPictureDefaults(ctx.Flat(), PictureRequest(args), so);
        so.aaMitchell = args.aaFilter == "mitchell";
        so.edges = args.edges;
        so.hatch = args.hatch;
        if (args.phong) so.model = ShadingModel::kPhong;
        so.linear = NeedsLinear(outputs);  // 8-bit files are encoded from the 8-bit pixels
    }
    // With --sort-first the ranks shade their own rows (batch/sort_first.h): `image` comes back.
    std::optional<Image> image;
    ok = ok && RenderMaybeShared(args, outputs, ctx, engine, NeedsImage(outputs) ? &so : nullptr,
                                 frame, image, report, diags, writer);
    MarkPhase("render");
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
    if (NeedsImage(outputs)) {
        if (!defaultsNote.empty())
            std::fprintf(stderr, "quadrix: note: %s\n", defaultsNote.c_str());
        if (!image) image = ctx.Shade(frame, so);
        MarkPhase("shade");
    }
    // A picture alone is written from the Image: the Frame's memory goes back now, and the
    // encoder's buffers are made in its pages, already faulted in, instead of fresh ones (a
    // fresh page costs far more than the write on these virtual machines: docs/performance.md).
    if (image && !NeedsFrame(outputs) && !args.stats) frame = Frame{};
    std::string error;  // the encoders' parallel loops on the context's threads (--threads)
    ctx.InArena([&] { error = WriteOutputs(outputs, frame, image ? &*image : nullptr); });
    MarkPhase("write");
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
