// The PNG encoder of the writers (io/writers.h): a PNG file (ISO/IEC 15948, W3C PNG 2nd ed.)
// written without libpng, so that the image data is compressed in parallel.
//
// File layout: signature, IHDR, then (sRGB images) gAMA 45455, sRGB (perceptual), cHRM (BT.709
// primaries, D65 white: the values libpng's png_set_sRGB_gAMA_and_cHRM writes), a tEXt chunk,
// one IDAT chunk per strip, IEND. Every chunk carries its CRC-32 (of type and data).
//
// Image data: each row is its filter type (None or Sub, PngRaster::filter) and its samples; the
// filtered rows form ONE zlib stream (RFC 1950: header 78 01, raw deflate, Adler-32 of all rows),
// as PNG requires. The rows are cut into strips of about 128 KiB and each strip is deflated on its
// own (zlib level 1, no preset dictionary) in parallel: a strip other than the last ends with a
// sync flush (an empty stored block, so the next strip's deflate blocks start on a byte boundary)
// and the last with the final block. A strip's matches never reach back into the previous strip, so
// the concatenation is one valid deflate stream; its Adler-32 is the strips' combined in order
// (adler32_combine). Level, filter and strip size were chosen by measurement
// (docs/performance.md "Output"): None + level 1 gives files within a few percent of the old
// Sub + level 2 ones, and strips cost < 0.5 % of size. A picture of under 64 KiB of filtered
// rows is one strip deflated with a window of its own size (2^9 to 2^15 bytes, said by the zlib
// header) and a hash table as large, on the heap: the same pixels, without first touching the
// thread's 2 MiB arena and 32 KiB-window state for a few KiB of rows (png_encoder.cpp).
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>

namespace quadrix {

struct PngRaster {
    int width = 0, height = 0;
    int channels = 1;      // 1 gray, 3 RGB
    int bitDepth = 8;      // 8 or 16 (samples big-endian)
    bool srgb = true;      // write the gAMA, sRGB and cHRM chunks
    std::string software;  // the tEXt "Software" value; empty: no text chunk
    // Row filter: 0 None, 1 Sub (each byte minus the one a pixel to its left). None suits 8-bit
    // renderings (flat runs); Sub 16-bit ones, whose smooth gradients None leaves 1.5–2.6×
    // larger (measured on the examples and benchmark scenes, docs/performance.md "Output").
    int filter = 0;
    // Writes the samples of row y (width·channels·bitDepth/8 bytes) to `out`. Called from
    // several threads at once, for different rows.
    std::function<void(int y, std::uint8_t* out)> row;
};

// Writes the whole file to `out`. Returns an empty string, or why it failed (a write error).
std::string EncodePng(const PngRaster& raster, std::FILE* out);

}  // namespace quadrix
