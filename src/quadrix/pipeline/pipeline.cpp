#include "quadrix/pipeline/pipeline.h"

namespace quadrix {

InputRequest PipelineOptions::Input() const {
    InputRequest r;
    r.paths = scenePaths;
    r.text = sceneText;
    r.topObjects = topObjects;
    r.strict = strict;
    r.allowMissing = allowMissing;
    return r;
}

ViewRequest PipelineOptions::View() const {
    ViewRequest v;
    v.width = width;
    v.height = height;
    v.viewName = viewName;
    v.azimuth = azimuth;
    v.elevation = elevation;
    v.viewsize = viewsize;
    v.rtView = rtView;
    v.section = section;
    return v;
}

EngineRequest PipelineOptions::EngineRun() const {
    EngineRequest e;
    e.engine = engine;
    e.options = engineOptions;
    e.strict = strict;
    return e;
}

namespace {

bool ReadAndFlattenIn(RenderContext& ctx, const PipelineOptions& options, PipelineResult& result,
                      Diagnostics& diags) {
    if (auto e = CheckImageSize(options.width, options.height); !e.empty()) {
        diags.Error({}, e, {}, "command line");
        return false;
    }
    const bool read = ctx.Read(options.Input(), diags);
    result.readSeconds = ctx.readSeconds;
    result.inputs = ctx.Inputs();
    if (!read) {
        result.scene = ctx.Scene();
        return false;
    }
    const bool flat = ctx.Flatten(options.View(), diags);
    result.flattenSeconds = ctx.flattenSeconds;
    result.scene = ctx.Scene();
    if (!flat) return false;
    result.flat = ctx.Flat();
    return true;
}

}  // namespace

bool ReadAndFlatten(const PipelineOptions& options, PipelineResult& result, Diagnostics& diags) {
    RenderContext ctx(options.threads);
    return ReadAndFlattenIn(ctx, options, result, diags);
}

bool RunPipeline(const PipelineOptions& options, PipelineResult& result, Diagnostics& diags) {
    if (auto e = CheckImageSize(options.width, options.height); !e.empty()) {
        diags.Error({}, e, {}, "command line");
        return false;
    }
    const EngineRequest request = options.EngineRun();
    if (auto e = RenderContext::CheckEngine(request); !e.empty()) {
        diags.Error({}, e, {}, "command line");
        return false;
    }
    RenderContext ctx(options.threads);
    if (!ReadAndFlattenIn(ctx, options, result, diags)) return false;
    if (!ctx.Render(request, result.frame, result.report, diags)) return false;
    result.stats = result.report.stats;
    result.stats.counters = result.report.Counters();
    for (const std::string& n : result.report.notes) result.stats.report += "note: " + n + "\n";
    if (!result.report.isocurveSummary.empty())
        result.stats.report += result.report.isocurveSummary + "\n";
    result.renderSeconds = result.report.seconds;
    return true;
}

}  // namespace quadrix
