// The statistics of one render, for people (--stats) and for programs (--stats --json): the
// stage times, the scene's size, what composition did, every counter the engine declared and
// its free-form report. Formatted here, once, for every engine and front end.
#pragma once

#include <string>

#include "quadrix/engines/stats_table.h"
#include "quadrix/frame/frame.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix {

struct StatsInput {
    const RenderContext* context = nullptr;
    const RenderReport* report = nullptr;
    const Frame* frame = nullptr;
    double shadeWriteSeconds = 0;
};

// Multi-line text, as --stats prints it to standard error.
std::string FormatStatsText(const StatsInput& in);
// One engine table (engines/stats_table.h) as aligned text: the title, the header lines, the
// rows (text left-aligned, numbers right-aligned, a real with its decimals and unit), the notes;
// every line indented by two spaces except the title.
std::string FormatStatsTable(const StatsTable& table);

// One JSON object (nlohmann-json): {"engine", "width", "height", "scene": {...}, "seconds":
// {"read", "flatten", "render", "shade_write"}, "composition": {...}, "counters": {...},
// "tables": [{"title", "columns", "rows", "notes"}], "warnings": [...], "notes": [...],
// "report": "..."}.
std::string FormatStatsJson(const StatsInput& in);

}  // namespace quadrix
