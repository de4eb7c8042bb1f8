// Issue 18's viewer targets, measured (never asserted): a fixed orbit through the viewer's render
// thread (viewer/render_worker.h), frames/s at full and at reduced resolution, side by side with
// the still frame of the same view (a re-render that reuses the flat scene).
#pragma once

#include <string>
#include <vector>

#include "scenes.h"

namespace quadrix::bench {

// A markdown section: per scene, the still frame, the full-resolution orbit and the orbit at the
// progressive schedule's moving scale, at width×height over `frames` frames.
std::string ViewerOrbitTable(const std::vector<BenchScene>& scenes, int width, int height,
                             int frames, int threads);

}  // namespace quadrix::bench
