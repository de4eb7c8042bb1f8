#include "draw_sheet.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "quadrix/draw/drawing.h"
#include "quadrix/draw/sheet.h"
#include "quadrix/pipeline/render_context.h"

extern char** environ;

namespace quadrix::bench {

namespace {

using Clock = std::chrono::steady_clock;

double MedianOf(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Wall seconds of one run of argv (output to /dev/null); −1 when it fails.
double TimeProcess(const std::vector<std::string>& argv) {
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    const auto t0 = Clock::now();
    pid_t pid;
    double seconds = -1;
    if (posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ) == 0) {
        int status = 0;
        waitpid(pid, &status, 0);
        if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
            seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    }
    posix_spawn_file_actions_destroy(&actions);
    return seconds;
}

constexpr int kViewSize = 1000;  // the device size of each view of a sheet (draw_command.cpp)

}  // namespace

std::string DrawSheetTable(const std::string& sourceDir, const std::string& quadrixBin,
                           const std::string& outDir, int reps) {
    const std::string part = sourceDir + "/examples/machined_part.uq";
    const std::string views = "front,top,right,iso";
    std::string md =
        "\n## Drawings: the machined part's four-view sheet (issue 19; target < 1 s on two "
        "cores)\n\n";

    // Whole processes, alternating so that both see the same machine state: the sheet, and a
    // raycast render of one view-sized picture plain (no anti-aliasing, no shadows) and with the
    // scene's shadows.
    const std::string size = fmt::format("{}x{}", kViewSize, kViewSize);
    const std::string png = outDir + "/scenes/machined_part_plain.png";
    std::vector<double> drawS, plainS, shadowS;
    for (int i = 0; i < reps; ++i) {
        const double d =
            TimeProcess({quadrixBin, "draw", part, "-o", outDir + "/scenes/machined_part_sheet.svg",
                         "--views", views});
        const double p = TimeProcess(
            {quadrixBin, "render", part, "--size", size, "--aa", "off", "--no-shadows", "-o", png});
        const double s =
            TimeProcess({quadrixBin, "render", part, "--size", size, "--aa", "off", "-o", png});
        if (d > 0) drawS.push_back(d);
        if (p > 0) plainS.push_back(p);
        if (s > 0) shadowS.push_back(s);
    }
    auto ms = [](const std::vector<double>& v) {
        return v.empty() ? std::string("failed") : fmt::format("{:.1f}", 1e3 * MedianOf(v));
    };
    const double draw = MedianOf(drawS), plain = MedianOf(plainS);
    md += fmt::format(
        "| command | process ms (median of {}) |\n|---|---|\n"
        "| `quadrix draw machined_part.uq -o part.svg --views {}` | {} |\n"
        "| `quadrix render machined_part.uq --size {} --aa off --no-shadows -o part.png` | {} |\n"
        "| `quadrix render machined_part.uq --size {} --aa off -o part.png` (shadows) | {} |\n"
        "| ratio draw / plain render | {} |\n",
        reps, views, ms(drawS), size, ms(plainS), size, ms(shadowS),
        draw > 0 && plain > 0 ? fmt::format("{:.2f}×", draw / plain) : "–");

    // In process, per view: the drawer's phases beside raycast's frame of the same flat scene.
    md += fmt::format(
        "\n| view ({}×{}) | candidates | ray tests | curves ms | trim ms | visibility ms | "
        "strokes ms | drawing ms | raycast frame ms | drawing / frame |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n",
        kViewSize, kViewSize);
    RenderContext context(0);
    Diagnostics diags;
    InputRequest input;
    input.paths = {part};
    if (!context.Read(input, diags) || diags.HasErrors()) {
        diags.Print(stderr);
        return md + "(the part could not be read)\n";
    }
    double totalDraw = 0, totalFrame = 0;
    for (const char* name : {"front", "top", "right", "iso"}) {
        scene::View sv;
        draw::StandardView(name, sv);
        ViewRequest vr;
        vr.width = vr.height = kViewSize;
        vr.view = sv;  // the view given directly: the same flat scene as draw_command.cpp's
        const bool ok = context.Flatten(vr, diags);
        if (!ok || diags.HasErrors()) {
            diags.Print(stderr);
            continue;
        }
        std::vector<double> ms, curves, trim, vis, strokes, frameMs;
        draw::DrawStats st;
        for (int i = 0; i < reps; ++i) {
            const draw::Drawing d = draw::MakeDrawing(context.Flat());
            st = d.stats;
            ms.push_back(1e3 * st.seconds);
            curves.push_back(1e3 * st.curveSeconds);
            trim.push_back(1e3 * st.trimSeconds);
            vis.push_back(1e3 * st.visibilitySeconds);
            strokes.push_back(1e3 * st.strokeSeconds);
            Frame frame;
            RenderReport report;
            const auto t0 = Clock::now();
            context.Render(EngineRequest{}, frame, report, diags);
            frameMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        }
        totalDraw += MedianOf(ms);
        totalFrame += MedianOf(frameMs);
        md += fmt::format(
            "| {} | {} | {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.2f}× |\n",
            name, st.candidates, st.rayTests, MedianOf(curves), MedianOf(trim), MedianOf(vis),
            MedianOf(strokes), MedianOf(ms), MedianOf(frameMs), MedianOf(ms) / MedianOf(frameMs));
    }
    md += fmt::format("| all four | | | | | | | {:.1f} | {:.1f} | {:.2f}× |\n", totalDraw,
                      totalFrame, totalFrame > 0 ? totalDraw / totalFrame : 0.0);
    std::fprintf(stderr, "draw sheet done\n");
    return md;
}

}  // namespace quadrix::bench
