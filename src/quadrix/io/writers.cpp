#include "quadrix/io/writers.h"

#include <png.h>

#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace quadrix {

namespace {

std::string Lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string CheckImage(const Image& image) {
    if (image.width <= 0 || image.height <= 0 || (image.channels != 1 && image.channels != 3) ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
        return "internal error: malformed image";
    return {};
}

}  // namespace

bool ImageFormatFromPath(const std::string& path, ImageFormat& format) {
    std::string ext = Lower(std::filesystem::path(path).extension().string());
    if (ext == ".png") format = ImageFormat::kPng;
    else if (ext == ".pgm" || ext == ".ppm" || ext == ".pnm") format = ImageFormat::kPnm;
    else if (ext == ".qxf") format = ImageFormat::kFrameDump;
    else return false;
    return true;
}

std::string WriteFileAtomically(const std::string& path, const std::string& contents) {
    return WriteOutputFile(path, contents);
}

std::string WritePng(OutputFile& f, const Image& image) {
    if (auto e = CheckImage(image); !e.empty()) return e;
    if (!f.ok()) return f.error();
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    if (!png) return "cannot initialise libpng";
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        return "cannot initialise libpng";
    }
    // libpng reports errors by longjmp; nothing with a destructor is created between here and
    // the end of the block.
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return fmt::format("cannot write '{}': PNG encoding failed", f.path());
    }
    png_init_io(png, f.stream());
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8,
                 image.channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // Speed over size (docs/performance.md): libpng's defaults try five row filters and zlib
    // level 6, which cost more than rendering a frame. Rendered images are mostly smooth
    // gradients and flat background, where the Sub filter and a low level lose little (measured:
    // a few percent larger files, several times faster).
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_compression_level(png, 2);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y)
        png_write_row(png, const_cast<png_bytep>(image.At(0, y)));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return {};
}

std::string WritePnm(OutputFile& f, const Image& image) {
    if (auto e = CheckImage(image); !e.empty()) return e;
    if (!f.ok()) return f.error();
    std::fprintf(f.stream(), "P%c\n%d %d\n255\n", image.channels == 3 ? '6' : '5', image.width,
                 image.height);
    std::fwrite(image.pixels.data(), 1, image.pixels.size(), f.stream());
    return {};
}

std::string WriteFrameDump(OutputFile& f, const Frame& frame) {
    if (!f.ok()) return f.error();
    std::fprintf(f.stream(), "QXF1 %d %d\n", frame.width, frame.height);
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            std::size_t i = frame.Index(x, y);
            if (frame.surface[i] == Frame::kNone) continue;
            const Vec3& n = frame.normal[i];
            std::fprintf(f.stream(), "%d %d %.17g %.17g %.17g %.17g %d %d %d\n", x, y,
                         frame.depth[i], n.x, n.y, n.z, frame.surface[i], frame.body[i],
                         frame.solid[i]);
        }
    return {};
}

namespace {
template <typename T>
std::string WriteThrough(const std::string& path, const T& data,
                         std::string (*write)(OutputFile&, const T&)) {
    OutputFile f(path);
    if (auto e = write(f, data); !e.empty()) return e;
    return f.Commit();
}
}  // namespace

std::string WritePng(const std::string& path, const Image& image) {
    if (auto e = CheckImage(image); !e.empty()) return e;
    return WriteThrough<Image>(path, image, WritePng);
}

std::string WritePnm(const std::string& path, const Image& image) {
    if (auto e = CheckImage(image); !e.empty()) return e;
    return WriteThrough<Image>(path, image, WritePnm);
}

std::string WriteFrameDump(const std::string& path, const Frame& frame) {
    return WriteThrough<Frame>(path, frame, WriteFrameDump);
}

std::string ReadFrameDump(const std::string& path, Frame& frame) {
    std::ifstream in(path);
    if (!in) return fmt::format("cannot read '{}'", path);
    std::string magic;
    int w = 0, h = 0;
    if (!(in >> magic >> w >> h) || magic != "QXF1" || w <= 0 || h <= 0 || w > 65536 || h > 65536)
        return fmt::format("'{}' is not a Quadrix frame dump", path);
    frame.Reset(w, h);
    int x, y, s, b, o;
    double z, nx, ny, nz;
    while (in >> x >> y >> z >> nx >> ny >> nz >> s >> b >> o) {
        if (x < 0 || y < 0 || x >= w || y >= h) return fmt::format("'{}': pixel out of range", path);
        std::size_t i = frame.Index(x, y);
        frame.depth[i] = z;
        frame.normal[i] = {nx, ny, nz};
        frame.surface[i] = s;
        frame.body[i] = b;
        frame.solid[i] = o;
    }
    if (!in.eof()) return fmt::format("'{}': malformed pixel line", path);
    return {};
}

}  // namespace quadrix
