// The device table ("Manager maintains a hash table of such structures", seed 001 §6.5.2), device
// creation from a user's spec, and the span output of §6.5.1.
#include "quadrix/device/device.h"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "quadrix/device/device_internal.h"
#include "quadrix/frame/image_limits.h"
#include "quadrix/io/output_file.h"

namespace quadrix::device {

namespace {

std::string Lower(std::string_view s) {
    std::string r(s);
    for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return r;
}

// Columns and rows of the terminal behind `f`, or of $COLUMNS/$LINES; 0 when unknown.
void TerminalSize(std::FILE* f, int& columns, int& rows) {
    columns = rows = 0;
    winsize ws{};
    if (f && isatty(fileno(f)) && ioctl(fileno(f), TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) {
        columns = ws.ws_col;
        rows = ws.ws_row;
        return;
    }
    if (const char* c = std::getenv("COLUMNS")) columns = std::atoi(c);
    if (const char* l = std::getenv("LINES")) rows = std::atoi(l);
}

// The built-in characteristics of each device before the user's settings.
DeviceInfo DefaultInfo(const std::string& name, std::FILE* screen) {
    DeviceInfo info;
    info.name = name;
    if (name == "ascii") {
        // A listing has a line per span: keep the default picture small enough to read.
        info.width = info.height = 128;
        info.path = "uq.out";  // seed 001 §2.2: "Human-readable file uq.out"
    } else if (name == "png") {
        info.path = "uq.png";
    } else if (name == "pnm") {
        info.path = "uq.pnm";
    } else if (name == "pgm") {
        info.color = false;
        info.path = "uq.pgm";
    } else if (name == "ppm") {
        info.path = "uq.ppm";
    } else if (name == "halftone" || name == "stipple") {
        // The Varian plotter of seed 001 §7.1 has 200 dots per inch; 4 × 4 inches by default.
        info.dotsPerInch = 200;
        info.width = info.height = 800;
        info.levels = 65;  // an 8 × 8 pattern sets 0..64 dots
        info.color = false;
        info.path = "uq.pbm";
    } else if (name == "terminal") {
        // One character cell shows two pixels (upper and lower half block), and cells are about
        // twice as tall as wide, so the pixels are close to square.
        info.hard = false;
        info.path = "-";
        info.dotsPerInch = 10;  // about ten columns an inch on a screen
        int columns = 0, rows = 0;
        TerminalSize(screen ? screen : stdout, columns, rows);
        if (columns <= 1) columns = 81;
        info.width = std::clamp(columns - 1, 8, 120);
        info.height = info.width;
        if (rows > 4) info.height = std::min(info.height, 2 * (rows - 3));
    }
    return info;
}

}  // namespace

const std::vector<DeviceName>& DeviceNames() {
    static const std::vector<DeviceName> kNames = {
        {"ascii", {"file", "a"}, "human-readable span listing (default file uq.out)"},
        {"png", {}, "8-bit PNG, gray or RGB (uq.png)"},
        {"pnm", {}, "binary PGM for gray pictures, PPM for color ones (uq.pnm)"},
        {"pgm", {}, "binary PGM, gray (uq.pgm)"},
        {"ppm", {}, "binary PPM, RGB (uq.ppm)"},
        {"halftone", {"dither", "pbm"}, "bilevel 8x8 ordered dither; .pbm or .png (uq.pbm)"},
        {"stipple",
         {"varian", "v", "va", "var", "versatek", "w", "vp", "ver"},
         "bilevel clustered-dot stipple, as the Varian and Versatek drivers; .pbm or .png"},
        {"terminal", {"term", "tty"}, "preview on the terminal: ANSI colors, half blocks"},
    };
    return kNames;
}

std::string CanonicalDeviceName(std::string_view name) {
    std::string n = Lower(name);
    for (const DeviceName& d : DeviceNames()) {
        if (d.name == n) return d.name;
        for (const std::string& s : d.synonyms)
            if (s == n) return d.name;
    }
    return {};
}

std::string KnownDevicesText() {
    std::string s;
    for (const DeviceName& d : DeviceNames()) s += (s.empty() ? "" : ", ") + d.name;
    return s;
}

std::uint8_t Device::Quantize(std::uint8_t v) const {
    int levels = std::clamp(info_.levels, 2, 256);
    if (levels == 256) return v;
    long q = std::lround(v * (levels - 1) / 255.0);
    return static_cast<std::uint8_t>(std::lround(q * 255.0 / (levels - 1)));
}

std::unique_ptr<Device> MakeDevice(std::string_view spec, const DeviceSettings& settings,
                                   std::string& error) {
    std::string_view nameText = spec, pathText;
    if (auto colon = spec.find(':'); colon != std::string_view::npos) {
        nameText = spec.substr(0, colon);
        pathText = spec.substr(colon + 1);
        if (pathText.empty()) {
            error = fmt::format("device '{}': empty file name after ':'", spec);
            return nullptr;
        }
    }
    std::string name = CanonicalDeviceName(nameText);
    if (name.empty()) {
        error = fmt::format("unknown device '{}' (known: {})", nameText, KnownDevicesText());
        return nullptr;
    }
    DeviceInfo info = DefaultInfo(name, settings.screen);
    if (!pathText.empty())
        info.path = std::string(pathText);
    else if (!settings.path.empty())
        info.path = settings.path;
    // The output is checked before anything is drawn (io/output_file.h): never a device node,
    // FIFO, directory or input file, even though the write itself checks again.
    if (!info.path.empty() && info.path != "-") {
        if (auto e = CheckOutputPath(info.path); !e.empty()) {
            error = e;
            return nullptr;
        }
    }

    // Sizes in inches, as the paper's -sx/-sy and xsize/ysize.
    auto pixels = [&](double inches) { return std::llround(inches * info.dotsPerInch); };
    long long w = info.width, h = info.height;
    if (settings.xInches != 0) w = pixels(settings.xInches);
    if (settings.yInches != 0) h = pixels(settings.yInches);
    if (!std::isfinite(settings.xInches) || !std::isfinite(settings.yInches) ||
        settings.xInches < 0 || settings.yInches < 0) {
        error = "drawing size must be a positive number of inches";
        return nullptr;
    }
    if (auto e = CheckImageSize(w, h); !e.empty()) {
        error = fmt::format("device {}: {} ({} dots per inch)", name, e, info.dotsPerInch);
        return nullptr;
    }
    info.width = static_cast<int>(w);
    info.height = static_cast<int>(h);
    if (settings.deltaMax < 0) {
        error = fmt::format("shading interval {} is negative", settings.deltaMax);
        return nullptr;
    }
    if (settings.deltaMax > 0) info.deltaMax = settings.deltaMax;

    const std::string ext = internal::Extension(info.path);
    auto wrongExtension = [&](const char* allowed) {
        error = fmt::format("device {} writes {}; '{}' has another extension", name, allowed,
                            info.path);
        return nullptr;
    };
    if (name == "ascii") return internal::MakeAsciiDevice(std::move(info));
    if (name == "png") {
        if (ext != ".png") return wrongExtension(".png files");
        return internal::MakePngDevice(std::move(info));
    }
    if (name == "pnm" || name == "pgm" || name == "ppm") {
        if (ext != ".pnm" && ext != ".pgm" && ext != ".ppm")
            return wrongExtension(".pgm, .ppm or .pnm files");
        return internal::MakePnmDevice(std::move(info), name == "ppm");
    }
    if (name == "halftone" || name == "stipple") {
        if (ext != ".pbm" && ext != ".png") return wrongExtension(".pbm or .png files");
        return internal::MakeHalftoneDevice(
            std::move(info), name == "halftone" ? Pattern::kBayer : Pattern::kCluster);
    }
    return internal::MakeTerminalDevice(std::move(info), settings.screen);
}

namespace {

// Merges consecutive equal colors of one row into one Span call (§6.5.1: "the device driver is
// called only when intensity changes").
class SpanEmitter {
  public:
    SpanEmitter(Device& device, DrawStats& stats) : device_(device), stats_(stats) {}
    void Add(int row, int x0, int x1, Rgb c) {
        if (open_ && row == row_ && x0 == x1_ && c == color_) {
            x1_ = x1;
            return;
        }
        Flush();
        open_ = true;
        row_ = row;
        x0_ = x0;
        x1_ = x1;
        color_ = c;
    }
    void Flush() {
        if (!open_) return;
        device_.Span(row_, x0_, x1_, color_);
        ++stats_.spans;
        open_ = false;
    }

  private:
    Device& device_;
    DrawStats& stats_;
    bool open_ = false;
    int row_ = 0, x0_ = 0, x1_ = 0;
    Rgb color_;
};

Rgb PixelColor(const Image& image, int x, int y) {
    const std::uint8_t* p = image.At(x, y);
    return image.channels == 3 ? Rgb{p[0], p[1], p[2]} : Rgb{p[0], p[0], p[0]};
}

// Integer average of the two ends of a Δ interval, per channel, "in C integer arithmetic".
Rgb Average(Rgb a, Rgb b) {
    return {static_cast<std::uint8_t>((a.r + b.r) / 2), static_cast<std::uint8_t>((a.g + b.g) / 2),
            static_cast<std::uint8_t>((a.b + b.b) / 2)};
}

}  // namespace

DrawStats DrawImage(Device& device, const Image& image, const Frame* frame, int deltaMax) {
    DrawStats stats;
    SpanEmitter out(device, stats);
    const bool useFrame = frame && frame->width == image.width && frame->height == image.height;
    auto sameRun = [&](int x, int y, int x2) {
        if (useFrame) {
            std::size_t a = frame->Index(x, y), b = frame->Index(x2, y);
            return frame->surface[a] == frame->surface[b] && frame->body[a] == frame->body[b];
        }
        return PixelColor(image, x, y) == PixelColor(image, x2, y);
    };
    for (int y = 0; y < image.height; ++y) {
        int x = 0;
        while (x < image.width) {
            int xr = x;
            while (xr + 1 < image.width && sameRun(x, y, xr + 1)) ++xr;
            // (6.9): Δ = min((xr − xl)/k + 1, Δmax), in integer arithmetic.
            int delta = deltaMax <= 1 ? 1 : std::min((xr - x) / kShadingK + 1, deltaMax);
            if (delta == 1) {
                for (int i = x; i <= xr; ++i) out.Add(y, i, i + 1, PixelColor(image, i, y));
                stats.evaluations += xr - x + 1;
            } else {
                for (int s = x; s < xr;) {
                    int e = std::min(s + delta, xr);
                    out.Add(y, s, e, Average(PixelColor(image, s, y), PixelColor(image, e, y)));
                    ++stats.evaluations;
                    s = e;
                }
                out.Add(y, xr, xr + 1, PixelColor(image, xr, y));
                ++stats.evaluations;
            }
            x = xr + 1;
        }
        out.Flush();
    }
    return stats;
}

namespace internal {

std::uint8_t Luminance(Rgb c) {
    // Rec. 709 luma weights applied to the linear intensities the shader produces.
    double y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    return static_cast<std::uint8_t>(std::clamp(std::lround(y), 0L, 255L));
}

std::string Extension(const std::string& path) {
    return Lower(std::filesystem::path(path).extension().string());
}

std::string BufferedDevice::Open(bool color) {
    image_ = Image(info_.width, info_.height, color && info_.color ? 3 : 1);
    open_ = true;
    return {};
}

void BufferedDevice::Span(int row, int x0, int x1, Rgb color) {
    if (!open_ || row < 0 || row >= image_.height) return;
    x0 = std::max(x0, 0);
    x1 = std::min(x1, image_.width);
    for (int x = x0; x < x1; ++x) {
        std::uint8_t* p = image_.At(x, row);
        if (image_.channels == 3) {
            p[0] = Quantize(color.r);
            p[1] = Quantize(color.g);
            p[2] = Quantize(color.b);
        } else {
            p[0] = Quantize(color.r == color.g && color.g == color.b ? color.r : Luminance(color));
        }
    }
}

std::string BufferedDevice::Close() {
    if (!open_) return "device is not open";
    open_ = false;
    return Write(image_);
}

}  // namespace internal

}  // namespace quadrix::device
