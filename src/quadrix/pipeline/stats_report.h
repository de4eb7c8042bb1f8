// The statistics of one render, for people (--stats) and for programs (--stats --json): the
// stage times, the scene's size, what composition did, every counter the engine declared and
// its free-form report. Formatted here, once, for every engine and front end.
#pragma once

#include <string>

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
// One JSON object (nlohmann-json): {"engine", "width", "height", "scene": {...}, "seconds":
// {"read", "flatten", "render", "shade_write"}, "composition": {...}, "counters": {...},
// "warnings": [...], "notes": [...], "report": "..."}.
std::string FormatStatsJson(const StatsInput& in);

}  // namespace quadrix
