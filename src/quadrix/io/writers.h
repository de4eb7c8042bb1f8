// Output files. Every writer goes through the one output writer (io/output_file.h, docs/output.md):
// a temporary file next to the target, renamed into place only when everything succeeded, so a
// failed or interrupted render never leaves a truncated file (DESIGN.md "Reliability rules"), and
// never in place of a device, FIFO, directory or input file.
#pragma once

#include <string>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/io/output_file.h"

namespace quadrix {

enum class ImageFormat { kPng, kPnm, kFrameDump };

// From the file extension: .png, .pgm/.ppm/.pnm, .qxf (frame dump). Unknown → false.
bool ImageFormatFromPath(const std::string& path, ImageFormat& format);

// Returns an empty string on success, else a one-line error message (no file left behind).
std::string WritePng(const std::string& path, const Image& image);
// PGM (gray) or PPM (RGB), binary.
std::string WritePnm(const std::string& path, const Image& image);

// Frame dump for tests and tools: a text header then one line per pixel
//   QXF1 <width> <height>
//   <x> <y> <depth> <nx> <ny> <nz> <surface> <body> <solid>     (covered pixels only, %.17g)
std::string WriteFrameDump(const std::string& path, const Frame& frame);
// Reads a dump back (for tests); returns an error message or empty.
std::string ReadFrameDump(const std::string& path, Frame& frame);

// Writes `contents` atomically (WriteOutputFile: temporary file + rename). Empty string on success.
std::string WriteFileAtomically(const std::string& path, const std::string& contents);

// The same encoders into an OutputFile that the caller commits (CommitAll for a command with
// several outputs). Empty string on success.
std::string WritePng(OutputFile& file, const Image& image);
std::string WritePnm(OutputFile& file, const Image& image);
std::string WriteFrameDump(OutputFile& file, const Frame& frame);

}  // namespace quadrix
