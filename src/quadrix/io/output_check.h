// Whether an output file that exists is complete and of the expected size: what a resumed batch
// run (batch/job_renderer.h, docs/batch.md "Resuming") asks before it skips a frame. Quadrix
// writes every output to a temporary file renamed into place when complete (io/output_file.h), so
// its own files are complete; the check catches the others — a copy cut short, a file another
// program was writing when it was stopped, a picture of another size from an earlier version of
// the job — which are then rendered again.
//
// By format (the extension): PNG — the signature, the IHDR size and an IEND chunk at the very
// end; PGM/PPM — the header's size and the exact file length; .qxf — the header's size and a
// last line that ends; OpenEXR — every scan line present and the size (io/exr.h CheckExrFile).
#pragma once

#include <string>

namespace quadrix {

// Empty when `path` is a complete file of width × height pixels, else why not (one phrase).
std::string CheckCompleteOutput(const std::string& path, int width, int height);

}  // namespace quadrix
