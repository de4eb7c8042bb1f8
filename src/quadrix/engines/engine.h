// The engine interface: FlatScene in, Frame out. Engines never parse and never write files.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"

namespace quadrix {

struct RenderOptions {
    int threads = 0;  // 0 = all hardware threads
    // Engine-specific settings, "key" → "value" (CLI: --engine-opt key=value). An engine rejects
    // keys it does not know through ValidateOptions, so a typo is an error, not a silent default.
    std::map<std::string, std::string> engineOptions;
};

// What an engine reports after a render (printed by --stats).
struct RenderStats {
    double seconds = 0;
    std::vector<std::pair<std::string, double>> counters;
    std::string report;  // free-form multi-line text (tables of a paper's layout, histograms)
    // What the user must hear even without --stats (a solid the engine could not draw, a guard
    // that stopped it): printed by the CLI as "warning: ..." lines after every render.
    std::vector<std::string> warnings;
};

class Engine {
public:
    virtual ~Engine() = default;
    virtual std::string_view Name() const = 0;
    // Checks engineOptions before any work; returns an error message or empty.
    virtual std::string ValidateOptions(const RenderOptions& options) const {
        if (!options.engineOptions.empty())
            return "engine '" + std::string(Name()) + "' has no option '" +
                   options.engineOptions.begin()->first + "'";
        return {};
    }
    // Fills `frame` (resized to the scene's width × height). Never throws for degenerate geometry.
    virtual RenderStats Render(const FlatScene& scene, const RenderOptions& options,
                               Frame& frame) = 0;
};

// nullptr when `name` is not an engine.
std::unique_ptr<Engine> MakeEngine(std::string_view name);
std::vector<std::string> EngineNames();

}  // namespace quadrix
