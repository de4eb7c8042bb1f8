#include "quadrix/viewer/render_worker.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <set>

#include "quadrix/io/writers.h"
#include "quadrix/pipeline/drawing_output.h"
#include "quadrix/shade/section_hatch.h"
#include "quadrix/util/parallel.h"
#include "quadrix/viewer/edges.h"
#include "quadrix/viewer/picking.h"

namespace quadrix::viewer {

namespace {

std::string Printed(const Diagnostics& diags) {
    char* buffer = nullptr;
    std::size_t size = 0;
    std::FILE* f = open_memstream(&buffer, &size);
    if (!f) return {};
    diags.Print(f);
    std::fclose(f);
    std::string s(buffer, size);
    std::free(buffer);
    return s;
}

// Every file a statement of the scene came from (top-level inputs and `read` files).
std::vector<std::string> SourceFiles(const scene::Scene& scene) {
    std::set<std::string> files;
    auto add = [&](const SourceLoc& loc) {
        if (loc.file && loc.line > 0) files.insert(*loc.file);
    };
    auto scope = [&](const scene::Scope& s) {
        for (const auto& h : s.halfSpaces) add(h.loc);
        for (const auto& b : s.bodies) add(b.loc);
        for (const auto& i : s.instances) add(i.loc);
        for (const auto& c : s.csgs) add(c.loc);
        for (const auto& f : s.freeforms) add(f.loc);
    };
    scope(scene.top);
    for (const auto& d : scene.definitions) scope(d);
    for (const auto& l : scene.lights) add(l.loc);
    for (const auto& v : scene.views) add(v.loc);
    return {files.begin(), files.end()};
}

double Since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

FrameArray<std::uint32_t> DisplayPixels(const Image& image) {
    // EncodeSrgb8's table applied and the words packed in one pass, in parallel over blocks of
    // pixels (the same bytes as encoding to sRGB first, without the intermediate image).
    const std::uint8_t* t = Srgb8Table();
    const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
    FrameArray<std::uint32_t> out(n);  // not zeroed: every word is written below
    const std::uint8_t* p = image.pixels.data();
    std::uint32_t* o = out.data();
    const tbb::blocked_range<std::size_t> all(0, n, std::size_t{1} << 15);
    if (image.channels == 3 && image.pixels.size() == 3 * n) {
        ParallelFor(all, [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i < r.end(); ++i)
                o[i] = std::uint32_t{t[p[3 * i]]} << 16 | std::uint32_t{t[p[3 * i + 1]]} << 8 |
                       t[p[3 * i + 2]];
        });
    } else if (image.pixels.size() == n) {
        ParallelFor(all, [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i < r.end(); ++i) o[i] = t[p[i]] * 0x010101u;
        });
    } else {
        std::fill(out.begin(), out.end(), 0u);  // no pixels of this size: black
    }
    return out;
}

std::vector<std::uint8_t> RgbBytes(const FrameArray<std::uint32_t>& pixels) {
    std::vector<std::uint8_t> rgb(pixels.size() * 3);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        rgb[3 * i] = static_cast<std::uint8_t>(pixels[i] >> 16);
        rgb[3 * i + 1] = static_cast<std::uint8_t>(pixels[i] >> 8);
        rgb[3 * i + 2] = static_cast<std::uint8_t>(pixels[i]);
    }
    return rgb;
}

RenderWorker::RenderWorker(InputRequest input, int threads, std::function<void()> wake)
    : input_(std::move(input)), threads_(threads), wake_(std::move(wake)) {
    thread_ = std::thread([this] { Loop(); });
}

RenderWorker::~RenderWorker() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
    if (drawingThread_.joinable()) drawingThread_.join();
}

void RenderWorker::Loop() {
    for (;;) {
        std::function<void()> call;
        std::optional<FrameJob> job;
        {
            std::unique_lock lock(mutex_);
            cv_.wait(lock, [&] { return stop_ || !calls_.empty() || job_; });
            if (stop_) return;
            if (!calls_.empty()) {
                call = std::move(calls_.front());
                calls_.pop_front();
            } else {
                job = std::move(job_);
                job_.reset();
            }
        }
        if (call) {
            call();
            continue;
        }
        FrameOutcome outcome = Draw(*job);
        {
            std::lock_guard lock(mutex_);
            frameDone_ = std::move(outcome);
        }
        cv_.notify_all();  // WaitFrame
        if (wake_) wake_();
    }
}

void RenderWorker::Call(std::function<void()> task) {
    std::promise<void> done;
    auto future = done.get_future();
    {
        std::lock_guard lock(mutex_);
        calls_.push_back([&] {
            task();
            done.set_value();
        });
    }
    cv_.notify_all();
    future.wait();
}

LoadOutcome RenderWorker::ReadInto(std::unique_ptr<RenderContext>& ctx) {
    auto fresh = std::make_unique<RenderContext>(threads_);
    fresh->SetCancellation(&cancel_);
    Diagnostics diags;
    LoadOutcome out;
    out.ok = fresh->Read(input_, diags) && !diags.HasErrors();
    out.messages = Printed(diags);
    for (const Diagnostic& d : diags.Items())
        if (d.severity == Diagnostic::Severity::kError) {
            out.firstError = d.Format(false);
            break;
        }
    out.files = input_.paths;
    if (out.ok) {
        for (std::string& f : SourceFiles(fresh->Scene())) out.files.push_back(std::move(f));
        auto snapshot = std::make_shared<const scene::Scene>(fresh->Scene());
        ctx = std::move(fresh);
        drawnView_.reset();  // drawn_ is the old scene's: never picked or shaded again
        std::lock_guard lock(mutex_);
        scene_ = std::move(snapshot);
    } else {
        // Watch the files of the errors as well: a new `read` may be the broken one.
        for (const Diagnostic& d : diags.Items())
            if (d.loc.file) out.files.push_back(*d.loc.file);
        if (ctx)
            for (std::string& f : SourceFiles(ctx->Scene())) out.files.push_back(std::move(f));
    }
    return out;
}

LoadOutcome RenderWorker::Load() {
    LoadOutcome out;
    Call([&] { out = ReadInto(ctx_); });
    return out;
}

void RenderWorker::ReloadAsync() {
    {
        std::lock_guard lock(mutex_);
        calls_.push_back([this] {
            LoadOutcome out = ReadInto(ctx_);
            {
                std::lock_guard inner(mutex_);
                reloadDone_ = std::move(out);
            }
            if (wake_) wake_();
        });
    }
    cv_.notify_all();
}

std::optional<LoadOutcome> RenderWorker::TakeReload() {
    std::lock_guard lock(mutex_);
    auto r = std::move(reloadDone_);
    reloadDone_.reset();
    return r;
}

void RenderWorker::Submit(const FrameJob& job) {
    {
        std::lock_guard lock(mutex_);
        job_ = job;
    }
    cv_.notify_all();
}

std::optional<FrameOutcome> RenderWorker::TakeFrame() {
    std::lock_guard lock(mutex_);
    auto r = std::move(frameDone_);
    frameDone_.reset();
    return r;
}

FrameOutcome RenderWorker::WaitFrame() {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return frameDone_.has_value(); });
    FrameOutcome r = std::move(*frameDone_);
    frameDone_.reset();
    return r;
}

FrameOutcome RenderWorker::RenderNow(const FrameJob& job) {
    FrameOutcome out;
    Call([&] { out = Draw(job); });
    return out;
}

FrameOutcome RenderWorker::Draw(const FrameJob& job) {
    FrameOutcome out;
    out.job = job;
    const auto t0 = std::chrono::steady_clock::now();
    cancel_.Reset();  // a cancellation was meant for an earlier frame
    if (!ctx_) {
        out.error = "no scene has been read";
        return out;
    }
    const int s = std::max(1, job.request.scale);
    ViewRequest view;
    view.width = std::max(1, (job.width + s - 1) / s);
    view.height = std::max(1, (job.height + s - 1) / s);
    view.view = job.view;
    view.section = job.section;
    EngineRequest engine;
    engine.engine = job.engine;
    Diagnostics diags;
    RenderReport report;
    // The anti-aliased stage of the Frame delivered last shades it again; anything else renders
    // into the scratch Frame, which replaces it only once whole.
    const bool reuse = job.request.antialiased && drawnView_ && SameView(*drawnView_, view) &&
                       drawnEngine_ == job.engine && drawn_.width == view.width &&
                       drawn_.height == view.height;
    const bool flattened = ctx_->Flatten(view, diags);
    out.flattenSeconds = Since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    if (!flattened || (!reuse && !ctx_->Render(engine, frame_, report, diags)) ||
        diags.HasErrors()) {
        if (report.cancelled) {
            out.cancelled = true;
            return out;
        }
        out.error = Printed(diags);
        if (out.error.empty()) out.error = "the frame could not be drawn";
        return out;
    }
    out.renderSeconds = Since(t1);
    const auto t2 = std::chrono::steady_clock::now();
    Frame& frame = reuse ? drawn_ : frame_;
    ShadeOptions so;
    if (job.request.antialiased) so.aaSamples = job.aaSamples;
    // The window shows the 8-bit pixels (DisplayPixels), so the unquantised floats are only
    // needed where the anti-aliasing mixes its samples from them (11 MB less a frame at 720p).
    so.linear = so.aaSamples > 1;
    // A reduced frame keeps the world spacing of the full one (the same lines, while moving),
    // down to 3 of its pixels.
    so.hatch = job.hatch && job.section.has_value();
    so.hatchSpacing = std::max(kHatchSpacingPixels / s, 3.0);
    out.image = ctx_->Shade(frame, so);
    if (cancel_.Cancelled()) {  // the anti-aliasing pass was stopped: a partial image
        out.image = Image{};
        out.cancelled = true;
        return out;
    }
    if (job.edges) DrawEdges(frame, out.image);
    out.shadeSeconds = Since(t2);
    if (!reuse) {
        std::swap(frame_, drawn_);
        drawnView_ = view;
        drawnEngine_ = job.engine;
        drawnScale_ = s;
    }
    if (job.display) {
        const auto t3 = std::chrono::steady_clock::now();
        ctx_->InArena([&] { out.display = DisplayPixels(out.image); });
        out.encodeSeconds = Since(t3);
    }
    out.notes = report.notes;
    out.seconds = Since(t0);
    return out;
}

bool RenderWorker::StartDrawing(const std::string& path, const scene::View& view, int width,
                                int height, const std::optional<Plane>& section,
                                const std::string& title) {
    std::shared_ptr<const scene::Scene> scene;
    {
        std::lock_guard lock(mutex_);
        if (drawingBusy_) return false;
        drawingBusy_ = true;
        scene = scene_;
    }
    if (drawingThread_.joinable()) drawingThread_.join();  // the previous one, finished
    DrawingRequest request;
    request.view.width = width;
    request.view.height = height;
    request.view.view = view;
    request.view.section = section;
    request.allowMissing = input_.allowMissing;
    request.title = title;
    drawingThread_ = std::thread([this, scene, request, path] {
        const auto t0 = std::chrono::steady_clock::now();
        DrawingOutcome out;
        out.path = path;
        if (!scene) {
            out.messages = out.first = "quadrix: error: no scene has been read\n";
        } else {
            // A context of its own on a copy of the scene: the render thread's context is
            // drawing frames meanwhile.
            RenderContext context(threads_);
            context.Scene() = *scene;
            context.SceneChanged();
            Diagnostics diags;
            out.ok = WriteDrawingFile(context, request, path, diags);
            out.messages = Printed(diags);
            if (!diags.Items().empty()) out.first = diags.Items().front().Format(false);
        }
        out.seconds = Since(t0);
        {
            std::lock_guard lock(mutex_);
            drawingDone_ = std::move(out);
            drawingBusy_ = false;
        }
        if (wake_) wake_();
    });
    return true;
}

std::optional<DrawingOutcome> RenderWorker::TakeDrawing() {
    std::lock_guard lock(mutex_);
    auto r = std::move(drawingDone_);
    drawingDone_.reset();
    return r;
}

bool RenderWorker::DrawingInProgress() {
    std::lock_guard lock(mutex_);
    return drawingBusy_;
}

std::size_t RenderWorker::BodyCount() {
    std::size_t n = 0;
    Call([&] { n = ctx_ ? ctx_->Flat().bodies.size() : 0; });
    return n;
}

std::string RenderWorker::InitialCamera(const std::string& viewName, int width, int height,
                                        Camera& camera, SceneSphere& sphere) {
    std::string error;
    Call([&] {
        if (!ctx_) {
            error = "no scene has been read";
            return;
        }
        std::optional<scene::View> view = ctx_->Scene().ViewToUse(viewName);
        if (!view) {
            error = "no view named '" + viewName + "' in the scene";
            return;
        }
        Diagnostics diags;
        ViewRequest request;
        request.width = width;
        request.height = height;
        request.viewName = viewName;
        if (!ctx_->Flatten(request, diags)) {
            error = Printed(diags);
            return;
        }
        std::optional<Camera> c = CameraFromView(*view, ctx_->Flat());
        if (!c) {
            error = "the scene's view cannot be turned into a camera";
            return;
        }
        camera = *c;
        // The bounded part of the scene seen along z with an automatic window: the device axes
        // are the world's, so the boxes map back to a tight world box.
        scene::View along;
        along.id = "fit";
        along.dop = Vec3{0, 0, -1};
        along.vpn = Vec3{0, 0, 1};
        along.vup = Vec3{0, 1, 0};
        ViewRequest fit;
        fit.width = width;
        fit.height = height;
        fit.view = along;
        Diagnostics fitDiags;
        std::optional<SceneSphere> s;
        if (ctx_->Flatten(fit, fitDiags)) s = BoundingSphere(ctx_->Flat());
        sphere = s ? *s : SceneSphere{camera.target, camera.halfHeight};
        camera.MoveTargetToDepthOf(sphere.centre);
    });
    return error;
}

PickOutcome RenderWorker::DoPick(int x, int y) {
    PickOutcome out;
    Diagnostics diags;
    // The flat scene of the frame delivered (a cancelled frame may have flattened another view
    // since; the context keeps the last one, so this is free when nothing else was flattened).
    if (ctx_ && drawnView_ && ctx_->Flatten(*drawnView_, diags)) {
        out.drawn = true;
        out.pick = Pick(drawn_, ctx_->Flat(), &ctx_->Scene(), x / drawnScale_, y / drawnScale_);
    }
    out.pick.x = x;
    out.pick.y = y;
    return out;
}

void RenderWorker::RequestPick(int x, int y, int tag) {
    {
        std::lock_guard lock(mutex_);
        calls_.push_back([this, x, y, tag] {
            PickOutcome out = DoPick(x, y);
            out.tag = tag;
            {
                std::lock_guard inner(mutex_);
                picksDone_.push_back(std::move(out));
            }
            if (wake_) wake_();
        });
    }
    cv_.notify_all();
}

std::optional<PickOutcome> RenderWorker::TakePick() {
    std::lock_guard lock(mutex_);
    if (picksDone_.empty()) return std::nullopt;
    PickOutcome r = std::move(picksDone_.front());
    picksDone_.pop_front();
    return r;
}

PickResult RenderWorker::PickAt(int x, int y) {
    PickResult p;
    Call([&] { p = DoPick(x, y).pick; });
    return p;
}

std::string RenderWorker::PickText(int x, int y) {
    PickOutcome out;
    Call([&] { out = DoPick(x, y); });
    return out.drawn ? FormatPick(out.pick) : "pick: nothing drawn yet";
}

}  // namespace quadrix::viewer
