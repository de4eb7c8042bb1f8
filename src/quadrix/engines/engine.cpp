#include "quadrix/engines/engine.h"

#include <tbb/task_arena.h>

#include "quadrix/engines/registry.h"
#include "quadrix/util/parallel.h"

namespace quadrix {

const OptionSchema& Engine::Schema() const {
    static const OptionSchema kNone;
    return kNone;
}

std::string Engine::ValidateOptions(const RenderOptions& options) const {
    EngineOptions parsed;
    if (std::string e = ParseEngineOptions(Name(), Schema(), options.engineOptions, parsed);
        !e.empty())
        return e;
    return CheckOptions(parsed);
}

void SetBodySolids(const FlatScene& scene, Frame& frame) {
    frame.bodySolid.resize(scene.bodies.size());
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
        frame.bodySolid[b] = scene.bodies[b].solid;
}

RenderStats Engine::Render(const FlatScene& scene, const RenderOptions& options, Frame& frame) {
    EngineOptions parsed;
    std::string error = ParseEngineOptions(Name(), Schema(), options.engineOptions, parsed);
    if (error.empty()) error = CheckOptions(parsed);
    if (!error.empty()) {
        RenderStats stats;
        frame.Reset(std::max(scene.width, 0), std::max(scene.height, 0));
        stats.warnings.push_back(error + "; nothing drawn");
        return stats;
    }
    region_ = options.region ? &*options.region : nullptr;
    // Before Draw: an engine may read its Frame's solids (comparisons against raycast).
    SetBodySolids(scene, frame);
    RenderStats stats;
    if (options.threads > 0) {
        tbb::task_arena arena(options.threads);
        stats = arena.execute([&] {
            // The loops in this arena, not in a caller's loop arena (util/parallel.h).
            LoopArenaScope own(nullptr);
            return Draw(scene, parsed, frame);
        });
    } else {
        stats = Draw(scene, parsed, frame);
    }
    region_ = nullptr;
    if (options.region && !options.regionOnly) CropToRegion(frame, *options.region);
    return stats;
}

std::unique_ptr<Engine> MakeEngine(std::string_view name) {
    const EngineInfo* info = FindEngine(name);
    return info ? info->make() : nullptr;
}

std::vector<std::string> EngineNames() {
    std::vector<std::string> names;
    for (const EngineInfo& e : Engines()) names.push_back(e.name);
    return names;
}

}  // namespace quadrix
