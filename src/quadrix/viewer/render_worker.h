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
//   - calls: small tasks run between frames, before any waiting frame job: the initial camera
//     (synchronous, before the window opens), a pick (asynchronous: RequestPick, TakePick), and
//     a reload, which reads into a NEW context and swaps it in only when the read succeeded: a
//     scene with an error keeps the last good scene (and picture).
// The Frame is double-buffered: a frame is drawn into a scratch Frame and becomes the picked one
// only when it is delivered whole, so a pick always answers about the picture last delivered,
// even after a cancelled frame (the flat scene of that view is made again when needed; the
// render context keeps it, so this costs nothing when nothing else was flattened since).
// A drawing (`D`, StartDrawing) runs on a thread of its own, on a render context of its own
// holding a copy of the scene last read successfully: frames go on while it is written.
// Results are taken by polling; `wake` is called (from the worker's threads) whenever one is
// ready, so an event loop can sleep until then and never waits for the render thread.
#pragma once

#include <condition_variable>
#include <cstdint>
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

// A drawing written (or not) by StartDrawing.
struct DrawingOutcome {
    bool ok = false;
    std::string path;
    std::string messages;  // the diagnostics as printed (errors, or warnings of what was left out)
    std::string first;   // "file:line:col: error: message" of the first diagnostic, for the window
    double seconds = 0;  // from the request to the file written
};

// A pick asked for by RequestPick.
struct PickOutcome {
    PickResult pick;
    int tag = 0;         // as given (what the window asked it for)
    bool drawn = false;  // false: no frame of the current scene had been delivered to pick from
};

struct FrameJob {
    FrameRequest request;
    scene::View view;
    int width = 0, height = 0;  // the full-resolution size; the image is divided by request.scale
    std::string engine = "raycast";
    bool edges = false;            // show-edges over the shading (viewer/edges.h)
    std::optional<Plane> section;  // viewer/section.h
    bool hatch = false;            // hatch the section's cut faces (shade/section_hatch.h)
    int aaSamples = 0;     // samples per edge pixel when request.antialiased (shade/antialias.h)
    bool display = false;  // also encode the sRGB pixels a window shows (FrameOutcome)
};

struct FrameOutcome {
    FrameJob job;
    Image image;  // empty on error
    double seconds = 0;
    std::string error;  // the diagnostics when the frame could not be drawn
    std::vector<std::string> notes;
    bool cancelled = false;  // abandoned by CancelFrame: no image, no error
    // With job.display: DisplayPixels(image), encoded on the render thread.
    // In the Frame's storage (frame/frame.h): the mapping is kept for the next frame's words.
    FrameArray<std::uint32_t> display;
    // Where `seconds` went (the profile of a frame; --bench prints the means).
    double flattenSeconds = 0, renderSeconds = 0, shadeSeconds = 0, encodeSeconds = 0;
};

// The 8-bit sRGB values of an image (gray expanded), as the PNG writer encodes them, packed as
// 0x00RRGGBB words: SDL_PIXELFORMAT_RGB888, the X server's own format at depth 24, so the
// window's texture takes them without a conversion on the window's thread.
FrameArray<std::uint32_t> DisplayPixels(const Image& image);
// Those words back to RGB bytes (a screenshot's check against the window's read-back pixels).
std::vector<std::uint8_t> RgbBytes(const FrameArray<std::uint32_t>& pixels);

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
    // Waits for the frame submitted (the bench, which overlaps showing frame N with drawing
    // frame N + 1).
    FrameOutcome WaitFrame();
    // Draws a frame now and waits for it (the bench; no job may be pending).
    FrameOutcome RenderNow(const FrameJob& job);
    // Any thread: abandons the frame being drawn (if any; a frame started later is not
    // affected).
    void CancelFrame() { cancel_.Cancel(); }

    // Starts writing the hidden-line drawing of `view` at width×height to `path` (.svg, .pdf,
    // .eps by extension) by the path `quadrix draw` takes (pipeline/drawing_output.h), with the
    // same view, size, section and `title`, on a thread of its own (the frames go on meanwhile):
    // what cannot be drawn is refused as there (freeform surfaces unless the input's
    // allowMissing, --allow-missing). The outcome comes from TakeDrawing. false (nothing
    // started) while the previous drawing is being written.
    bool StartDrawing(const std::string& path, const scene::View& view, int width, int height,
                      const std::optional<Plane>& section, const std::string& title);
    std::optional<DrawingOutcome> TakeDrawing();
    bool DrawingInProgress();
    // Bodies of the last flattened scene (the picture defaults depend on it, as quadrix
    // render's).
    std::size_t BodyCount();

    // The camera for the scene's view `viewName` at width×height and the scene's bounding sphere
    // (falling back to the camera's window when nothing is bounded); a parallel camera's target
    // is moved to the depth of the sphere's centre, the orbit centre. Error message or empty.
    std::string InitialCamera(const std::string& viewName, int width, int height, Camera& camera,
                              SceneSphere& sphere);
    // Asks for the pick at window pixel (x, y) of the last frame delivered (scaled to its
    // resolution), run between frames; the outcome, with `tag`, comes from TakePick. A frame in
    // flight is finished first: cancel it (CancelFrame) for a prompt answer.
    void RequestPick(int x, int y, int tag = 0);
    std::optional<PickOutcome> TakePick();
    // The same, waiting for it (tests): the printed line (FormatPick) and the data.
    std::string PickText(int x, int y);
    PickResult PickAt(int x, int y);

  private:
    void Loop();
    // Runs `task` on the worker thread and waits for it.
    void Call(std::function<void()> task);
    LoadOutcome ReadInto(std::unique_ptr<RenderContext>& ctx);
    FrameOutcome Draw(const FrameJob& job);
    PickOutcome DoPick(int x, int y);

    InputRequest input_;
    int threads_;
    std::function<void()> wake_;
    // Worker-thread state.
    std::unique_ptr<RenderContext> ctx_;
    Frame frame_;  // the frame being drawn
    Frame drawn_;  // the last frame delivered whole (picks; an anti-aliasing job shades it)
    int drawnScale_ = 1;
    // What drawn_ holds: view request and engine; empty when nothing of this scene was drawn.
    std::optional<ViewRequest> drawnView_;
    std::string drawnEngine_;
    Cancellation cancel_;
    // Shared state, under mutex_.
    std::mutex mutex_;
    std::condition_variable cv_;
    std::deque<std::function<void()>> calls_;
    std::optional<FrameJob> job_;
    std::optional<FrameOutcome> frameDone_;
    std::optional<LoadOutcome> reloadDone_;
    std::deque<PickOutcome> picksDone_;
    // The scene last read successfully, for the drawing thread; its outcome.
    std::shared_ptr<const scene::Scene> scene_;
    bool drawingBusy_ = false;
    std::optional<DrawingOutcome> drawingDone_;
    std::thread drawingThread_;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace quadrix::viewer
