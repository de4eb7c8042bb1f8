// Job files of `quadrix batch` (docs/batch.md "Job files"): one JSON object per line, one job
// each. Blank lines and lines whose first non-blank character is '#' are skipped.
//
//   {"inputs": ["part.uq"], "output": "part.png", "size": "640x480", "engine": "raycast",
//    "view": "iso" | "az": 35, "el": 25, "viewsize": 120, "rt_view": "v.rt",
//    "frames": 36, "frame_range": "0:9", "turntable": 36, "views": "views.uq",
//    "dump_frame": "part.qxf", "fast": false, "phong": false, "shadows": false, "png16": false,
//    "engine_options": {"key": "value"}, "top": ["all.g"], "strict": false,
//    "allow_missing": false}
//
// "inputs" (a list, or "input": one path) and "output" are required. Paths are taken as written
// (relative ones from the working directory). An unknown key, a value of the wrong type, or a
// line that is not a JSON object makes that job invalid (JobEntry::error, "FILE:LINE: ...";
// a JSON syntax error "FILE:LINE:COLUMN: invalid JSON: ...", a key given twice likewise);
// the other jobs still run.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "quadrix/batch/run.h"

namespace quadrix::batch {

std::vector<JobEntry> ParseJobFile(std::string_view text, const std::string& file);

// "a:b" (inclusive; either side may be left out: "5:" or ":9"), or one number "a". Error or
// empty; last = -1 when open-ended.
std::string ParseFrameRange(const std::string& text, int& first, int& last);

}  // namespace quadrix::batch
