#include "quadrix/viewer/render_worker.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <set>

#include "quadrix/pipeline/drawing_output.h"
#include "quadrix/shade/section_hatch.h"
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

}  // namespace

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
        ctx = std::move(fresh);
        frameView_.reset();  // frame_ is the old scene's: never shaded again
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
    // The anti-aliased stage of the Frame already drawn shades it again; anything else renders.
    const bool reuse = job.request.antialiased && frameView_ && SameView(*frameView_, view) &&
                       frameEngine_ == job.engine && frame_.width == view.width &&
                       frame_.height == view.height;
    if (!ctx_->Flatten(view, diags) || (!reuse && !ctx_->Render(engine, frame_, report, diags)) ||
        diags.HasErrors()) {
        frameView_.reset();  // frame_ may be partial
        if (report.cancelled) {
            out.cancelled = true;
            return out;
        }
        out.error = Printed(diags);
        if (out.error.empty()) out.error = "the frame could not be drawn";
        return out;
    }
    frameView_ = view;
    frameEngine_ = job.engine;
    frameScale_ = s;
    ShadeOptions so;
    if (job.request.antialiased) so.aaSamples = job.aaSamples;
    // A reduced frame keeps the world spacing of the full one (the same lines, while moving),
    // down to 3 of its pixels.
    so.hatch = job.hatch && job.section.has_value();
    so.hatchSpacing = std::max(kHatchSpacingPixels / s, 3.0);
    out.image = ctx_->Shade(frame_, so);
    if (cancel_.Cancelled()) {  // the anti-aliasing pass was stopped: a partial image
        out.image = Image{};
        out.cancelled = true;
        return out;
    }
    if (job.edges) DrawEdges(frame_, out.image);
    out.notes = report.notes;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

DrawingOutcome RenderWorker::WriteDrawing(const std::string& path, const scene::View& view,
                                          int width, int height,
                                          const std::optional<Plane>& section,
                                          const std::string& title) {
    DrawingOutcome out;
    Call([&] {
        if (!ctx_) {
            out.messages = out.first = "quadrix: error: no scene has been read\n";
            return;
        }
        DrawingRequest request;
        request.view.width = width;
        request.view.height = height;
        request.view.view = view;
        request.view.section = section;
        request.allowMissing = input_.allowMissing;
        request.title = title;
        Diagnostics diags;
        out.ok = WriteDrawingFile(*ctx_, request, path, diags);
        out.messages = Printed(diags);
        if (!diags.Items().empty()) out.first = diags.Items().front().Format(false);
    });
    return out;
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

PickResult RenderWorker::PickAt(int x, int y) {
    PickResult p;
    Call([&] {
        if (ctx_ && frame_.width > 0)
            p = Pick(frame_, ctx_->Flat(), &ctx_->Scene(), x / frameScale_, y / frameScale_);
        p.x = x;
        p.y = y;
    });
    return p;
}

std::string RenderWorker::PickText(int x, int y) {
    std::string text;
    Call([&] {
        if (!ctx_ || frame_.width == 0) {
            text = "pick: nothing drawn yet";
            return;
        }
        PickResult p = Pick(frame_, ctx_->Flat(), &ctx_->Scene(), x / frameScale_, y / frameScale_);
        p.x = x;
        p.y = y;
        text = FormatPick(p);
    });
    return text;
}

}  // namespace quadrix::viewer
