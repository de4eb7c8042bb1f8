#include "quadrix/pipeline/pipeline.h"

#include <chrono>

#include <fmt/format.h>

#include "quadrix/flatten/flattener.h"
#include "quadrix/lang/reader.h"

namespace quadrix {

namespace {
double SecondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

std::string CheckImageSize(long long width, long long height) {
    if (width <= 0 || height <= 0)
        return fmt::format("image size {}x{} is not positive", width, height);
    if (width > kMaxSide || height > kMaxSide || width * height > kMaxPixels)
        return fmt::format("image size {}x{} is too large (at most {} pixels a side and {} pixels)",
                           width, height, kMaxSide, kMaxPixels);
    return {};
}

bool RunPipeline(const PipelineOptions& options, PipelineResult& result, Diagnostics& diags) {
    if (auto e = CheckImageSize(options.width, options.height); !e.empty()) {
        diags.Error({}, e, {}, "command line");
        return false;
    }
    auto engine = MakeEngine(options.engine);
    if (!engine) {
        std::string names;
        for (const auto& n : EngineNames()) names += (names.empty() ? "" : ", ") + n;
        diags.Error({}, fmt::format("unknown engine '{}' (known: {})", options.engine, names), {},
                    "command line");
        return false;
    }

    RenderOptions ro;
    ro.threads = options.threads;
    ro.engineOptions = options.engineOptions;
    if (auto e = engine->ValidateOptions(ro); !e.empty()) {
        diags.Error({}, e, {}, "command line");
        return false;
    }

    auto t0 = std::chrono::steady_clock::now();
    {
        lang::Reader reader(result.scene, diags);
        if (options.scenePaths.empty()) {
            reader.ReadText(options.sceneText, "<text>");
        } else {
            for (const std::string& path : options.scenePaths) reader.ReadFile(path);
        }
    }
    result.readSeconds = SecondsSince(t0);
    if (diags.HasErrors()) return false;

    t0 = std::chrono::steady_clock::now();
    FlattenOptions fo;
    fo.width = options.width;
    fo.height = options.height;
    fo.viewName = options.viewName;
    auto flat = Flatten(result.scene, fo, diags);
    result.flattenSeconds = SecondsSince(t0);
    if (!flat || diags.HasErrors()) return false;
    result.flat = std::move(*flat);

    t0 = std::chrono::steady_clock::now();
    result.stats = engine->Render(result.flat, ro, result.frame);
    result.renderSeconds = SecondsSince(t0);
    return true;
}

}  // namespace quadrix
