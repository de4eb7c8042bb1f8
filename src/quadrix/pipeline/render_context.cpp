#include "quadrix/pipeline/render_context.h"

#include <fmt/format.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <thread>

#include "quadrix/engines/engine_limit.h"
#include "quadrix/engines/isocurve/isocurve_engine.h"
#include "quadrix/engines/registry.h"
#include "quadrix/flatten/blank_quartics.h"
#include "quadrix/frame/image_limits.h"
#include "quadrix/lang/reader.h"
#include "quadrix/shade/antialias.h"
#include "quadrix/shade/section_hatch.h"
#include "quadrix/util/check.h"
#include "quadrix/util/parallel.h"

namespace quadrix {

namespace {

double SecondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool SameLights(const std::optional<std::vector<scene::Light>>& a,
                const std::optional<std::vector<scene::Light>>& b) {
    if (a.has_value() != b.has_value()) return false;
    if (!a) return true;
    if (a->size() != b->size()) return false;
    for (std::size_t i = 0; i < a->size(); ++i) {
        const scene::Light &x = (*a)[i], &y = (*b)[i];
        if (x.id != y.id || x.kind != y.kind || x.intensity != y.intensity ||
            !(x.direction == y.direction) || x.isDefault != y.isDefault)
            return false;
    }
    return true;
}

bool SameSceneView(const std::optional<scene::View>& a, const std::optional<scene::View>& b) {
    if (a.has_value() != b.has_value()) return false;
    if (!a) return true;
    return a->id == b->id && a->vrp == b->vrp && a->vpn == b->vpn && a->vup == b->vup &&
           a->dop == b->dop && a->cop == b->cop && a->whh == b->whh && a->whw == b->whw &&
           a->front == b->front && a->back == b->back && a->isDefault == b->isDefault;
}

bool SameRtView(const std::optional<import::RtView>& a, const std::optional<import::RtView>& b) {
    if (a.has_value() != b.has_value()) return false;
    if (!a) return true;
    if (a->viewsize != b->viewsize || !(a->eye == b->eye)) return false;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (a->viewrot.m[i][j] != b->viewrot.m[i][j]) return false;
    return true;
}

// The flat scene with only `solids` (in order) left to draw and no freeform surfaces; half-space
// and body indices are unchanged, so Frame surface and body ids mean the same in both.
FlatScene SubsetOfSolids(const FlatScene& flat, const std::vector<int>& solids) {
    FlatScene sub = flat;  // every field, so none is forgotten when FlatScene grows
    sub.freeforms.clear();
    sub.solids.clear();
    for (int s : solids) sub.solids.push_back(flat.solids[static_cast<std::size_t>(s)]);
    return sub;
}

// The first quartic half-space that solid `s` uses (math/quartic_surface.h), or -1.
int FirstQuarticOf(const FlatScene& flat, int s) {
    std::vector<int> stack{flat.solids[static_cast<std::size_t>(s)].root};
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        if (n < 0) continue;
        const FlatCsgNode& node = flat.nodes[static_cast<std::size_t>(n)];
        if (!node.isLeaf) {
            stack.insert(stack.end(), node.children.begin(), node.children.end());
            continue;
        }
        if (node.body < 0) continue;
        for (const FlatLiteral& l : flat.bodies[static_cast<std::size_t>(node.body)].literals)
            if (flat.halfSpaces[static_cast<std::size_t>(l.halfSpace)].IsQuartic())
                return l.halfSpace;
    }
    return -1;
}

// The flat scene without any quartic: the solids `solids` only (none of them uses a quartic) and
// every quartic half-space replaced by a transparent plane that holds nowhere (no body names it
// any more; indices stay, so Frame ids mean the same). Freeform surfaces are kept.
FlatScene WithoutQuartics(const FlatScene& flat, const std::vector<int>& solids) {
    FlatScene sub = SubsetOfSolids(flat, solids);
    sub.freeforms = flat.freeforms;
    BlankQuarticHalfSpaces(sub);
    return sub;
}

}  // namespace

bool SameView(const ViewRequest& a, const ViewRequest& b) {
    return a.width == b.width && a.height == b.height && a.viewName == b.viewName &&
           a.azimuth == b.azimuth && a.elevation == b.elevation && a.viewsize == b.viewsize &&
           SameSceneView(a.view, b.view) && SameRtView(a.rtView, b.rtView) &&
           SameLights(a.lights, b.lights) && a.section == b.section;
}

std::vector<std::pair<std::string, double>> RenderReport::Counters() const {
    std::vector<std::pair<std::string, double>> c;
    CounterValues composition(kCompositionCounters);
    composition.Set(kFreeformsByIsocurve, freeformsByIsocurve);
    composition.Set(kSolidsByRaycast, byReference.size());
    composition.AppendTo(c);
    c.insert(c.end(), stats.counters.begin(), stats.counters.end());
    return c;
}

// A context of one thread runs its work inline, without oneTBB (util/parallel.h: its start costs
// more than a small render); the arena is then never initialised. A context whose threads were
// not given (0) chooses at each Flatten: inline for a small job (SmallJob), else all the threads.
// A cancellable context (the viewer's) always goes through the arena: oneTBB stops a cancelled
// loop between its tasks, an inline loop only at its end (RenderContext::Inline).
struct RenderContext::Arena {
    explicit Arena(int threads)
        : arena(threads > 0 ? threads : tbb::task_arena::automatic),
          serial(threads == 1),
          chooses(threads <= 0) {}
    ~Arena() {
        if (starter.joinable()) starter.join();
    }
    Arena(const Arena&) = delete;
    Arena& operator=(const Arena&) = delete;
    tbb::task_arena arena;
    bool serial;
    const bool chooses;
    // oneTBB and the arena start on this thread (Start), while the caller goes on: loops begun
    // meanwhile run their first grains on the caller's thread (util/parallel.h LoopArenaScope).
    std::thread starter;
    std::once_flag started;
    void Start() {
        std::call_once(started, [this] {
            if (!arena.is_active()) starter = std::thread([this] { arena.initialize(); });
        });
    }
    // `work` inline (a context of one thread), inside the arena (a cancellable context: oneTBB
    // cancels the loops of its task group), or with the arena as its loops' (the others; the
    // arena started if it is not).
    template <class Work>
    void Run(bool inlineRun, bool cancellable, const Work& work) {
        if (inlineRun) {
            SerialScope inline_;
            work();
        } else if (cancellable) {
            arena.execute(work);
        } else {
            Start();
            LoopArenaScope loops(&arena);
            work();
        }
    }
};

RenderContext::RenderContext(int threads) : arena_(std::make_unique<Arena>(threads)) {}

namespace {

// A job small enough that oneTBB's start (2-3.5 ms in a fresh process, util/parallel.h) would
// cost more than two threads save: at most 128 × 128 pixels and a scene of at most 2,000
// half-spaces and instance copies in all its scopes. Measured on the machined part with the
// picture defaults, whole process: 64 × 64 22.4 ms inline against 26-27 ms on two threads;
// 128 × 128 28.8 against 32.6 ms; 256 × 256 47.1 against 45.2 ms (two threads ahead).
bool SmallJob(const scene::Scene& scene, int width, int height) {
    constexpr double kPixels = 128 * 128, kScene = 2000;
    if (double(width) * double(height) > kPixels) return false;
    double size = 0;
    auto add = [&](const scene::Scope& s) {
        size += double(s.halfSpaces.size());
        for (const scene::Instance& i : s.instances) size += std::max(0, i.count);
    };
    add(scene.top);
    for (const scene::Scope& d : scene.definitions) add(d);
    return size <= kScene;
}

}  // namespace

RenderContext::~RenderContext() = default;

bool RenderContext::Read(const InputRequest& request, Diagnostics& diags) {
    const auto t0 = std::chrono::steady_clock::now();
    scene_ = scene::Scene{};
    inputs_ = InputReport{};
    flatValid_ = worldValid_ = flattenedOnce_ = rtLights_ = false;
    spare_ = FlatScene{};
    if (request.paths.empty()) {
        lang::ReadOptions ro;
        ro.clock = request.clock;
        lang::Reader reader(scene_, diags, ro);
        reader.ReadText(request.text, request.textName);
        inputs_.usesClock = reader.UsesClock();
        inputs_.clockOutsideViews = reader.UsesClockOutsideViews();
        if (inputs_.usesClock && !inputs_.clockOutsideViews)
            inputs_.viewStatements = reader.ViewStatements();
    } else {
        // Files of mixed formats (UniQuadrix, BRL-CAD, OpenSCAD) into one scene (docs/import.md).
        InputOptions io;
        io.import.topObjects = request.topObjects;
        io.import.strict = request.strict;
        io.import.allowMissing = request.allowMissing;
        io.clock = request.clock;
        ReadSceneInputs(request.paths, io, scene_, diags, inputs_);
    }
    readSeconds = SecondsSince(t0);
    lastInput_ = request;
    ++sceneReads;
    readOk_ = !diags.HasErrors();
    return readOk_;
}

namespace {

// The view statements of a reading, read again at `clock` into `views` (a scene of views alone),
// each at its line and column, so that a message names the place in its file: statements of one
// file in a row make one text, their gaps blanked (newlines kept).
void ReadViewStatements(const std::vector<lang::ViewStatement>& statements, double clock,
                        scene::Scene& views, Diagnostics& diags) {
    lang::ReadOptions ro;
    ro.clock = clock;
    lang::Reader reader(views, diags, ro);
    std::string text;
    const std::string* name = nullptr;
    int line = 1, column = 1;  // where the end of `text` is
    auto flush = [&] {
        if (name) reader.ReadText(text, *name);
        text.clear();
        line = column = 1;
    };
    static const std::string kText = "<text>";
    for (const lang::ViewStatement& s : statements) {
        const std::string* file = s.file ? s.file.get() : &kText;
        if (!name || *file != *name || s.line < line || (s.line == line && s.column < column))
            flush();
        name = file;
        for (; line < s.line; ++line, column = 1) text += '\n';
        text.append(static_cast<std::size_t>(s.column - column), ' ');
        column = s.column;
        text += s.text;
        for (char c : s.text) {
            if (c == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
    }
    flush();
}

}  // namespace

bool RenderContext::ReadViewsAtClock(double clock, Diagnostics& diags) {
    const auto t0 = std::chrono::steady_clock::now();
    const int errorsBefore = diags.ErrorCount();
    scene::Scene views;
    ReadViewStatements(inputs_.viewStatements, clock, views, diags);
    readSeconds = SecondsSince(t0);
    if (diags.ErrorCount() != errorsBefore) return false;
    // Each view replaces the scene's of the same id (the same views as the whole reading made).
    std::vector<std::size_t> at;
    for (const scene::View& v : views.views) {
        auto it = std::find_if(scene_.views.begin(), scene_.views.end(),
                               [&](const scene::View& w) { return w.id == v.id; });
        if (it == scene_.views.end()) return false;
        at.push_back(static_cast<std::size_t>(it - scene_.views.begin()));
    }
    for (std::size_t k = 0; k < at.size(); ++k) scene_.views[at[k]] = views.views[k];
    flatValid_ = false;
    lastInput_.clock = clock;
    return true;
}

bool RenderContext::ReadAtClock(double clock, Diagnostics& diags) {
    // Only the camera moves: the view statements are read again, the rest is kept.
    if (readOk_ && inputs_.usesClock && !inputs_.clockOutsideViews) {
        Diagnostics viewDiags;
        if (ReadViewsAtClock(clock, viewDiags)) {
            for (const Diagnostic& d : viewDiags.Items()) diags.Add(d);
            return true;
        }
        // An error at this clock: the whole reading reports it as a single render would.
    }
    const bool cameraOnly = (worldValid_ || flattenedOnce_) && !inputs_.clockOutsideViews;
    const bool hadWorld = worldValid_;
    InputRequest request = lastInput_;
    request.clock = clock;
    const int errorsBefore = diags.ErrorCount();
    if (!Read(request, diags) || diags.ErrorCount() != errorsBefore) return false;
    // The geometry read at this clock is the kept one when neither reading used the clock
    // outside views (Read invalidated it; world_ still holds it).
    if (cameraOnly && !inputs_.clockOutsideViews) {
        worldValid_ = hadWorld;
        flattenedOnce_ = true;  // the next view builds the world stage (or reuses it)
    }
    return true;
}

bool RenderContext::Flatten(const ViewRequest& view, Diagnostics& diags) {
    lastReused_ = false;
    if (auto e = CheckImageSize(view.width, view.height); !e.empty()) {
        diags.Error({}, e, {}, "command line");
        return false;
    }
    if (flatValid_ && flatFor_ && SameView(*flatFor_, view)) {
        lastReused_ = true;
        flattenSeconds = 0;
        return true;
    }
    flatValid_ = false;
    const auto t0 = std::chrono::steady_clock::now();
    std::string viewName = view.viewName;
    if (!view.view && (view.rtView || view.azimuth || view.elevation)) {
        // An rt-style view is made once per request and added to the scene like a view statement
        // (with rt's lights when the scene has none); asking again replaces it, and the lights
        // made for the last one (their eye light looks along its direction), never the scene's.
        std::erase_if(scene_.views, [](const scene::View& v) { return v.id == "rt"; });
        if (rtLights_)
            std::erase_if(scene_.lights, [](const scene::Light& l) {
                return l.id == "rt_ambient" || l.id == "rt_eye";  // AddRtLights' ids
            });
        scene::View made =
            view.rtView ? import::MakeRtView(*view.rtView, view.width, view.height)
                        : import::MakeAzElView(view.azimuth.value_or(35),
                                               view.elevation.value_or(25), inputs_.importedBounds,
                                               view.viewsize, view.width, view.height);
        rtLights_ = scene_.lights.empty();
        import::AddRtLights(scene_, made);
        scene_.views.push_back(made);
        viewName = made.id;
    }
    FlattenOptions fo;
    fo.width = view.width;
    fo.height = view.height;
    fo.viewName = viewName;
    fo.view = view.view;
    fo.lights = view.lights;
    fo.section = view.section;
    fo.halfSpaceNames = halfSpaceNames_;
    const int errorsBefore = diags.ErrorCount();
    lastReusedWorld_ = worldValid_;
    std::optional<FlatScene> flat;
    if (arena_->chooses) arena_->serial = SmallJob(scene_, view.width, view.height);
    // In the context's arena, so that its parallel steps use the threads asked for. The first
    // time, oneTBB and the arena start on another thread meanwhile (Arena::Start): the flatten
    // begins with its serial walk of the scene's hierarchy, and loops begun before the arena is
    // active run their first grains on this thread (util/parallel.h LoopArenaScope); so does the
    // render of a scene whose flatten is done before the start. (Started while
    // the scene is read instead, the two contended for the process's memory map; the walk
    // touches little fresh memory.)
    bool worldFailed = false;
    auto flatten = [&] {
        if (!worldValid_ && !flattenedOnce_) {
            flat = quadrix::Flatten(scene_, fo, diags);  // the first view: in one go
            ++worldFlattens;
            flattenedOnce_ = true;
            return;
        }
        if (!worldValid_) {
            std::optional<WorldScene> world = FlattenWorld(scene_, diags);
            ++worldFlattens;
            if (!world || diags.ErrorCount() != errorsBefore) {
                worldFailed = true;
                return;
            }
            world_ = std::move(*world);
            worldValid_ = true;
        }
        flat = FlattenView(scene_, world_, fo, diags, std::move(spare_));
    };
    // Under the loop arena even for a cancellable context (the flatten is not cancelled).
    arena_->Run(Inline(), false, flatten);
    flattenSeconds = SecondsSince(t0);
    if (worldFailed || !flat || diags.ErrorCount() != errorsBefore) return false;
    if (worldValid_)
        spare_ = std::move(flat_);  // for the next view (FlattenView)
    else
        spare_ = FlatScene{};
    flat_ = std::move(*flat);
    {
        const std::lock_guard<std::mutex> lock(wideMutex_);
        wideTrees_.reset();
    }
    const std::string invalid = flat_.Validate();
    QUADRIX_CHECK(invalid.empty(), "{}", invalid);
    flatValid_ = true;
    flatFor_ = view;
    return true;
}

std::string RenderContext::CheckEngine(const EngineRequest& request) {
    const EngineInfo* info = FindEngine(request.engine);
    if (!info) return fmt::format("unknown engine '{}' (known: {})", request.engine, EngineList());
    RenderOptions ro;
    ro.engineOptions = request.options;
    return info->make()->ValidateOptions(ro);
}

Engine* RenderContext::EngineNamed(const std::string& name) {
    auto it = engines_.find(name);
    if (it != engines_.end()) return it->second.get();
    const EngineInfo* info = FindEngine(name);
    if (!info) return nullptr;
    return engines_.emplace(name, info->make()).first->second.get();
}

namespace {

// ComposeMin over the request's pixels: with regionOnly, the region's alone (outside it both
// Frames are unspecified).
void ComposeMinOf(Frame& frame, const Frame& other, const EngineRequest& request) {
    if (request.region && request.regionOnly)
        ComposeMinInRegion(frame, other, *request.region);
    else
        ComposeMin(frame, other);
}

}  // namespace

void RenderContext::ComposeReference(const std::vector<int>& solids, const EngineRequest& request,
                                     Frame& frame) {
    Engine* reference = EngineNamed(std::string(kReferenceEngine));
    QUADRIX_CHECK(reference != nullptr, "the reference engine is not registered");
    Frame other;
    RenderOptions ro;
    ro.region = request.region;
    ro.regionOnly = request.regionOnly;
    if (solids.size() == flat_.solids.size()) {
        reference->Render(flat_, ro, other);
    } else {
        // The subset keeps the flat scene's bodies, so the Frame's solids (each body's, frame.h)
        // are already the flat scene's.
        reference->Render(SubsetOfSolids(flat_, solids), ro, other);
    }
    ComposeMinOf(frame, other, request);
}

void RenderContext::StrictRefusal(const std::string& engine,
                                  const std::vector<UndrawnSolid>& undrawn, std::size_t freeforms,
                                  Diagnostics& diags) const {
    // One line (diagnostics are one line each): the first five solids, then a count.
    std::string what;
    for (std::size_t k = 0; k < undrawn.size() && k < 5; ++k)
        what += fmt::format("{}solid '{}': {}", what.empty() ? "" : "; ",
                            flat_.solids[static_cast<std::size_t>(undrawn[k].solid)].name,
                            undrawn[k].reason);
    if (undrawn.size() > 5) what += fmt::format("; ... and {} more", undrawn.size() - 5);
    if (freeforms > 0)
        what += fmt::format("{}{} freeform surface(s)", what.empty() ? "" : "; ", freeforms);
    diags.Error({},
                fmt::format("engine '{}' cannot draw the whole scene (strict: nothing is drawn by "
                            "another engine): {}",
                            engine, what),
                {}, "engine");
}

bool RenderContext::Execute(const std::function<void()>& work) {
    bool done = true;
    arena_->Run(Inline(), cancel_ != nullptr,
                [&] { done = cancel_ ? cancel_->Run(work) : (work(), true); });
    return done;
}

bool RenderContext::Render(const EngineRequest& request, Frame& frame, RenderReport& report,
                           Diagnostics& diags) {
    QUADRIX_CHECK(flatValid_, "RenderContext::Render before a successful Flatten");
    if (request.share) {
        // A share of the solids: the flat scene without the others while the engine draws, then
        // the report's solid ids mapped back to the whole scene's.
        for (int s : *request.share)
            if (s < 0 || static_cast<std::size_t>(s) >= flat_.solids.size()) {
                diags.Error({}, fmt::format("solid {} of a share is not in the scene", s), {},
                            "command line");
                return false;
            }
        EngineRequest whole = request;
        whole.share.reset();
        FlatScene kept = std::move(flat_);
        flat_ = SubsetOfSolids(kept, *request.share);
        if (request.shareFreeforms) flat_.freeforms = kept.freeforms;
        const bool ok = Render(whole, frame, report, diags);
        flat_ = std::move(kept);
        // The Frame's solids are its bodies' (frame.h), whose ids the subset keeps.
        const std::vector<int>& ids = *request.share;
        for (UndrawnSolid& u : report.byReference) u.solid = ids[static_cast<std::size_t>(u.solid)];
        return ok;
    }
    const auto t0 = std::chrono::steady_clock::now();
    report = RenderReport{};
    report.engine = request.engine;
    const EngineInfo* info = FindEngine(request.engine);
    if (auto e = CheckEngine(request); !e.empty()) {
        diags.Error({}, e, {}, "command line");
        return false;
    }
    if (info->capabilities.solids && !info->capabilities.quartics) {
        // Solids with a quartic literal (torus, elliptical torus, general cone) are drawn by
        // raycast and composed by depth; the engine never sees a quartic half-space.
        std::vector<int> plain, quartic;
        std::vector<int> firstQuartic;
        for (std::size_t s = 0; s < flat_.solids.size(); ++s) {
            const int q = FirstQuarticOf(flat_, static_cast<int>(s));
            (q >= 0 ? quartic : plain).push_back(static_cast<int>(s));
            if (q >= 0) firstQuartic.push_back(q);
        }
        if (!quartic.empty())
            return RenderAroundQuartics(request, plain, quartic, firstQuartic, frame, report, diags,
                                        t0);
    }
    Engine* engine = EngineNamed(request.engine);
    RenderOptions ro;
    ro.engineOptions = request.options;
    ro.region = request.region;
    ro.regionOnly = request.regionOnly;
    const EngineCapabilities caps = info->capabilities;
    const bool drawsSomething =
        (caps.solids && !flat_.solids.empty()) || (caps.freeforms && !flat_.freeforms.empty());

    auto cancelled = [&] {
        report.cancelled = true;
        report.seconds = SecondsSince(t0);
        return false;
    };
    // Runs a drawing stage: done, cancelled (a newer view), or stopped by a complexity guard of
    // the engine or of the reference engine composing for it — an error: no picture rather than
    // a partial one.
    enum class Outcome { kDone, kCancelled, kStopped };
    auto guarded = [&](const std::function<void()>& draw) {
        try {
            return Execute(draw) ? Outcome::kDone : Outcome::kCancelled;
        } catch (const EngineLimitError& e) {
            diags.Error({}, e.what(), {}, "engine");
            return Outcome::kStopped;
        }
    };
    auto stop = [&](Outcome o) { return o == Outcome::kCancelled ? cancelled() : false; };
    if (Outcome o = guarded([&] {
            if (drawsSomething || (flat_.solids.empty() && flat_.freeforms.empty()))
                report.stats = engine->Render(flat_, ro, frame);
            else
                frame.Reset(flat_.width, flat_.height);
        });
        o != Outcome::kDone)
        return stop(o);

    // What the engine left out, and why.
    std::vector<UndrawnSolid> undrawn;
    if (!caps.solids) {
        for (std::size_t s = 0; s < flat_.solids.size(); ++s)
            undrawn.push_back({static_cast<int>(s),
                               fmt::format("engine '{}' draws no quadric solids", request.engine)});
    } else {
        undrawn = report.stats.undrawn;
    }
    const bool freeformsLeft = !caps.freeforms && !flat_.freeforms.empty();
    if (request.strict && (!undrawn.empty() || freeformsLeft)) {
        StrictRefusal(request.engine, undrawn, freeformsLeft ? flat_.freeforms.size() : 0, diags);
        return false;
    }
    if (!undrawn.empty()) {
        std::vector<int> solids;
        for (const UndrawnSolid& u : undrawn) solids.push_back(u.solid);
        if (Outcome o = guarded([&] { ComposeReference(solids, request, frame); });
            o != Outcome::kDone)
            return stop(o);
        report.byReference = undrawn;
        if (caps.solids) {
            std::map<std::string, int> reasons;
            for (const UndrawnSolid& u : undrawn) ++reasons[u.reason];
            std::string why;
            for (const auto& [reason, n] : reasons)
                why += fmt::format("{}{} × {}", why.empty() ? "" : "; ", n, reason);
            report.notes.push_back(fmt::format(
                "engine {} cannot draw {} of {} solid{}; drawn by raycast and composed by depth "
                "({}; --strict refuses instead)",
                request.engine, undrawn.size(), flat_.solids.size(),
                flat_.solids.size() == 1 ? "" : "s", why));
        }
    }
    if (freeformsLeft) {
        // Freeform surfaces by adaptive isocurves (seed 002) with the isocurve engine's default
        // tolerance (curves at most one pixel apart), composed by depth.
        Frame other(flat_.width, flat_.height);
        isocurve::IsocurveStats st;
        if (!Execute([&] {
                st = isocurve::RenderFreeform(isocurve::SceneDrawables(flat_), flat_.projection, {},
                                              other);
            }))
            return cancelled();
        if (request.region && !request.regionOnly) CropToRegion(other, *request.region);
        ComposeMinOf(frame, other, request);
        report.freeformsByIsocurve = st.surfaces;
        report.isocurveSummary = fmt::format(
            "freeform surfaces: {} drawn by adaptive isocurves after engine '{}' ({} curves, "
            "delta {:.3g}; --engine isocurve gives the isocurve options and statistics)",
            st.surfaces, request.engine, st.curves, st.delta);
    }
    report.seconds = SecondsSince(t0);
    return true;
}

bool RenderContext::RenderAroundQuartics(const EngineRequest& request,
                                         const std::vector<int>& plain,
                                         const std::vector<int>& quartic,
                                         const std::vector<int>& firstQuartic, Frame& frame,
                                         RenderReport& report, Diagnostics& diags,
                                         std::chrono::steady_clock::time_point t0) {
    std::vector<UndrawnSolid> undrawn;
    for (std::size_t k = 0; k < quartic.size(); ++k) {
        const QuarticSurface& q =
            *flat_.halfSpaces[static_cast<std::size_t>(firstQuartic[k])].quartic;
        undrawn.push_back(
            {quartic[k],
             fmt::format("a quartic surface ({}) is drawn only by raycast", q.KindName())});
    }
    if (request.strict) {
        StrictRefusal(request.engine, undrawn, 0, diags);
        return false;
    }
    FlatScene kept = std::move(flat_);
    flat_ = WithoutQuartics(kept, plain);
    const bool ok = Render(request, frame, report, diags);
    flat_ = std::move(kept);
    if (!ok) return false;
    for (UndrawnSolid& u : report.byReference) u.solid = plain[static_cast<std::size_t>(u.solid)];
    try {
        if (!Execute([&] { ComposeReference(quartic, request, frame); })) {
            report.cancelled = true;
            report.seconds = SecondsSince(t0);
            return false;
        }
    } catch (const EngineLimitError& e) {
        diags.Error({}, e.what(), {}, "engine");
        return false;
    }
    report.byReference.insert(report.byReference.end(), undrawn.begin(), undrawn.end());
    report.notes.push_back(fmt::format(
        "engine {} cannot draw {} of {} solid{}; drawn by raycast and composed by depth ({} × "
        "a quartic surface (torus, elliptical torus or general cone) is drawn only by raycast; "
        "--strict refuses instead)",
        request.engine, quartic.size(), flat_.solids.size(), flat_.solids.size() == 1 ? "" : "s",
        quartic.size()));
    report.seconds = SecondsSince(t0);
    return true;
}

bool RenderContext::Inline() const { return arena_->serial && !cancel_; }

int RenderContext::Threads() const { return Inline() ? 1 : arena_->arena.max_concurrency(); }

void RenderContext::InArena(const std::function<void()>& work) const {
    arena_->Run(Inline(), cancel_ != nullptr, work);
}

Image RenderContext::Shade(const Frame& frame, const ShadeOptions& options) const {
    Image image;
    InArena([&] { image = ShadeInArena(frame, options); });
    return image;
}

Image RenderContext::ShadeInArena(const Frame& frame, const ShadeOptions& options) const {
    // The wide-node trees once per flat scene, for the shadow rays and the samples.
    std::shared_ptr<const WideNodeTrees> wide;
    if ((options.shadows || options.aaSamples > 1) && options.spatialIndex) {
        const std::lock_guard<std::mutex> lock(wideMutex_);
        if (!wideTrees_) wideTrees_ = WideNodeTrees::Shared(flat_, true);
        wide = wideTrees_;
    }
    Image image = quadrix::Shade(frame, flat_, options, wide);
    // Edge pixels re-rendered by sub-pixel samples, the section's hatching
    // (shade/section_hatch.h), then the edge lines (shade/antialias.h).
    if (options.aaSamples > 1) {
        if (cancel_) {
            cancel_->Run([&] { Antialias(frame, flat_, options, image, wide); });
        } else {
            // A small job chosen inline still has the machine's second processor for its
            // heaviest pass (shader.h aaHelperThread).
            ShadeOptions aa = options;
            aa.aaHelperThread = Inline() && arena_->chooses && AvailableProcessors() >= 2;
            Antialias(frame, flat_, aa, image, wide);
        }
    }
    if (options.hatch) HatchSection(frame, flat_, options, image);
    if (options.edges) DrawEdgeLines(frame, options, image);
    return image;
}

}  // namespace quadrix
