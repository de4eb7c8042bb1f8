#include "quadrix/pipeline/stats_report.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace quadrix {

std::string FormatStatsText(const StatsInput& in) {
    const RenderContext& ctx = *in.context;
    const RenderReport& r = *in.report;
    const FlatScene& flat = ctx.Flat();
    std::string s = fmt::format(
        "engine {}  {}x{}  solids {}  bodies {}  half-spaces {}  covered {} px\n"
        "read {:.3f} s  flatten {:.3f} s  render {:.3f} s  shade+write {:.3f} s\n",
        r.engine, in.frame->width, in.frame->height, flat.solids.size(), flat.bodies.size(),
        flat.halfSpaces.size(), in.frame->CoveredCount(), ctx.readSeconds, ctx.flattenSeconds,
        r.seconds, in.shadeWriteSeconds);
    for (const auto& [path, imp] : ctx.Inputs().imports)
        s += fmt::format("{}: {}, {} solids drawn; {}{}{}\n", path, imp.format, imp.solids,
                         imp.CensusText(),
                         imp.skipped.empty() ? "" : "; left out: ", imp.SkippedText());
    for (const UndrawnSolid& u : r.byReference)
        s += fmt::format("  by raycast: solid '{}' ({})\n",
                         flat.solids[static_cast<std::size_t>(u.solid)].name, u.reason);
    if (!r.isocurveSummary.empty()) s += r.isocurveSummary + "\n";
    for (const auto& [name, value] : r.Counters()) s += fmt::format("  {}: {:.17g}\n", name, value);
    if (!r.stats.report.empty()) s += r.stats.report + "\n";
    return s;
}

std::string FormatStatsJson(const StatsInput& in) {
    using nlohmann::json;
    const RenderContext& ctx = *in.context;
    const RenderReport& r = *in.report;
    const FlatScene& flat = ctx.Flat();
    json j;
    j["engine"] = r.engine;
    j["width"] = in.frame->width;
    j["height"] = in.frame->height;
    j["scene"] = {{"solids", flat.solids.size()},
                  {"bodies", flat.bodies.size()},
                  {"half_spaces", flat.halfSpaces.size()},
                  {"freeforms", flat.freeforms.size()},
                  {"covered_pixels", in.frame->CoveredCount()}};
    j["seconds"] = {{"read", ctx.readSeconds},
                    {"flatten", ctx.flattenSeconds},
                    {"render", r.seconds},
                    {"shade_write", in.shadeWriteSeconds}};
    json imports = json::array();
    for (const auto& [path, imp] : ctx.Inputs().imports)
        imports.push_back({{"path", path},
                           {"format", imp.format},
                           {"solids", imp.solids},
                           {"left_out", imp.skipped}});  // --allow-missing: type → count
    j["imports"] = imports;
    json byRef = json::array();
    for (const UndrawnSolid& u : r.byReference)
        byRef.push_back(
            {{"solid", flat.solids[static_cast<std::size_t>(u.solid)].name}, {"reason", u.reason}});
    j["composition"] = {{"solids_by_raycast", byRef},
                        {"freeforms_by_isocurve", r.freeformsByIsocurve}};
    json counters = json::object();
    for (const auto& [name, value] : r.stats.counters) {
        // Counts as integers, measures as numbers.
        if (value == std::floor(value) && std::fabs(value) < 9007199254740992.0)
            counters[name] = static_cast<long long>(value);
        else
            counters[name] = value;
    }
    j["counters"] = counters;
    j["warnings"] = r.stats.warnings;
    j["notes"] = r.notes;
    j["report"] = r.stats.report;
    return j.dump(2) + "\n";
}

}  // namespace quadrix
