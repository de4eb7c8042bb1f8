// View lists (`quadrix render --views FILE`, a job's "views"): one frame per view, in order.
//
// The file is either
//   - UniQuadrix `view` statements (docs/language.md §3.8): every view the file defines, in
//     order of definition (other statements are read too but not used); or
//   - an rt view script (FORMAT.md §9.4: viewsize, eye_pt, viewrot/orientation, ae), one view,
//     or several framed by rt's animation commands `start N;` … `end;` (as rt reads them from a
//     matrix script), each frame one view.
// The kind is told by the first word of the file: rt's commands (viewsize, eye_pt, viewrot,
// orientation, ae, start) make an rt script. Errors name file:line:column.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/batch/job.h"
#include "quadrix/scene/diagnostics.h"

namespace quadrix::batch {

// The views of `text` (named `file` in diagnostics). nullopt with errors in diags; a file with
// no view at all is an error.
std::optional<std::vector<ListedView>> ParseViewList(std::string_view text, const std::string& file,
                                                     Diagnostics& diags);
// Reads the file (bounded reader) and parses it.
std::optional<std::vector<ListedView>> ReadViewList(const std::string& path, Diagnostics& diags);

}  // namespace quadrix::batch
