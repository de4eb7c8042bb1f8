// The parallel PNG encoder (png_encoder.h) read back by libpng: images of many strips (the zlib
// stream is the strips' deflate streams concatenated with one Adler-32), every colour type and
// bit depth, sizes of one row and one column, against the samples that were given.
#include "quadrix/io/png_encoder.h"

#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

namespace quadrix {
namespace {

struct Decoded {
    int width = 0, height = 0, channels = 0, depth = 0;
    bool srgb = false;
    std::string software;
    std::vector<std::uint8_t> samples;
};

Decoded ReadBack(const std::string& path) {
    Decoded d;
    std::FILE* f = std::fopen(path.c_str(), "rb");
    EXPECT_TRUE(f);
    if (!f) return d;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {  // libpng found the file malformed
        ADD_FAILURE() << "libpng could not read " << path;
        png_destroy_read_struct(&png, &info, nullptr);
        std::fclose(f);
        return Decoded{};
    }
    png_init_io(png, f);
    png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
    d.width = static_cast<int>(png_get_image_width(png, info));
    d.height = static_cast<int>(png_get_image_height(png, info));
    d.channels = png_get_channels(png, info);
    d.depth = png_get_bit_depth(png, info);
    int intent = 0;
    d.srgb = png_get_sRGB(png, info, &intent) != 0;
    png_textp text = nullptr;
    int n = 0;
    png_get_text(png, info, &text, &n);
    if (n == 1) d.software = text[0].text;
    png_bytepp rows = png_get_rows(png, info);
    const std::size_t rowBytes = png_get_rowbytes(png, info);
    for (int y = 0; y < d.height; ++y)
        d.samples.insert(d.samples.end(), rows[y], rows[y] + rowBytes);
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    return d;
}

TEST(PngEncoder, ManyStripsReadBackExactly) {
    std::mt19937 rng(7);
    const std::string path =
        ::testing::TempDir() + "quadrix_png_encoder_" + std::to_string(::getpid()) + ".png";
    struct Case {
        int w, h, channels, depth;
    };
    // 1000×300 RGB8: 3,001 bytes a row, 43 rows a strip, 7 strips; 16-bit: 14 strips. Under
    // 64 KiB of rows, one stream with a window of 2^9 (1×1) to 2^15 bytes (150×145 RGB8: 65,395
    // bytes of rows, more than its window) and a header that says so (libpng checks it).
    for (const Case c :
         {Case{1000, 300, 3, 8}, Case{1000, 300, 3, 16}, Case{777, 401, 1, 8}, Case{1, 1, 1, 8},
          Case{1, 5000, 3, 8}, Case{70000, 1, 1, 16}, Case{64, 64, 3, 8}, Case{150, 145, 3, 8},
          Case{20, 20, 3, 16}, Case{300, 7, 1, 8}, Case{151, 145, 3, 8}}) {
        const std::size_t rowBytes = static_cast<std::size_t>(c.w) * c.channels * c.depth / 8;
        std::vector<std::uint8_t> want(rowBytes * static_cast<std::size_t>(c.h));
        // Runs (compressible) and noise (not), so that strips end in both kinds of data.
        for (std::size_t k = 0; k < want.size(); ++k)
            want[k] = (k / 997) % 3 == 0 ? static_cast<std::uint8_t>(rng())
                                         : static_cast<std::uint8_t>(k / 5000);
        PngRaster r;
        r.width = c.w;
        r.height = c.h;
        r.channels = c.channels;
        r.bitDepth = c.depth;
        r.srgb = c.channels == 3;
        r.software = "Quadrix test";
        r.filter = c.depth == 16 ? 1 : 0;
        r.row = [&](int y, std::uint8_t* out) {
            std::copy_n(want.data() + static_cast<std::size_t>(y) * rowBytes, rowBytes, out);
        };
        std::FILE* f = std::fopen(path.c_str(), "wb");
        ASSERT_TRUE(f);
        EXPECT_EQ(EncodePng(r, f), "");
        std::fclose(f);
        const Decoded d = ReadBack(path);
        SCOPED_TRACE(std::to_string(c.w) + "x" + std::to_string(c.h));
        EXPECT_EQ(d.width, c.w);
        EXPECT_EQ(d.height, c.h);
        EXPECT_EQ(d.channels, c.channels);
        EXPECT_EQ(d.depth, c.depth);
        EXPECT_EQ(d.srgb, r.srgb);
        EXPECT_EQ(d.software, "Quadrix test");
        EXPECT_TRUE(d.samples == want);
    }
    std::remove(path.c_str());
}

TEST(PngEncoder, RefusesMalformedRasters) {
    PngRaster r;
    r.width = 4;
    r.height = 4;
    r.bitDepth = 12;
    r.row = [](int, std::uint8_t*) {};
    EXPECT_NE(EncodePng(r, stdout), "");
}

}  // namespace
}  // namespace quadrix
