// Issue 19's drawing target, measured (never asserted): the machined part's four-view sheet
// (`quadrix draw examples/machined_part.uq -o part.svg --views front,top,right,iso`) as a whole
// process, beside a plain raycast render of the same part (`quadrix render … --size 1000x1000
// --aa off --no-shadows`, one picture the size of one of the sheet's views; also with the
// scene's shadows) in the same run, for a ratio; and
// in process, per view, the drawer's phases (candidate curves, trimming, visibility, strokes)
// beside the raycast frame of the same flattened view.
#pragma once

#include <string>

namespace quadrix::bench {

// A markdown section. `sourceDir` holds examples/, `quadrixBin` is the binary timed as a whole
// process, `outDir` receives the sheet and the render; medians of `reps` runs.
std::string DrawSheetTable(const std::string& sourceDir, const std::string& quadrixBin,
                           const std::string& outDir, int reps);

}  // namespace quadrix::bench
