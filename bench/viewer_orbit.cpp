#include "viewer_orbit.h"

#include <fmt/format.h>

#include <chrono>

#include "quadrix/viewer/bench_orbit.h"
#include "quadrix/viewer/progressive.h"
#include "quadrix/viewer/render_worker.h"

namespace quadrix::bench {

namespace {

using Clock = std::chrono::steady_clock;

// Mean seconds a frame of the viewer's bench orbit (viewer/bench_orbit.h) at 1/scale
// resolution; -1 when a frame fails.
double Orbit(viewer::RenderWorker& worker, const viewer::Camera& cam, int w, int h, int frames,
             int scale) {
    const viewer::BenchResult r =
        viewer::RunBenchOrbit(worker, cam, w, h, "raycast", frames, scale);
    return r.error.empty() && r.frames > 0 ? r.seconds / r.frames : -1;
}

}  // namespace

std::string ViewerOrbitTable(const std::vector<BenchScene>& scenes, int width, int height,
                             int frames, int threads) {
    std::string md = fmt::format(
        "\n## Viewer: orbit frames through the render thread ({}×{}, {} frames, raycast; "
        "flatten + render + shade, no blit)\n\n"
        "| scene | still frame ms | orbit ms | orbit frames/s | moving scale | moving ms | "
        "moving frames/s |\n|---|---|---|---|---|---|---|\n",
        width, height, frames);
    for (const BenchScene& s : scenes) {
        InputRequest in;
        in.text = s.text;
        in.textName = s.name;
        viewer::RenderWorker worker(in, threads);
        if (!worker.Load().ok) continue;
        viewer::Camera cam;
        viewer::SceneSphere sphere;
        if (!worker.InitialCamera("", width, height, cam, sphere).empty()) continue;
        viewer::FrameJob still;
        still.view = cam.ToView();
        still.width = width;
        still.height = height;
        worker.RenderNow(still);  // warm: flatten once
        const auto t0 = Clock::now();
        const viewer::FrameOutcome again = worker.RenderNow(still);
        const double stillS = std::chrono::duration<double>(Clock::now() - t0).count();
        if (!again.error.empty()) continue;
        const double full = Orbit(worker, cam, width, height, frames, 1);
        viewer::FrameScheduler schedule;
        schedule.Delivered(*schedule.Next(), full);
        const int scale = schedule.MovingScale();
        const double moving = Orbit(worker, cam, width, height, frames, scale);
        md += fmt::format("| {} | {:.1f} | {:.1f} | {:.1f} | 1/{} | {:.1f} | {:.1f} |\n", s.name,
                          1e3 * stillS, 1e3 * full, full > 0 ? 1 / full : 0, scale, 1e3 * moving,
                          moving > 0 ? 1 / moving : 0);
    }
    return md;
}

}  // namespace quadrix::bench
