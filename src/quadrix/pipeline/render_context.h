// The render context: the one place where "read → flatten → engines → compose → shade → write"
// happens, for every front end (quadrix render, uq and the uq> prompt, export, the benchmark, and
// the viewer, drawings, batch runs and bindings to come). No front end assembles these stages.
//
// Stages, each a method, each keeping what the next one needs:
//   1. Read      every input format (pipeline/inputs.h dispatches by extension and content) into
//                one scene::Scene; rt-style views (--az/--el, --rt-view) are made here.
//   2. Flatten   the scene for one view and image size (FlattenOptions, lights passed in, never
//                swapped into the scene). The flat scene is kept: asking again for the same view,
//                size and lights costs nothing, so re-rendering (another engine, the viewer's next
//                frame of a still view) does not flatten again. The world stage (flattener.h:
//                the hierarchy walk into world space) is made when a second view of the scene
//                is asked for, and kept: every later view, size, light or section runs only the
//                view stage (projection, bounds, window fit); a scene change (Read,
//                SceneChanged) starts again. (The first view is flattened in one go, so a
//                one-shot render pays nothing for the cache and keeps the fewest roundings.)
//   3. Render    the requested engine (a registry row, engines/registry.h) draws what it can into
//                the Frame; what it cannot — solids it reports undrawn, or all solids for an
//                engine without that capability — the reference engine (raycast) draws into a
//                second Frame, and freeform surfaces an engine cannot draw the isocurve drawer
//                draws into a third; the Frames are merged by per-pixel minimum depth
//                (ComposeMin). A request may ask for a share of the solids (sort-last) or a
//                region of the pixels (sort-first; the pixels outside are background). With
//                `strict` the context refuses instead (an error naming what
//                could not be drawn). Engines are kept per name, so their tables stay warm.
//   4. Shade     the Frame into an Image (shade/), by the chosen model.
//   5. Write     the outputs (pipeline/output.h): PNG, PNM, .qxf frame dumps, all checked before
//                any is written.
// One oneTBB arena, owned here, runs every engine: engines never make their own.
// Cancellation (pipeline/cancellation.h): with SetCancellation, stages 3 and 4 run their
// parallel work under it; a cancelled Render returns false with report.cancelled and no error,
// a cancelled Shade an incomplete image (the caller asks the Cancellation).
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "quadrix/engines/counters.h"
#include "quadrix/engines/engine.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/flatten/flattener.h"
#include "quadrix/flatten/wide_node_trees.h"
#include "quadrix/frame/frame.h"
#include "quadrix/frame/pixel_region.h"
#include "quadrix/import/rt_view.h"
#include "quadrix/io/image.h"
#include "quadrix/pipeline/cancellation.h"
#include "quadrix/pipeline/inputs.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"
#include "quadrix/shade/shader.h"

namespace quadrix {

// Stage 1: what to read.
struct InputRequest {
    std::vector<std::string> paths;  // "-" = standard input; empty: read `text`
    std::string text;
    std::string textName = "<text>";
    // Importers (docs/import.md): objects to draw from BRL-CAD/OpenSCAD files (--top), and
    // whether primitives that cannot be drawn exactly are an error (--strict).
    std::vector<std::string> topObjects;
    bool strict = false;
    // Primitives that cannot be drawn are an error unless allowMissing (--allow-missing): then
    // they are left out with a warning and counted in Inputs() (ImportReport::skipped).
    bool allowMissing = false;
    // The value of `clock` in the scene's numbers (an animation frame's time, 0 → 1;
    // docs/language.md §3.14). Inputs().usesClock tells whether the scene depends on it.
    double clock = 0;
};

// Stage 2: the view of one picture.
struct ViewRequest {
    int width = 512, height = 512;
    std::string viewName;  // empty = the last view defined (or the default view)
    // A view given directly (viewer camera, turntable frame, --camera): replaces viewName and the
    // rt-style views below. Compared field by field for reuse (SameView).
    std::optional<scene::View> view;
    // rt-style views (FORMAT.md §9.4) in the imported model's coordinates; they replace viewName.
    // Azimuth/elevation in degrees, fitted to the imported model's bounding box.
    std::optional<double> azimuth, elevation, viewsize;
    std::optional<import::RtView> rtView;
    // Lights to shade with instead of the scene's own (uq's current light, seed 001 §2.3).
    std::optional<std::vector<scene::Light>> lights;
    // A section plane, world coordinates: the part A x + B y + C z + D <= 0 is kept and the cut
    // faces drawn (FlattenOptions::section; `quadrix render --section`, the viewer's X key).
    std::optional<Plane> section;
};

// Stage 3: which engine and how.
struct EngineRequest {
    std::string engine = "raycast";
    std::map<std::string, std::string> options;  // --engine-opt KEY=VALUE
    // Refuse (an error) rather than compose what the engine cannot draw.
    bool strict = false;
    // Sort-last distributed rendering (batch/sort_last.h): when set, only these solids of the
    // flat scene are drawn, and its freeform surfaces only with shareFreeforms. Frame ids stay
    // those of the whole flat scene, so the Frames of several shares compose by ComposeMin.
    std::optional<std::vector<int>> share;
    bool shareFreeforms = true;
    // Sort-first distributed rendering (batch/sort_first.h): when set, only these pixels are
    // drawn (by the engine, the reference engine and the isocurve drawer alike); every pixel
    // outside is background (frame/pixel_region.h), or, with regionOnly, unspecified: for a
    // caller that reads only the region, whose Frame's pages outside it are then not touched
    // by an engine that skips its work there (raycast).
    std::optional<PixelRegion> region;
    bool regionOnly = false;
};

// How the picture was made: the engine's own statistics and what composition added.
struct RenderReport {
    std::string engine;
    RenderStats stats;                      // the requested engine's
    std::vector<UndrawnSolid> byReference;  // solids drawn by raycast instead, with the reason
    int freeformsByIsocurve = 0;            // freeform surfaces drawn by the isocurve drawer
    std::string isocurveSummary;            // one line about them (curves, tolerance)
    double seconds = 0;                     // whole stage, composition included
    bool cancelled = false;                 // stopped by the Cancellation: the Frame is partial
    // Lines for the user ("note: ..."): printed without --stats, like warnings.
    std::vector<std::string> notes;
    // Counters of the composition (kCompositionCounters) followed by the engine's own.
    std::vector<std::pair<std::string, double>> Counters() const;
};

// The counters the composition adds to every report, declared once (engines/counters.h).
#define QUADRIX_COMPOSITION_COUNTERS(X)                            \
    X(kFreeformsByIsocurve, "freeforms_by_isocurve",               \
      "freeform surfaces the isocurve drawer drew for the engine") \
    X(kSolidsByRaycast, "solids_by_raycast", "solids raycast drew for the engine (by depth)")
enum CompositionCounter : std::size_t { QUADRIX_COMPOSITION_COUNTERS(QUADRIX_COUNTER_ID) };
inline constexpr CounterDecl kCompositionCounters[] = {
    QUADRIX_COMPOSITION_COUNTERS(QUADRIX_COUNTER_DECL)};

class RenderContext {
  public:
    // threads: 0 = chosen at each Flatten: inline for a small job (at most 128 × 128 pixels and
    // a small scene), else all hardware threads; 1 = inline, without oneTBB (util/parallel.h:
    // its start costs 2-3.5 ms); n = an arena of n threads.
    explicit RenderContext(int threads = 0);
    ~RenderContext();
    RenderContext(const RenderContext&) = delete;
    RenderContext& operator=(const RenderContext&) = delete;

    // Stage 1. Replaces the scene. false with errors in diags.
    bool Read(const InputRequest& request, Diagnostics& diags);
    // Stage 1 again, the last Read's request at another `clock` (an animation's next frame).
    // When the last reading found `clock` only in view statements (the camera moves, the
    // geometry does not: !Inputs().clockOutsideViews), only those statements are read again
    // (InputReport::viewStatements) and their views replace the scene's: the inputs are not read
    // and the world stage is kept. (A view statement with an error at this clock reads the
    // whole inputs again, so that its messages are those of a single render.)
    bool ReadAtClock(double clock, Diagnostics& diags);
    // The scene, for front ends that build it statement by statement (uq's prompt). Call
    // SceneChanged() after changing it so that the next Flatten does not reuse a stale result.
    scene::Scene& Scene() { return scene_; }
    const scene::Scene& Scene() const { return scene_; }
    void SceneChanged() { flatValid_ = worldValid_ = flattenedOnce_ = false; }
    const InputReport& Inputs() const { return inputs_; }

    // Stage 2. false with errors in diags. Reuses the kept flat scene when nothing changed.
    bool Flatten(const ViewRequest& view, Diagnostics& diags);
    // Whether the first view's flatten names the half-spaces (FlattenOptions::halfSpaceNames;
    // on by default): a front end that never shows them (`render`: its messages name solids and
    // bodies, and it picks nothing) turns it off before its first Flatten.
    void NameHalfSpaces(bool on) {
        if (on != halfSpaceNames_) flatValid_ = flattenedOnce_ = false;
        halfSpaceNames_ = on;
    }
    const FlatScene& Flat() const { return flat_; }
    // Whether the last Flatten call reused the kept result (for tests and --stats).
    bool LastFlattenReused() const { return lastReused_; }
    // Whether the last Flatten call that flattened reused the kept world stage (flattener.h:
    // FlattenWorld), i.e. redid only what the view change invalidates.
    bool LastFlattenReusedWorld() const { return lastReusedWorld_; }
    // Times the geometry was flattened since construction (tests, batch summaries): the first
    // view of a scene is flattened in one go (flattener.h Flatten); a second view builds the
    // world stage, which every later view reuses.
    int worldFlattens = 0;

    // Stage 3 on the last flattened scene. false with errors in diags (unknown engine, bad
    // options, or — strict — something the engine cannot draw). `frame` is resized.
    bool Render(const EngineRequest& request, Frame& frame, RenderReport& report,
                Diagnostics& diags);
    // Checks the engine name and options without rendering (front ends call it before reading,
    // so a typo fails at once). Error message or empty.
    static std::string CheckEngine(const EngineRequest& request);

    // Stage 4, in the context's arena (its threads, as stage 3).
    Image Shade(const Frame& frame, const ShadeOptions& options) const;

    // Whether the context's work runs inline, on the calling thread without oneTBB (a context of
    // one thread, or a small job chosen by Flatten; never with a Cancellation), and how many
    // threads it uses.
    bool Inline() const;
    int Threads() const;

    // Runs `work` in the context's arena, so that its parallel loops use the context's threads
    // (`--threads`) and no others: the front ends' own shading of rows (sort-first) and the
    // encoding of the outputs.
    void InArena(const std::function<void()>& work) const;

    // Not owned; null = nothing can be cancelled. Kept by Read (the viewer's worker sets it once
    // per context).
    void SetCancellation(Cancellation* cancellation) { cancel_ = cancellation; }

    // Seconds spent by the last Read (or ReadAtClock) and Flatten calls.
    double readSeconds = 0, flattenSeconds = 0;
    // Times the inputs were read since construction (Read, and ReadAtClock when it reads them).
    int sceneReads = 0;

  private:
    struct Arena;
    Engine* EngineNamed(const std::string& name);
    // ReadAtClock's camera-only case: false (the scene unchanged) when a view statement has an
    // error at `clock` or the views read are not the scene's.
    bool ReadViewsAtClock(double clock, Diagnostics& diags);
    Image ShadeInArena(const Frame& frame, const ShadeOptions& options) const;
    // Draws `solids` of the flat scene with the reference engine and merges them into `frame`.
    void ComposeReference(const std::vector<int>& solids, const EngineRequest& request,
                          Frame& frame);
    // Runs `work` in the arena, under the cancellation when there is one; false when cancelled.
    bool Execute(const std::function<void()>& work);
    // The --strict error naming what the engine could not draw (undrawn solids, freeforms).
    void StrictRefusal(const std::string& engine, const std::vector<UndrawnSolid>& undrawn,
                       std::size_t freeforms, Diagnostics& diags) const;
    // Render for an engine without the `quartics` capability: it draws the `plain` solids on a
    // flat scene without quartic half-spaces, raycast draws the `quartic` ones (their first
    // quartic half-space in firstQuartic, for the message), composed by depth.
    bool RenderAroundQuartics(const EngineRequest& request, const std::vector<int>& plain,
                              const std::vector<int>& quartic, const std::vector<int>& firstQuartic,
                              Frame& frame, RenderReport& report, Diagnostics& diags,
                              std::chrono::steady_clock::time_point t0);

    std::unique_ptr<Arena> arena_;
    scene::Scene scene_;
    InputReport inputs_;
    InputRequest lastInput_;  // what the last Read read (ReadAtClock)
    bool readOk_ = false;     // the last Read had no error
    FlatScene flat_;
    bool flatValid_ = false, lastReused_ = false;
    // The box trees of flat_'s wide CSG nodes (flatten/wide_node_trees.h), made by the first
    // Shade that needs them (shadows or anti-aliasing) and shared by its shadow rays and samples
    // and by every later Shade of the same flat scene (the viewer's frames); dropped by Flatten.
    mutable std::mutex wideMutex_;
    mutable std::shared_ptr<const WideNodeTrees> wideTrees_;
    WorldScene world_;  // the kept world stage, valid with worldValid_
    // The flat scene of the view before flat_'s, kept while the world stage is: the next
    // FlattenView assigns over its elements instead of freeing them and making new ones.
    FlatScene spare_;
    bool worldValid_ = false, lastReusedWorld_ = false;
    bool flattenedOnce_ = false;  // the scene was flattened for one view (one-shot)
    bool halfSpaceNames_ = true;  // NameHalfSpaces
    // The scene's lights are those AddRtLights made for the last rt-style view (the scene had
    // none): the next rt-style view replaces them with its own.
    bool rtLights_ = false;
    // The request the kept flat scene was made for (lights and view as given).
    std::optional<ViewRequest> flatFor_;
    std::string flatViewName_;
    std::map<std::string, std::unique_ptr<Engine>> engines_;
    Cancellation* cancel_ = nullptr;
};

// Whether two view requests give the same flat scene.
bool SameView(const ViewRequest& a, const ViewRequest& b);

}  // namespace quadrix
