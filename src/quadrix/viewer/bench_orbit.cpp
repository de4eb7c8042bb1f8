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
    auto jobAt = [&] {
        // A drag of 2H/N pixels is a turn of 2π/N (camera.h: a drag over the height is π).
        camera.Orbit(2.0 * height / frames, 0, height);
        FrameJob job;
        job.view = camera.ToView();
        job.width = width;
        job.height = height;
        job.engine = engine;
        job.request.scale = scale;
        job.display = static_cast<bool>(show);  // the window's bytes, encoded on its thread
        return job;
    };
    BenchResult r;
    r.scale = scale;
    const auto t0 = Clock::now();
    auto f0 = Clock::now();
    if (show && frames > 0) worker.Submit(jobAt());
    for (int i = 0; i < frames; ++i) {
        FrameOutcome out;
        if (show) {
            out = worker.WaitFrame();
            if (out.error.empty() && i + 1 < frames) worker.Submit(jobAt());  // overlap
        } else {
            out = worker.RenderNow(jobAt());
        }
        if (!out.error.empty()) {
            r.error = out.error;
            break;
        }
        r.flatten += out.flattenSeconds;
        r.render += out.renderSeconds;
        r.shade += out.shadeSeconds;
        r.encode += out.encodeSeconds;
        const auto s0 = Clock::now();
        const bool go = !show || show(out);
        r.show += since(s0);
        ++r.frames;
        r.slowestSeconds = std::max(r.slowestSeconds, since(f0));
        f0 = Clock::now();
        if (!go) {
            if (i + 1 < frames) worker.WaitFrame();  // the one asked for already
            break;
        }
    }
    r.seconds = since(t0);
    return r;
}

std::string FormatBench(const BenchResult& r, int width, int height, const std::string& engine,
                        const std::string& where) {
    const int n = std::max(1, r.frames);
    return fmt::format(
        "view bench: {} frames {}x{}{} engine {} {}: {:.1f} frames/s (mean {:.2f} ms, slowest "
        "{:.2f} ms)\n"
        "view bench profile, mean a frame: flatten {:.2f} ms, render {:.2f} ms, shade {:.2f} ms, "
        "sRGB encoding {:.2f} ms (render thread); texture upload + present {:.2f} ms (window "
        "thread)\n",
        r.frames, width, height, r.scale > 1 ? fmt::format(" at 1/{}", r.scale) : "", engine, where,
        r.frames / r.seconds, 1e3 * r.seconds / n, 1e3 * r.slowestSeconds, 1e3 * r.flatten / n,
        1e3 * r.render / n, 1e3 * r.shade / n, 1e3 * r.encode / n, 1e3 * r.show / n);
}

}  // namespace quadrix::viewer
