// The whole pipeline in one call, for tests and simple callers: a RenderContext
// (pipeline/render_context.h) run once — read, flatten, render with composition — with the
// products copied out. Front ends that render more than once (uq, the viewer, batch runs) keep a
// RenderContext instead.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "quadrix/engines/engine.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/frame/image_limits.h"
#include "quadrix/import/rt_view.h"
#include "quadrix/pipeline/inputs.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix {

struct PipelineOptions {
    std::vector<std::string> scenePaths;  // "-" = standard input
    std::string sceneText;                // used instead of files when scenePaths is empty
    int width = 512, height = 512;
    std::string viewName;
    std::string engine = "raycast";
    int threads = 0;
    std::map<std::string, std::string> engineOptions;  // --engine-opt key=value
    // Importers (docs/import.md): objects to draw from BRL-CAD/OpenSCAD files (--top) and whether
    // primitives that cannot be drawn exactly are an error (--strict); strict also refuses to
    // compose what the engine cannot draw.
    std::vector<std::string> topObjects;
    bool strict = false;
    // Primitives that cannot be drawn are an error unless allowMissing (--allow-missing): then
    // they are left out with a warning and counted in inputs (ImportReport::skipped).
    bool allowMissing = false;
    // rt-style views (FORMAT.md §9.4), in the imported model's coordinates; they replace
    // viewName. azimuth/elevation in degrees, fitted to the imported model's bounding box.
    std::optional<double> azimuth, elevation, viewsize;
    std::optional<import::RtView> rtView;
    // A section plane (ViewRequest::section; --section).
    std::optional<Plane> section;

    InputRequest Input() const;
    ViewRequest View() const;
    EngineRequest EngineRun() const;
};

struct PipelineResult {
    scene::Scene scene;
    FlatScene flat;
    Frame frame;
    // The engine's statistics; the composition's counters first, its notes and the isocurve
    // summary appended to the report.
    RenderStats stats;
    RenderReport report;
    InputReport inputs;  // what the importers found (census, skipped primitives, bounds)
    double readSeconds = 0, flattenSeconds = 0, renderSeconds = 0;
};

// Reads (every input format, docs/import.md), applies rt-style views and flattens: fills
// result.scene, result.flat, result.inputs and the read/flatten times. The engine is not involved
// (quadrix export uses this). Returns false with errors in diags.
bool ReadAndFlatten(const PipelineOptions& options, PipelineResult& result, Diagnostics& diags);

// Reads, flattens and renders. Returns false with errors in diags.
bool RunPipeline(const PipelineOptions& options, PipelineResult& result, Diagnostics& diags);

}  // namespace quadrix
