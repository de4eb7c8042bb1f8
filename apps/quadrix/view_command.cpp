// `quadrix view SCENE...`: the interactive window on the exact picture (issue 18,
// docs/viewer.md). This file reads the options, the scene (through the render thread's
// RenderContext) and the script; viewer_window.cpp runs the window, src/quadrix/viewer/ holds
// the camera, the progressive schedule, picking and the script's syntax.
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "commands.h"
#include "quadrix/engines/registry.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/viewer/bench_orbit.h"
#include "quadrix/viewer/camera.h"
#include "quadrix/viewer/render_worker.h"
#include "quadrix/viewer/script.h"
#include "viewer_window.h"

namespace quadrix::cli {

void AddViewCommand(CLI::App& app, ViewArgs& args) {
    CLI::App* cmd = app.add_subcommand(
        "view",
        "Open an interactive window on the exact picture (orbit, pan, zoom, pick, live "
        "reload; docs/viewer.md)");
    cmd->add_option("scenes", args.scenes, "Scene files, read in order")->required();
    cmd->add_option("--size", args.size, "Window size WIDTHxHEIGHT in pixels")
        ->capture_default_str();
    cmd->add_option("--view", args.view, "The scene's view to start from (default: the last one)");
    cmd->add_option("--engine", args.engine,
                    "Rendering engine to start with (" + EngineList() + ")")
        ->capture_default_str();
    cmd->add_option("--threads", args.threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024));
    cmd->add_option("--script", args.script,
                    "Play the events of this file (orbit, zoom, key, click, screenshot, ...; "
                    "docs/viewer.md) and close the window at its end");
    cmd->add_option("--bench", args.bench,
                    "Play a fixed orbit of N full-resolution frames and report frames/s "
                    "(offscreen when there is no display)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--bench-scale", args.benchScale,
                    "With --bench: draw the orbit's frames at 1/S of the resolution (the "
                    "progressive schedule's moving frames), shown stretched to the window")
        ->check(CLI::Range(1, 16));
    cmd->add_flag("--offscreen", args.offscreen, "With --bench: render without a window");
    cmd->add_option("--aa", args.aa,
                    "Anti-aliasing of the still frame, as quadrix render's: off|4|16|64 (default " +
                        std::to_string(kDefaultAaSamples) + " for scenes of at most " +
                        std::to_string(kPictureDefaultBodies) + " bodies, else off)");
    cmd->add_flag("--no-cancel", args.noCancel,
                  "Finish a refining frame even when the view changed meanwhile (to measure "
                  "what cancelling saves)");
    cmd->add_flag("--stats", args.stats,
                  "At exit, print the latency from input events to the first picture of their "
                  "view");
    cmd->add_option("--top", args.top, "Objects to draw from BRL-CAD/OpenSCAD files")
        ->delimiter(',')
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmd->add_flag("--allow-missing", args.allowMissing,
                  "Draw an imported model without the primitives that cannot be drawn, and the "
                  "drawing key's drawing without the freeform surfaces (a warning, not an "
                  "error)");
    cmd->footer(viewer::KeyHelp());
    AddLimitOptions(*cmd, args);
}

int RunView(const ViewArgs& args) {
    if (auto e = ApplyLimits(args); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    ViewerSession session;
    if (auto e = ParseSize(args.size, session.width, session.height); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    EngineRequest engine;
    engine.engine = args.engine;
    if (auto e = RenderContext::CheckEngine(engine); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    session.engine = args.engine;
    int aaSamples = kDefaultAaSamples;
    if (auto e = ParseAaSamples(args.aa, aaSamples); !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 2;
    }
    session.cancelStale = !args.noCancel;
    session.stats = args.stats;
    std::vector<viewer::ScriptEvent> script;
    if (!args.script.empty()) {
        std::string text;
        if (auto why = ReadBoundedFile(args.script, text); !why.empty()) {
            std::fprintf(stderr, "quadrix: error: --script: cannot read '%s': %s\n",
                         args.script.c_str(), why.c_str());
            return 2;
        }
        Diagnostics diags;
        auto parsed = viewer::ParseScript(text, args.script, diags);
        diags.Print(stderr);
        if (!parsed) {
            std::fprintf(stderr, "quadrix: the script has errors; no window opened\n");
            return 2;
        }
        script = std::move(*parsed);
        session.script = &script;
    }
    for (const std::string& s : args.scenes)
        if (s == "-") {
            std::fprintf(stderr,
                         "quadrix: error: quadrix view reads files, not standard input "
                         "(it watches them for changes)\n");
            return 2;
        }
    const bool offscreen =
        args.bench > 0 && (args.offscreen || !HaveViewerWindow() ||
                           (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")));
    if (!offscreen && !HaveViewerWindow()) return RunViewerWindow(session);  // the error

    InputRequest input;
    input.paths = args.scenes;
    input.topObjects = args.top;
    input.allowMissing = args.allowMissing;
    viewer::RenderWorker worker(input, args.threads, [] { WakeViewerWindow(); });
    viewer::LoadOutcome load = worker.Load();
    std::fputs(load.messages.c_str(), stderr);
    if (!load.ok) {
        std::fprintf(stderr, "quadrix: the scene has errors; no window opened\n");
        return 1;
    }
    if (auto e = worker.InitialCamera(args.view, session.width, session.height, session.camera,
                                      session.sphere);
        !e.empty()) {
        std::fprintf(stderr, "quadrix: error: %s\n", e.c_str());
        return 1;
    }
    if (offscreen) {
        const viewer::BenchResult r =
            viewer::RunBenchOrbit(worker, session.camera, session.width, session.height,
                                  args.engine, args.bench, args.benchScale);
        if (!r.error.empty()) {
            std::fputs(r.error.c_str(), stderr);
            return 1;
        }
        std::fputs(
            viewer::FormatBench(r, session.width, session.height, args.engine, "offscreen").c_str(),
            stdout);
        return 0;
    }
    // The picture defaults of quadrix render: anti-aliasing unless asked otherwise, but not by
    // default for scenes of many bodies (their sub-pixel rays are not pruned).
    const std::size_t bodies = worker.BodyCount();
    if (args.aa == "default" && bodies > kPictureDefaultBodies) {
        aaSamples = 0;
        std::fprintf(stderr,
                     "quadrix: note: %zu bodies: no default anti-aliasing (--aa N asks for it)\n",
                     bodies);
    }
    session.aaSamples = aaSamples;
    session.worker = &worker;
    session.files = load.files;
    session.name = args.scenes.front();
    session.benchFrames = args.bench;
    session.benchScale = args.benchScale;
    return RunViewerWindow(session);
}

}  // namespace quadrix::cli
