#include "quadrix/batch/job_file.h"

#include <fmt/format.h>

#include <cctype>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "quadrix/batch/view_list.h"
#include "quadrix/engines/options.h"
#include "quadrix/frame/image_limits.h"
#include "quadrix/import/rt_view.h"
#include "quadrix/io/bounded_read.h"

namespace quadrix::batch {

namespace {

using nlohmann::json;

std::string ParseSizeText(const std::string& text, int& width, int& height) {
    long long w = 0, h = 0;
    char x = 0, rest = 0;
    if (std::sscanf(text.c_str(), "%lld%c%lld%c", &w, &x, &h, &rest) != 3 || (x != 'x' && x != 'X'))
        return fmt::format("\"size\": expected \"WIDTHxHEIGHT\", found \"{}\"", text);
    if (auto e = CheckImageSize(w, h); !e.empty()) return "\"size\": " + e;
    width = static_cast<int>(w);
    height = static_cast<int>(h);
    return {};
}

const std::set<std::string>& Keys() {
    static const std::set<std::string> keys = {
        "inputs",        "input",     "output", "size",       "engine",  "engine_options",
        "view",          "az",        "el",     "viewsize",   "rt_view", "frames",
        "frame_range",   "turntable", "views",  "dump_frame", "exr",     "fast",
        "phong",         "shadows",   "aa",     "png16",      "top",     "strict",
        "allow_missing", "threads"};
    return keys;
}

// One job from one JSON object; error or empty.
std::string JobFromJson(const json& j, Job& job) {
    if (!j.is_object()) return "a job is a JSON object ({...})";
    for (const auto& [k, v] : j.items())
        if (!Keys().contains(k)) return fmt::format("unknown key \"{}\"", k);
    auto str = [&](const char* k, std::string& out) -> std::string {
        if (!j.contains(k)) return {};
        if (!j[k].is_string()) return fmt::format("\"{}\" must be a string", k);
        out = j[k].get<std::string>();
        return {};
    };
    auto num = [&](const char* k, std::optional<double>& out) -> std::string {
        if (!j.contains(k)) return {};
        if (!j[k].is_number()) return fmt::format("\"{}\" must be a number", k);
        out = j[k].get<double>();
        return {};
    };
    auto flag = [&](const char* k, bool& out) -> std::string {
        if (!j.contains(k)) return {};
        if (!j[k].is_boolean()) return fmt::format("\"{}\" must be true or false", k);
        out = j[k].get<bool>();
        return {};
    };
    auto integer = [&](const char* k, int& out) -> std::string {
        if (!j.contains(k)) return {};
        if (!j[k].is_number_integer() || j[k].get<long long>() < 1 ||
            j[k].get<long long>() > 10'000'000)
            return fmt::format("\"{}\" must be a whole number from 1 to 10000000", k);
        out = j[k].get<int>();
        return {};
    };
    auto strings = [&](const char* k, std::vector<std::string>& out) -> std::string {
        if (!j.contains(k)) return {};
        if (j[k].is_string()) {
            out = {j[k].get<std::string>()};
            return {};
        }
        if (!j[k].is_array()) return fmt::format("\"{}\" must be a list of strings", k);
        for (const json& e : j[k]) {
            if (!e.is_string()) return fmt::format("\"{}\" must be a list of strings", k);
            out.push_back(e.get<std::string>());
        }
        return {};
    };
    std::string e;
    std::vector<std::string> input;
    if (!(e = strings("inputs", job.input.paths)).empty()) return e;
    if (!(e = strings("input", input)).empty()) return e;
    job.input.paths.insert(job.input.paths.end(), input.begin(), input.end());
    if (job.input.paths.empty()) return "no \"inputs\"";
    if (!(e = str("output", job.output.image)).empty()) return e;
    if (job.output.image.empty()) return "no \"output\"";
    if (!(e = str("dump_frame", job.output.dumpFrame)).empty()) return e;
    if (!(e = str("exr", job.output.exr)).empty()) return e;
    std::string size = "512x512";
    if (!(e = str("size", size)).empty()) return e;
    if (!(e = ParseSizeText(size, job.view.width, job.view.height)).empty()) return e;
    if (!(e = str("engine", job.engine.engine)).empty()) return e;
    if (j.contains("engine_options")) {
        if (!j["engine_options"].is_object()) return "\"engine_options\" must be an object";
        for (const auto& [k, v] : j["engine_options"].items()) {
            if (!v.is_string()) return "\"engine_options\" values must be strings";
            job.engine.options[k] = v.get<std::string>();
        }
    }
    if (!(e = str("view", job.view.viewName)).empty()) return e;
    if (!(e = num("az", job.view.azimuth)).empty()) return e;
    if (!(e = num("el", job.view.elevation)).empty()) return e;
    if (!(e = num("viewsize", job.view.viewsize)).empty()) return e;
    if (job.view.viewsize && !(*job.view.viewsize > 0)) return "\"viewsize\" must be positive";
    std::string rtView, views, range;
    if (!(e = str("rt_view", rtView)).empty()) return e;
    if (!(e = str("views", views)).empty()) return e;
    if (!(e = str("frame_range", range)).empty()) return e;
    if (!(e = integer("frames", job.frames)).empty()) return e;
    int turntable = 0;
    if (!(e = integer("turntable", turntable)).empty()) return e;
    bool png16 = false, phong = false;
    if (!(e = flag("fast", job.shade.fast)).empty()) return e;
    if (!(e = flag("phong", phong)).empty()) return e;
    if (j.contains("shadows")) {
        // true: always; false: never; absent: the picture default (shade/picture_defaults.h).
        if (!(e = flag("shadows", job.shade.shadows)).empty()) return e;
        job.picture.shadows = false;
    }
    if (j.contains("aa")) {
        // What render's --aa accepts, with its meaning (shade/picture_defaults.h): "default" is
        // the picture default, decided frame by frame; anything else is asked for as given.
        const json& aa = j["aa"];
        const std::string expected = "\"aa\" must be \"off\", \"default\", 4, 16 or 64";
        if (!aa.is_string() && !aa.is_number_integer()) return expected;
        const std::string text = aa.is_string() ? aa.get<std::string>() : aa.dump();
        int samples = 0;
        if (!ParseAaSamples(text, samples).empty())
            return fmt::format("{}, found {}", expected, aa.dump());
        if (text != "default") {
            job.shade.aaSamples = samples;
            job.picture.antialiasing = false;
        }
    }
    if (!(e = flag("png16", png16)).empty()) return e;
    if (!(e = flag("strict", job.input.strict)).empty()) return e;
    job.engine.strict = job.input.strict;
    if (!(e = flag("allow_missing", job.input.allowMissing)).empty()) return e;
    if (!(e = strings("top", job.input.topObjects)).empty()) return e;
    if (phong) job.shade.model = ShadingModel::kPhong;
    job.output.png.bitDepth = png16 ? 16 : 8;
    job.shade.linear = NeedsLinear(job.output);  // 8-bit files: from the 8-bit pixels
    if (!job.view.viewName.empty() && (job.view.azimuth || job.view.elevation || !rtView.empty()))
        return "\"view\" cannot be combined with \"az\"/\"el\" or \"rt_view\"";
    if (turntable > 0) {
        if (job.frames > 0 && job.frames != turntable)
            return "\"turntable\" gives the number of frames; \"frames\" disagrees";
        job.frames = turntable;
        Turntable t;
        if (job.view.azimuth) t.azimuth0 = *job.view.azimuth;
        if (job.view.elevation) t.elevation = *job.view.elevation;
        job.view.azimuth.reset();
        job.view.elevation.reset();
        job.turntable = t;
    }
    if (!rtView.empty()) {
        std::string text;
        if (auto why = ReadBoundedFile(rtView, text); !why.empty())
            return fmt::format("\"rt_view\": cannot read '{}': {}", rtView, why);
        Diagnostics d;
        auto rt = import::ParseRtViewScript(text, rtView, d);
        if (!rt) return d.Items().empty() ? "bad rt view" : d.Items().front().Format(false);
        if (rt->Fitted()) {  // rt's `ae`: the view of "az"/"el" (import/rt_view.h)
            if (job.view.azimuth || job.view.elevation)
                return "\"az\"/\"el\" cannot be combined with an \"rt_view\" script's 'ae'";
            job.view.azimuth = rt->aeAzimuth;
            job.view.elevation = rt->aeElevation;
            if (rt->viewsize > 0) job.view.viewsize = rt->viewsize;
        } else {
            job.view.rtView = *rt;
        }
    }
    if (!views.empty()) {
        Diagnostics d;
        auto list = ReadViewList(views, d);
        if (!list) return d.Items().empty() ? "bad view list" : d.Items().front().Format(false);
        job.views = std::move(*list);
    }
    if (!range.empty())
        if (!(e = ParseFrameRange(range, job.first, job.last)).empty()) return e;
    if (auto c = RenderContext::CheckEngine(job.engine); !c.empty()) return c;
    if (auto c = CheckOutputs(job.output); !c.empty()) return c;
    return CheckJob(job);
}

// `quadrix render x.uq --top NAME` warns that --top has no effect (no BRL-CAD or OpenSCAD file
// was given) and draws the scene: so does a job whose "top" names objects while every input is a
// UniQuadrix file by its name. The pipeline's own warning (which speaks of --top, and which a
// batch would give once per frame as a note) is then not given: the job's objects are cleared.
// Inputs told apart by their text (no known extension) are left to the pipeline's warning.
std::string TopWithoutImports(Job& job) {
    if (job.input.topObjects.empty()) return {};
    for (const std::string& path : job.input.paths) {
        std::string lower = path;
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (!lower.ends_with(".uq")) return {};
    }
    job.input.topObjects.clear();
    return "\"top\" has no effect: no BRL-CAD or OpenSCAD file among the inputs (the scene is "
           "drawn whole, as `quadrix render` does with --top)";
}

// The column (from 1) of the key `key` in a JSON line: its quoted name followed by a ':'; 1 when
// it is not found as written (escapes).
std::size_t KeyColumn(std::string_view row, const std::string& key) {
    const std::string quoted = "\"" + key + "\"";
    for (std::size_t at = row.find(quoted); at != std::string_view::npos;
         at = row.find(quoted, at + 1)) {
        const std::size_t next = row.find_first_not_of(" \t", at + quoted.size());
        if (next != std::string_view::npos && row[next] == ':') return at + 1;
    }
    return 1;
}

}  // namespace

std::string ParseFrameRange(const std::string& text, int& first, int& last) {
    const auto colon = text.find(':');
    auto number = [](const std::string& s, int& out) {
        if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos)
            return false;
        out = std::stoi(s);
        return true;
    };
    const std::string bad =
        fmt::format("frame range: expected FIRST:LAST (frame numbers from 0), found '{}'", text);
    if (colon == std::string::npos) {
        if (!number(text, first)) return bad;
        last = first;
        return {};
    }
    const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
    first = 0;
    last = -1;
    if (!a.empty() && !number(a, first)) return bad;
    if (!b.empty() && !number(b, last)) return bad;
    if (a.empty() && b.empty()) return bad;
    return {};
}

// One line of a job file as JSON, or the error: "COLUMN: invalid JSON: why" for a syntax error
// (the column is the byte of the line where parsing stopped), or a key given twice in one object
// (nlohmann would keep the last one silently: `"output"` twice wrote the second file only).
std::string ParseJsonRow(std::string_view row, json& out) {
    std::vector<std::set<std::string>> keys;  // per open object, its keys so far
    std::string duplicate;
    const json::parser_callback_t noteKeys = [&](int, json::parse_event_t event, json& parsed) {
        if (event == json::parse_event_t::object_start) keys.emplace_back();
        if (event == json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
        if (event == json::parse_event_t::key && !keys.empty() && parsed.is_string() &&
            !keys.back().insert(parsed.get<std::string>()).second && duplicate.empty())
            duplicate = parsed.get<std::string>();
        return true;
    };
    try {
        out = json::parse(row, noteKeys);
    } catch (const json::out_of_range& e) {  // a number too large for a double (1e400)
        std::string why = e.what();
        if (std::size_t p = why.find("] "); p != std::string::npos) why = why.substr(p + 2);
        return fmt::format("1: invalid JSON: {}", why);
    } catch (const json::parse_error& e) {
        // what() is "[json.exception.parse_error.101] parse error at line 1, column 9: syntax
        // error while parsing ..."; the reason is what follows the position.
        std::string why = e.what();
        if (std::size_t p = why.find(": ", why.find("column")); p != std::string::npos)
            why = why.substr(p + 2);
        return fmt::format("{}: invalid JSON: {}", e.byte, why);
    }
    if (!duplicate.empty()) {
        // The column of its second spelling (the key as written, which escapes could hide: then
        // the line's start).
        const std::string quoted = "\"" + duplicate + "\"";
        std::size_t at = row.find(quoted);
        at = at == std::string_view::npos ? at : row.find(quoted, at + 1);
        return fmt::format("{}: the key \"{}\" is given twice in one object",
                           at == std::string_view::npos ? 1 : at + 1, duplicate);
    }
    return {};
}

std::vector<JobEntry> ParseJobFile(std::string_view text, const std::string& file) {
    std::vector<JobEntry> jobs;
    std::size_t at = 0;
    int line = 0;
    while (at < text.size()) {
        std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view row = text.substr(at, end - at);
        at = end + 1;
        ++line;
        const std::size_t first = row.find_first_not_of(" \t\r");
        if (first == std::string_view::npos || row[first] == '#') continue;
        JobEntry entry;
        entry.job.label = fmt::format("job {} ({}:{})", jobs.size(), file, line);
        entry.file = file;
        entry.line = line;
        json j;
        if (std::string e = ParseJsonRow(row, j); !e.empty()) {
            entry.error = fmt::format("{}:{}:{}", file, line, e);
        } else if (std::string e = JobFromJson(j, entry.job); !e.empty()) {
            entry.error = fmt::format("{}:{}: {}", file, line, e);
        } else if (std::string w = TopWithoutImports(entry.job); !w.empty()) {
            entry.warnings.push_back(
                fmt::format("{}:{}:{}: warning: {}", file, line, KeyColumn(row, "top"), w));
        }
        jobs.push_back(std::move(entry));
    }
    return jobs;
}

}  // namespace quadrix::batch
