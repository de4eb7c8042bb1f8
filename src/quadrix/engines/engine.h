// The engine interface: FlatScene in, Frame out. Engines never parse scene text and never write
// files; they draw what they can and say what they left out.
//
// An engine is one folder under engines/ and one row of the registry (engines/registry.h): name,
// factory, typed option schema (engines/options.h), capabilities and one line of help. Callers
// reach engines through the render context (pipeline/render_context.h), which composes what an
// engine cannot draw from other engines' Frames; tests may call Render directly.
//
// Threads: Render runs Draw in the caller's oneTBB arena (the render context owns one), or, when
// RenderOptions::threads > 0, in a temporary arena of that many threads. Engines never make their
// own arenas; they use tbb::parallel_for and friends, and their results never depend on threads.
//
// Regions: RenderOptions::region asks for part of the picture (frame/pixel_region.h, sort-first
// rendering). The Frame keeps the scene's full size; Render sets every pixel outside the region
// to background after Draw (unless RenderOptions::regionOnly), so an engine may ignore the region
// (draw everything, cropped) or use Region() to skip the work outside it, which must not change a
// pixel inside it.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/engines/options.h"
#include "quadrix/engines/stats_table.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/frame/pixel_region.h"

namespace quadrix {

struct RenderOptions {
    int threads = 0;  // 0 = the caller's arena (all hardware threads by default)
    // The user's option request, "key" → "value" (CLI: --engine-opt key=value), checked against
    // the engine's schema: an unknown key or a bad value is an error, not a silent default.
    std::map<std::string, std::string> engineOptions;
    // Only these pixels (see the header comment); unset = the whole picture.
    std::optional<PixelRegion> region;
    // With a region: the pixels outside it are left as the engine left them (unspecified; an
    // engine that skips its work there never writes them), instead of being made background.
    // For callers that read the region only (sort-first): a fresh Frame's pages outside it are
    // then not touched.
    bool regionOnly = false;
};

// A solid the engine did not draw at all (no pixel of it is in the Frame), and why. The render
// context draws these with the reference engine and composes the two Frames by depth.
struct UndrawnSolid {
    int solid = -1;  // FlatScene::solids index
    std::string reason;
};

// What an engine reports after a render (printed by --stats, or as JSON with --stats --json).
struct RenderStats {
    double seconds = 0;
    std::vector<std::pair<std::string, double>> counters;
    // Tables laid out like the engine's paper (engines/stats_table.h), formatted by the report.
    std::vector<StatsTable> tables;
    std::string report;  // free-form multi-line text (notes, histograms)
    // What the user must hear even without --stats (a guard that stopped it, an accuracy bound
    // that did not hold): printed by the CLI as "warning: ..." lines after every render.
    std::vector<std::string> warnings;
    // Solids left out (see UndrawnSolid). Not a warning: the render context composes them.
    std::vector<UndrawnSolid> undrawn;
};

// What an engine can draw; solids it declines at run time are reported in RenderStats::undrawn.
struct EngineCapabilities {
    bool solids = true;      // FlatScene::solids (planes and quadrics, CSG)
    bool freeforms = false;  // FlatScene::freeforms (Bézier/NURBS surfaces)
    // Quartic half-spaces (math/quartic_surface.h: tori, general cones). Without it the render
    // context draws every solid that has one with raycast and composes it by depth, and the
    // engine never sees a quartic half-space (pipeline/render_context.cpp).
    bool quartics = false;
};

class Engine {
  public:
    virtual ~Engine() = default;
    virtual std::string_view Name() const = 0;
    // The engine's options (engines/options.h); none by default.
    virtual const OptionSchema& Schema() const;
    // Checks between options that the schema cannot express (min-level <= max-level, ...).
    virtual std::string CheckOptions(const EngineOptions&) const { return {}; }

    // Parses options.engineOptions against Schema() and CheckOptions; error message or empty.
    std::string ValidateOptions(const RenderOptions& options) const;
    // Parses the options, then draws. The Frame is resized to the scene's width × height. With
    // options that do not validate (ValidateOptions reports them before any work) nothing is
    // drawn and the error is a warning. Never throws for degenerate geometry.
    RenderStats Render(const FlatScene& scene, const RenderOptions& options, Frame& frame);

  protected:
    // The region of the current Render call, or nullptr for the whole picture (for Draw).
    const PixelRegion* Region() const { return region_; }
    virtual RenderStats Draw(const FlatScene& scene, const EngineOptions& options,
                             Frame& frame) = 0;

  private:
    const PixelRegion* region_ = nullptr;
};

// Fills frame.bodySolid from the scene (each body's FlatBody::solid): what Frame::Solid reads.
// Render calls it before Draw; whoever fills a Frame another way calls it too.
void SetBodySolids(const FlatScene& scene, Frame& frame);

// Registry shortcuts (engines/registry.h): nullptr when `name` is not a registered engine.
std::unique_ptr<Engine> MakeEngine(std::string_view name);
std::vector<std::string> EngineNames();

}  // namespace quadrix
