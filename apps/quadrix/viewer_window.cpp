// The SDL2 window of `quadrix view` (issue 18). Software frames from the render thread
// (viewer/render_worker.h) are blitted as a streaming texture: no OpenGL is needed, and under
// Xvfb SDL's software renderer does the same job. The event thread only turns events into camera
// moves and commands, asks the render thread for frames (viewer/progressive.h), picks and
// drawings, and uploads what comes back; it never renders and never waits for the render thread
// (a pick is answered between two frames, a drawing is written on a thread of its own: both are
// polled like frames), except in the bench. --stats reports the longest pass of the event loop,
// which shows it.
//
// Scripted input (viewer/script.h) is replayed as SDL events pushed onto the window's own queue,
// so a script drives exactly the code a user does: the same mouse and key handlers.
//
// What the window shows: the frame's texture, scaled to the window when it is a reduced frame,
// and over it the overlay's texture (viewer/overlay.h: text in an opaque box, transparent
// elsewhere) when the overlay is on. A view change while a refining frame (full resolution or
// anti-aliased) is drawn cancels it (viewer/progressive.h); the latency from an input event to
// the first picture of a view at least that new is measured (--stats prints it at exit).
#include "viewer_window.h"

#ifdef QUADRIX_HAVE_SDL2

#include <SDL.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "quadrix/engines/registry.h"
#include "quadrix/io/writers.h"
#include "quadrix/pipeline/section_plane.h"
#include "quadrix/viewer/bench_orbit.h"
#include "quadrix/viewer/file_watch.h"
#include "quadrix/viewer/overlay.h"
#include "quadrix/viewer/progressive.h"
#include "quadrix/viewer/section.h"

namespace quadrix::cli {

namespace {

using Clock = std::chrono::steady_clock;
using viewer::Command;
using viewer::ScriptEvent;

double Since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::vector<std::string> UserEngines() {
    std::vector<std::string> names;
    for (const EngineInfo& e : Engines())
        if (!e.hidden) names.push_back(e.name);
    return names;
}

using SysClock = std::chrono::system_clock;

// What a pick was asked for (RenderWorker::RequestPick's tag).
enum PickTag : int { kPickShow = 0, kPickPivot = 1 };

// The statistics of a list of seconds, as "mean M ms, median D ms, max X ms".
std::string Summary(std::vector<double> v) {
    if (v.empty()) return "none";
    std::sort(v.begin(), v.end());
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
    return fmt::format("mean {:.2f} ms, median {:.2f} ms, max {:.2f} ms", 1e3 * mean,
                       1e3 * v[v.size() / 2], 1e3 * v.back());
}

class Viewer {
  public:
    explicit Viewer(const ViewerSession& s)
        : s_(s),
          camera_(s.camera),
          width_(s.width),
          height_(s.height),
          engine_(s.engine),
          engines_(UserEngines()),
          scheduler_(1.0 / 40, s.aaSamples > 1) {
        watch_.SetFiles(s.files);
    }
    ~Viewer() {
        if (overlayTexture_) SDL_DestroyTexture(overlayTexture_);
        if (texture_) SDL_DestroyTexture(texture_);
        if (renderer_) SDL_DestroyRenderer(renderer_);
        if (window_) SDL_DestroyWindow(window_);
        SDL_Quit();
    }

    bool Open();
    int Run();
    int Bench();

  private:
    void Title();
    void Changed();
    // The overlay's lines for the current state, and its texture made again when they changed.
    std::vector<std::string> OverlayLines() const;
    void UpdateOverlay();
    // The section plane as `quadrix render` options (empty when off), with --hatch when its
    // faces are hatched unless `drawing` (quadrix draw's options).
    std::string SectionOptions(bool drawing = false) const;
    void MoveSection(double pixels);  // along its normal, by `pixels` of the window's scale
    // Starts the drawing of the current view (written on the worker's drawing thread); false
    // when the previous one is still being written.
    bool StartDrawing(const std::string& path);
    void DrawingDone(const viewer::DrawingOutcome& d);
    void PickDone(const viewer::PickOutcome& p);
    // A pick or reload would wait for the refining frame in flight: cancel it (it is asked for
    // again), unless --no-cancel.
    void CancelRefinement();
    void PrintLatency() const;
    void HandleEvent(const SDL_Event& ev);
    void RunCommand(Command c);
    void Upload(viewer::FrameOutcome& frame);
    void Present(std::vector<std::uint8_t>* readback);
    void PumpWorker();
    void PollFiles();
    // Runs script events until one must wait; false when the script asks to quit.
    void StepScript();
    // Saves the frame (window = false) or the window's pixels with the overlay (true).
    bool Screenshot(const std::string& path, bool window = false);
    void PushMouse(Uint32 type, Uint8 button, int x, int y, int dx = 0, int dy = 0);

    const ViewerSession& s_;
    viewer::Camera camera_;
    int width_, height_;
    std::string engine_;
    bool edges_ = false;
    bool overlayOn_ = true;
    viewer::SectionPlane section_;
    bool hatch_ = true;  // the section's cut faces hatched (C), on with the plane
    std::vector<std::string> engines_;
    viewer::FrameScheduler scheduler_;
    viewer::FileWatch watch_;
    Clock::time_point lastPoll_ = Clock::now();
    SDL_Window* window_ = nullptr;
    SDL_Renderer* renderer_ = nullptr;
    SDL_Texture* texture_ = nullptr;
    int textureW_ = 0, textureH_ = 0;
    SDL_Texture* overlayTexture_ = nullptr;
    viewer::OverlayImage overlay_;
    std::vector<std::string> overlayLines_;
    FrameArray<std::uint32_t> shown_;  // the pixels in the texture (0x00RRGGBB)
    // The bench's profile of the window thread: texture upload, present (summed).
    double uploadSeconds_ = 0, presentSeconds_ = 0;
    Image shownImage_;  // the image they came from
    int shownScale_ = 1;
    bool shownAntialiased_ = false;
    double shownSeconds_ = 0;
    std::string error_;          // the current reload/frame error, for the title
    std::string drawingNotice_;  // the last drawing's first diagnostic, until the view changes
    std::vector<std::string> pickLines_;  // the last pick, in the overlay until the view changes
    std::string lastNote_;
    // Picks asked for and not answered yet; the drawing being written (its view, as printed).
    int picksPending_ = 0;
    struct PendingDrawing {
        std::string path, viewText, drawOptions;
        int width = 0, height = 0;
    };
    std::optional<PendingDrawing> drawing_;
    // The event loop's health (--stats): its longest pass (events handled + frames uploaded +
    // script), the frames shown while a drawing was being written, answer times.
    double longestPass_ = 0;
    long passes_ = 0;
    int framesDuringDrawing_ = 0;
    std::vector<double> pickSeconds_, drawingSeconds_;
    std::vector<Clock::time_point> pickAsked_;
    double slowestFrame_ = 0;
    // Live reload: the save (the file's modification time) of a reload asked for, and of the
    // reloaded scene's first picture and full-resolution picture still to come.
    std::optional<SysClock::time_point> reloadSaved_;
    std::optional<std::pair<std::uint64_t, SysClock::time_point>> reloadFirst_, reloadFull_;
    std::vector<double> reloadFirstSeconds_, reloadFullSeconds_;
    // Its parts: from the save to the change seen (polling), from then to the scene read.
    std::vector<double> reloadSeenSeconds_, reloadReadSeconds_;
    Clock::time_point reloadSeen_{};
    double lastReloadSeconds_ = -1;
    // Mouse (and ctrl, held for section drags).
    int dragButton_ = 0, downX_ = 0, downY_ = 0;
    bool moved_ = false, ctrlDown_ = false, sectionDrag_ = false;
    // Cancellation and latency: the first change not yet shown (generation, time).
    bool cancelSent_ = false;
    int framesCancelled_ = 0;
    std::optional<std::pair<std::uint64_t, Clock::time_point>> pendingChange_;
    std::vector<double> latencies_;
    int drawingCount_ = 0;
    // Script.
    std::size_t scriptPos_ = 0;
    bool scriptWaitsFinal_ = false;
    bool scriptWaitsAnswer_ = false;  // for the script's own pick or drawing
    Clock::time_point sleepUntil_{};
    bool running_ = true;
    int exitCode_ = 0;
    int screenshotCount_ = 0;
    std::string pendingScreenshot_;
    int reloads_ = 0;       // reloads done (successful or not)
    int reloadTarget_ = 0;  // the script waits until reloads_ reaches it
    Clock::time_point reloadDeadline_{};
};

bool Viewer::Open() {
    // Without a display server SDL may still initialise a console or offscreen driver and open
    // an invisible "window" that no one can close: refuse unless a driver was asked for.
    if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY") &&
        !std::getenv("SDL_VIDEODRIVER")) {
        std::fprintf(stderr,
                     "quadrix: error: cannot open a window: no display (DISPLAY and "
                     "WAYLAND_DISPLAY are unset; run under a desktop session or `xvfb-run -a`; "
                     "`quadrix view --bench N` renders offscreen)\n");
        return false;
    }
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        std::fprintf(stderr,
                     "quadrix: error: cannot open a window: %s\n(no display? run under a desktop "
                     "session or `xvfb-run -a`; `quadrix view --bench N` renders offscreen)\n",
                     SDL_GetError());
        return false;
    }
    SDL_SetHint(SDL_HINT_RENDER_SCALE_QUALITY, "nearest");
    window_ = SDL_CreateWindow("quadrix view", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED,
                               width_, height_, SDL_WINDOW_RESIZABLE);
    if (window_) renderer_ = SDL_CreateRenderer(window_, -1, 0);
    if (window_ && !renderer_) renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
    if (!window_ || !renderer_) {
        std::fprintf(stderr, "quadrix: error: cannot open a window: %s\n", SDL_GetError());
        return false;
    }
    SDL_SetRenderDrawColor(renderer_, 0, 0, 0, 255);
    Title();
    return true;
}

void Viewer::Title() {
    std::string t =
        fmt::format("quadrix view — {} — {} — {}x{}", s_.name, engine_, width_, height_);
    if (shownScale_ > 1) t += fmt::format(" (1/{})", shownScale_);
    if (shownSeconds_ > 0) t += fmt::format(" — {:.1f} ms", 1e3 * shownSeconds_);
    t += camera_.perspective ? " — perspective" : " — parallel";
    if (edges_) t += " — edges";
    if (section_.on) t += hatch_ ? " — section (hatched)" : " — section";
    if (!error_.empty())
        t += " — ERROR " + error_;
    else
        t += " — H: help";
    SDL_SetWindowTitle(window_, t.c_str());
    UpdateOverlay();
}

void Viewer::Changed() {
    drawingNotice_.clear();
    pickLines_.clear();
    scheduler_.ViewChanged();
    if (!pendingChange_) pendingChange_.emplace(scheduler_.Generation(), Clock::now());
    if (s_.cancelStale && !cancelSent_ && scheduler_.StaleRefinementInFlight()) {
        s_.worker->CancelFrame();
        cancelSent_ = true;
    }
}

std::vector<std::string> Viewer::OverlayLines() const {
    std::string a = fmt::format("{}  {}x{}", engine_, width_, height_);
    if (shownScale_ > 1) a += fmt::format(" (1/{})", shownScale_);
    if (shownSeconds_ > 0) a += fmt::format("  {:.1f} ms", 1e3 * shownSeconds_);
    if (shownAntialiased_) a += fmt::format("  aa {}", s_.aaSamples);
    a += camera_.perspective ? "  perspective" : "  parallel";
    if (edges_) a += "  edges";
    if (section_.on) a += hatch_ ? "  section hatched" : "  section";
    if (lastReloadSeconds_ >= 0) a += fmt::format("  reload {:.0f} ms", 1e3 * lastReloadSeconds_);
    std::vector<std::string> lines = {a};
    if (!error_.empty()) lines.push_back("error: " + error_);
    if (!drawingNotice_.empty()) lines.push_back(drawingNotice_);
    lines.insert(lines.end(), pickLines_.begin(), pickLines_.end());
    // The help in one row: the longest form that fits the window (the overlay wraps the rest).
    int w = width_, h = height_;
    if (renderer_) SDL_GetRendererOutputSize(renderer_, &w, &h);
    const int columns = viewer::OverlayColumns(w, h);
    static const std::string kHelps[] = {
        "H help  X section  [ ] move it  C hatch  D drawing  V view  O overlay  Q quit",
        "H help  X section  D drawing  V view  Q quit", "H help  V view  Q quit", "H help"};
    for (const std::string& help : kHelps)
        if (static_cast<int>(help.size()) <= columns || &help == &kHelps[3]) {
            lines.push_back(help);
            break;
        }
    return lines;
}

void Viewer::UpdateOverlay() {
    if (!renderer_) return;
    std::vector<std::string> lines = overlayOn_ ? OverlayLines() : std::vector<std::string>{};
    int w = 0, h = 0;
    SDL_GetRendererOutputSize(renderer_, &w, &h);
    if (lines == overlayLines_ && overlay_.width == w && overlay_.height == h) return;
    overlayLines_ = lines;
    overlay_ = viewer::DrawOverlay(lines, w, h);
    if (overlayTexture_) SDL_DestroyTexture(overlayTexture_);
    overlayTexture_ = nullptr;
    if (overlay_.Empty() || overlay_.boxWidth == 0 || overlay_.boxHeight == 0) return;
    // Only the box, copied without blending (every pixel of it is opaque, every other one
    // transparent): blending a window-sized texture cost the software renderer milliseconds
    // a frame at 1280×720.
    overlayTexture_ =
        SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGBA32, SDL_TEXTUREACCESS_STREAMING,
                          overlay_.boxWidth, overlay_.boxHeight);
    if (!overlayTexture_) return;
    SDL_SetTextureBlendMode(overlayTexture_, SDL_BLENDMODE_NONE);
    SDL_UpdateTexture(overlayTexture_, nullptr, overlay_.rgba.data(), overlay_.width * 4);
}

std::string Viewer::SectionOptions(bool drawing) const {
    const std::optional<Plane> p = section_.ToPlane();
    if (!p) return {};
    return fmt::format(" --section \"{}\"{}", FormatSectionPlane(*p),
                       hatch_ && !drawing ? " --hatch" : "");
}

void Viewer::MoveSection(double pixels) {
    if (!section_.on) return;
    section_.Move(pixels * 2 * camera_.halfHeight / height_);
    Changed();
}

bool Viewer::StartDrawing(const std::string& path) {
    if (!s_.worker->StartDrawing(path, camera_.ToView(), width_, height_, section_.ToPlane(),
                                 s_.name)) {
        drawingNotice_ = "drawing: the previous drawing is still being written";
        Title();
        return false;
    }
    // The view drawn is the view now, whatever happens while it is written.
    drawing_ = PendingDrawing{
        path, viewer::FormatViewStatement(camera_, width_, height_, "camera", SectionOptions()),
        SectionOptions(true), width_, height_};
    drawingNotice_ = "drawing " + path + " ...";
    Title();
    return true;
}

void Viewer::DrawingDone(const viewer::DrawingOutcome& d) {
    const std::optional<PendingDrawing> pending = std::move(drawing_);
    drawing_.reset();
    drawingSeconds_.push_back(d.seconds);
    // What was refused or left out (freeform surfaces, draw/undrawable.h) is said on standard
    // error and in the window's overlay until the view changes, never passed over.
    std::fputs(d.messages.c_str(), stderr);
    drawingNotice_ = d.first.empty() ? std::string() : "drawing: " + d.first;
    Title();
    if (renderer_) Present(nullptr);
    if (!d.ok) {
        std::fprintf(stderr, "quadrix: error: drawing %s not written\n", d.path.c_str());
        exitCode_ = 1;
        return;
    }
    if (!pending) return;
    std::fprintf(stderr,
                 "quadrix: drawing %s (%.0f ms): the view below, drawn as `quadrix draw %s "
                 "VIEW.uq --size %dx%d%s -o %s`\n",
                 d.path.c_str(), 1e3 * d.seconds, s_.name.c_str(), pending->width, pending->height,
                 pending->drawOptions.c_str(), d.path.c_str());
    std::fputs(pending->viewText.c_str(), stdout);
    std::fflush(stdout);
}

void Viewer::PickDone(const viewer::PickOutcome& p) {
    --picksPending_;
    if (!pickAsked_.empty()) {
        pickSeconds_.push_back(Since(pickAsked_.front()));
        pickAsked_.erase(pickAsked_.begin());
    }
    if (p.tag == kPickPivot) {
        // A double-click makes the picked point the orbit centre.
        if (p.drawn && p.pick.hit) {
            camera_.pivot = p.pick.point;
            std::printf("orbit centre %.6g %.6g %.6g\n", p.pick.point.x, p.pick.point.y,
                        p.pick.point.z);
            std::fflush(stdout);
        }
        return;
    }
    const std::string text = p.drawn ? viewer::FormatPick(p.pick) : "pick: nothing drawn yet";
    std::printf("%s\n", text.c_str());
    std::fflush(stdout);
    pickLines_ = p.drawn ? viewer::PickOverlayLines(p.pick) : std::vector<std::string>{text};
    Title();
    if (renderer_) Present(nullptr);
}

void Viewer::CancelRefinement() {
    if (s_.cancelStale && !cancelSent_ && scheduler_.RefinementInFlight()) {
        s_.worker->CancelFrame();
        cancelSent_ = true;
    }
}

void Viewer::PrintLatency() const {
    if (latencies_.empty()) {
        std::fprintf(stderr, "quadrix: latency: no input event was followed by a picture\n");
    } else {
        std::vector<double> v = latencies_;
        std::sort(v.begin(), v.end());
        const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
        std::fprintf(stderr,
                     "quadrix: latency from an input event to the first picture of its view: %zu "
                     "events, mean %.1f ms, median %.1f ms, 90th %.1f ms, max %.1f ms; %d stale "
                     "frames cancelled\n",
                     v.size(), 1e3 * mean, 1e3 * v[v.size() / 2], 1e3 * v[(v.size() * 9) / 10],
                     1e3 * v.back(), framesCancelled_);
    }
    std::fprintf(stderr,
                 "quadrix: event loop: %ld passes, longest %.1f ms; slowest frame %.1f ms; "
                 "picks: %zu answered (%s); drawings: %zu written (%s), %d frames shown while "
                 "one was written\n",
                 passes_, 1e3 * longestPass_, 1e3 * slowestFrame_, pickSeconds_.size(),
                 Summary(pickSeconds_).c_str(), drawingSeconds_.size(),
                 Summary(drawingSeconds_).c_str(), framesDuringDrawing_);
    std::fprintf(stderr,
                 "quadrix: live reload: %zu reloads; from saving a file to the first picture "
                 "of the new scene: %s; to its full-resolution picture: %s; of which the change "
                 "seen (10 ms polling): %s, the scene read: %s\n",
                 reloadFirstSeconds_.size(), Summary(reloadFirstSeconds_).c_str(),
                 Summary(reloadFullSeconds_).c_str(), Summary(reloadSeenSeconds_).c_str(),
                 Summary(reloadReadSeconds_).c_str());
}

void Viewer::Upload(viewer::FrameOutcome& frame) {
    const Image& im = frame.image;
    if (!texture_ || textureW_ != im.width || textureH_ != im.height) {
        if (texture_) SDL_DestroyTexture(texture_);
        texture_ = SDL_CreateTexture(renderer_, SDL_PIXELFORMAT_RGB888, SDL_TEXTUREACCESS_STREAMING,
                                     im.width, im.height);
        textureW_ = im.width;
        textureH_ = im.height;
    }
    // The sRGB bytes were encoded on the render thread (FrameJob::display).
    const auto t0 = Clock::now();
    shown_ = frame.display.empty() ? viewer::DisplayPixels(im) : std::move(frame.display);
    if (texture_) SDL_UpdateTexture(texture_, nullptr, shown_.data(), im.width * 4);
    uploadSeconds_ += Since(t0);
    shownImage_ = std::move(frame.image);  // `im` is not used below
    shownScale_ = frame.job.request.scale;
    shownAntialiased_ = frame.job.request.antialiased;
    if (!frame.job.request.antialiased) shownSeconds_ = frame.seconds;
    if (pendingChange_ && frame.job.request.generation >= pendingChange_->first) {
        latencies_.push_back(Since(pendingChange_->second));
        pendingChange_.reset();
    }
    if (drawing_) ++framesDuringDrawing_;
    const auto t1 = Clock::now();
    Present(nullptr);
    presentSeconds_ += Since(t1);
    // From the save of a reloaded file to its first picture, and to its full-resolution one.
    const std::uint64_t generation = frame.job.request.generation;
    auto sinceSave = [](SysClock::time_point saved) {
        return std::chrono::duration<double>(SysClock::now() - saved).count();
    };
    if (reloadFirst_ && generation >= reloadFirst_->first) {
        lastReloadSeconds_ = sinceSave(reloadFirst_->second);
        reloadFirstSeconds_.push_back(lastReloadSeconds_);
        reloadFirst_.reset();
    }
    if (reloadFull_ && generation >= reloadFull_->first && shownScale_ == 1) {
        reloadFullSeconds_.push_back(sinceSave(reloadFull_->second));
        reloadFull_.reset();
    }
}

void Viewer::Present(std::vector<std::uint8_t>* readback) {
    if (!texture_) SDL_RenderClear(renderer_);  // the texture covers the window
    if (texture_) SDL_RenderCopy(renderer_, texture_, nullptr, nullptr);
    if (overlayTexture_ && overlayOn_) {
        const SDL_Rect box{0, 0, overlay_.boxWidth, overlay_.boxHeight};
        SDL_RenderCopy(renderer_, overlayTexture_, nullptr, &box);
    }
    if (readback) {
        int w = 0, h = 0;
        SDL_GetRendererOutputSize(renderer_, &w, &h);
        readback->assign(static_cast<std::size_t>(w) * h * 3, 0);
        if (SDL_RenderReadPixels(renderer_, nullptr, SDL_PIXELFORMAT_RGB24, readback->data(),
                                 w * 3) != 0)
            readback->clear();
    }
    SDL_RenderPresent(renderer_);
}

void Viewer::PumpWorker() {
    if (auto frame = s_.worker->TakeFrame()) {
        cancelSent_ = false;
        if (frame->cancelled) {
            scheduler_.Abandoned();  // a newer view is asked for below
            ++framesCancelled_;
        } else if (!frame->error.empty()) {
            scheduler_.Delivered(frame->job.request, frame->seconds);
            if (frame->error != error_) std::fputs(frame->error.c_str(), stderr);
            error_ = frame->error.substr(0, frame->error.find('\n'));
            if (s_.script) {  // a scripted session cannot go on with a picture it did not get
                exitCode_ = 1;
                running_ = false;
            }
        } else {
            scheduler_.Delivered(frame->job.request, frame->seconds);
            slowestFrame_ = std::max(slowestFrame_, frame->seconds);
            for (const std::string& n : frame->notes)
                if (frame->job.request.scale == 1 && n != lastNote_) {
                    std::fprintf(stderr, "quadrix: note: %s\n", n.c_str());
                    lastNote_ = n;
                }
            Upload(*frame);
        }
        Title();
    }
    while (auto pick = s_.worker->TakePick()) PickDone(*pick);
    if (auto d = s_.worker->TakeDrawing()) DrawingDone(*d);
    if (auto load = s_.worker->TakeReload()) {
        ++reloads_;
        watch_.SetFiles(load->files);
        if (load->ok) {
            if (!load->messages.empty()) std::fputs(load->messages.c_str(), stderr);
            std::fprintf(stderr, "quadrix: reloaded\n");
            error_.clear();
            Changed();
            if (reloadSaved_) {
                reloadReadSeconds_.push_back(Since(reloadSeen_));
                reloadFirst_.emplace(scheduler_.Generation(), *reloadSaved_);
                reloadFull_ = reloadFirst_;
            }
            reloadSaved_.reset();
        } else {
            std::fputs(load->messages.c_str(), stderr);
            std::fprintf(stderr, "quadrix: the scene has errors; keeping the last good picture\n");
            error_ = load->firstError;
        }
        Title();
    }
    if (!scheduler_.InFlight()) {
        if (auto req = scheduler_.Next()) {
            viewer::FrameJob job;
            job.request = *req;
            job.view = camera_.ToView();
            job.width = width_;
            job.height = height_;
            job.engine = engine_;
            job.edges = edges_;
            job.section = section_.ToPlane();
            job.hatch = hatch_;
            job.aaSamples = s_.aaSamples;
            job.display = true;
            cancelSent_ = false;
            s_.worker->Submit(job);
        }
    }
}

void Viewer::PollFiles() {
    // Every 10 ms (each pass of the loop, which waits 10 ms at most for an event): one stat()
    // per watched file.
    if (Since(lastPoll_) < 0.01) return;
    lastPoll_ = Clock::now();
    if (!watch_.Changed()) return;
    reloadSaved_ = watch_.LastChangeTime();
    if (!reloadSaved_) reloadSaved_ = SysClock::now();  // a file went away
    reloadSeen_ = Clock::now();
    reloadSeenSeconds_.push_back(
        std::max(0.0, std::chrono::duration<double>(SysClock::now() - *reloadSaved_).count()));
    CancelRefinement();  // its picture is of the old scene: let the reload start at once
    s_.worker->ReloadAsync();
}

bool Viewer::Screenshot(const std::string& path, bool window) {
    UpdateOverlay();
    std::vector<std::uint8_t> pixels;
    Present(&pixels);
    int w = 0, h = 0;
    SDL_GetRendererOutputSize(renderer_, &w, &h);
    // The window must show the image byte for byte when it is at its full resolution, with the
    // overlay's opaque pixels over it.
    std::vector<std::uint8_t> expected = viewer::RgbBytes(shown_);
    if (overlayOn_ && overlayTexture_) viewer::CompositeOverlay(overlay_, expected);
    if (shownScale_ == 1 && w == shownImage_.width && h == shownImage_.height &&
        pixels != expected) {
        std::fprintf(stderr, "quadrix: error: the window's pixels differ from the frame drawn\n");
        exitCode_ = 1;
    }
    if (window) {
        // The window's bytes are sRGB already (the image writers encode linear pixels): written
        // as they are, a binary PPM.
        const bool ppm = path.size() > 4 && path.compare(path.size() - 4, 4, ".ppm") == 0;
        if (!ppm || pixels.size() != static_cast<std::size_t>(w) * h * 3) {
            std::fprintf(stderr, "quadrix: error: screenshot-window '%s': %s\n", path.c_str(),
                         ppm ? "the window cannot be read back" : "use .ppm");
            exitCode_ = 1;
            return false;
        }
        std::string bytes = fmt::format("P6\n{} {}\n255\n", w, h);
        bytes.append(pixels.begin(), pixels.end());
        if (auto e = WriteFileAtomically(path, bytes); !e.empty()) {
            std::fprintf(stderr, "quadrix: error: screenshot-window: %s\n", e.c_str());
            exitCode_ = 1;
            return false;
        }
        std::fprintf(stderr, "quadrix: screenshot %s (%dx%d, the window with its overlay)\n",
                     path.c_str(), w, h);
        return true;
    }
    ImageFormat format;
    if (!ImageFormatFromPath(path, format) || format == ImageFormat::kFrameDump) {
        std::fprintf(stderr, "quadrix: error: screenshot '%s': use .png, .ppm or .pgm\n",
                     path.c_str());
        exitCode_ = 1;
        return false;
    }
    const std::string e =
        format == ImageFormat::kPng ? WritePng(path, shownImage_) : WritePnm(path, shownImage_);
    if (!e.empty()) {
        std::fprintf(stderr, "quadrix: error: screenshot: %s\n", e.c_str());
        exitCode_ = 1;
        return false;
    }
    std::fprintf(stderr, "quadrix: screenshot %s (%dx%d)\n", path.c_str(), shownImage_.width,
                 shownImage_.height);
    return true;
}

void Viewer::RunCommand(Command c) {
    using viewer::StandardView;
    auto standard = [&](StandardView v) {
        camera_.SetStandardView(v, s_.sphere);
        Changed();
    };
    switch (c) {
        case Command::kNone:
            break;
        case Command::kFront:
            standard(StandardView::kFront);
            break;
        case Command::kBack:
            standard(StandardView::kBack);
            break;
        case Command::kLeft:
            standard(StandardView::kLeft);
            break;
        case Command::kRight:
            standard(StandardView::kRight);
            break;
        case Command::kTop:
            standard(StandardView::kTop);
            break;
        case Command::kBottom:
            standard(StandardView::kBottom);
            break;
        case Command::kIso:
            standard(StandardView::kIso);
            break;
        case Command::kTogglePerspective:
            camera_.SetPerspective(!camera_.perspective, 3 * s_.sphere.radius);
            Changed();
            break;
        case Command::kToggleEdges:
            edges_ = !edges_;
            Changed();
            break;
        case Command::kReset:
            camera_ = s_.camera;
            Changed();
            break;
        case Command::kFitAll:
            camera_.FitAll(s_.sphere, width_, height_);
            Changed();
            break;
        case Command::kPrintView:
            std::fputs(
                viewer::FormatViewStatement(camera_, width_, height_, "camera", SectionOptions())
                    .c_str(),
                stdout);
            std::fflush(stdout);
            break;
        case Command::kNextEngine:
        case Command::kPreviousEngine: {
            if (engines_.empty()) break;
            auto it = std::find(engines_.begin(), engines_.end(), engine_);
            std::size_t i =
                it == engines_.end() ? 0 : static_cast<std::size_t>(it - engines_.begin());
            const std::size_t n = engines_.size();
            i = c == Command::kNextEngine ? (i + 1) % n : (i + n - 1) % n;
            engine_ = engines_[i];
            std::fprintf(stderr, "quadrix: engine %s\n", engine_.c_str());
            Changed();
            break;
        }
        case Command::kScreenshot:
            pendingScreenshot_ = fmt::format("quadrix-view-{}.png", ++screenshotCount_);
            break;
        case Command::kHelp:
            std::fputs(viewer::KeyHelp().c_str(), stdout);
            break;
        case Command::kQuit:
            running_ = false;
            break;
        case Command::kToggleSection:
            section_.Toggle(camera_, camera_.pivot.value_or(camera_.target));
            if (section_.on)
                std::fprintf(stderr, "quadrix: section plane%s\n", SectionOptions().c_str());
            Changed();
            break;
        case Command::kFlipSection:
            if (!section_.on) break;
            section_.Flip();
            Changed();
            break;
        case Command::kSectionAway:
        case Command::kSectionToward:
            // A twentieth of the window's height a press.
            MoveSection((c == Command::kSectionToward ? 1 : -1) * height_ / 20.0);
            break;
        case Command::kToggleHatch:
            hatch_ = !hatch_;
            if (section_.on) Changed();
            break;
        case Command::kToggleOverlay:
            overlayOn_ = !overlayOn_;
            UpdateOverlay();
            Present(nullptr);
            break;
        case Command::kDrawing:
            StartDrawing(fmt::format("quadrix-view-{}.svg", ++drawingCount_));
            break;
    }
    Title();
}

void Viewer::HandleEvent(const SDL_Event& ev) {
    switch (ev.type) {
        case SDL_QUIT:
            running_ = false;
            break;
        case SDL_WINDOWEVENT:
            if (ev.window.event == SDL_WINDOWEVENT_SIZE_CHANGED) {
                width_ = std::max(1, ev.window.data1);
                height_ = std::max(1, ev.window.data2);
                Changed();
                UpdateOverlay();
                Present(nullptr);
            } else if (ev.window.event == SDL_WINDOWEVENT_EXPOSED) {
                Present(nullptr);
            }
            break;
        case SDL_MOUSEBUTTONDOWN:
            if (ev.button.button == SDL_BUTTON_LEFT && ev.button.clicks == 2) {
                // A double-click makes the picked point the orbit centre (PickDone).
                CancelRefinement();
                s_.worker->RequestPick(ev.button.x, ev.button.y, kPickPivot);
                ++picksPending_;
                pickAsked_.push_back(Clock::now());
            }
            if (dragButton_ == 0) {
                dragButton_ = ev.button.button;
                downX_ = ev.button.x;
                downY_ = ev.button.y;
                moved_ = false;
                sectionDrag_ = ctrlDown_ && section_.on && dragButton_ == SDL_BUTTON_LEFT;
            }
            break;
        case SDL_MOUSEBUTTONUP:
            if (ev.button.button == dragButton_) {
                if (!moved_ && dragButton_ == SDL_BUTTON_LEFT && !sectionDrag_) {
                    // Answered between two frames (PickDone): the refining frame in flight, if
                    // any, is cancelled so that the answer does not wait for it.
                    CancelRefinement();
                    s_.worker->RequestPick(ev.button.x, ev.button.y, kPickShow);
                    ++picksPending_;
                    pickAsked_.push_back(Clock::now());
                }
                dragButton_ = 0;
            }
            break;
        case SDL_MOUSEMOTION:
            if (dragButton_ == 0) break;
            if (!moved_ && std::abs(ev.motion.x - downX_) + std::abs(ev.motion.y - downY_) < 3 &&
                std::abs(ev.motion.xrel) + std::abs(ev.motion.yrel) < 3)
                break;  // a click that trembles is still a click
            moved_ = true;
            if (sectionDrag_)
                MoveSection(-ev.motion.yrel);  // dragging up moves it toward the viewer
            else if (dragButton_ == SDL_BUTTON_LEFT)
                camera_.Orbit(ev.motion.xrel, ev.motion.yrel, height_);
            else
                camera_.Pan(ev.motion.xrel, ev.motion.yrel, height_);
            Changed();
            break;
        case SDL_MOUSEWHEEL: {
            if (ev.wheel.y == 0) break;
            int x = 0, y = 0;
#if SDL_VERSION_ATLEAST(2, 26, 0)
            x = ev.wheel.mouseX;
            y = ev.wheel.mouseY;
#else
            SDL_GetMouseState(&x, &y);
#endif
            const int clicks =
                ev.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -ev.wheel.y : ev.wheel.y;
            camera_.Zoom(clicks, x, y, width_, height_);
            Changed();
            break;
        }
        case SDL_KEYUP:
            if (ev.key.keysym.sym == SDLK_LCTRL || ev.key.keysym.sym == SDLK_RCTRL)
                ctrlDown_ = false;
            break;
        case SDL_KEYDOWN:
            if (ev.key.keysym.sym == SDLK_LCTRL || ev.key.keysym.sym == SDLK_RCTRL) {
                ctrlDown_ = true;
                break;
            }
            RunCommand(viewer::CommandForKey(SDL_GetKeyName(ev.key.keysym.sym),
                                             (ev.key.keysym.mod & KMOD_SHIFT) != 0));
            break;
        default:
            break;
    }
}

void Viewer::PushMouse(Uint32 type, Uint8 button, int x, int y, int dx, int dy) {
    SDL_Event ev{};
    ev.type = type;
    if (type == SDL_MOUSEMOTION) {
        ev.motion.x = x;
        ev.motion.y = y;
        ev.motion.xrel = dx;
        ev.motion.yrel = dy;
    } else {
        ev.button.button = button;
        ev.button.x = x;
        ev.button.y = y;
        ev.button.state = type == SDL_MOUSEBUTTONDOWN ? SDL_PRESSED : SDL_RELEASED;
        ev.button.clicks = 1;
    }
    SDL_PushEvent(&ev);
}

void Viewer::StepScript() {
    if (!s_.script) return;
    const auto& script = *s_.script;
    if (Clock::now() < sleepUntil_) return;
    if (scriptWaitsFinal_ && !scheduler_.Final()) return;
    if (reloads_ < reloadTarget_) {
        if (Clock::now() < reloadDeadline_) return;
        std::fprintf(stderr, "quadrix: error: wait-reload: no reload within 20 s\n");
        exitCode_ = 1;
        running_ = false;
        return;
    }
    // The script's own picks and drawings are waited for before its next line; any pick or
    // drawing (a `key D`) before its end.
    const bool answersPending = picksPending_ > 0 || drawing_;
    if (scriptWaitsAnswer_ && answersPending) return;
    scriptWaitsAnswer_ = false;
    if (scriptPos_ >= script.size() && answersPending) return;
    scriptWaitsFinal_ = false;
    while (running_ && scriptPos_ < script.size()) {
        const ScriptEvent& e = script[scriptPos_];
        // Picks and screenshots need the full-resolution frame of the view so far.
        if ((e.kind == ScriptEvent::Kind::kClick || e.kind == ScriptEvent::Kind::kScreenshot ||
             e.kind == ScriptEvent::Kind::kScreenshotWindow ||
             e.kind == ScriptEvent::Kind::kDrawing || e.kind == ScriptEvent::Kind::kWait) &&
            !scheduler_.Final()) {
            scriptWaitsFinal_ = true;
            return;
        }
        if (e.kind == ScriptEvent::Kind::kDrawing && drawing_) return;  // one at a time
        ++scriptPos_;
        const int cx = width_ / 2, cy = height_ / 2;
        switch (e.kind) {
            case ScriptEvent::Kind::kOrbit:
            case ScriptEvent::Kind::kPan: {
                const Uint8 button =
                    e.kind == ScriptEvent::Kind::kOrbit ? SDL_BUTTON_LEFT : SDL_BUTTON_RIGHT;
                PushMouse(SDL_MOUSEBUTTONDOWN, button, cx, cy);
                // Integer motions summing exactly to the total.
                int doneX = 0, doneY = 0;
                for (int k = 1; k <= e.steps; ++k) {
                    const int toX = static_cast<int>(std::lround(e.x * k / e.steps));
                    const int toY = static_cast<int>(std::lround(e.y * k / e.steps));
                    PushMouse(SDL_MOUSEMOTION, 0, cx + toX, cy + toY, toX - doneX, toY - doneY);
                    doneX = toX;
                    doneY = toY;
                }
                PushMouse(SDL_MOUSEBUTTONUP, button, cx + doneX, cy + doneY);
                return;  // let the window handle them before the next script line
            }
            case ScriptEvent::Kind::kSectionDrag: {
                auto key = [](Uint32 type) {
                    SDL_Event ev{};
                    ev.type = type;
                    ev.key.state = type == SDL_KEYDOWN ? SDL_PRESSED : SDL_RELEASED;
                    ev.key.keysym.sym = SDLK_LCTRL;
                    ev.key.keysym.scancode = SDL_SCANCODE_LCTRL;
                    SDL_PushEvent(&ev);
                };
                key(SDL_KEYDOWN);
                PushMouse(SDL_MOUSEBUTTONDOWN, SDL_BUTTON_LEFT, cx, cy);
                int done = 0;
                for (int k = 1; k <= e.steps; ++k) {
                    const int to = static_cast<int>(std::lround(e.y * k / e.steps));
                    PushMouse(SDL_MOUSEMOTION, 0, cx, cy + to, 0, to - done);
                    done = to;
                }
                PushMouse(SDL_MOUSEBUTTONUP, SDL_BUTTON_LEFT, cx, cy + done);
                key(SDL_KEYUP);
                return;
            }
            case ScriptEvent::Kind::kZoom: {
                SDL_Event ev{};
                ev.type = SDL_MOUSEWHEEL;
                ev.wheel.y = static_cast<Sint32>(std::lround(e.amount));
                ev.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
#if SDL_VERSION_ATLEAST(2, 26, 0)
                ev.wheel.mouseX = std::isnan(e.x) ? cx : static_cast<Sint32>(e.x);
                ev.wheel.mouseY = std::isnan(e.y) ? cy : static_cast<Sint32>(e.y);
#endif
                SDL_PushEvent(&ev);
                return;
            }
            case ScriptEvent::Kind::kClick:
            case ScriptEvent::Kind::kClickNow:
                scriptWaitsAnswer_ = true;
                PushMouse(SDL_MOUSEBUTTONDOWN, SDL_BUTTON_LEFT, int(e.x), int(e.y));
                PushMouse(SDL_MOUSEBUTTONUP, SDL_BUTTON_LEFT, int(e.x), int(e.y));
                return;
            case ScriptEvent::Kind::kKey: {
                SDL_Event ev{};
                ev.type = SDL_KEYDOWN;
                ev.key.state = SDL_PRESSED;
                ev.key.keysym.sym = SDL_GetKeyFromName(e.text.c_str());
                ev.key.keysym.scancode = SDL_GetScancodeFromKey(ev.key.keysym.sym);
                SDL_PushEvent(&ev);
                return;
            }
            case ScriptEvent::Kind::kEngine:
                if (e.text == "next") {
                    RunCommand(Command::kNextEngine);
                } else if (std::find(engines_.begin(), engines_.end(), e.text) != engines_.end()) {
                    engine_ = e.text;
                    Changed();
                } else {
                    std::fprintf(stderr, "%s: error: unknown engine '%s' (%s)\n",
                                 e.loc.ToString().c_str(), e.text.c_str(), EngineList().c_str());
                    exitCode_ = 1;
                    running_ = false;
                }
                break;
            case ScriptEvent::Kind::kWait:
                break;
            case ScriptEvent::Kind::kScreenshot:
            case ScriptEvent::Kind::kScreenshotWindow:
                if (!Screenshot(e.text, e.kind == ScriptEvent::Kind::kScreenshotWindow))
                    running_ = false;
                break;
            case ScriptEvent::Kind::kDrawing:
                // A failed drawing is reported (the exit status too), and the script goes on:
                // what the window shows about it can be looked at. The script waits for it.
                scriptWaitsAnswer_ = StartDrawing(e.text);
                return;
            case ScriptEvent::Kind::kPrintView:
                if (e.text.empty()) {
                    RunCommand(Command::kPrintView);
                } else if (auto err = WriteFileAtomically(
                               e.text, viewer::FormatViewStatement(camera_, width_, height_,
                                                                   "camera", SectionOptions()));
                           !err.empty()) {
                    std::fprintf(stderr, "quadrix: error: print-view: %s\n", err.c_str());
                    exitCode_ = 1;
                    running_ = false;
                }
                break;
            case ScriptEvent::Kind::kSleep:
                sleepUntil_ = Clock::now() +
                              std::chrono::microseconds(static_cast<long long>(e.amount * 1000));
                return;
            case ScriptEvent::Kind::kWaitReload:
                reloadTarget_ = reloads_ + 1;
                reloadDeadline_ = Clock::now() + std::chrono::seconds(20);
                return;
            case ScriptEvent::Kind::kQuit:
                running_ = false;
                break;
        }
    }
    // The end of a script closes the window, once its picks and drawings are answered.
    if (scriptPos_ >= script.size() && picksPending_ == 0 && !drawing_) running_ = false;
}

int Viewer::Run() {
    while (running_) {
        SDL_Event ev;
        const bool got = SDL_WaitEventTimeout(&ev, 10);
        // A pass: what the event thread does between two waits for events. It never waits for
        // the render thread, so its longest pass (--stats) stays short while frames, picks and
        // drawings of any size are in flight.
        const auto pass = Clock::now();
        if (got) {
            HandleEvent(ev);
            while (running_ && SDL_PollEvent(&ev)) HandleEvent(ev);
        }
        PumpWorker();
        if (!pendingScreenshot_.empty() && scheduler_.Final()) {
            Screenshot(pendingScreenshot_);
            pendingScreenshot_.clear();
        }
        PollFiles();
        StepScript();
        longestPass_ = std::max(longestPass_, Since(pass));
        ++passes_;
    }
    if (s_.stats) PrintLatency();
    return exitCode_;
}

int Viewer::Bench() {
    // The fixed orbit (viewer/bench_orbit.h), each frame shown: render + encode + blit.
    const viewer::BenchResult r =
        viewer::RunBenchOrbit(*s_.worker, camera_, width_, height_, engine_, s_.benchFrames,
                              s_.benchScale, [&](viewer::FrameOutcome& frame) {
                                  Upload(frame);
                                  SDL_Event ev;
                                  while (SDL_PollEvent(&ev))
                                      if (ev.type == SDL_QUIT) return false;
                                  return true;
                              });
    if (!r.error.empty()) {
        std::fputs(r.error.c_str(), stderr);
        return 1;
    }
    SDL_RendererInfo info{};
    SDL_GetRendererInfo(renderer_, &info);
    std::fputs(viewer::FormatBench(
                   r, width_, height_, engine_,
                   fmt::format("in a window (SDL renderer {})", info.name ? info.name : "?"))
                   .c_str(),
               stdout);
    const int n = std::max(1, r.frames);
    std::printf("view bench window thread, mean a frame: texture upload %.2f ms, present %.2f ms\n",
                1e3 * uploadSeconds_ / n, 1e3 * presentSeconds_ / n);
    return 0;
}

}  // namespace

}  // namespace quadrix::cli

// The module's entry points (viewer_window_loader.cpp finds them with dlsym). The functions of
// the window are internal to the module: the program's own RunViewerWindow (the loader) must not
// be confused with them.
extern "C" __attribute__((visibility("default"))) void quadrix_view_wake() {
    // SDL_PushEvent may be called from any thread; before SDL_Init it is simply not done.
    if (SDL_WasInit(SDL_INIT_VIDEO) == 0) return;
    SDL_Event ev{};
    ev.type = SDL_USEREVENT;
    SDL_PushEvent(&ev);
}

extern "C" __attribute__((visibility("default"))) int quadrix_view_run(
    const quadrix::cli::ViewerSession* session) {
    quadrix::cli::Viewer viewer(*session);
    if (!viewer.Open()) return 1;
    return session->benchFrames > 0 ? viewer.Bench() : viewer.Run();
}

#endif  // QUADRIX_HAVE_SDL2
