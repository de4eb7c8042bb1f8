// The fixed orbit of `quadrix view --bench N` (issue 18's targets), one copy for the window and
// the offscreen run: one full turn about the scene's up axis in N full-resolution frames, each
// drawn by the render thread (RenderWorker::RenderNow: flatten + render + shade) and handed to
// `show` (the window uploads and presents it; offscreen and quadrix_bench pass nothing). Timed
// from the first request to the last frame shown. quadrix_bench (bench/viewer_orbit.cpp) runs the
// same orbit.
#pragma once

#include <functional>
#include <string>

#include "quadrix/viewer/camera.h"
#include "quadrix/viewer/render_worker.h"

namespace quadrix::viewer {

struct BenchResult {
    int frames = 0;  // frames drawn (and shown)
    double seconds = 0, slowestSeconds = 0;
    std::string error;  // a frame that could not be drawn
};

// Frames at 1/scale of the resolution (quadrix_bench's moving frames; the window's bench is at
// full resolution). `show` returns false to stop early (the window was closed).
BenchResult RunBenchOrbit(RenderWorker& worker, Camera camera, int width, int height,
                          const std::string& engine, int frames, int scale = 1,
                          const std::function<bool(FrameOutcome&)>& show = {});

// "view bench: N frames WxH engine E <where>: F frames/s (mean M ms, slowest S ms)".
std::string FormatBench(const BenchResult& r, int width, int height, const std::string& engine,
                        const std::string& where);

}  // namespace quadrix::viewer
