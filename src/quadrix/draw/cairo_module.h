// The interface between Quadrix and its Cairo module, quadrix-cairo.so (modules/cairo/), which
// turns a drawing page into PDF, EPS or a PNG preview. The module is loaded only when a drawing
// is written in one of those formats (util/module_loader.h says why and how it is found).
//
// Quadrix flattens a Page into a CairoJob: a list of plain drawing commands in page units
// (cairo_writer.cpp holds the order and the styles of the strokes), and the module plays them on
// a Cairo surface and returns the file's bytes, which Quadrix writes through its one output
// writer (io/output_file.h). The module depends on nothing of Quadrix but this header.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace quadrix::draw {

// Raised whenever CairoJob, CairoCommand or CairoModule change, so that a module of another
// build is refused instead of misread.
inline constexpr int kCairoModuleAbi = 1;

struct CairoCommand {
    enum class Op : std::uint8_t {
        kNewPath,     // start a path (Cairo's current point is cleared)
        kMoveTo,      // v[0], v[1]
        kLineTo,      // v[0], v[1]
        kCurveTo,     // cubic Bézier: v[0..5] = two control points and the end point
        kEllipseArc,  // the unit circle from angle v[6] to v[7] (increasing) under the affine map
                      // (x, y) -> (v[0] x + v[2] y + v[4], v[1] x + v[3] y + v[5])
        kStroke,      // stroke the path with the current width, dash and gray
        kLineWidth,   // v[0]
        kDash,        // dashes of v[0] on, v[1] off
        kSolid,       // no dashes
        kGray,        // source colour gray level v[0] (0 black, 1 white)
        kText,        // texts[index] at (v[0], v[1]) (baseline start), size v[2], sans-serif
    };
    Op op = Op::kNewPath;
    std::uint32_t index = 0;  // kText: index into CairoJob::texts
    double v[8] = {};
};

struct CairoJob {
    enum class Format : int { kPdf, kEps, kPng };
    Format format = Format::kPdf;
    // PDF/EPS: page size in points and points per page unit.
    double widthPt = 0, heightPt = 0, pointsPerUnit = 1;
    // PNG: image size in pixels and pixels per page unit.
    int pixelWidth = 0, pixelHeight = 0;
    double pixelsPerUnit = 1;
    std::string title;  // PDF metadata; empty for none
    // Played in order on a white page, black, round caps and joins, curve tolerance 0.001.
    std::vector<CairoCommand> commands;
    std::vector<std::string> texts;
};

// The module's table (quadrix_cairo_module() returns it).
struct CairoModule {
    int abi = kCairoModuleAbi;
    // Renders `job` into `bytes` (the whole file). False, with `*error` set, on failure.
    bool (*render)(const CairoJob& job, std::string* bytes, std::string* error) = nullptr;
};

}  // namespace quadrix::draw

// Defined by modules/cairo/cairo_module.cpp: in quadrix-cairo.so, or linked into targets that
// link Cairo themselves (quadrix_modules_linked).
extern "C" const quadrix::draw::CairoModule* quadrix_cairo_module();
