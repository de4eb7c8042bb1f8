// The engine interface: FlatScene in, Frame out. Engines never parse and never write files.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"

namespace quadrix {

struct RenderOptions {
    int threads = 0;  // 0 = all hardware threads
};

// Counters an engine reports after a render (printed by --stats).
struct RenderStats {
    double seconds = 0;
    std::vector<std::pair<std::string, double>> counters;
};

class Engine {
public:
    virtual ~Engine() = default;
    virtual std::string_view Name() const = 0;
    // Fills `frame` (resized to the scene's width × height). Never throws for degenerate geometry.
    virtual RenderStats Render(const FlatScene& scene, const RenderOptions& options,
                               Frame& frame) = 0;
};

// nullptr when `name` is not an engine.
std::unique_ptr<Engine> MakeEngine(std::string_view name);
std::vector<std::string> EngineNames();

}  // namespace quadrix
