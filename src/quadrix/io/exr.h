// OpenEXR output (issue 21, "output formats people use downstream"): the shaded image and the
// Frame's per-pixel layers (arbitrary output variables, AOVs) in one scan-line file, so that a
// compositor or a dataset pipeline gets exact depth, normals and ids next to the picture.
//
// Channels (all at the image's resolution, rows top to bottom, ZIP compression):
//   R, G, B      FLOAT  the shaded image in LINEAR light (Image::linear when present, else the
//                       8-bit linear pixels / 255); a gray image repeats its value in R, G, B
//   A            FLOAT  coverage: 1 where a surface was drawn, 0 on the background
//   Z            FLOAT  Frame::depth, device z (z grows away from the viewer, DESIGN.md "Device
//                       space"); +inf on the background
//   N.x N.y N.z  FLOAT  Frame::normal, world-space unit normal facing the viewer; 0 on the
//                       background
//   id.surface, id.body, id.solid
//                UINT   Frame::surface/body/solid + 1 (FlatScene indices), 0 = background, the
//                       usual convention of object-id passes
// Header attributes: "software" (Quadrix <version>) and the chromaticities of sRGB/BT.709.
//
// Written by the module quadrix-exr.so (io/exr_module.h), built when OpenEXR is found
// (QUADRIX_HAVE_OPENEXR) and loaded on first use; without it WriteExr returns a clear error.
#pragma once

#include <string>

#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/io/output_file.h"

namespace quadrix {

// True when this build can write OpenEXR files (loads the module on first call).
bool HaveOpenExr();
// Why it cannot (a one-line message), or empty when it can.
std::string OpenExrUnavailable();
// Writes `image` (may be null: then R, G, B, A are left out) and the layers of `frame` into
// `file` (committed by the caller). Empty string on success, else a one-line message.
std::string WriteExr(OutputFile& file, const Frame& frame, const Image* image);
std::string WriteExr(const std::string& path, const Frame& frame, const Image* image);
// Whether `path` is a complete OpenEXR file (every scan line present, OpenEXR's isComplete) of
// width × height pixels: empty, else why not. Without OpenEXR only the magic number is checked.
std::string CheckExrFile(const std::string& path, int width, int height);

}  // namespace quadrix
