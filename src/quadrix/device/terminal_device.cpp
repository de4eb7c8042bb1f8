// The terminal device: a soft device that previews the picture in a terminal, the modern stand-in
// for the Sun screens of seed 001 §2.2. Each character cell shows two pixels with the upper half
// block '▀' (U+2580): the foreground color paints the upper pixel, the background color the lower
// one. Colors are 24-bit ANSI escapes when $COLORTERM says the terminal has them ("truecolor" or
// "24bit"), else the xterm 256-color palette (6 × 6 × 6 cube and 24 grays).
// It draws on standard output (or the FILE* it is given); with a path other than "-" it writes
// the same text atomically to that file, which `cat` shows later.
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "quadrix/device/device_internal.h"
#include "quadrix/io/writers.h"

namespace quadrix::device::internal {

namespace {

bool TrueColor() {
    const char* c = std::getenv("COLORTERM");
    return c && (std::strstr(c, "truecolor") || std::strstr(c, "24bit"));
}

// Nearest entry of the xterm 256-color palette: the 6-level cube or the 24-step gray ramp.
int Xterm256(Rgb c) {
    static constexpr int kCube[6] = {0, 95, 135, 175, 215, 255};
    auto cubeIndex = [](int v) {
        int best = 0;
        for (int i = 1; i < 6; ++i)
            if (std::abs(kCube[i] - v) < std::abs(kCube[best] - v)) best = i;
        return best;
    };
    int r = cubeIndex(c.r), g = cubeIndex(c.g), b = cubeIndex(c.b);
    auto dist = [&](int R, int G, int B) {
        return (R - c.r) * (R - c.r) + (G - c.g) * (G - c.g) + (B - c.b) * (B - c.b);
    };
    int cubeDist = dist(kCube[r], kCube[g], kCube[b]);
    int mean = (c.r + c.g + c.b) / 3;
    int grayIndex = std::clamp((mean - 8 + 5) / 10, 0, 23);  // grays 8, 18, ..., 238
    int grayLevel = 8 + 10 * grayIndex;
    if (dist(grayLevel, grayLevel, grayLevel) < cubeDist) return 232 + grayIndex;
    return 16 + 36 * r + 6 * g + b;
}

class TerminalDevice : public BufferedDevice {
  public:
    TerminalDevice(DeviceInfo info, std::FILE* screen) : screen_(screen ? screen : stdout) {
        info_ = std::move(info);
        trueColor_ = TrueColor();
    }

  protected:
    std::string Write(const Image& image) override {
        std::string text = Render(image);
        if (info_.path != "-") return WriteOutputFile(info_.path, text);
        std::fwrite(text.data(), 1, text.size(), screen_);
        std::fflush(screen_);
        return {};
    }

  private:
    std::string Color(bool foreground, Rgb c) const {
        if (trueColor_)
            return fmt::format("\x1b[{};2;{};{};{}m", foreground ? 38 : 48, c.r, c.g, c.b);
        return fmt::format("\x1b[{};5;{}m", foreground ? 38 : 48, Xterm256(c));
    }

    std::string Render(const Image& image) const {
        auto pixel = [&](int x, int y) {
            const std::uint8_t* p = image.At(x, y);
            return image.channels == 3 ? Rgb{p[0], p[1], p[2]} : Rgb{p[0], p[0], p[0]};
        };
        std::string out;
        for (int y = 0; y < image.height; y += 2) {
            bool haveFg = false, haveBg = false;
            Rgb fg, bg;
            for (int x = 0; x < image.width; ++x) {
                Rgb top = pixel(x, y);
                if (!haveFg || !(top == fg)) out += Color(true, top);
                fg = top;
                haveFg = true;
                if (y + 1 < image.height) {
                    Rgb bottom = pixel(x, y + 1);
                    if (!haveBg || !(bottom == bg)) out += Color(false, bottom);
                    bg = bottom;
                    haveBg = true;
                }
                out += "\u2580";
            }
            out += "\x1b[0m\n";
        }
        return out;
    }

    std::FILE* screen_;
    bool trueColor_ = false;
};

}  // namespace

std::unique_ptr<Device> MakeTerminalDevice(DeviceInfo info, std::FILE* screen) {
    return std::make_unique<TerminalDevice>(std::move(info), screen);
}

}  // namespace quadrix::device::internal
