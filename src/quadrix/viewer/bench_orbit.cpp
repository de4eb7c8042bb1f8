#include "quadrix/viewer/bench_orbit.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

namespace quadrix::viewer {

BenchResult RunBenchOrbit(RenderWorker& worker, Camera camera, int width, int height,
                          const std::string& engine, int frames, int scale,
                          const std::function<bool(FrameOutcome&)>& show) {
    using Clock = std::chrono::steady_clock;
    auto since = [](Clock::time_point t) {
        return std::chrono::duration<double>(Clock::now() - t).count();
    };
    BenchResult r;
    const auto t0 = Clock::now();
    for (int i = 0; i < frames; ++i) {
        // A drag of 2H/N pixels is a turn of 2π/N (camera.h: a drag over the height is π).
        camera.Orbit(2.0 * height / frames, 0, height);
        FrameJob job;
        job.view = camera.ToView();
        job.width = width;
        job.height = height;
        job.engine = engine;
        job.request.scale = scale;
        const auto f0 = Clock::now();
        FrameOutcome out = worker.RenderNow(job);
        if (!out.error.empty()) {
            r.error = out.error;
            break;
        }
        const bool go = !show || show(out);
        ++r.frames;
        r.slowestSeconds = std::max(r.slowestSeconds, since(f0));
        if (!go) break;
    }
    r.seconds = since(t0);
    return r;
}

std::string FormatBench(const BenchResult& r, int width, int height, const std::string& engine,
                        const std::string& where) {
    const int n = std::max(1, r.frames);
    return fmt::format(
        "view bench: {} frames {}x{} engine {} {}: {:.1f} frames/s (mean {:.2f} ms, slowest "
        "{:.2f} ms)\n",
        r.frames, width, height, engine, where, r.frames / r.seconds, 1e3 * r.seconds / n,
        1e3 * r.slowestSeconds);
}

}  // namespace quadrix::viewer
