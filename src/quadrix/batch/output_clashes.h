// Outputs that two jobs of one batch would both write (docs/batch.md "Job files"): a job file in
// which two jobs, or two outputs of one job, name the same file for some frame is refused before
// anything is rendered — otherwise the later frame silently replaces the earlier one, and a
// resumed run takes the one for the other as done.
//
// Every frame of every valid job (entry.error empty) is expanded to its output paths (FramePath,
// job.h) for the image, the Frame dump and the EXR file, and the paths are compared as files: the
// directory made absolute and canonical (links followed where it exists, io/output_file.h's
// rule), the file name as written. Standard output ("-") is not a file and never clashes.
#pragma once

#include <string>
#include <vector>

#include "quadrix/batch/run.h"

namespace quadrix::batch {

// One message per pair of outputs that name the same file, in job order:
//   FILE:LINE: "output", frame 3, writes 'PATH', which job 0 (FILE:LINE), "output", frame 3, writes
//   too: ...
// At most `limit` messages, then one "... and N more" line. Empty when no two outputs clash.
std::vector<std::string> OutputClashes(const std::vector<JobEntry>& jobs, std::size_t limit = 20);

}  // namespace quadrix::batch
