// quadrix_bench: the benchmark suite of issue 8. One command (bench/run.sh) runs it.
//
// For every scene and image size it measures, side by side in the same run:
//   * each Quadrix engine in process: frame time after one warm-up render, median of several;
//   * the whole `quadrix render` process (read, flatten, render, shade, PNG), median, with the
//     picture defaults (anti-aliasing, shadows) and with `--aa off`, and its phases (start-up,
//     read, flatten, render, shade, encode, write, exit: io/phase_times.h);
//   * POV-Ray 3.7 on the exported scene (`quadrix export --to pov`, 2 threads), whole process,
//     without anti-aliasing and (at 1280×720) with it, alternating with the Quadrix process runs
//     so both see the same machine state;
// and writes a Markdown table with ratios and a CSV to the output directory. Nothing is asserted:
// benchmarks report, they do not fail on time. Every in-process frame, shading and anti-aliasing
// goes through the render context (pipeline/render_context.h), the one render path: the suite
// assembles no stages itself.
#include <fcntl.h>
#include <fmt/format.h>
#include <malloc.h>
#include <sched.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "draw_sheet.h"
#include "quadrix/engines/engine.h"
#include "quadrix/engines/isocurve/isocurve_engine.h"
#include "quadrix/engines/isocurve/render.h"
#include "quadrix/engines/registry.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/shade/antialias.h"
#include "quadrix/shade/picture_defaults.h"
#include "quadrix/shade/section_hatch.h"
#include "scenes.h"
#include "viewer_orbit.h"

extern char** environ;

namespace quadrix::bench {
namespace {

// Whether --only selects scene `name`: its text anywhere in the name, or with a trailing '$' the
// whole name ("spheres10000$" is not "spheres100000").
bool Selected(const std::string& name, const std::string& only) {
    if (only.empty()) return true;
    if (only.back() == '$') return name == only.substr(0, only.size() - 1);
    return name.find(only) != std::string::npos;
}

// The machine every result was measured on (issue 24: these VMs change CPU between sessions):
// the CPU model from /proc/cpuinfo, the core count and the load average when the run began.
std::string MachineLine() {
    std::string model = "unknown CPU";
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);) {
        if (line.rfind("model name", 0) != 0) continue;
        if (auto colon = line.find(':'); colon != std::string::npos) {
            model = line.substr(colon + 1);
            model.erase(0, model.find_first_not_of(" \t"));
        }
        break;
    }
    double load[3] = {0, 0, 0};
    if (getloadavg(load, 3) < 0) load[0] = load[1] = load[2] = -1;
    return fmt::format("{}, {} hardware threads, load average {:.2f} {:.2f} {:.2f}", model,
                       sysconf(_SC_NPROCESSORS_ONLN), load[0], load[1], load[2]);
}

struct ProcessRun {
    double seconds = 0;
    double peakMiB = 0;
    int exitCode = -1;
    long long startNs = 0, endNs = 0;  // steady clock before posix_spawn and after wait4
};

long long SteadyNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// Runs argv with stdout to /dev/null and stderr to `stderrPath` (/dev/null when empty); wall
// time and the child's peak RSS. `env` entries (NAME=VALUE) are added to the environment.
ProcessRun Spawn(const std::vector<std::string>& argv, const std::string& stderrPath = "",
                 const std::vector<std::string>& env = {}) {
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    std::vector<char*> envp;
    for (char** e = environ; *e; ++e) envp.push_back(*e);
    for (const auto& e : env) envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2,
                                     stderrPath.empty() ? "/dev/null" : stderrPath.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ProcessRun r;
    r.startNs = SteadyNs();
    pid_t pid;
    if (posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), envp.data()) != 0) {
        posix_spawn_file_actions_destroy(&actions);
        return r;
    }
    int status = 0;
    struct rusage usage {};
    wait4(pid, &status, 0, &usage);
    r.endNs = SteadyNs();
    r.seconds = 1e-9 * static_cast<double>(r.endNs - r.startNs);
    r.peakMiB = usage.ru_maxrss / 1024.0;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    posix_spawn_file_actions_destroy(&actions);
    return r;
}

// The phases of one `quadrix render` process (ms), from the line QUADRIX_PHASE_TIMES makes it
// print (io/phase_times.h) and the suite's own clock readings around the spawn: start-up (spawn →
// main: exec, the dynamic loader, static initialisers), cli (main → the render command), read,
// flatten, render, shade (anti-aliasing included), encode, write (temporary file, fsync,
// rename, and the --stats report when asked), exit (the last mark → reaped: freeing, unmapping, the
// kernel's teardown). Empty when the line is missing.
const std::vector<std::string> kPhases = {"start-up", "cli",    "read",  "flatten", "render",
                                          "shade",    "encode", "write", "exit"};
std::vector<double> ParsePhases(const std::string& stderrPath, const ProcessRun& run) {
    std::ifstream in(stderrPath);
    std::map<std::string, long long> mark;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("quadrix phases:", 0) != 0) continue;
        std::istringstream words(line.substr(15));
        for (std::string w; words >> w;)
            if (auto eq = w.find('='); eq != std::string::npos)
                mark[w.substr(0, eq)] = std::atoll(w.c_str() + eq + 1);
    }
    for (const char* need : {"main", "start", "read", "flatten", "render", "exit"})
        if (!mark.count(need)) return {};
    if (!mark.count("shade")) mark["shade"] = mark["render"];
    if (!mark.count("encode")) mark["encode"] = mark["shade"];
    const long long points[] = {run.startNs,     mark["main"],   mark["start"], mark["read"],
                                mark["flatten"], mark["render"], mark["shade"], mark["encode"],
                                mark["exit"],    run.endNs};
    std::vector<double> ms;
    for (std::size_t i = 0; i + 1 < std::size(points); ++i)
        ms.push_back(1e-6 * static_cast<double>(points[i + 1] - points[i]));
    return ms;
}

// A spawned child's peak resident set (wait4's ru_maxrss) starts from the high-water mark of the
// memory of the process that spawned it (posix_spawn shares the parent's memory until exec, and
// Linux records that memory's peak at exec). So before spawning, the suite returns freed memory
// to the system and resets its own high-water mark (/proc/self/clear_refs, "5"); a child's peak
// is then max(its own, the suite's resident set at that moment), which is returned (MiB) and
// reported as the floor under which a peak means nothing.
double ResetPeakRss() {
    malloc_trim(0);
    if (FILE* f = std::fopen("/proc/self/clear_refs", "w")) {
        std::fputs("5", f);
        std::fclose(f);
    }
    double rssMiB = 0;
    if (FILE* f = std::fopen("/proc/self/status", "r")) {
        char line[256];
        while (std::fgets(line, sizeof line, f))
            if (std::strncmp(line, "VmRSS:", 6) == 0) rssMiB = std::atof(line + 6) / 1024.0;
        std::fclose(f);
    }
    return rssMiB;
}

double Median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct Size {
    int w, h;
};

// Reads and flattens a scene file for one image size in the render context (the one render path,
// pipeline/render_context.h), as `quadrix render FILE --size WxH` does. false (diagnostics
// printed) when the scene has errors.
bool Prepare(RenderContext& ctx, const std::string& path, Size size) {
    PipelineOptions po;
    po.scenePaths = {path};
    po.width = size.w;
    po.height = size.h;
    Diagnostics diags;
    const bool ok = ctx.Read(po.Input(), diags) && ctx.Flatten(po.View(), diags);
    if (!ok || diags.HasErrors()) {
        diags.Print(stderr);
        return false;
    }
    return true;
}

// One frame of `engine` through the context (composition included); milliseconds, or -1 when the
// context refuses (diagnostics printed).
double RenderMs(RenderContext& ctx, const EngineRequest& request, Frame& frame,
                RenderReport* reportOut = nullptr) {
    RenderReport report;
    Diagnostics diags;
    const auto t0 = std::chrono::steady_clock::now();
    const bool ok = ctx.Render(request, frame, report, diags);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!ok) {
        diags.Print(stderr);
        return -1;
    }
    if (reportOut) *reportOut = std::move(report);
    return ms;
}

struct Row {
    std::string scene;
    int primitives = 0;
    Size size{};
    std::vector<std::pair<std::string, double>> engineMs;  // in-process frame time per engine
    // Per engine: percentage of pixels whose coverage differs from raycast's (the exact
    // reference); an engine that skips what it cannot draw shows it here instead of looking fast.
    std::vector<double> engineDiffPct;
    // Per engine: solids the context gave to raycast because the engine cannot draw them
    // (composition, pipeline/render_context.h); its frame time includes raycast's share.
    std::vector<std::size_t> engineComposed;
    double flattenMs = 0;
    // `quadrix render` with the picture defaults (shade/picture_defaults.h) and with --aa off.
    double quadrixProcessMs = 0, quadrixPeakMiB = 0, quadrixNoAaMs = 0;
    bool defaultAa = false, defaultShadows = false;  // what the defaults gave this scene
    std::vector<double> phasesMs;                    // medians per kPhases, default picture
    // POV-Ray without anti-aliasing (every size) and with it (+A0.3 +AM1 +R2 -J, 1280×720 only).
    double povProcessMs = 0, povPeakMiB = 0, povAaMs = 0;
    bool povTimedOut = false;
    // --baseline: another quadrix binary (e.g. the build before a change), timed in the same
    // rounds as this one, picture defaults, and its phases when it prints them.
    double baselineMs = 0;
    std::vector<double> baselinePhasesMs;
    double benchFloorMiB = 0;  // the suite's own resident set when the processes ran
    bool povOk = false;
};

// POV-Ray runs longer than this are stopped (timeout(1)); the ratio is then a lower bound.
constexpr int kPovTimeLimitSeconds = 600;

std::string Ratio(double slow, double fast) {
    if (slow <= 0 || fast <= 0) return "–";
    return fmt::format("{:.1f}×", slow / fast);
}

// Issue 6: the isocurve engine's extraction and drawing time per tea-set model and tolerance, at
// 1024×1024 (teapot view of docs/isocurve.md). The tolerance is given as the screen gap between
// adjacent isocurves (δ = gap / pixels-per-unit; render.h); median of `reps` runs.
std::string IsocurveTable(const std::string& sourceDir, int reps) {
    std::string out =
        "\n## Isocurve engine: extraction and drawing per model and tolerance "
        "(1024×1024)\n\n"
        "| model | patches | gap px | δ (world) | curves | extraction ms | drawing ms "
        "| pixels drawn | redundancy |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const char* model : {"teapot", "teacup", "teaspoon"}) {
        // The scene read and flattened by the render context; the drawer's two phases
        // (extraction, drawing) are timed apart here, which the context's Render does not show.
        PipelineOptions po;
        po.sceneText = fmt::format(
            "patches m \"{}/src/quadrix/import/freeform/testdata/newell/{}.txt\" newell =rx -90;\n"
            "view v dop .5 .8 -1;\n",
            sourceDir, model);
        po.width = po.height = 1024;
        RenderContext ctx;
        Diagnostics diags;
        if (!ctx.Read(po.Input(), diags) || !ctx.Flatten(po.View(), diags)) {
            diags.Print(stderr);
            continue;
        }
        const auto drawables = isocurve::SceneDrawables(ctx.Flat());
        for (double gap : {4.0, 2.0, 1.0, 0.5}) {
            isocurve::IsocurveOptions o;
            o.pixelSpacing = gap;
            std::vector<double> ex, dr;
            isocurve::IsocurveStats st;
            for (int i = 0; i < reps; ++i) {
                Frame frame(1024, 1024);
                st = isocurve::RenderFreeform(drawables, ctx.Flat().projection, o, frame);
                ex.push_back(st.extractSeconds * 1e3);
                dr.push_back(st.drawSeconds * 1e3);
            }
            out += fmt::format("| {} | {} | {} | {:.4g} | {} | {:.1f} | {:.1f} | {} | {:.2f} |\n",
                               model, drawables.size(), gap, st.delta, st.curves, Median(ex),
                               Median(dr), st.raster.pixelsDrawn, st.raster.Redundancy());
        }
        std::fprintf(stderr, "isocurve %s done\n", model);
    }
    return out;
}

// Issue 17: the cost of anti-aliasing (shade/antialias.h) per scene at 1280×720: the in-process
// raycast frame plus plain shading, against the same plus the edge pixels' sub-pixel samples at
// 4, 16 and 64 (median of `reps`); and the edge test alone (shade/edge_pixels.h, with the
// shading jumps of the plain picture), which the anti-aliasing pass begins with. Scenes of more
// than 256 bodies are left out here (64 samples per edge pixel of 10,000 spheres at 1280×720 is
// long); RayIndexTable measures those.
std::string AntialiasTable(const std::vector<BenchScene>& scenes, const std::string& outDir,
                           const std::string& only, int reps) {
    std::string out =
        "\n## Anti-aliasing cost (1280×720, raycast frame + shading, median)\n\n"
        "| scene | edge pixels | edge test ms | plain ms | --aa 4 | --aa 16 | --aa 64 |\n"
        "|---|---|---|---|---|---|---|\n";
    for (const BenchScene& scene : scenes) {
        if (!Selected(scene.name, only)) continue;
        RenderContext ctx;
        if (!Prepare(ctx, outDir + "/scenes/" + scene.name + ".uq", {1280, 720}) ||
            ctx.Flat().bodies.size() > 256)
            continue;
        const EngineRequest raycast;
        auto timed = [&](int samples, std::size_t* edges) {
            std::vector<double> ms;
            for (int i = 0; i < reps; ++i) {
                const auto t0 = std::chrono::steady_clock::now();
                Frame frame;
                RenderMs(ctx, raycast, frame);
                ShadeOptions so;
                so.aaSamples = samples;
                Image img = ctx.Shade(frame, so);
                ms.push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count());
                if (edges) {  // the pixels Antialias re-renders (shade/antialias.h), counted
                    ShadeOptions plain;
                    const std::vector<std::uint8_t> marked =
                        FindEdgesAndShadingJumps(frame, ctx.Shade(frame, plain));
                    *edges = static_cast<std::size_t>(
                        std::count_if(marked.begin(), marked.end(), [](auto m) { return m != 0; }));
                }
            }
            return Median(ms);
        };
        std::size_t edges = 0;
        const double plain = timed(0, nullptr);
        const double a4 = timed(4, &edges), a16 = timed(16, nullptr), a64 = timed(64, nullptr);
        std::vector<double> edgeMs;
        {
            Frame frame;
            RenderMs(ctx, raycast, frame);
            const Image image = ctx.Shade(frame, ShadeOptions{});
            for (int i = 0; i < reps; ++i) {
                const auto t0 = std::chrono::steady_clock::now();
                const std::vector<std::uint8_t> marked = FindEdgesAndShadingJumps(frame, image);
                edgeMs.push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count());
            }
        }
        out += fmt::format(
            "| {} | {} | {:.2f} | {:.1f} | {:.1f} ms ({:.2f}×) | {:.1f} ms ({:.2f}×) | "
            "{:.1f} ms ({:.2f}×) |\n",
            scene.name, edges, Median(edgeMs), plain, a4, a4 / plain, a16, a16 / plain, a64,
            a64 / plain);
        std::fprintf(stderr, "antialias %s done\n", scene.name.c_str());
    }
    return out;
}

// Issue 18: the cost of hatching the section's cut faces (shade/section_hatch.h) at 1280×720:
// the machined part seen obliquely, cut by the plane through its centre facing the view (as the
// viewer's X makes it); one raycast Frame, shaded plain and with --hatch, and the hatch step
// alone (median of `reps`).
std::string HatchTable(const std::string& sourceDir, int reps) {
    RenderContext ctx;
    PipelineOptions po;
    po.scenePaths = {sourceDir + "/examples/machined_part.uq"};
    po.width = 1280;
    po.height = 720;
    // The scene's view's dop (.9 1.1 -1.3) points toward the viewer: the plane through the
    // part's centre (0 10 0) facing it keeps the far side.
    const Vec3 n = Normalize(Vec3{0.9, 1.1, -1.3});
    po.section = Plane{n.x, n.y, n.z, -10 * n.y};
    Diagnostics diags;
    if (!ctx.Read(po.Input(), diags) || !ctx.Flatten(po.View(), diags)) {
        diags.Print(stderr);
        return {};
    }
    Frame frame;
    RenderMs(ctx, EngineRequest{}, frame);
    std::size_t cap = 0;
    for (auto id : frame.surface) cap += id == ctx.Flat().sectionHalfSpace;
    auto timed = [&](auto&& f) {
        std::vector<double> ms;
        for (int i = 0; i < reps; ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            f();
            ms.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count());
        }
        return Median(ms);
    };
    ShadeOptions plain, hatched;
    hatched.hatch = true;
    Image image = ctx.Shade(frame, plain);
    std::size_t lines = 0;
    const double a = timed([&] { image = ctx.Shade(frame, plain); });
    const double b = timed([&] { image = ctx.Shade(frame, hatched); });
    const double c = timed([&] { lines = HatchSection(frame, ctx.Flat(), hatched, image); });
    std::fprintf(stderr, "hatch done\n");
    return fmt::format(
        "\n## Section hatching cost (machined part, 1280×720, raycast frame, median)\n\n"
        "| cut pixels | hatch pixels | shade ms | shade + hatch ms | hatch alone ms |\n"
        "|---|---|---|---|---|\n| {} | {} | {:.2f} | {:.2f} ({:.2f}×) | {:.2f} |\n",
        cap, lines, a, b, b / a, c);
}

// The box trees of the shadow and sample rays (math/box_tree.h): shading with shadows, and
// --aa 4, with the trees (ShadeOptions::spatialIndex) and without them (every solid and child
// box-tested per ray, as before), same frame, same run, at 640×360 (median of `reps`; one run
// without trees above 2,000 bodies, where it takes tens of seconds). The pictures are the same.
std::string RayIndexTable(const std::vector<BenchScene>& scenes, const std::string& outDir,
                          const std::string& only, int reps) {
    std::string out =
        "\n## Shadow and sample rays with and without box trees (640×360, shading after the "
        "raycast frame, median)\n\n"
        "| scene | bodies | frame ms | plain shade ms | shadows: no trees | shadows: trees | "
        "gain | --aa 4: no trees | --aa 4: trees | gain |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const BenchScene& scene : scenes) {
        if (!Selected(scene.name, only)) continue;
        if (scene.name.find("spheres") == std::string::npos &&
            scene.name.find("machined") == std::string::npos)
            continue;
        RenderContext ctx;
        // Above kPictureDefaultBodies (100,000 spheres) the rays without trees take many minutes.
        if (!Prepare(ctx, outDir + "/scenes/" + scene.name + ".uq", {640, 360}) ||
            ctx.Flat().bodies.size() > kPictureDefaultBodies)
            continue;
        Frame frame;
        std::vector<double> frameMs;
        for (int i = 0; i < reps; ++i) frameMs.push_back(RenderMs(ctx, EngineRequest{}, frame));
        const bool big = ctx.Flat().bodies.size() > 2000;
        auto timed = [&](bool shadows, int aa, bool index) {
            std::vector<double> ms;
            for (int i = 0; i < (big && !index ? 1 : reps); ++i) {
                const auto t0 = std::chrono::steady_clock::now();
                ShadeOptions so;
                so.shadows = shadows;
                so.aaSamples = aa;
                so.spatialIndex = index;
                Image img = ctx.Shade(frame, so);
                ms.push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count());
            }
            return Median(ms);
        };
        const double plain = timed(false, 0, true);
        const double sOff = timed(true, 0, false), sOn = timed(true, 0, true);
        const double aOff = timed(false, 4, false), aOn = timed(false, 4, true);
        out += fmt::format(
            "| {} | {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f}× | {:.1f} | {:.1f} | {:.1f}× "
            "|\n",
            scene.name, ctx.Flat().bodies.size(), Median(frameMs), plain, sOff, sOn, sOff / sOn,
            aOff, aOn, aOff / aOn);
        std::fprintf(stderr, "ray index %s done\n", scene.name.c_str());
    }
    return out;
}

// Issue 24 item 5: the raycast frame on one thread and on two (warm, in process): the machined
// part and the 10,000 spheres at 1280×720 and 1920×1080. The one-thread frames run on CPU 0 and
// on CPU 1 in turn (on a helper thread pinned to each): the two virtual CPUs of these machines are
// not always equally fast (one took 18 ms a frame while the other took 13, docs/performance.md), so
// the two-thread frame is also compared with the best two threads could do at the CPUs' own
// speeds, 1 / (1/t₀ + 1/t₁). The three take turns, a few frames at a time, so that they see
// the same minutes. The frames are the same bits (the engine's tests); only the time differs.
std::string ThreadsTable(const std::vector<BenchScene>& scenes, const std::string& outDir,
                         const std::string& only, int reps) {
    std::string out =
        "\n## The raycast frame on one thread and on two (warm, in process, in turns; "
        "min / median ms)\n\n";
    cpu_set_t all;
    if (sched_getaffinity(0, sizeof all, &all) != 0 || !CPU_ISSET(0, &all) || !CPU_ISSET(1, &all))
        return out + "Not measured: this process may not run on CPUs 0 and 1.\n";
    // One run: an untimed frame, then kRun frames back to back (as a viewer's or a batch's are),
    // their times appended to `ms`.
    constexpr int kRun = 4;
    auto timedRun = [](RenderContext& ctx, Frame& frame, std::vector<double>& ms) {
        if (RenderMs(ctx, EngineRequest{}, frame) < 0) return false;
        for (int i = 0; i < kRun; ++i) ms.push_back(RenderMs(ctx, EngineRequest{}, frame));
        return true;
    };
    // A run of one-thread frames on a thread of its own pinned to `cpu` (the context of one
    // thread runs its work on the calling thread); this thread's affinity, and so oneTBB's, is
    // left alone.
    auto runOnCpu = [&](int cpu, RenderContext& ctx, Frame& frame, std::vector<double>& ms) {
        bool ok = false;
        std::thread t([&] {
            cpu_set_t one;
            CPU_ZERO(&one);
            CPU_SET(cpu, &one);
            ok = sched_setaffinity(0, sizeof one, &one) == 0 && timedRun(ctx, frame, ms);
        });
        t.join();
        return ok;
    };
    out +=
        "| scene | size | one thread, CPU 0 | one thread, CPU 1 | two threads | two / one "
        "(faster CPU) | two / the CPUs' combined speed |\n|---|---|---|---|---|---|---|\n";
    for (const BenchScene& scene : scenes) {
        if (!Selected(scene.name, only)) continue;
        if (scene.name != "machined_part" && scene.name != "spheres10000") continue;
        for (const Size size : {Size{1280, 720}, Size{1920, 1080}}) {
            RenderContext one(1), two(2);
            const std::string path = outDir + "/scenes/" + scene.name + ".uq";
            if (!Prepare(one, path, size) || !Prepare(two, path, size)) continue;
            Frame a, b;
            std::vector<double> ms0, ms1, ms2;
            bool ok = true;
            for (int i = 0; ok && i < std::max(1, reps / kRun); ++i)
                ok = runOnCpu(0, one, a, ms0) && runOnCpu(1, one, a, ms1) && timedRun(two, b, ms2);
            if (!ok) {
                out += fmt::format(
                    "| {} | {}×{} | not measured (a frame or the pinning failed) "
                    "| | | | |\n",
                    scene.name, size.w, size.h);
                continue;
            }
            const double t0 = Median(ms0), t1 = Median(ms1), t2 = Median(ms2);
            auto cell = [](const std::vector<double>& ms) {
                return fmt::format("{:.2f} / {:.2f}", *std::min_element(ms.begin(), ms.end()),
                                   Median(ms));
            };
            out += fmt::format("| {} | {}×{} | {} | {} | {} | {:.2f}× | {:.2f} |\n", scene.name,
                               size.w, size.h, cell(ms0), cell(ms1), cell(ms2),
                               std::min(t0, t1) / t2, 1.0 / (1.0 / t0 + 1.0 / t1) / t2);
        }
        std::fprintf(stderr, "threads %s done\n", scene.name.c_str());
    }
    return out;
}

// Issue 24 item 6: where the time of a whole `quadrix render SCENE --size WxH -o x.png` process
// goes (picture defaults), phase by phase (median of the runs; ParsePhases says what each is).
std::string PhaseTable(const std::vector<Row>& rows, const std::string& machine) {
    std::string out = fmt::format(
        "\n## Whole process, phase by phase (`quadrix render … -o x.png`, picture defaults, "
        "median ms)\n\nMachine: {}. start-up = spawn → main (exec, dynamic loader, static "
        "initialisers); cli = main → the render command; shade includes anti-aliasing and "
        "shadows; write = temporary file and rename (fsync only with QUADRIX_FSYNC=1); exit = "
        "the last mark → reaped (io/phase_times.h).\n\n| scene | size |",
        machine);
    for (const std::string& ph : kPhases) out += " " + ph + " |";
    out += " sum | process |\n|---|---|";
    for (std::size_t k = 0; k < kPhases.size(); ++k) out += "---|";
    out += "---|---|\n";
    for (const Row& r : rows) {
        if (r.phasesMs.size() != kPhases.size()) continue;
        out += fmt::format("| {} | {}×{} |", r.scene, r.size.w, r.size.h);
        double sum = 0;
        for (double ms : r.phasesMs) {
            out += fmt::format(" {:.2f} |", ms);
            sum += ms;
        }
        out += fmt::format(" {:.1f} | {:.1f} |\n", sum, r.quadrixProcessMs);
    }
    return out;
}

// --baseline: the same processes by the other binary, in the same rounds (before → after).
std::string BaselineTable(const std::vector<Row>& rows, const std::string& before,
                          const std::string& after) {
    std::string out = fmt::format(
        "\n## Before ({}) and after ({}), whole process, picture defaults (median ms, same "
        "rounds)\n\n| scene | size | before | after | before / after |",
        before, after);
    for (const std::string& ph : kPhases) out += " " + ph + " before → after |";
    out += "\n|---|---|---|---|---|";
    for (std::size_t k = 0; k < kPhases.size(); ++k) out += "---|";
    out += "\n";
    for (const Row& r : rows) {
        if (r.baselineMs <= 0) continue;
        out += fmt::format("| {} | {}×{} | {:.1f} | {:.1f} | {} |", r.scene, r.size.w, r.size.h,
                           r.baselineMs, r.quadrixProcessMs,
                           fmt::format("{:.2f}×", r.baselineMs / r.quadrixProcessMs));
        for (std::size_t k = 0; k < kPhases.size(); ++k)
            out += k < r.baselinePhasesMs.size() && k < r.phasesMs.size()
                       ? fmt::format(" {:.2f} → {:.2f} |", r.baselinePhasesMs[k], r.phasesMs[k])
                       : std::string(" – |");
        out += "\n";
    }
    return out;
}

// Growth of every engine's frame time: with pixels (each scene, smallest to largest size) and
// with primitives (each family of scenes, e.g. spheres100 → spheres10000, at each size), as
// exponents of power laws, time ∝ n^e, and as the factor per doubling, 2^e. e ≈ 1 for pixels and
// e < 1 for primitives mean cost ∝ pixels + covered area, not their product. Frames of an engine
// that did not draw the whole scene (coverage ≠ raycast's on > 0.5 % of pixels) or was skipped
// are left out.
std::string Scaling(const std::vector<Row>& rows) {
    auto frameMs = [](const Row& r, std::size_t e) {
        if (e >= r.engineMs.size() || r.engineDiffPct[e] > 0.5) return -1.0;
        return r.engineMs[e].second;
    };
    auto familyOf = [](const std::string& name) {
        std::size_t e = name.size();
        while (e > 0 && std::isdigit(static_cast<unsigned char>(name[e - 1]))) --e;
        return name.substr(0, e);
    };
    const std::size_t engines = rows.empty() ? 0 : rows[0].engineMs.size();
    std::string out = "\n## Scaling with pixels\n\n";
    out +=
        "| engine | scene | from | to | pixels × | time × | exponent | × per doubling |\n"
        "|---|---|---|---|---|---|---|---|\n";
    for (std::size_t e = 0; e < engines; ++e) {
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const Row* lo = &rows[i];
            if (i > 0 && rows[i - 1].scene == lo->scene) continue;  // first row of each scene
            const Row* hi = nullptr;
            for (std::size_t j = i; j < rows.size() && rows[j].scene == lo->scene; ++j)
                if (frameMs(rows[j], e) > 0) hi = &rows[j];
            if (!hi || hi == lo || frameMs(*lo, e) <= 0) continue;
            const double px = double(hi->size.w) * hi->size.h / (double(lo->size.w) * lo->size.h);
            const double t = frameMs(*hi, e) / frameMs(*lo, e);
            const double ex = std::log(t) / std::log(px);
            out += fmt::format("| {} | {} | {}×{} | {}×{} | {:.1f} | {:.2f} | {:.2f} | {:.2f} |\n",
                               lo->engineMs[e].first, lo->scene, lo->size.w, lo->size.h, hi->size.w,
                               hi->size.h, px, t, ex, std::pow(2.0, ex));
        }
    }
    out +=
        "\n## Scaling with primitives\n\n"
        "| engine | size | from | to | primitives × | time × | exponent | × per doubling |\n"
        "|---|---|---|---|---|---|---|---|\n";
    for (std::size_t e = 0; e < engines; ++e) {
        for (const Row& a : rows) {
            const std::string fam = familyOf(a.scene);
            if (fam == a.scene || frameMs(a, e) <= 0) continue;
            bool smallest = true;
            const Row* best = nullptr;
            for (const Row& b : rows) {
                if (familyOf(b.scene) != fam || b.size.w != a.size.w || b.size.h != a.size.h)
                    continue;
                if (b.primitives < a.primitives && frameMs(b, e) > 0) smallest = false;
                if (b.primitives > a.primitives && frameMs(b, e) > 0 &&
                    (!best || b.primitives > best->primitives))
                    best = &b;
            }
            if (!best || !smallest) continue;
            const double n = double(best->primitives) / a.primitives;
            const double t = frameMs(*best, e) / frameMs(a, e);
            const double ex = std::log(t) / std::log(n);
            out += fmt::format("| {} | {}×{} | {} | {} | {:.0f} | {:.2f} | {:.2f} | {:.2f} |\n",
                               a.engineMs[e].first, a.size.w, a.size.h, a.scene, best->scene, n, t,
                               ex, std::pow(2.0, ex));
        }
    }
    // The sum-of-products explosion: A − B1∩C1 − … − Bk∩Ck has 2^k products in sum-of-products
    // form; the default engine evaluates the tree as it is, so its time per frame should grow
    // linearly (or less) with k.
    out +=
        "\n## Sum-of-products explosion (A − B1∩C1 − … − Bk∩Ck), default engine\n\n"
        "| size | k | primitives | products in SOP form | frame ms | ms per primitive |\n"
        "|---|---|---|---|---|---|\n";
    for (const Row& r : rows) {
        if (familyOf(r.scene) != "sop" || frameMs(r, 0) <= 0) continue;
        const int k = (r.primitives - 1) / 2;
        out += fmt::format("| {}×{} | {} | {} | 2^{} | {:.1f} | {:.3f} |\n", r.size.w, r.size.h, k,
                           r.primitives, k, frameMs(r, 0), frameMs(r, 0) / r.primitives);
    }
    return out;
}

}  // namespace
}  // namespace quadrix::bench

int main(int argc, char** argv) {
    using namespace quadrix;
    using namespace quadrix::bench;
    CLI::App app{"Quadrix benchmark suite (issue 8): engines vs each other and vs POV-Ray"};
    std::string outDir = "bench/results", quadrixBin = "build/quadrix", sourceDir = ".";
    std::string baselineBin;
    bool quick = false, noPov = false, noProcess = false;
    int reps = 5, povReps = 3, threads = 0;
    std::string sizeList;
    std::string only, engineList;
    app.add_option("--out", outDir, "Directory for results and generated scenes");
    app.add_option("--quadrix", quadrixBin, "The quadrix binary to time as a whole process");
    app.add_option("--baseline", baselineBin,
                   "Another quadrix binary (before a change) timed in the same rounds: a "
                   "before/after table");
    app.add_option("--source", sourceDir, "Source tree (for examples/)");
    app.add_flag("--quick", quick, "Small subset: one size, fewer repetitions");
    app.add_flag("--no-pov", noPov, "Do not run POV-Ray");
    app.add_option("--reps", reps, "Repetitions of Quadrix measurements (median)");
    app.add_option("--pov-reps", povReps,
                   "Repetitions of POV-Ray runs (median; 1 for slow scenes)");
    app.add_option("--only", only,
                   "Run only scenes whose name contains this text (ending in '$': is exactly it)");
    app.add_option("--sizes", sizeList,
                   "Comma-separated image sizes WxH (default: the suite's three)");
    app.add_option("--threads", threads, "Worker threads for in-process frames (0 = all cores)");
    app.add_flag("--no-process", noProcess,
                 "Time in-process frames only (no whole processes, no POV-Ray)");
    std::vector<std::string> engineOpts;
    app.add_option("--engine-opt", engineOpts,
                   "ENGINE:KEY=VALUE, an engine option for the in-process frames (repeatable), "
                   "e.g. raycast:batch=off");
    app.add_option("--engines", engineList,
                   "Comma-separated engines to time in process (default: all; raycast is always "
                   "run as the coverage reference)");
    CLI11_PARSE(app, argc, argv);

    // Engine options, checked before any work: ENGINE:KEY=VALUE with a known engine that takes it.
    std::map<std::string, std::map<std::string, std::string>> optionsOf;
    for (const std::string& opt : engineOpts) {
        const auto colon = opt.find(':'), eq = opt.find('=');
        if (colon == std::string::npos || eq == std::string::npos || eq < colon) {
            std::fprintf(stderr, "error: --engine-opt '%s' is not ENGINE:KEY=VALUE\n", opt.c_str());
            return 2;
        }
        const std::string engineName = opt.substr(0, colon);
        if (!FindEngine(engineName)) {
            std::fprintf(stderr, "error: --engine-opt '%s': no engine '%s'\n", opt.c_str(),
                         engineName.c_str());
            return 2;
        }
        optionsOf[engineName][opt.substr(colon + 1, eq - colon - 1)] = opt.substr(eq + 1);
    }
    for (const auto& [engineName, options] : optionsOf) {
        EngineRequest request;
        request.engine = engineName;
        request.options = options;
        if (std::string err = RenderContext::CheckEngine(request); !err.empty()) {
            std::fprintf(stderr, "error: %s\n", err.c_str());
            return 2;
        }
    }

    std::filesystem::create_directories(outDir + "/scenes");
    std::vector<BenchScene> scenes = {
        FromFile("machined_part", sourceDir + "/examples/machined_part.uq"),
        TwoCylinders('|'),
        TwoCylinders('-'),
        TwoCylinders('&'),
        FromFile("stack_of_bundles", sourceDir + "/examples/stack_of_bundles.uq"),
        FromFile("quartics", sourceDir + "/examples/quartics.uq"),
        MiteredKnot(36),
        SpheresMinusCylinder(100),
        SpheresMinusCylinder(1000),
        SpheresMinusCylinder(10000),
        SpheresMinusCylinder(10000, /*distributed=*/true),
        SpheresMinusCylinder(100000),
        SumOfProductsExplosion(8),
        SumOfProductsExplosion(16),
        SumOfProductsExplosion(32),
        SumOfProductsExplosion(64),
    };
    std::vector<Size> sizes = {{512, 512}, {1280, 720}, {1920, 1080}, {3840, 2160}};
    if (quick) {
        sizes = {{1280, 720}};
        reps = std::min(reps, 3);
        povReps = 1;
    }
    if (!sizeList.empty()) {
        sizes.clear();
        std::stringstream ss(sizeList);
        std::string item;
        while (std::getline(ss, item, ',')) {
            Size sz{};
            if (std::sscanf(item.c_str(), "%dx%d", &sz.w, &sz.h) != 2 || sz.w <= 0 || sz.h <= 0 ||
                sz.w > 16384 || sz.h > 16384) {
                std::fprintf(stderr, "error: --sizes: '%s' is not WIDTHxHEIGHT\n", item.c_str());
                return 2;
            }
            sizes.push_back(sz);
        }
    }
    if (noProcess) noPov = true;
    bool havePov = !noPov && std::system("command -v povray >/dev/null 2>&1") == 0;

    const std::string machine = MachineLine();  // before the suite loads the machine itself
    std::vector<Row> rows;
    std::set<std::string> tooSlow;  // "scene/engine" pairs over 10 s a frame
    // Per "family/engine/size" (family = scene name without its trailing count, e.g. spheres):
    // the primitives and frame time of the last member measured, to predict the next one.
    std::map<std::string, std::pair<int, double>> lastOfFamily;
    auto familyOf = [](const std::string& name) {
        std::size_t e = name.size();
        while (e > 0 && std::isdigit(static_cast<unsigned char>(name[e - 1]))) --e;
        return name.substr(0, e);
    };
    const std::string phaseLog = outDir + "/scenes/phases.log";
    for (const BenchScene& scene : scenes) {
        if (!Selected(scene.name, only)) continue;
        std::string scenePath = outDir + "/scenes/" + scene.name + ".uq";
        std::ofstream(scenePath) << scene.text;
        for (Size size : sizes) {
            Row row;
            row.scene = scene.name;
            row.primitives = scene.primitives;
            row.size = size;
            std::fprintf(stderr, "%-22s %4dx%-4d ", scene.name.c_str(), size.w, size.h);
            // Above 1920×1080 (the 4K case) only raycast is timed in process: the other engines'
            // growth with pixels is measured up to 1080p.
            const bool huge = static_cast<long>(size.w) * size.h > 1920L * 1080L;

            // In process, through the render context: read + flatten once, then each engine
            // warm. (A block: its frames and scene are freed before the processes are spawned;
            // see ResetPeakRss.)
            {
                RenderContext ctx(threads);
                if (!Prepare(ctx, scenePath, size)) continue;
                row.flattenMs = ctx.flattenSeconds * 1e3;
                ShadeOptions defaults;  // what `quadrix render` gives this scene unasked
                ApplyPictureDefaults(ctx.Flat(), PictureDefaults{}, defaults);
                row.defaultAa = defaults.aaSamples > 1;
                row.defaultShadows = defaults.shadows;
                Frame reference;
                for (const std::string& name : EngineNames()) {
                    // An engine that took over 10 s for a frame of this scene at a smaller size is
                    // not run at the larger ones (reported as skipped), so the suite ends.
                    const bool unselected =
                        (huge && name != "raycast") ||
                        (!engineList.empty() &&
                         ("," + engineList + ",").find("," + name + ",") == std::string::npos);
                    // An engine whose frame on the family's previous, smaller member at this size,
                    // scaled linearly by the primitive count, would exceed 10 s is not started: a
                    // frame cannot be interrupted, and scanline or pixelpowers on 10,000 spheres
                    // would hold the suite for many minutes.
                    const std::string famKey =
                        familyOf(scene.name) + "/" + name + fmt::format("/{}x{}", size.w, size.h);
                    if (auto it = lastOfFamily.find(famKey);
                        it != lastOfFamily.end() && name != "raycast" &&
                        (it->second.second < 0 ||
                         it->second.second * scene.primitives / std::max(it->second.first, 1) >
                             10000))
                        tooSlow.insert(scene.name + "/" + name);
                    if (name != "raycast" &&
                        (unselected || tooSlow.count(scene.name + "/" + name))) {
                        if (!unselected) lastOfFamily[famKey] = {scene.primitives, -1.0};
                        row.engineMs.emplace_back(name, unselected ? -2.0 : -1.0);
                        row.engineDiffPct.push_back(0.0);
                        row.engineComposed.push_back(0);
                        continue;
                    }
                    EngineRequest request;
                    request.engine = name;
                    if (auto it = optionsOf.find(name); it != optionsOf.end())
                        request.options = it->second;
                    Frame frame;
                    RenderReport report;
                    const double warmMs = RenderMs(ctx, request, frame, &report);  // warm-up
                    if (warmMs < 0) {  // refused (reported): shown as skipped
                        row.engineMs.emplace_back(name, -1.0);
                        row.engineDiffPct.push_back(0.0);
                        row.engineComposed.push_back(0);
                        continue;
                    }
                    row.engineComposed.push_back(report.byReference.size());
                    if (name == "raycast") reference = frame;
                    std::size_t differ = 0;
                    for (std::size_t i = 0;
                         i < frame.surface.size() && i < reference.surface.size(); ++i)
                        differ += (frame.surface[i] == Frame::kNone) !=
                                  (reference.surface[i] == Frame::kNone);
                    row.engineDiffPct.push_back(frame.surface.size() == reference.surface.size() &&
                                                        !frame.surface.empty()
                                                    ? 100.0 * static_cast<double>(differ) /
                                                          static_cast<double>(frame.surface.size())
                                                    : 100.0);
                    std::vector<double> ms;
                    // A slow engine (over 2 s a frame) is timed once more, not `reps` times, so the
                    // suite stays within minutes; its time is still a warm frame.
                    const int engineReps = warmMs > 2000 ? 1 : reps;
                    if (warmMs > 10000) tooSlow.insert(scene.name + "/" + name);
                    for (int i = 0; i < engineReps; ++i)
                        ms.push_back(RenderMs(ctx, request, frame));
                    row.engineMs.emplace_back(name, Median(ms));
                    lastOfFamily[famKey] = {scene.primitives, Median(ms)};
                }
            }
            row.benchFloorMiB = ResetPeakRss();

            // Whole processes, Quadrix and POV-Ray alternating. POV-Ray gets the scene exported
            // with shadows when Quadrix's picture defaults give it shadows.
            std::string sizeArg = fmt::format("{}x{}", size.w, size.h);
            std::string png = outDir + "/scenes/" + scene.name + ".png";
            std::string pov = outDir + "/scenes/" + scene.name + ".pov";
            // POV-Ray at 4K only up to 1,000 primitives (10,000 spheres take minutes at 1080p).
            if (havePov && !(huge && scene.primitives > 1000)) {
                std::vector<std::string> ex = {quadrixBin, "export", "--to", "pov", scenePath,
                                               "--size",   sizeArg,  "-o",   pov};
                if (row.defaultShadows) ex.push_back("--shadows");
                row.povOk = Spawn(ex).exitCode == 0;
            }
            // With anti-aliasing, POV-Ray runs at 1280×720 only, where the defaults give Quadrix
            // anti-aliasing: supersampling 2×2 (+AM1 +R2, the 4 samples of --aa 4) where a pixel
            // differs from a neighbour by more than POV-Ray's default threshold (+A0.3).
            const bool povAa = row.povOk && row.defaultAa && size.w == 1280 && size.h == 720;
            std::vector<double> qMs, qPlainMs, pMs, pAaMs;
            std::vector<std::vector<double>> phases(kPhases.size()), basePhases(kPhases.size());
            std::vector<double> baseMs;
            int rounds = noProcess ? 0 : std::max(reps, havePov ? povReps : 0);
            auto runPov = [&](bool aa, std::vector<double>& into) {
                std::vector<std::string> argv = {
                    "timeout",
                    std::to_string(kPovTimeLimitSeconds),
                    "povray",
                    "+I" + pov,
                    "+O" + outDir + "/scenes/" + scene.name + "_pov.png",
                    fmt::format("+W{}", size.w),
                    fmt::format("+H{}", size.h)};
                if (aa) {
                    for (const char* a : {"+A0.3", "+AM1", "+R2", "-J"}) argv.push_back(a);
                } else {
                    argv.push_back("-A");
                }
                for (const char* a : {"-D", "-V", "-GA", "+WT2"}) argv.push_back(a);
                ProcessRun p = Spawn(argv);
                if (p.exitCode == 0) {
                    into.push_back(p.seconds * 1e3);
                    row.povPeakMiB = std::max(row.povPeakMiB, p.peakMiB);
                } else if (p.exitCode == 124) {
                    row.povTimedOut = true;
                }
            };
            for (int i = 0; i < rounds; ++i) {
                if (i < reps) {
                    auto runQuadrix = [&] {
                        ProcessRun q =
                            Spawn({quadrixBin, "render", scenePath, "--size", sizeArg, "-o", png},
                                  phaseLog, {"QUADRIX_PHASE_TIMES=1"});
                        if (q.exitCode != 0) return;
                        qMs.push_back(q.seconds * 1e3);
                        row.quadrixPeakMiB = std::max(row.quadrixPeakMiB, q.peakMiB);
                        const std::vector<double> ph = ParsePhases(phaseLog, q);
                        for (std::size_t k = 0; k < ph.size(); ++k) phases[k].push_back(ph[k]);
                    };
                    auto runBaseline = [&] {
                        ProcessRun b =
                            Spawn({baselineBin, "render", scenePath, "--size", sizeArg, "-o", png},
                                  phaseLog, {"QUADRIX_PHASE_TIMES=1"});
                        if (b.exitCode != 0) return;
                        baseMs.push_back(b.seconds * 1e3);
                        const std::vector<double> ph = ParsePhases(phaseLog, b);
                        for (std::size_t k = 0; k < ph.size(); ++k) basePhases[k].push_back(ph[k]);
                    };
                    // The two binaries take turns at going first, so that neither is always the
                    // run after POV-Ray's: with the build always first, the 2026-12-07 11:56
                    // suite had it slower than the baseline in most rows, shade phases included,
                    // though the shading code was the same; the same binary twice after POV-Ray
                    // was slower first in 4 rounds of 6.
                    if (baselineBin.empty()) {
                        runQuadrix();
                    } else if (i % 2 == 0) {
                        runQuadrix();
                        runBaseline();
                    } else {
                        runBaseline();
                        runQuadrix();
                    }
                    if (row.defaultAa) {
                        ProcessRun plain = Spawn({quadrixBin, "render", scenePath, "--size",
                                                  sizeArg, "--aa", "off", "-o", png});
                        if (plain.exitCode == 0) qPlainMs.push_back(plain.seconds * 1e3);
                    }
                }
                // POV-Ray at 10,000 primitives takes minutes a run: one run is enough there.
                bool slow = scene.primitives > 5000;
                if (row.povOk && !row.povTimedOut && i < (slow ? 1 : povReps)) {
                    runPov(false, pMs);
                    if (povAa && !row.povTimedOut) runPov(true, pAaMs);
                }
            }
            row.quadrixProcessMs = Median(qMs);
            row.quadrixNoAaMs = row.defaultAa ? Median(qPlainMs) : row.quadrixProcessMs;
            if (!phases[0].empty())
                for (const auto& p : phases) row.phasesMs.push_back(Median(p));
            row.baselineMs = Median(baseMs);
            if (!basePhases[0].empty())
                for (const auto& p : basePhases) row.baselinePhasesMs.push_back(Median(p));
            row.povProcessMs = Median(pMs);
            row.povAaMs = Median(pAaMs);
            std::fprintf(
                stderr, "engine %.1f ms  process %.1f ms (--aa off %.1f)  povray %.1f ms%s\n",
                row.engineMs.empty() ? 0.0 : row.engineMs[0].second, row.quadrixProcessMs,
                row.quadrixNoAaMs, row.povProcessMs, row.povTimedOut ? " (timed out)" : "");
            rows.push_back(row);
        }
    }

    // Results: Markdown table and CSV.
    char stamp[32];
    std::time_t now = std::time(nullptr);
    std::strftime(stamp, sizeof stamp, "%Y-%m-%d_%H%M%S", std::gmtime(&now));
    std::string md = fmt::format(
        "# Quadrix benchmark results {}\n\nMachine: {}\n\nFrame: {} bytes a pixel "
        "(frame/frame.h; issue 24 target ≤ 16).\n\n",
        stamp, machine, Frame::kBytesPerPixel);
    md +=
        "Frame = in-process render of a flattened scene (warm, median); process = whole "
        "`quadrix render … -o x.png` or `povray` run (median); ratio = POV-Ray process / Quadrix "
        "process. Peak = maximum resident set of the process; a peak at the suite's own resident "
        "set "
        "(floor) only says the process stayed below it (see ResetPeakRss). An engine time "
        "marked (≠ p %) "
        "comes from a frame whose coverage differs from raycast's on p % of the pixels; one "
        "marked (+k by raycast) includes the k solids the render context gave to raycast "
        "because the engine cannot draw them (composition). Quadrix processes run with the "
        "picture defaults (anti-aliasing --aa 4 and shadows, for scenes of at most 20,000 "
        "bodies) and with `--aa off`; POV-Ray runs on the scene exported with shadows where the "
        "defaults give them, with `-A`, and at 1280×720 also with anti-aliasing (+A0.3 +AM1 +R2 "
        "-J: 2×2 samples where a pixel differs from a neighbour). ratio = POV-Ray -A / Quadrix "
        "--aa off; AA ratio = POV-Ray anti-aliased / Quadrix defaults. A POV-Ray run is stopped "
        "after 600 s (then \"> 600 s\" and the ratio is a lower bound). Above 1920×1080 only "
        "raycast is timed in process, and POV-Ray only up to 1,000 primitives.\n\n";
    md += "| scene | prims | size | flatten ms |";
    for (const auto& e : EngineNames()) md += fmt::format(" {} frame ms |", e);
    md +=
        " quadrix process ms (defaults) | quadrix --aa off ms | povray -A ms | ratio | povray AA "
        "ms | AA ratio | quadrix peak MiB | povray peak MiB | floor MiB |\n|---|---|---|---|";
    for (std::size_t i = 0; i < EngineNames().size(); ++i) md += "---|";
    md += "---|---|---|---|---|---|---|---|---|\n";
    std::string csv = "scene,primitives,width,height,flatten_ms";
    for (const auto& e : EngineNames()) csv += "," + e + "_frame_ms";
    csv +=
        ",quadrix_process_ms,quadrix_noaa_process_ms,povray_process_ms,povray_aa_process_ms,"
        "quadrix_peak_mib,povray_peak_mib";
    for (const std::string& ph : kPhases) csv += ",phase_" + ph + "_ms";
    csv += ",machine\n";
    std::string machineCsv = machine;  // one CSV field: quoted, inner quotes doubled
    for (std::size_t q = machineCsv.find('"'); q != std::string::npos;
         q = machineCsv.find('"', q + 2))
        machineCsv.insert(q, 1, '"');
    machineCsv = "\"" + machineCsv + "\"";
    auto povCell = [](const Row& r, double ms) {
        return ms > 0 ? fmt::format("{:.1f}", ms)
                      : (r.povTimedOut ? fmt::format("> {} s", kPovTimeLimitSeconds) : "–");
    };
    auto ratioCell = [](const Row& r, double pov, double quadrix) {
        if (pov <= 0 && r.povTimedOut && quadrix > 0)
            return fmt::format("≥ {:.0f}×", kPovTimeLimitSeconds * 1e3 / quadrix);
        return Ratio(pov, quadrix);
    };
    for (const Row& r : rows) {
        md += fmt::format("| {} | {} | {}×{} | {:.1f} |", r.scene, r.primitives, r.size.w, r.size.h,
                          r.flattenMs);
        csv += fmt::format("{},{},{},{},{:.3f}", r.scene, r.primitives, r.size.w, r.size.h,
                           r.flattenMs);
        for (std::size_t e = 0; e < r.engineMs.size(); ++e) {
            const double ms = r.engineMs[e].second, diff = r.engineDiffPct[e];
            const std::size_t composed = r.engineComposed[e];
            // Coverage differing on more than 0.5 % of the pixels (more than silhouette
            // rounding): the engine did not draw the whole scene, so its time is not comparable.
            md += ms == -2.0   ? std::string(" – |")
                  : ms < 0     ? std::string(" skipped (> 10 s, measured or predicted) |")
                  : diff > 0.5 ? fmt::format(" {:.1f} (≠{:.0f} %) |", ms, diff)
                  : composed   ? fmt::format(" {:.1f} (+{} by raycast) |", ms, composed)
                               : fmt::format(" {:.1f} |", ms);
            csv += fmt::format(",{:.3f}", ms);
        }
        md += fmt::format(
            " {:.1f} | {} | {} | {} | {} | {} | {:.0f} | {} | {:.0f} |\n", r.quadrixProcessMs,
            r.defaultAa ? fmt::format("{:.1f}", r.quadrixNoAaMs) : "(no default AA)",
            povCell(r, r.povProcessMs), ratioCell(r, r.povProcessMs, r.quadrixNoAaMs),
            r.povAaMs > 0 ? fmt::format("{:.1f}", r.povAaMs) : "–",
            Ratio(r.povAaMs, r.quadrixProcessMs), r.quadrixPeakMiB,
            r.povPeakMiB > 0 ? fmt::format("{:.0f}", r.povPeakMiB) : "–", r.benchFloorMiB);
        csv +=
            fmt::format(",{:.3f},{:.3f},{:.3f},{:.3f},{:.1f},{:.1f}", r.quadrixProcessMs,
                        r.quadrixNoAaMs, r.povProcessMs, r.povAaMs, r.quadrixPeakMiB, r.povPeakMiB);
        for (std::size_t k = 0; k < kPhases.size(); ++k)
            csv += fmt::format(",{:.3f}", k < r.phasesMs.size() ? r.phasesMs[k] : 0.0);
        csv += "," + machineCsv + "\n";
    }
    md += PhaseTable(rows, machine);
    if (!baselineBin.empty()) md += BaselineTable(rows, baselineBin, quadrixBin);
    md += Scaling(rows);
    md += ThreadsTable(scenes, outDir, only, quick ? 5 : 41);
    md += AntialiasTable(scenes, outDir, only, quick ? 1 : 3);
    md += RayIndexTable(scenes, outDir, only, quick ? 1 : 3);
    if (only.empty() || std::string("hatch").find(only) != std::string::npos)
        md += HatchTable(sourceDir, quick ? 5 : 21);
    if (only.empty() || std::string("isocurve").find(only) != std::string::npos)
        md += IsocurveTable(sourceDir, quick ? 1 : 3);
    if (only.empty() || std::string("viewer").find(only) != std::string::npos)
        md += ViewerOrbitTable({FromFile("machined_part", sourceDir + "/examples/machined_part.uq"),
                                SpheresMinusCylinder(1000)},
                               1280, 720, quick ? 12 : 36, threads);
    if (only.empty() || std::string("draw").find(only) != std::string::npos)
        md += DrawSheetTable(sourceDir, quadrixBin, outDir, quick ? 3 : reps);
    std::ofstream(outDir + "/results_" + std::string(stamp) + ".md") << md;
    std::ofstream(outDir + "/results_" + std::string(stamp) + ".csv") << csv;
    std::ofstream(outDir + "/latest.md") << md;
    std::fputs(md.c_str(), stdout);
    return 0;
}
