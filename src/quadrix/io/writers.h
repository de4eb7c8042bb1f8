// Output files. Every writer is atomic: it writes a temporary file next to the target and renames
// it into place only when everything succeeded, so a failed or interrupted render never leaves a
// truncated file (DESIGN.md "Reliability rules").
#pragma once

#include <string>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"

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

// Writes `contents` atomically (temporary file + rename). Empty string on success.
std::string WriteFileAtomically(const std::string& path, const std::string& contents);

}  // namespace quadrix
