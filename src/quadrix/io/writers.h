// Output files. Every writer goes through the one output writer (io/output_file.h, docs/output.md):
// a temporary file next to the target, renamed into place only when everything succeeded, so a
// failed or interrupted render never leaves a truncated file (DESIGN.md "Reliability rules"), and
// never in place of a device, FIFO, directory or input file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/io/output_file.h"

namespace quadrix {

enum class ImageFormat { kPng, kPnm, kFrameDump, kExr };

// From the file extension: .png, .pgm/.ppm/.pnm, .qxf (frame dump), .exr (OpenEXR, io/exr.h).
// Unknown → false.
bool ImageFormatFromPath(const std::string& path, ImageFormat& format);

// Colour encoding (issue 17): images are shaded in linear light (io/image.h); PNG and PNM files
// are written sRGB-encoded (math/srgb.h). 8-bit output is encoded from the 8-bit linear pixels,
// so that every front end (render, and uq's devices, which rebuild the picture from 8-bit spans)
// writes the same bytes; this loses levels in the darks (linear 1/255 is sRGB 13/255). 16-bit
// PNG is encoded from Image::linear when the shader filled it (no banding). PNG files carry the
// sRGB chunk (perceptual intent) with the gAMA (1/2.2) and cHRM (BT.709 primaries, D65) chunks
// libpng would write with it for readers that do not know sRGB (io/png_encoder.h writes the file),
// and a Software text chunk "Quadrix <version>".
struct PngOptions {
    int bitDepth = 8;  // 8 or 16 bits per channel
    bool srgb = true;  // false: the pixels as they are (8-bit), no colour chunks (bilevel output)
};

// Returns an empty string on success, else a one-line error message (no file left behind).
std::string WritePng(const std::string& path, const Image& image, const PngOptions& options = {});
// Which Netpbm file: by the path's extension (.ppm colour P6, .pgm gray P5, anything else -
// .pnm, standard output - as the image is), or forced. A gray image written as .ppm repeats its
// value in the three channels; a colour image written as .pgm is reduced to its luminance
// (BT.709 weights in linear light).
enum class PnmKind { kFromPath, kAsImage, kGray, kColor };
PnmKind PnmKindFromPath(const std::string& path);
// The image with 1 or 3 channels, converted as above.
Image ConvertChannels(const Image& image, int channels);
// PGM (gray, P5) or PPM (RGB, P6), binary, 8-bit sRGB-encoded (Netpbm's samples are
// gamma-encoded).
std::string WritePnm(const std::string& path, const Image& image,
                     PnmKind kind = PnmKind::kFromPath);

// The sRGB-encoded samples of an image, 8 bits: from the 8-bit pixels (what the writers use), or
// from Image::linear when present (for viewers that want the smoother darks).
std::vector<std::uint8_t> EncodeSrgb8(const Image& image);
std::vector<std::uint8_t> EncodeSrgb8Precise(const Image& image);
// The table EncodeSrgb8 applies to each 8-bit linear sample (for encoders fused with other work).
const std::uint8_t* Srgb8Table();

// Frame dump for tests and tools: a text header then one line per pixel
//   QXF1 <width> <height>
//   <x> <y> <depth> <nx> <ny> <nz> <surface> <body> <solid>     (covered pixels only, %.17g)
// The values are the Frame's (frame.h): depth a float, the normal decoded from its packing, the
// solid the body's. Reading a dump packs the normal again and takes each body's solid from its
// pixels (pixels of one body naming two solids are an error).
std::string WriteFrameDump(const std::string& path, const Frame& frame);
// Reads a dump back (for tests); returns an error message or empty.
std::string ReadFrameDump(const std::string& path, Frame& frame);

// Writes `contents` atomically (WriteOutputFile: temporary file + rename). Empty string on success.
std::string WriteFileAtomically(const std::string& path, const std::string& contents);

// The same encoders into an OutputFile that the caller commits (CommitAll for a command with
// several outputs). Empty string on success.
std::string WritePng(OutputFile& file, const Image& image, const PngOptions& options = {});
std::string WritePnm(OutputFile& file, const Image& image, PnmKind kind = PnmKind::kFromPath);
std::string WriteFrameDump(OutputFile& file, const Frame& frame);

}  // namespace quadrix
