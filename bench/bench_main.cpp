// quadrix_bench: the benchmark suite of issue 8. One command (bench/run.sh) runs it.
//
// For every scene and image size it measures, side by side in the same run:
//   * each Quadrix engine in process: frame time after one warm-up render, median of several;
//   * the whole `quadrix render` process (read, flatten, render, shade, PNG), median;
//   * POV-Ray 3.7 on the exported scene (`quadrix export --to pov`, no antialiasing, 2 threads),
//     whole process, alternating with the Quadrix process runs so both see the same machine state;
// and writes a Markdown table with ratios and a CSV to the output directory. Nothing is asserted:
// benchmarks report, they do not fail on time.
#include <fcntl.h>
#include <fmt/format.h>
#include <malloc.h>
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
#include <vector>

#include "draw_sheet.h"
#include "quadrix/engines/engine.h"
#include "quadrix/engines/isocurve/isocurve_engine.h"
#include "quadrix/engines/isocurve/render.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/shade/antialias.h"
#include "scenes.h"
#include "viewer_orbit.h"

extern char** environ;

namespace quadrix::bench {
namespace {

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
};

// Runs argv with stdout/stderr to /dev/null; wall time and the child's peak RSS.
ProcessRun Spawn(const std::vector<std::string>& argv) {
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    ProcessRun r;
    auto t0 = std::chrono::steady_clock::now();
    pid_t pid;
    if (posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ) != 0) {
        posix_spawn_file_actions_destroy(&actions);
        return r;
    }
    int status = 0;
    struct rusage usage {};
    wait4(pid, &status, 0, &usage);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.peakMiB = usage.ru_maxrss / 1024.0;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    posix_spawn_file_actions_destroy(&actions);
    return r;
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

struct Row {
    std::string scene;
    int primitives = 0;
    Size size{};
    std::vector<std::pair<std::string, double>> engineMs;  // in-process frame time per engine
    // Per engine: percentage of pixels whose coverage differs from raycast's (the exact
    // reference); an engine that skips what it cannot draw shows it here instead of looking fast.
    std::vector<double> engineDiffPct;
    double flattenMs = 0;
    double quadrixProcessMs = 0, quadrixPeakMiB = 0;
    double povProcessMs = 0, povPeakMiB = 0;
    double benchFloorMiB = 0;  // the suite's own resident set when the processes ran
    bool povOk = false;
};

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
        PipelineOptions po;
        po.sceneText = fmt::format(
            "patches m \"{}/src/quadrix/import/freeform/testdata/newell/{}.txt\" newell =rx -90;\n"
            "view v dop .5 .8 -1;\n",
            sourceDir, model);
        po.width = po.height = 1024;
        PipelineResult pr;
        Diagnostics diags;
        if (!ReadAndFlatten(po, pr, diags)) {
            diags.Print(stderr);
            continue;
        }
        const auto drawables = isocurve::SceneDrawables(pr.flat);
        for (double gap : {4.0, 2.0, 1.0, 0.5}) {
            isocurve::IsocurveOptions o;
            o.pixelSpacing = gap;
            std::vector<double> ex, dr;
            isocurve::IsocurveStats st;
            for (int i = 0; i < reps; ++i) {
                Frame frame(1024, 1024);
                st = isocurve::RenderFreeform(drawables, pr.flat.projection, o, frame);
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
// 4, 16 and 64 (median of `reps`). Scenes of more than 256 bodies are left out here (64 samples
// per edge pixel of 10,000 spheres at 1280×720 is long); RayIndexTable measures those.
std::string AntialiasTable(const std::vector<BenchScene>& scenes, const std::string& outDir,
                           const std::string& only, int reps) {
    std::string out =
        "\n## Anti-aliasing cost (1280×720, raycast frame + shading, median)\n\n"
        "| scene | edge pixels | plain ms | --aa 4 | --aa 16 | --aa 64 |\n"
        "|---|---|---|---|---|---|\n";
    for (const BenchScene& scene : scenes) {
        if (!only.empty() && scene.name.find(only) == std::string::npos) continue;
        PipelineOptions po;
        po.scenePaths = {outDir + "/scenes/" + scene.name + ".uq"};
        po.width = 1280;
        po.height = 720;
        PipelineResult pr;
        Diagnostics diags;
        if (!RunPipeline(po, pr, diags) || pr.flat.bodies.size() > 256) continue;
        auto engine = MakeEngine("raycast");
        auto timed = [&](int samples, std::size_t* edges) {
            std::vector<double> ms;
            for (int i = 0; i < reps; ++i) {
                const auto t0 = std::chrono::steady_clock::now();
                Frame frame;
                engine->Render(pr.flat, RenderOptions{}, frame);
                ShadeOptions so;
                so.aaSamples = samples;
                Image img = Shade(frame, pr.flat, so);
                const AntialiasStats st = Antialias(frame, pr.flat, so, img);
                if (edges) *edges = st.edgePixels;
                ms.push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count());
            }
            return Median(ms);
        };
        std::size_t edges = 0;
        const double plain = timed(0, nullptr);
        const double a4 = timed(4, &edges), a16 = timed(16, nullptr), a64 = timed(64, nullptr);
        out += fmt::format(
            "| {} | {} | {:.1f} | {:.1f} ms ({:.2f}×) | {:.1f} ms ({:.2f}×) | "
            "{:.1f} ms ({:.2f}×) |\n",
            scene.name, edges, plain, a4, a4 / plain, a16, a16 / plain, a64, a64 / plain);
        std::fprintf(stderr, "antialias %s done\n", scene.name.c_str());
    }
    return out;
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
        if (!only.empty() && scene.name.find(only) == std::string::npos) continue;
        if (scene.name.find("spheres") == std::string::npos &&
            scene.name.find("machined") == std::string::npos)
            continue;
        PipelineOptions po;
        po.scenePaths = {outDir + "/scenes/" + scene.name + ".uq"};
        po.width = 640;
        po.height = 360;
        PipelineResult pr;
        Diagnostics diags;
        if (!RunPipeline(po, pr, diags)) continue;
        auto engine = MakeEngine("raycast");
        Frame frame;
        std::vector<double> frameMs;
        for (int i = 0; i < reps; ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            engine->Render(pr.flat, RenderOptions{}, frame);
            frameMs.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count());
        }
        const bool big = pr.flat.bodies.size() > 2000;
        auto timed = [&](bool shadows, int aa, bool index) {
            std::vector<double> ms;
            for (int i = 0; i < (big && !index ? 1 : reps); ++i) {
                const auto t0 = std::chrono::steady_clock::now();
                ShadeOptions so;
                so.shadows = shadows;
                so.aaSamples = aa;
                so.spatialIndex = index;
                Image img = Shade(frame, pr.flat, so);
                Antialias(frame, pr.flat, so, img);
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
            scene.name, pr.flat.bodies.size(), Median(frameMs), plain, sOff, sOn, sOff / sOn, aOff,
            aOn, aOff / aOn);
        std::fprintf(stderr, "ray index %s done\n", scene.name.c_str());
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
    bool quick = false, noPov = false, noProcess = false;
    int reps = 5, povReps = 3, threads = 0;
    std::string sizeList;
    std::string only, engineList;
    app.add_option("--out", outDir, "Directory for results and generated scenes");
    app.add_option("--quadrix", quadrixBin, "The quadrix binary to time as a whole process");
    app.add_option("--source", sourceDir, "Source tree (for examples/)");
    app.add_flag("--quick", quick, "Small subset: one size, fewer repetitions");
    app.add_flag("--no-pov", noPov, "Do not run POV-Ray");
    app.add_option("--reps", reps, "Repetitions of Quadrix measurements (median)");
    app.add_option("--pov-reps", povReps,
                   "Repetitions of POV-Ray runs (median; 1 for slow scenes)");
    app.add_option("--only", only, "Run only scenes whose name contains this text");
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
        if (!MakeEngine(engineName)) {
            std::fprintf(stderr, "error: --engine-opt '%s': no engine '%s'\n", opt.c_str(),
                         engineName.c_str());
            return 2;
        }
        optionsOf[engineName][opt.substr(colon + 1, eq - colon - 1)] = opt.substr(eq + 1);
    }
    for (const auto& [engineName, options] : optionsOf) {
        RenderOptions ro;
        ro.engineOptions = options;
        if (std::string err = MakeEngine(engineName)->ValidateOptions(ro); !err.empty()) {
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
        MiteredKnot(36),
        SpheresMinusCylinder(100),
        SpheresMinusCylinder(1000),
        SpheresMinusCylinder(10000),
        SpheresMinusCylinder(10000, /*distributed=*/true),
        SumOfProductsExplosion(8),
        SumOfProductsExplosion(16),
        SumOfProductsExplosion(32),
        SumOfProductsExplosion(64),
    };
    std::vector<Size> sizes = {{512, 512}, {1280, 720}, {1920, 1080}};
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
    for (const BenchScene& scene : scenes) {
        if (!only.empty() && scene.name.find(only) == std::string::npos) continue;
        std::string scenePath = outDir + "/scenes/" + scene.name + ".uq";
        std::ofstream(scenePath) << scene.text;
        for (Size size : sizes) {
            Row row;
            row.scene = scene.name;
            row.primitives = scene.primitives;
            row.size = size;
            std::fprintf(stderr, "%-22s %4dx%-4d ", scene.name.c_str(), size.w, size.h);

            // In process: read + flatten once, then each engine warm. (A block: its frames and
            // scene are freed before the processes are spawned; see ResetPeakRss.)
            {
                PipelineOptions po;
                po.scenePaths = {scenePath};
                po.width = size.w;
                po.height = size.h;
                PipelineResult pr;
                Diagnostics diags;
                if (!RunPipeline(po, pr, diags)) {
                    diags.Print(stderr);
                    continue;
                }
                row.flattenMs = pr.flattenSeconds * 1e3;
                Frame reference;
                for (const std::string& name : EngineNames()) {
                    // An engine that took over 10 s for a frame of this scene at a smaller size is
                    // not run at the larger ones (reported as skipped), so the suite ends.
                    const bool unselected =
                        !engineList.empty() &&
                        ("," + engineList + ",").find("," + name + ",") == std::string::npos;
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
                        continue;
                    }
                    auto engine = MakeEngine(name);
                    RenderOptions ro;
                    ro.threads = threads;
                    if (auto it = optionsOf.find(name); it != optionsOf.end())
                        ro.engineOptions = it->second;
                    Frame frame;
                    const auto tw = std::chrono::steady_clock::now();
                    engine->Render(pr.flat, ro, frame);  // warm-up
                    const double warmMs = std::chrono::duration<double, std::milli>(
                                              std::chrono::steady_clock::now() - tw)
                                              .count();
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
                    for (int i = 0; i < engineReps; ++i) {
                        auto t0 = std::chrono::steady_clock::now();
                        engine->Render(pr.flat, ro, frame);
                        ms.push_back(std::chrono::duration<double, std::milli>(
                                         std::chrono::steady_clock::now() - t0)
                                         .count());
                    }
                    row.engineMs.emplace_back(name, Median(ms));
                    lastOfFamily[famKey] = {scene.primitives, Median(ms)};
                }
            }
            row.benchFloorMiB = ResetPeakRss();

            // Whole processes, Quadrix and POV-Ray alternating.
            std::string sizeArg = fmt::format("{}x{}", size.w, size.h);
            std::string png = outDir + "/scenes/" + scene.name + ".png";
            std::string pov = outDir + "/scenes/" + scene.name + ".pov";
            if (havePov) {
                ProcessRun ex = Spawn(
                    {quadrixBin, "export", "--to", "pov", scenePath, "--size", sizeArg, "-o", pov});
                row.povOk = ex.exitCode == 0;
            }
            std::vector<double> qMs, pMs;
            int rounds = noProcess ? 0 : std::max(reps, havePov ? povReps : 0);
            for (int i = 0; i < rounds; ++i) {
                if (i < reps) {
                    ProcessRun q =
                        Spawn({quadrixBin, "render", scenePath, "--size", sizeArg, "-o", png});
                    if (q.exitCode == 0) {
                        qMs.push_back(q.seconds * 1e3);
                        row.quadrixPeakMiB = std::max(row.quadrixPeakMiB, q.peakMiB);
                    }
                }
                // POV-Ray at 10,000 primitives takes a minute a run: one run is enough there.
                bool slow = scene.primitives > 5000;
                if (row.povOk && i < (slow ? 1 : povReps)) {
                    ProcessRun p = Spawn({"povray", "+I" + pov,
                                          "+O" + outDir + "/scenes/" + scene.name + "_pov.png",
                                          fmt::format("+W{}", size.w), fmt::format("+H{}", size.h),
                                          "-A", "-D", "-V", "-GA", "+WT2"});
                    if (p.exitCode == 0) {
                        pMs.push_back(p.seconds * 1e3);
                        row.povPeakMiB = std::max(row.povPeakMiB, p.peakMiB);
                    }
                }
            }
            row.quadrixProcessMs = Median(qMs);
            row.povProcessMs = Median(pMs);
            std::fprintf(stderr, "engine %.1f ms  process %.1f ms  povray %.1f ms\n",
                         row.engineMs.empty() ? 0.0 : row.engineMs[0].second, row.quadrixProcessMs,
                         row.povProcessMs);
            rows.push_back(row);
        }
    }

    // Results: Markdown table and CSV.
    char stamp[32];
    std::time_t now = std::time(nullptr);
    std::strftime(stamp, sizeof stamp, "%Y-%m-%d_%H%M%S", std::gmtime(&now));
    std::string md =
        fmt::format("# Quadrix benchmark results {}\n\nMachine: {}\n\n", stamp, machine);
    md +=
        "Frame = in-process render of a flattened scene (warm, median); process = whole "
        "`quadrix render … -o x.png` or `povray` run (median); ratio = POV-Ray process / Quadrix "
        "process. Peak = maximum resident set of the process; a peak at the suite's own resident "
        "set "
        "(floor) only says the process stayed below it (see ResetPeakRss). An engine time "
        "marked (≠ p %) "
        "comes from a frame whose coverage differs from raycast's on p % of the pixels: that "
        "engine does not draw the whole scene (e.g. `patch` skips CSG solids).\n\n";
    md += "| scene | prims | size | flatten ms |";
    for (const auto& e : EngineNames()) md += fmt::format(" {} frame ms |", e);
    md +=
        " quadrix process ms | povray process ms | ratio | quadrix peak MiB | povray peak MiB | "
        "floor MiB |\n|---|---|---|---|";
    for (std::size_t i = 0; i < EngineNames().size(); ++i) md += "---|";
    md += "---|---|---|---|---|---|\n";
    std::string csv = "scene,primitives,width,height,flatten_ms";
    for (const auto& e : EngineNames()) csv += "," + e + "_frame_ms";
    csv += ",quadrix_process_ms,povray_process_ms,quadrix_peak_mib,povray_peak_mib,machine\n";
    std::string machineCsv = machine;  // one CSV field: quoted, inner quotes doubled
    for (std::size_t q = machineCsv.find('"'); q != std::string::npos;
         q = machineCsv.find('"', q + 2))
        machineCsv.insert(q, 1, '"');
    machineCsv = "\"" + machineCsv + "\"";
    for (const Row& r : rows) {
        md += fmt::format("| {} | {} | {}×{} | {:.1f} |", r.scene, r.primitives, r.size.w, r.size.h,
                          r.flattenMs);
        csv += fmt::format("{},{},{},{},{:.3f}", r.scene, r.primitives, r.size.w, r.size.h,
                           r.flattenMs);
        for (std::size_t e = 0; e < r.engineMs.size(); ++e) {
            const double ms = r.engineMs[e].second, diff = r.engineDiffPct[e];
            // Coverage differing on more than 0.5 % of the pixels (more than silhouette
            // rounding): the engine did not draw the whole scene, so its time is not comparable.
            md += ms == -2.0   ? std::string(" – |")
                  : ms < 0     ? std::string(" skipped (> 10 s, measured or predicted) |")
                  : diff > 0.5 ? fmt::format(" {:.1f} (≠{:.0f} %) |", ms, diff)
                               : fmt::format(" {:.1f} |", ms);
            csv += fmt::format(",{:.3f}", ms);
        }
        md += fmt::format(" {:.1f} | {} | {} | {:.0f} | {} | {:.0f} |\n", r.quadrixProcessMs,
                          r.povProcessMs > 0 ? fmt::format("{:.1f}", r.povProcessMs) : "–",
                          Ratio(r.povProcessMs, r.quadrixProcessMs), r.quadrixPeakMiB,
                          r.povPeakMiB > 0 ? fmt::format("{:.0f}", r.povPeakMiB) : "–",
                          r.benchFloorMiB);
        csv += fmt::format(",{:.3f},{:.3f},{:.1f},{:.1f},{}\n", r.quadrixProcessMs, r.povProcessMs,
                           r.quadrixPeakMiB, r.povPeakMiB, machineCsv);
    }
    md += Scaling(rows);
    md += AntialiasTable(scenes, outDir, only, quick ? 1 : 3);
    md += RayIndexTable(scenes, outDir, only, quick ? 1 : 3);
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
