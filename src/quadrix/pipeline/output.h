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
    std::string image;      // the main output; its extension picks the format; "-" = stdout
    std::string dumpFrame;  // optional .qxf dump of the Frame (--dump-frame)
    // Optional OpenEXR file beside the main output: the picture in linear light and the Frame's
    // depth, normal and id layers (io/exr.h; a batch job's "exr").
    std::string exr;
    PngOptions png;  // bit depth of a PNG main output (--png16)
    // --format: png, ppm, pgm, exr or qxf; overrides the extension. Empty: the extension, and
    // png for standard output.
    std::string format;
};

// The format of the main output (the request's format, else the extension, else png for "-"),
// with the Netpbm kind for ppm/pgm. False when it cannot be told.
bool OutputFormat(const OutputRequest& request, ImageFormat& format, PnmKind& pnm);

// Checks the request before any work: a known format, two different paths. Error or empty.
std::string CheckOutputs(const OutputRequest& request);
// Whether the outputs need a shaded Image (a .qxf output alone does not).
bool NeedsImage(const OutputRequest& request);
// Whether the outputs keep the unquantised shading (ShadeOptions::linear): a 16-bit PNG or an
// OpenEXR picture; 8-bit files are encoded from the 8-bit pixels.
bool NeedsLinear(const OutputRequest& request);
// Whether writing the outputs reads the Frame: a .qxf dump or an OpenEXR file (its depth, normal
// and id layers). A picture alone is written from the Image, and its caller may free the Frame
// first (its memory then serves the encoder: frame.h AllocateFrameBytes).
bool NeedsFrame(const OutputRequest& request);
// Writes every output (atomically, each). Error message or empty.
std::string WriteOutputs(const OutputRequest& request, const Frame& frame, const Image* image);

}  // namespace quadrix
