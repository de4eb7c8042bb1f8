// The output stage of the render context: the picture (PNG, PGM/PPM, or a .qxf Frame dump by
// extension) and an optional extra Frame dump, checked together before anything is written so
// that a bad second output never follows a written first one.
#pragma once

#include <string>

#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/io/writers.h"

namespace quadrix {

struct OutputRequest {
    std::string image;      // the main output; its extension picks the format
    std::string dumpFrame;  // optional .qxf dump of the Frame (--dump-frame)
};

// Checks the request before any work: a known format, two different paths. Error or empty.
std::string CheckOutputs(const OutputRequest& request);
// Whether the main output needs a shaded Image (a .qxf output does not).
bool NeedsImage(const OutputRequest& request);
// Writes every output (atomically, each). Error message or empty.
std::string WriteOutputs(const OutputRequest& request, const Frame& frame, const Image* image);

}  // namespace quadrix
