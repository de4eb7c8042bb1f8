#include "quadrix/batch/job_renderer.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <chrono>
#include <cmath>

#include "quadrix/engines/engine_limit.h"
#include "quadrix/import/rt_view.h"
#include "quadrix/io/output_check.h"
#include "quadrix/util/seconds_since.h"

namespace quadrix::batch {

namespace {

// Errors (and, separately, warnings and notes) of `diags` as text, one diagnostic per line.
std::string ErrorText(const Diagnostics& diags) {
    std::string out;
    for (const Diagnostic& d : diags.Items())
        if (d.severity == Diagnostic::Severity::kError) out += d.Format(false) + "\n";
    return out;
}
std::string WarningText(const Diagnostics& diags) {
    std::string out;
    for (const Diagnostic& d : diags.Items())
        if (d.severity != Diagnostic::Severity::kError) out += d.Format(false) + "\n";
    return out;
}

bool Exists(const std::string& path) {
    struct stat st {};
    return !path.empty() && path != "-" && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

// Whether every output of the frame exists and is complete (io/output_check.h). An output that
// exists but is not complete is noted in r.warnings: the frame is rendered again.
bool AllComplete(FrameResult& r, int width, int height) {
    bool all = true;
    for (const std::string* path : {&r.image, &r.dumpFrame, &r.exr}) {
        if (path->empty()) continue;
        if (!Exists(*path)) {
            all = false;
            continue;
        }
        if (std::string why = CheckCompleteOutput(*path, width, height); !why.empty()) {
            r.warnings += fmt::format("note: '{}' exists but is {}: rendered again\n", *path, why);
            all = false;
        }
    }
    return all;
}

}  // namespace

bool FrameComplete(const Job& job, int frame) {
    FrameResult r;
    const bool animated = job.Animated();
    r.image = FramePath(job.output.image, frame, animated);
    r.dumpFrame = FramePath(job.output.dumpFrame, frame, animated);
    r.exr = FramePath(job.output.exr, frame, animated);
    return AllComplete(r, job.view.width, job.view.height);
}

Box3 SceneWorldBounds(RenderContext& ctx, Diagnostics& diags) {
    ViewRequest probe;
    probe.width = probe.height = 256;
    scene::View v;
    v.id = "bounds";
    v.dop = Vec3{0, 0, -1};  // toward the viewer; vpn into the scene
    v.vpn = Vec3{0, 0, 1};
    v.vup = Vec3{0, 1, 0};
    probe.view = v;
    Box3 world;
    if (!ctx.Flatten(probe, diags)) return world;
    const FlatScene& flat = ctx.Flat();
    const Transform worldFromDevice = flat.projection.deviceFromWorld.Inverted();
    for (const FlatSolid& s : flat.solids) {
        if (!s.bounds.Finite()) continue;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 p{(corner & 1) ? s.bounds.hi.x : s.bounds.lo.x,
                         (corner & 2) ? s.bounds.hi.y : s.bounds.lo.y,
                         (corner & 4) ? s.bounds.hi.z : s.bounds.lo.z};
            world.Extend(worldFromDevice.MapPoint(p));
        }
    }
    return world;
}

scene::View TurntableView(const Turntable& t, int frame, int count, const Box3& worldBox, int width,
                          int height) {
    const double az = t.azimuth0 + 360.0 * frame / count;
    scene::View v = import::MakeAzElView(az, t.elevation, worldBox, std::nullopt, width, height);
    v.id = fmt::format("turntable{}", frame);
    return v;
}

bool JobRenderer::Load(const Job& job, int jobId, double clock, FrameResult& r) {
    const bool same = loadedJob_ == jobId && (!ctx_.Inputs().usesClock || loadedClock_ == clock);
    if (same) {
        if (!loadedOk_) r.error = loadError_;
        return loadedOk_;
    }
    Diagnostics diags;
    InputRequest in = job.input;
    in.clock = clock;
    const auto t0 = std::chrono::steady_clock::now();
    // The same job at another clock: when only views use it, the context reads just the view
    // statements again and keeps the geometry.
    const int readsBefore = ctx_.sceneReads;
    loadedOk_ =
        loadedJob_ == jobId && loadedOk_ ? ctx_.ReadAtClock(clock, diags) : ctx_.Read(in, diags);
    r.read = ctx_.sceneReads != readsBefore;
    reads += ctx_.sceneReads - readsBefore;
    worldBox_.reset();
    if (loadedOk_ && job.turntable) {
        worldBox_ = SceneWorldBounds(ctx_, diags);
        if (diags.HasErrors()) loadedOk_ = false;
    }
    r.readSeconds = SecondsSince(t0);
    loadedJob_ = jobId;
    loadedClock_ = clock;
    loadError_ = loadedOk_ ? std::string() : ErrorText(diags);
    if (!loadedOk_) r.error = loadError_;
    r.warnings += WarningText(diags);
    return loadedOk_;
}

FrameResult JobRenderer::Render(const Job& job, int jobId, int frame, bool skipExisting) {
    const auto t0 = std::chrono::steady_clock::now();
    FrameResult r;
    const bool animated = job.Animated();
    r.image = FramePath(job.output.image, frame, animated);
    r.dumpFrame = FramePath(job.output.dumpFrame, frame, animated);
    r.exr = FramePath(job.output.exr, frame, animated);
    if (skipExisting && AllComplete(r, job.view.width, job.view.height)) {
        r.skipped = true;
        return r;
    }
    if (!Load(job, jobId, job.Clock(frame), r)) {
        r.seconds = SecondsSince(t0);
        return r;
    }
    ViewRequest view = job.view;
    if (job.turntable) {
        view.view = TurntableView(*job.turntable, frame, job.FrameCount(),
                                  worldBox_.value_or(Box3{}), view.width, view.height);
    } else if (!job.views.empty()) {
        const ListedView& lv = job.views[frame];
        view.viewName.clear();
        view.azimuth.reset();
        view.elevation.reset();
        view.view = lv.view;
        view.rtView = lv.rtView;
        if (lv.rtView && lv.rtView->Fitted()) {  // rt's `ae`: the --az/--el view
            view.rtView.reset();
            view.azimuth = lv.rtView->aeAzimuth;
            view.elevation = lv.rtView->aeElevation;
            view.viewsize.reset();
            if (lv.rtView->viewsize > 0) view.viewsize = lv.rtView->viewsize;
        }
    }
    Diagnostics diags;
    const auto t1 = std::chrono::steady_clock::now();
    if (!ctx_.Flatten(view, diags)) {
        r.error = ErrorText(diags);
        r.seconds = SecondsSince(t0);
        return r;
    }
    r.flattenSeconds = SecondsSince(t1);
    r.flattened = !ctx_.LastFlattenReused();
    if (r.flattened) ++flattens;
    Frame fb;
    RenderReport report;
    const auto t2 = std::chrono::steady_clock::now();
    if (!ctx_.Render(job.engine, fb, report, diags)) {
        r.error = ErrorText(diags);
        r.seconds = SecondsSince(t0);
        return r;
    }
    r.renderSeconds = SecondsSince(t2);
    for (const std::string& w : report.stats.warnings)
        r.warnings += fmt::format("warning: engine {}: {}\n", job.engine.engine, w);
    r.warnings += WarningText(diags);
    const auto t3 = std::chrono::steady_clock::now();
    OutputRequest out = job.output;
    out.image = r.image;
    out.dumpFrame = r.dumpFrame;
    out.exr = r.exr;
    std::optional<Image> image;
    if (NeedsImage(out)) {
        // The picture defaults of a single `quadrix render` (shade/picture_defaults.h), which
        // depend on the flat scene; a too-big scene's note once per flattening.
        ShadeOptions so = job.shade;
        if (auto note = ApplyPictureDefaults(ctx_.Flat(), job.picture, so);
            !note.empty() && r.flattened)
            r.warnings += "note: " + note + "\n";
        try {
            image = ctx_.Shade(fb, so);
        } catch (const EngineLimitError& e) {  // the shading budget (shade/shade_budget.h)
            r.error = std::string("error: ") + e.what() + "\n";
            r.seconds = SecondsSince(t0);
            return r;
        }
    }
    r.shadeSeconds = SecondsSince(t3);
    const auto t4 = std::chrono::steady_clock::now();
    if (std::string e = WriteOutputs(out, fb, image ? &*image : nullptr); !e.empty())
        r.error = e + "\n";
    r.writeSeconds = SecondsSince(t4);
    r.seconds = SecondsSince(t0);
    return r;
}

}  // namespace quadrix::batch
