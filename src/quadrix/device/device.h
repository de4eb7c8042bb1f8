// Output devices (seed 001 §6.5.2, "The Device Interface"): every part of the program sees one
// interface whatever the device. A device describes itself (pixels on each axis, the number of
// intensities it can render, pixel aspect ratio, the default shading interval Δmax) and is
// driven through open / span / close; "apply controls" are the settings of DeviceSettings.
//
// Spans are the unit of output, as in UniQuadrix: a run [x0, x1) of one row drawn with one
// color. DrawImage turns a shaded Image (and the Frame it came from) into spans the way the
// paper's Shader does (§6.5.1): one span per run of one show-face, the intensity evaluated every Δ
// pixels and averaged in between, and the driver called only when the intensity changes.
//
// Devices (docs/devices.md):
//   ascii (file, a)          human-readable span listing, uq.out          (ascii_device.cpp)
//   png                      8-bit PNG, gray or RGB, uq.png
//   pnm / pgm / ppm          binary PGM/PPM, uq.pgm / uq.ppm
//   halftone (dither, pbm)   bilevel, 8×8 ordered dither, PBM or PNG by extension, uq.pbm
//   stipple (varian, versatek and their short names)
//                            bilevel, clustered-dot stipple patterns as the plotter drivers
//   terminal (term, tty)     ANSI colors and half-block characters on standard output
//
// A hard device writes a file atomically at Close (nothing is written when drawing fails or is
// aborted); a soft device (terminal) draws on a screen.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"

namespace quadrix::device {

struct Rgb {
    std::uint8_t r = 0, g = 0, b = 0;
    bool operator==(const Rgb&) const = default;
};

// The characteristics of §6.5.2 plus where a hard device writes.
struct DeviceInfo {
    std::string name;  // canonical name ("png", "ascii", ...)
    int width = 512;   // pixels on each axis
    int height = 512;
    double dotsPerInch = 100;  // converts the paper's sizes in inches (-sx, -sy, xsize, ysize)
    int levels = 256;          // intensities the device can render per channel (2 = bilevel)
    double aspect = 1;         // pixel width / pixel height
    int deltaMax = 1;   // default shading interval Δmax in pixels (§6.5.1), 1 = every pixel
    bool hard = true;   // writes a file ("hard" drawing) rather than drawing on a screen
    bool color = true;  // renders color; false = gray (luminance)
    std::string path;   // output file of a hard device; "-" = standard output
};

// What a user may set on a device (the paper's device statement and options).
struct DeviceSettings {
    std::string path;                 // output path; empty = the device's default
    double xInches = 0, yInches = 0;  // drawing size, 0 = the device default
    int deltaMax = 0;                 // 0 = the device default
    std::FILE* screen = nullptr;      // where a soft device draws; nullptr = stdout
};

class Device {
  public:
    virtual ~Device() = default;
    const DeviceInfo& Info() const { return info_; }

    // Starts a picture of Info().width × Info().height; `color` says whether spans carry color
    // (else r = g = b). Returns an error message or empty.
    virtual std::string Open(bool color) = 0;
    // Draws [x0, x1) of `row` (row 0 at the top) in `color`. Spans outside the picture are
    // clipped.
    virtual void Span(int row, int x0, int x1, Rgb color) = 0;
    // Finishes the picture: a hard device writes its file atomically. Error message or empty.
    virtual std::string Close() = 0;
    // Drops the picture: nothing is written.
    virtual void Abort() = 0;

    // Quantizes one channel value to the device's intensity levels (still on the 0..255 scale).
    std::uint8_t Quantize(std::uint8_t v) const;

  protected:
    DeviceInfo info_;
};

struct DeviceName {
    std::string name;                   // canonical
    std::vector<std::string> synonyms;  // the paper's short names and ours
    std::string description;
};

// Every known device with its synonyms, for messages and docs.
const std::vector<DeviceName>& DeviceNames();
// Canonical name of `name` (a name or synonym, case-insensitive); empty when unknown.
std::string CanonicalDeviceName(std::string_view name);
// "png, pnm, ..." for error messages.
std::string KnownDevicesText();

// A device from a spec "NAME" or "NAME:PATH" (PATH overrides settings.path). nullptr with
// `error` set when the name is unknown, the path does not suit the device, or the size is bad.
std::unique_ptr<Device> MakeDevice(std::string_view spec, const DeviceSettings& settings,
                                   std::string& error);

// Counts of what DrawImage sent (for the trace).
struct DrawStats {
    long long spans = 0;        // device Span calls
    long long evaluations = 0;  // intensity evaluations (§6.5.1: ends and every Δ pixels)
};

// Sends `image` (of the device's size) to an opened device as spans, §6.5.1: a span is a run of
// one show-face (same surface and body in `frame`, or background); inside it the intensity is
// taken at both ends and every Δ = min((xr − xl)/16 + 1, deltaMax) pixels, each Δ interval is
// drawn with the integer average of the intensities at its ends, and Span is called only when
// the intensity changes. deltaMax = 1 draws every pixel's own intensity. `frame` may be null
// (every run of equal pixels is then a span).
DrawStats DrawImage(Device& device, const Image& image, const Frame* frame, int deltaMax);

// Shading interval constant k of (6.9): "A value of sixteen for k produces images almost
// identical to those with intensity calculated at each pixel".
inline constexpr int kShadingK = 16;

// --- the ASCII listing (device "ascii"), ascii_device.cpp --------------------------------------
//
//   quadrix-listing 1
//   size <width> <height>
//   levels <n>
//   color <0|1>
//   span <row> <x0> <x1> <v>          gray   (or: span <row> <x0> <x1> <r> <g> <b>)
//   ...
//   end <span count>
struct ListedSpan {
    int row = 0, x0 = 0, x1 = 0;
    Rgb color;
    bool operator==(const ListedSpan&) const = default;
};
struct Listing {
    int width = 0, height = 0, levels = 0;
    bool color = false;
    std::vector<ListedSpan> spans;
};
// Parses a listing; returns an error message ("line N: ...") or empty.
std::string ParseListing(std::string_view text, Listing& listing);

// --- halftone patterns (halftone_device.cpp) ---------------------------------------------------
enum class Pattern { kBayer, kCluster };
// The threshold rank 0..63 of cell (x mod 8, y mod 8): a pixel of intensity v (0..255) is set
// (white) when v / 255 > (rank + 0.5) / 64, so a flat area of intensity v sets round(64 v / 255)
// of every 64 pixels.
int ThresholdRank(Pattern pattern, int x, int y);

}  // namespace quadrix::device
