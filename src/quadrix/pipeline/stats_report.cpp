#include "quadrix/pipeline/stats_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

namespace quadrix {

namespace {

std::string CellText(const StatsCell& c) {
    switch (c.kind) {
        case StatsCell::Kind::kEmpty:
            return {};
        case StatsCell::Kind::kText:
            return c.text;
        case StatsCell::Kind::kInteger:
            return fmt::format("{}", c.integer);
        case StatsCell::Kind::kReal:
            return fmt::format("{:.{}f}{}{}", c.real, c.decimals, c.unit.empty() ? "" : " ",
                               c.unit);
    }
    return {};
}

bool IsNumber(const StatsCell& c) {
    return c.kind == StatsCell::Kind::kInteger || c.kind == StatsCell::Kind::kReal;
}

std::vector<std::string> Lines(const std::string& s) {
    std::vector<std::string> out(1);
    for (char ch : s) {
        if (ch == '\n')
            out.emplace_back();
        else
            out.back() += ch;
    }
    return out;
}

// Display width of UTF-8 text (headers may hold "×"): code points, not bytes.
std::size_t Width(const std::string& s) {
    std::size_t n = 0;
    for (unsigned char ch : s) n += (ch & 0xC0) != 0x80;
    return n;
}

std::string Pad(const std::string& s, std::size_t width, bool right) {
    const std::size_t w = Width(s);
    const std::string fill(width > w ? width - w : 0, ' ');
    return right ? fill + s : s + fill;
}

nlohmann::json CellJson(const StatsCell& c) {
    switch (c.kind) {
        case StatsCell::Kind::kEmpty:
            return nullptr;
        case StatsCell::Kind::kText:
            return c.text;
        case StatsCell::Kind::kInteger:
            return c.integer;
        case StatsCell::Kind::kReal:
            return c.real;
    }
    return nullptr;
}

}  // namespace

std::string FormatStatsTable(const StatsTable& t) {
    const std::size_t n = t.columns.size();
    std::vector<std::vector<std::string>> header(n);
    std::size_t headerLines = 0;
    for (std::size_t k = 0; k < n; ++k) {
        header[k] = Lines(t.columns[k]);
        headerLines = std::max(headerLines, header[k].size());
    }
    // A column is right-aligned when any of its cells is a number.
    std::vector<std::size_t> width(n, 0);
    std::vector<bool> right(n, false);
    for (std::size_t k = 0; k < n; ++k)
        for (const std::string& h : header[k]) width[k] = std::max(width[k], Width(h));
    std::vector<std::vector<std::string>> cells;
    for (const auto& row : t.rows) {
        std::vector<std::string>& out = cells.emplace_back();
        for (std::size_t k = 0; k < n; ++k) {
            const StatsCell c = k < row.size() ? row[k] : StatsCell::Empty();
            out.push_back(CellText(c));
            width[k] = std::max(width[k], Width(out.back()));
            if (IsNumber(c)) right[k] = true;
        }
    }
    auto line = [&](const std::vector<std::string>& v) {
        std::string s = " ";
        for (std::size_t k = 0; k < n; ++k) s += (k ? "  " : " ") + Pad(v[k], width[k], right[k]);
        while (!s.empty() && s.back() == ' ') s.pop_back();
        return s + "\n";
    };
    std::string s = t.title.empty() ? std::string() : t.title + "\n";
    for (std::size_t l = 0; l < headerLines; ++l) {
        std::vector<std::string> v(n);
        for (std::size_t k = 0; k < n; ++k) {
            // Headers are bottom-aligned: a one-line header sits on the last header line.
            const std::size_t skip = headerLines - header[k].size();
            if (l >= skip) v[k] = header[k][l - skip];
        }
        s += line(v);
    }
    for (const auto& row : cells) s += line(row);
    for (const std::string& note : t.notes) s += "  " + note + "\n";
    return s;
}

std::string FormatStatsText(const StatsInput& in) {
    const RenderContext& ctx = *in.context;
    const RenderReport& r = *in.report;
    const FlatScene& flat = ctx.Flat();
    std::string s = fmt::format(
        "engine {}  {}x{}  solids {}  bodies {}  half-spaces {}  covered {} px\n"
        "read {:.3f} s  flatten {:.3f} s  render {:.3f} s  shade+write {:.3f} s  threads {}{}\n",
        r.engine, in.frame->width, in.frame->height, flat.solids.size(), flat.bodies.size(),
        flat.halfSpaces.size(), in.frame->CoveredCount(), ctx.readSeconds, ctx.flattenSeconds,
        r.seconds, in.shadeWriteSeconds, ctx.Threads(), ctx.Inline() ? " (inline)" : "");
    for (const auto& [path, imp] : ctx.Inputs().imports)
        s += fmt::format("{}: {}, {} solids drawn; {}{}{}\n", path, imp.format, imp.solids,
                         imp.CensusText(),
                         imp.skipped.empty() ? "" : "; left out: ", imp.SkippedText());
    for (const UndrawnSolid& u : r.byReference)
        s += fmt::format("  by raycast: solid '{}' ({})\n",
                         flat.solids[static_cast<std::size_t>(u.solid)].name, u.reason);
    if (!r.isocurveSummary.empty()) s += r.isocurveSummary + "\n";
    for (const auto& [name, value] : r.Counters()) s += fmt::format("  {}: {:.17g}\n", name, value);
    for (const StatsTable& t : r.stats.tables) s += FormatStatsTable(t);
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
    j["threads"] = {{"count", ctx.Threads()}, {"inline", ctx.Inline()}};
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
    json tables = json::array();
    for (const StatsTable& t : r.stats.tables) {
        json rows = json::array();
        for (const auto& row : t.rows) {
            json cells = json::array();
            for (const StatsCell& c : row) cells.push_back(CellJson(c));
            rows.push_back(cells);
        }
        tables.push_back(
            {{"title", t.title}, {"columns", t.columns}, {"rows", rows}, {"notes", t.notes}});
    }
    j["tables"] = tables;
    j["warnings"] = r.stats.warnings;
    j["notes"] = r.notes;
    j["report"] = r.stats.report;
    return j.dump(2) + "\n";
}

}  // namespace quadrix
