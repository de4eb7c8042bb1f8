#include "quadrix/pipeline/pipeline.h"

#include <chrono>

#include <fmt/format.h>

#include "quadrix/engines/isocurve/isocurve_engine.h"
#include "quadrix/flatten/flattener.h"
#include "quadrix/frame/memory_budget.h"
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
    // Before the Frame is allocated (frame/memory_budget.h): a clear error, not std::bad_alloc.
    return CheckMemory(RenderBytes(width, height),
                       fmt::format("an image of {}x{} pixels", width, height));
}

bool ReadAndFlatten(const PipelineOptions& options, PipelineResult& result, Diagnostics& diags) {
    if (auto e = CheckImageSize(options.width, options.height); !e.empty()) {
        diags.Error({}, e, {}, "command line");
        return false;
    }
    auto t0 = std::chrono::steady_clock::now();
    std::string viewName = options.viewName;
    if (options.scenePaths.empty()) {
        lang::Reader reader(result.scene, diags);
        reader.ReadText(options.sceneText, "<text>");
    } else {
        // Files of mixed formats (UniQuadrix, BRL-CAD, OpenSCAD) into one scene (docs/import.md).
        import::InputOptions io;
        io.import.topObjects = options.topObjects;
        io.import.strict = options.strict;
        import::ReadSceneInputs(options.scenePaths, io, result.scene, diags, result.inputs);
    }
    result.readSeconds = SecondsSince(t0);
    if (diags.HasErrors()) return false;
    if (options.rtView || options.azimuth || options.elevation) {
        scene::View view =
            options.rtView
                ? import::MakeRtView(*options.rtView, options.width, options.height)
                : import::MakeAzElView(options.azimuth.value_or(35),
                                       options.elevation.value_or(25),
                                       result.inputs.importedBounds, options.viewsize,
                                       options.width, options.height);
        import::AddRtLights(result.scene, view);
        result.scene.views.push_back(view);
        viewName = view.id;
    }

    t0 = std::chrono::steady_clock::now();
    FlattenOptions fo;
    fo.width = options.width;
    fo.height = options.height;
    fo.viewName = viewName;
    auto flat = Flatten(result.scene, fo, diags);
    result.flattenSeconds = SecondsSince(t0);
    if (!flat || diags.HasErrors()) return false;
    result.flat = std::move(*flat);
    return true;
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

    if (!ReadAndFlatten(options, result, diags)) return false;

    auto t0 = std::chrono::steady_clock::now();
    result.stats = engine->Render(result.flat, ro, result.frame);
    if (engine->Name() != "isocurve" && !result.flat.freeforms.empty()) {
        // Freeform surfaces are drawn by adaptive isocurves (seed 002) over any engine's solids,
        // with the isocurve engine's default tolerance (curves at most one pixel apart).
        isocurve::IsocurveStats st = isocurve::RenderFreeform(
            isocurve::SceneDrawables(result.flat), result.flat.projection, {}, result.frame);
        result.stats.report += fmt::format(
            "freeform surfaces: {} drawn by adaptive isocurves after engine '{}' ({} curves, "
            "delta {:.3g}; --engine isocurve gives the isocurve options and statistics)\n",
            st.surfaces, engine->Name(), st.curves, st.delta);
    }
    result.renderSeconds = SecondsSince(t0);
    return true;
}

}  // namespace quadrix
