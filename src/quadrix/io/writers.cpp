#include "quadrix/io/writers.h"

#include <fmt/format.h>
#include <sys/uio.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "quadrix/frame/image_limits.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/io/phase_times.h"
#include "quadrix/io/png_encoder.h"
#include "quadrix/math/srgb.h"
#include "quadrix/util/parallel.h"

namespace quadrix {

namespace {

std::string Lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string CheckImage(const Image& image) {
    if (image.width <= 0 || image.height <= 0 || (image.channels != 1 && image.channels != 3) ||
        image.pixels.size() !=
            static_cast<std::size_t>(image.width) * image.height * image.channels)
        return "internal error: malformed image";
    return {};
}

// 8-bit linear → 8-bit sRGB.
const std::array<std::uint8_t, 256>& SrgbTable() {
    static const std::array<std::uint8_t, 256> table = [] {
        std::array<std::uint8_t, 256> t{};
        for (int i = 0; i < 256; ++i)
            t[static_cast<std::size_t>(i)] =
                static_cast<std::uint8_t>(std::lround(SrgbFromLinear(i / 255.0) * 255.0));
        return t;
    }();
    return table;
}

// Linear in [0, 1] quantised to 1/65535 → 8-bit sRGB. The quantisation moves a value by at most
// 1/131070, which is at most 0.026 of an 8-bit sRGB level (the steepest part of the curve, slope
// 12.92, is at black), so the byte is the correctly rounded one except within that distance of a
// rounding boundary. A pow per sample would cost more than shading the picture.
const std::vector<std::uint8_t>& SrgbTable16() {
    static const std::vector<std::uint8_t> table = [] {
        std::vector<std::uint8_t> t(65536);
        for (int i = 0; i < 65536; ++i)
            t[static_cast<std::size_t>(i)] =
                static_cast<std::uint8_t>(std::lround(SrgbFromLinear(i / 65535.0) * 255.0));
        return t;
    }();
    return table;
}

// Two 8-bit linear samples (the first in the low byte) → their two sRGB bytes, low byte first:
// half the lookups of SrgbTable for a row (128 KiB, built on first use).
const std::vector<std::uint16_t>& SrgbPairTable() {
    static const std::vector<std::uint16_t> table = [] {
        const auto& t = SrgbTable();
        std::vector<std::uint16_t> p(65536);
        for (std::size_t i = 0; i < 65536; ++i)
            p[i] = static_cast<std::uint16_t>(t[i & 0xff] | (t[i >> 8] << 8));
        return p;
    }();
    return table;
}

// Whether an image of n samples is encoded through SrgbPairTable: building it (65,536 entries,
// 32 pages) costs as much as the lookups it saves on 2^17 samples; a smaller picture is encoded
// a sample at a time (the same bytes).
bool UsePairs(std::size_t n) { return n >= (std::size_t{1} << 17); }

// n samples at `in` → their sRGB bytes at `out`, by pairs (SrgbPairTable) or one at a time.
void EncodeSrgbRow(const std::uint8_t* in, std::uint8_t* out, std::size_t n, bool byPairs) {
    if (!byPairs) {
        const std::uint8_t* t = SrgbTable().data();
        for (std::size_t k = 0; k < n; ++k) out[k] = t[in[k]];
        return;
    }
    const std::uint16_t* pairs = SrgbPairTable().data();
    std::size_t k = 0;
    for (; k + 2 <= n; k += 2) {
        const std::uint16_t v = pairs[in[k] | (in[k + 1] << 8)];
        out[k] = static_cast<std::uint8_t>(v);
        out[k + 1] = static_cast<std::uint8_t>(v >> 8);
    }
    if (k < n) out[k] = SrgbTable()[in[k]];
}

std::uint8_t EncodeLinear8(const std::uint8_t* table, float v) {
    if (!(v > 0)) return 0;
    if (v >= 1) return 255;
    return table[static_cast<std::size_t>(v * 65535.0f + 0.5f)];
}

bool HasLinear(const Image& image) { return image.linear.size() == image.pixels.size(); }

// Row y as big-endian 16-bit sRGB samples (2·width·channels bytes at `row`).
void EncodeRow16(const Image& image, int y, std::uint8_t* row) {
    const std::size_t n = static_cast<std::size_t>(image.width) * image.channels;
    const std::size_t at = static_cast<std::size_t>(y) * n;
    for (std::size_t k = 0; k < n; ++k) {
        const double v = HasLinear(image) ? image.linear[at + k] : image.pixels[at + k] / 255.0;
        const auto s = static_cast<unsigned>(std::lround(SrgbFromLinear(v) * 65535.0));
        row[2 * k] = static_cast<std::uint8_t>(s >> 8);
        row[2 * k + 1] = static_cast<std::uint8_t>(s & 0xff);
    }
}

}  // namespace

std::vector<std::uint8_t> EncodeSrgb8(const Image& image) {
    std::vector<std::uint8_t> out(image.pixels.size());
    // From the 8-bit pixels, not Image::linear: the devices (uq's png device, the prompt) rebuild
    // the picture from 8-bit spans, and every front end must write the same bytes
    // (tests/front_ends_test.cpp). EncodeSrgb8Precise uses the floats.
    const auto& t = SrgbTable();
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = t[image.pixels[k]];
    return out;
}

const std::uint8_t* Srgb8Table() { return SrgbTable().data(); }

std::vector<std::uint8_t> EncodeSrgb8Precise(const Image& image) {
    std::vector<std::uint8_t> out(image.pixels.size());
    if (HasLinear(image)) {
        const std::uint8_t* table = SrgbTable16().data();
        for (std::size_t k = 0; k < out.size(); ++k) out[k] = EncodeLinear8(table, image.linear[k]);
    } else {
        const auto& t = SrgbTable();
        for (std::size_t k = 0; k < out.size(); ++k) out[k] = t[image.pixels[k]];
    }
    return out;
}

bool ImageFormatFromPath(const std::string& path, ImageFormat& format) {
    std::string ext = Lower(std::filesystem::path(path).extension().string());
    if (ext == ".png")
        format = ImageFormat::kPng;
    else if (ext == ".pgm" || ext == ".ppm" || ext == ".pnm")
        format = ImageFormat::kPnm;
    else if (ext == ".qxf")
        format = ImageFormat::kFrameDump;
    else if (ext == ".exr")
        format = ImageFormat::kExr;
    else
        return false;
    return true;
}

std::string WriteFileAtomically(const std::string& path, const std::string& contents) {
    return WriteOutputFile(path, contents);
}

std::string WritePng(OutputFile& f, const Image& image, const PngOptions& options) {
    if (auto e = CheckImage(image); !e.empty()) return e;
    if (options.bitDepth != 8 && options.bitDepth != 16)
        return fmt::format("internal error: PNG bit depth {} (8 or 16)", options.bitDepth);
    if (!f.ok()) return f.error();
    const bool sixteen = options.srgb && options.bitDepth == 16;
    static const std::string software = std::string("Quadrix ") + QUADRIX_VERSION;
    PngRaster r;
    r.width = image.width;
    r.height = image.height;
    r.channels = image.channels;
    r.bitDepth = sixteen ? 16 : 8;
    r.srgb = options.srgb;
    r.software = software;
    r.filter = sixteen ? 1 : 0;
    // Speed over size (docs/performance.md "Output"): filter None (Sub for 16 bits), zlib level
    // 1, strips in parallel (io/png_encoder.h). The 8-bit sRGB encoding is done row by row as the
    // encoder asks for the rows (no whole-image copy).
    const std::size_t stride = static_cast<std::size_t>(image.width) * image.channels;
    if (sixteen) {
        r.row = [&](int y, std::uint8_t* out) { EncodeRow16(image, y, out); };
    } else if (options.srgb) {
        const bool byPairs = UsePairs(image.pixels.size());
        if (byPairs) SrgbPairTable();  // built before the threads ask for it
        r.row = [&, byPairs](int y, std::uint8_t* out) {
            EncodeSrgbRow(image.At(0, y), out, stride, byPairs);
        };
    } else {
        r.row = [&](int y, std::uint8_t* out) { std::memcpy(out, image.At(0, y), stride); };
    }
    if (auto e = EncodePng(r, f.stream()); !e.empty())
        return fmt::format("cannot write '{}': {}", f.path(), e);
    return {};
}

PnmKind PnmKindFromPath(const std::string& path) {
    const std::string ext = Lower(std::filesystem::path(path).extension().string());
    if (ext == ".ppm") return PnmKind::kColor;
    if (ext == ".pgm") return PnmKind::kGray;
    return PnmKind::kAsImage;
}

Image ConvertChannels(const Image& image, int channels) {
    if (image.channels == channels) return image;
    Image out(image.width, image.height, channels);
    const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
    const bool linear = HasLinear(image);
    if (linear) out.linear.resize(n * channels);
    if (channels == 3) {  // gray -> RGB: the same value in each channel
        for (std::size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
                out.pixels[3 * i + c] = image.pixels[i];
                if (linear) out.linear[3 * i + c] = image.linear[i];
            }
        return out;
    }
    // RGB -> gray: the luminance Y of the linear BT.709/sRGB primaries (IEC 61966-2-1), computed
    // in linear light (Image holds linear intensities), so a gray RGB pixel keeps its value.
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* p = &image.pixels[3 * i];
        const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        out.pixels[i] = static_cast<std::uint8_t>(std::clamp(std::lround(y), 0L, 255L));
        if (linear) {
            const float* l = &image.linear[3 * i];
            out.linear[i] = 0.2126f * l[0] + 0.7152f * l[1] + 0.0722f * l[2];
        }
    }
    return out;
}

std::string WritePnm(OutputFile& f, const Image& image, PnmKind kind) {
    if (auto e = CheckImage(image); !e.empty()) return e;
    if (!f.ok()) return f.error();
    if (kind == PnmKind::kFromPath) kind = PnmKindFromPath(f.path());
    const int channels = kind == PnmKind::kColor ? 3 : kind == PnmKind::kGray ? 1 : image.channels;
    Image converted;
    if (channels != image.channels) converted = ConvertChannels(image, channels);
    const Image& source = channels != image.channels ? converted : image;
    char header[64];
    const int h = std::snprintf(header, sizeof header, "P%c\n%d %d\n255\n",
                                channels == 3 ? '6' : '5', image.width, image.height);
    // The samples encoded in parallel, then the header and the samples in one writev.
    std::vector<std::uint8_t> encoded(source.pixels.size());
    const bool byPairs = UsePairs(encoded.size());
    if (byPairs) SrgbPairTable();
    ParallelFor(tbb::blocked_range<std::size_t>(0, encoded.size(), 1 << 18),
                [&](const tbb::blocked_range<std::size_t>& r) {
                    EncodeSrgbRow(source.pixels.data() + r.begin(), encoded.data() + r.begin(),
                                  r.size(), byPairs);
                });
    MarkPhase("encode");  // io/phase_times.h
    if (std::fflush(f.stream()) != 0) return fmt::format("cannot write '{}'", f.path());
    const int fd = fileno(f.stream());
    iovec v[2] = {{header, static_cast<std::size_t>(h)}, {encoded.data(), encoded.size()}};
    int first = 0;
    while (first < 2) {
        const ssize_t n = ::writev(fd, v + first, 2 - first);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return fmt::format("cannot write '{}': {}", f.path(), std::strerror(errno));
        std::size_t done = static_cast<std::size_t>(n);
        while (first < 2 && done >= v[first].iov_len) done -= v[first++].iov_len;
        if (first < 2) {
            v[first].iov_base = static_cast<char*>(v[first].iov_base) + done;
            v[first].iov_len -= done;
        }
    }
    return {};
}

std::string WriteFrameDump(OutputFile& f, const Frame& frame) {
    if (!f.ok()) return f.error();
    std::fprintf(f.stream(), "QXF1 %d %d\n", frame.width, frame.height);
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            std::size_t i = frame.Index(x, y);
            if (frame.surface[i] == Frame::kNone) continue;
            const Vec3 n = frame.normal[i];
            std::fprintf(f.stream(), "%d %d %.17g %.17g %.17g %.17g %d %d %d\n", x, y,
                         frame.depth[i], n.x, n.y, n.z, frame.surface[i], frame.body[i],
                         frame.Solid(i));
        }
    return {};
}

std::string WritePng(const std::string& path, const Image& image, const PngOptions& options) {
    if (auto e = CheckImage(image); !e.empty()) return e;
    OutputFile f(path);
    if (auto e = WritePng(f, image, options); !e.empty()) return e;
    return f.Commit();
}

std::string WritePnm(const std::string& path, const Image& image, PnmKind kind) {
    if (auto e = CheckImage(image); !e.empty()) return e;
    OutputFile f(path);
    if (auto e = WritePnm(f, image, kind); !e.empty()) return e;
    return f.Commit();
}

std::string WriteFrameDump(const std::string& path, const Frame& frame) {
    OutputFile f(path);
    if (auto e = WriteFrameDump(f, frame); !e.empty()) return e;
    return f.Commit();
}

namespace {

// A cursor over a frame dump's text with its line and column, for positioned errors.
struct DumpCursor {
    const char* p;
    const char* end;
    int line = 1;
    const char* lineStart;
    int Column() const { return static_cast<int>(p - lineStart) + 1; }
    void SkipBlanks() {
        while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
    }
    // The next field on this line as a number; false (p left at the field) when there is none or
    // it is not a number. The text is NUL-terminated (std::string), so strtod stops in it.
    bool Number(double& v) {
        SkipBlanks();
        if (p >= end || *p == '\n') return false;
        char* after = nullptr;
        v = std::strtod(p, &after);
        if (after == p ||
            (after < end && *after != ' ' && *after != '\t' && *after != '\r' && *after != '\n'))
            return false;
        p = after;
        return true;
    }
    bool Integer(long long& v, long long lo, long long hi) {
        double d;
        const char* at = p;
        if (!Number(d) || !(d >= static_cast<double>(lo) && d <= static_cast<double>(hi)) ||
            d != std::floor(d)) {
            p = at;
            SkipBlanks();
            return false;
        }
        v = static_cast<long long>(d);
        return true;
    }
    bool EndOfLine() {
        SkipBlanks();
        if (p >= end) return true;
        if (*p != '\n') return false;
        ++p;
        ++line;
        lineStart = p;
        return true;
    }
};

// The largest body id a dump may name: the Frame keeps a table of one solid per body.
constexpr long long kMaxDumpBodies = 1LL << 26;
constexpr std::int32_t kUnset = Frame::kNone - 1;

}  // namespace

std::string ReadFrameDump(const std::string& path, Frame& frame) {
    // The bounded reader (io/bounded_read.h): /dev/zero or a 300 MB file is an error after at
    // most kMaxInputBytes, never an unbounded allocation.
    std::string text;
    if (auto e = ReadBoundedFile(path, text); !e.empty())
        return fmt::format("error: cannot read '{}': {}", path, e);
    DumpCursor c{text.data(), text.data() + text.size(), 1, text.data()};
    auto at = [&](const std::string& what) {
        return fmt::format("{}:{}:{}: error: {}", path, c.line, c.Column(), what);
    };
    c.SkipBlanks();
    if (text.compare(static_cast<std::size_t>(c.p - text.data()), 5, "QXF1 ") != 0 &&
        text.compare(static_cast<std::size_t>(c.p - text.data()), 5, "QXF1\t") != 0)
        return at(fmt::format("'{}' is not a Quadrix frame dump (no QXF1 header)", path));
    c.p += 4;
    long long w = 0, h = 0;
    c.SkipBlanks();
    const int sizeColumn = c.Column();
    if (!c.Integer(w, 1, kMaxSide * 4LL)) return at("expected the frame's width");
    if (!c.Integer(h, 1, kMaxSide * 4LL)) return at("expected the frame's height");
    // The size is checked against the image limits and the memory budget before the Frame is
    // allocated (a header "QXF1 16384 16384" asked for 12 GB).
    if (auto e = CheckImageSize(w, h); !e.empty())
        return fmt::format("{}:1:{}: error: {}", path, sizeColumn, e);
    if (!c.EndOfLine()) return at("expected the end of the header line");
    frame.Reset(static_cast<int>(w), static_cast<int>(h));
    frame.bodySolid.clear();
    while (c.p < c.end) {
        if (c.EndOfLine()) continue;  // a blank line
        long long x, y, s, b, o;
        double z, nx, ny, nz;
        if (!c.Integer(x, 0, w - 1)) return at("expected a pixel x in 0.." + std::to_string(w - 1));
        if (!c.Integer(y, 0, h - 1)) return at("expected a pixel y in 0.." + std::to_string(h - 1));
        if (!c.Number(z) || !c.Number(nx) || !c.Number(ny) || !c.Number(nz))
            return at("expected a number (depth, then the normal's x, y, z)");
        constexpr long long kMin = std::numeric_limits<std::int32_t>::min(),
                            kMax = std::numeric_limits<std::int32_t>::max();
        if (!c.Integer(s, kMin, kMax)) return at("expected an id (surface, body, solid)");
        c.SkipBlanks();
        const int bodyColumn = c.Column();
        auto atBody = [&](const std::string& what) {
            return fmt::format("{}:{}:{}: error: {}", path, c.line, bodyColumn, what);
        };
        if (!c.Integer(b, kMin, kMax) || !c.Integer(o, kMin, kMax))
            return at("expected an id (surface, body, solid)");
        // The Frame keeps one solid per body (frame.h): a body's pixels must agree on it.
        if (b < Frame::kNone || b >= kMaxDumpBodies || o < Frame::kNone)
            return atBody(
                fmt::format("body {} or solid {} is not an id (-1 for none; bodies below {})", b, o,
                            kMaxDumpBodies));
        if (b == Frame::kNone && o != Frame::kNone)
            return atBody(fmt::format(
                "solid {} without a body (the Frame finds a pixel's solid by its body)", o));
        if (b != Frame::kNone) {
            const auto bi = static_cast<std::size_t>(b);
            if (frame.bodySolid.size() <= bi) frame.bodySolid.resize(bi + 1, kUnset);
            if (frame.bodySolid[bi] == kUnset)
                frame.bodySolid[bi] = static_cast<std::int32_t>(o);
            else if (frame.bodySolid[bi] != o)
                return atBody(fmt::format("body {} is in solid {} here but in solid {} earlier", b,
                                          o, frame.bodySolid[bi]));
        }
        if (!c.EndOfLine()) return at("expected the end of the pixel line");
        const std::size_t i = frame.Index(static_cast<int>(x), static_cast<int>(y));
        frame.depth[i] = static_cast<float>(z);
        frame.normal[i] = Vec3{nx, ny, nz};
        frame.surface[i] = static_cast<std::int32_t>(s);
        frame.body[i] = static_cast<std::int32_t>(b);
    }
    for (std::int32_t& solid : frame.bodySolid)
        if (solid == kUnset) solid = Frame::kNone;
    return {};
}

}  // namespace quadrix
