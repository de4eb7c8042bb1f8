// The fixed orbit of `quadrix view --bench N` (issue 18's targets), one copy for the window and
// the offscreen run: one full turn about the scene's up axis in N full-resolution frames, each
// drawn by the render thread (flatten + render + shade) and handed to `show` (the window uploads
// and presents it; offscreen and quadrix_bench pass nothing). With `show`, the frames are
// pipelined as in the window: frame N + 1 is asked for before frame N is shown, so the render
// thread draws it (and encodes its sRGB bytes) while the event thread uploads and presents N.
// Timed from the first request to the last frame shown. quadrix_bench (bench/viewer_orbit.cpp)
// runs the same orbit.
#pragma once

#include <functional>
#include <string>

#include "quadrix/viewer/camera.h"
#include "quadrix/viewer/render_worker.h"

namespace quadrix::viewer {

struct BenchResult {
    int frames = 0;  // frames drawn (and shown)
    int scale = 1;   // at 1/scale of the resolution
    double seconds = 0, slowestSeconds = 0;
    std::string error;  // a frame that could not be drawn
    // The profile, summed over the frames: the render thread's stages (FrameOutcome) and the
    // time `show` took (the window: texture upload + present).
    double flatten = 0, render = 0, shade = 0, encode = 0, show = 0;
};

// Frames at 1/scale of the resolution (quadrix_bench's moving frames; the window's bench is at
// full resolution). `show` returns false to stop early (the window was closed).
BenchResult RunBenchOrbit(RenderWorker& worker, Camera camera, int width, int height,
                          const std::string& engine, int frames, int scale = 1,
                          const std::function<bool(FrameOutcome&)>& show = {});

// "view bench: N frames WxH engine E <where>: F frames/s (mean M ms, slowest S ms)", then a
// line of the profile's means.
std::string FormatBench(const BenchResult& r, int width, int height, const std::string& engine,
                        const std::string& where);

}  // namespace quadrix::viewer
