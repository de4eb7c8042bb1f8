// The viewer's render thread (issue 18 §1, §3): everything that touches the RenderContext runs
// here, off the window's event thread, so the window never waits for a frame.
//
// It owns one RenderContext (pipeline/render_context.h: Read once, then per frame Flatten with
// ViewRequest::view = the camera's view, Render, Shade). Work comes in two kinds:
//   - frame jobs: a single slot; submitting replaces a job not yet started, so a superseded view
//     is never drawn; the frame being drawn can be abandoned by CancelFrame (pipeline/
//     cancellation.h: the engines' tiles not yet started are skipped) and comes back cancelled;
//     an anti-aliasing job for the view, size, engine and section of the last Frame drawn shades
//     that Frame again with sub-pixel samples instead of rendering it again;
//   - calls: small synchronous tasks (the initial camera, a pick) run between frames, before any
//     waiting frame job, and a reload, which reads into a NEW context and swaps it in only when
//     the read succeeded: a scene with an error keeps the last good scene (and picture).
// Results are taken by polling; `wake` is called (from the worker thread) whenever one is ready,
// so an event loop can sleep until then.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/viewer/camera.h"
#include "quadrix/viewer/picking.h"
#include "quadrix/viewer/progressive.h"

namespace quadrix::viewer {

struct LoadOutcome {
    bool ok = false;
    std::string messages;    // the diagnostics as printed (with source lines), may be warnings
    std::string firstError;  // "file:line:col: message" of the first error, for a title bar
    std::vector<std::string>
        files;  // what to watch: the inputs and every file statements came from
};

// A drawing written (or not) by WriteDrawing.
struct DrawingOutcome {
    bool ok = false;
    std::string messages;  // the diagnostics as printed (errors, or warnings of what was left out)
    std::string first;  // "file:line:col: error: message" of the first diagnostic, for the window
};

struct FrameJob {
    FrameRequest request;
    scene::View view;
    int width = 0, height = 0;  // the full-resolution size; the image is divided by request.scale
    std::string engine = "raycast";
    bool edges = false;            // show-edges over the shading (viewer/edges.h)
    std::optional<Plane> section;  // viewer/section.h
    bool hatch = false;            // hatch the section's cut faces (shade/section_hatch.h)
    int aaSamples = 0;  // samples per edge pixel when request.antialiased (shade/antialias.h)
};

struct FrameOutcome {
    FrameJob job;
    Image image;  // empty on error
    double seconds = 0;
    std::string error;  // the diagnostics when the frame could not be drawn
    std::vector<std::string> notes;
    bool cancelled = false;  // abandoned by CancelFrame: no image, no error
};

class RenderWorker {
  public:
    RenderWorker(InputRequest input, int threads, std::function<void()> wake = {});
    ~RenderWorker();
    RenderWorker(const RenderWorker&) = delete;
    RenderWorker& operator=(const RenderWorker&) = delete;

    // Reads the inputs (synchronously; a failure keeps the previous scene).
    LoadOutcome Load();
    // Reads them again in the background; the outcome comes from TakeReload.
    void ReloadAsync();
    std::optional<LoadOutcome> TakeReload();

    void Submit(const FrameJob& job);
    std::optional<FrameOutcome> TakeFrame();
    // Draws a frame now and waits for it (the bench; no job may be pending).
    FrameOutcome RenderNow(const FrameJob& job);
    // Any thread: abandons the frame being drawn (if any; a frame started later is not
    // affected).
    void CancelFrame() { cancel_.Cancel(); }

    // The hidden-line drawing of `view` at width×height, written to `path` (.svg, .pdf, .eps by
    // extension) by the path `quadrix draw` takes (pipeline/drawing_output.h), with the same
    // view, size, section and `title`: what cannot be drawn is refused as there (freeform
    // surfaces unless the input's allowMissing, --allow-missing).
    DrawingOutcome WriteDrawing(const std::string& path, const scene::View& view, int width,
                                int height, const std::optional<Plane>& section,
                                const std::string& title);
    // Bodies of the last flattened scene (the picture defaults depend on it, as quadrix
    // render's).
    std::size_t BodyCount();

    // The camera for the scene's view `viewName` at width×height and the scene's bounding sphere
    // (falling back to the camera's window when nothing is bounded); a parallel camera's target
    // is moved to the depth of the sphere's centre, the orbit centre. Error message or empty.
    std::string InitialCamera(const std::string& viewName, int width, int height, Camera& camera,
                              SceneSphere& sphere);
    // The pick at window pixel (x, y) of the last frame drawn (scaled to its resolution).
    std::string PickText(int x, int y);
    // The same pick as data (world point and normal, ids, names).
    PickResult PickAt(int x, int y);

  private:
    void Loop();
    // Runs `task` on the worker thread and waits for it.
    void Call(std::function<void()> task);
    LoadOutcome ReadInto(std::unique_ptr<RenderContext>& ctx);
    FrameOutcome Draw(const FrameJob& job);

    InputRequest input_;
    int threads_;
    std::function<void()> wake_;
    // Worker-thread state.
    std::unique_ptr<RenderContext> ctx_;
    Frame frame_;
    int frameScale_ = 1;
    // What frame_ holds (an anti-aliasing job reuses it): view request and engine.
    std::optional<ViewRequest> frameView_;
    std::string frameEngine_;
    Cancellation cancel_;
    // Shared state, under mutex_.
    std::mutex mutex_;
    std::condition_variable cv_;
    std::deque<std::function<void()>> calls_;
    std::optional<FrameJob> job_;
    std::optional<FrameOutcome> frameDone_;
    std::optional<LoadOutcome> reloadDone_;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace quadrix::viewer
