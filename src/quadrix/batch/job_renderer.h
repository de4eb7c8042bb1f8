// Renders the frames of jobs through one RenderContext (pipeline/render_context.h), keeping what
// can be kept between frames (issue 22: "read and flattened once per distinct geometry"):
//   - the scene is read once per job; a scene that uses `clock` (Scene::usesClock) is read again
//     for each frame whose clock differs; when the clock is only in its view statements (an
//     animated camera) only those statements are read again, the geometry is the same and its
//     world stage is kept (RenderContext::ReadAtClock): the scene is read once and its geometry
//     flattened once per job;
//   - the flat scene is reused by the context when the next frame has the same view (a still
//     animation of a clock-free scene renders from one flattening); another view (a turntable,
//     a view list) runs only the view stage of the flattener;
//   - a turntable orbits the centre of the scene's world bounds (SceneWorldBounds) at a fixed
//     distance and window, so the part keeps its size from frame to frame.
// Each frame is written through pipeline/output.h (an OutputFile each: temporary file + rename),
// so an output that exists is complete — what makes batch runs resumable.
#pragma once

#include <optional>
#include <string>

#include "quadrix/batch/job.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix::batch {

// What rendering one frame did and cost.
struct FrameResult {
    std::string image, dumpFrame, exr;     // the paths written (or that would have been)
    std::string error;                     // empty on success; diagnostics, one per line
    std::string warnings;                  // warnings and notes, one per line
    bool skipped = false;                  // every output existed already (SkipExisting)
    bool read = false, flattened = false;  // the inputs were read; a view was flattened
    // The frame's stages (docs/batch.md "Progress"): reading the inputs (or only the view
    // statements; a turntable's bounds included; 0 when the scene is kept from the frame
    // before), flattening the view, the engine's drawing with its composition, shading the
    // picture (picture defaults, anti-aliasing, edges), encoding and writing the outputs.
    double readSeconds = 0, flattenSeconds = 0, renderSeconds = 0, shadeSeconds = 0,
           writeSeconds = 0;
    double seconds = 0;  // the whole frame
};

// The world-space (Quadrix space) box of the scene's bounded solids, found by flattening it once
// with an axis-aligned parallel view and mapping the solids' device boxes back; unbounded solids
// (a ground plane) are left out. Empty box when nothing is bounded. Replaces the kept flat scene.
Box3 SceneWorldBounds(RenderContext& ctx, Diagnostics& diags);

// The view of turntable frame `frame` of `count`: rt's azimuth/elevation view about the box's
// centre, viewsize = the box's diagonal (import::MakeAzElView).
scene::View TurntableView(const Turntable& t, int frame, int count, const Box3& worldBox, int width,
                          int height);

// Whether every output of frame `frame` of `job` exists and is complete (io/output_check.h): what
// --resume skips. Used by the run to report, before it starts, what it resumes.
bool FrameComplete(const Job& job, int frame);

class JobRenderer {
  public:
    // threads: 0 = all cores (the context's oneTBB arena).
    explicit JobRenderer(int threads = 0) : ctx_(threads) {}

    // Renders frame `frame` of `job` (jobId tells jobs apart for the kept scene). With
    // skipExisting, a frame whose every output file exists is not rendered (result.skipped).
    FrameResult Render(const Job& job, int jobId, int frame, bool skipExisting = false);

    // Times the scene was read and flattened for a view (tests and the summary).
    int reads = 0, flattens = 0;
    // Times the geometry was flattened (the render context's world stage, kept across views and
    // across clocks that only move the camera).
    int GeometryFlattens() const { return ctx_.worldFlattens; }

  private:
    bool Load(const Job& job, int jobId, double clock, FrameResult& r);

    RenderContext ctx_;
    int loadedJob_ = -1;
    double loadedClock_ = 0;
    bool loadedOk_ = false;
    std::string loadError_;
    std::optional<Box3> worldBox_;
};

}  // namespace quadrix::batch
