// Readers for freeform (Bézier / B-spline / NURBS) models.
//
// Formats (testdata/SOURCES.md describes the files and where they come from):
//  - Newell tea set ("teaset" format of the Utah teapot, teacup and teaspoon): a patch count, one
//    line of 16 one-based vertex indices per bicubic patch (commas or blanks between numbers), a
//    vertex count, one "x,y,z" line per vertex. Index k of a patch line is control point
//    (u = k mod 4, v = k div 4).
//  - BPT ("Bézier patch text"): a patch count, then per patch "du dv" and (du+1)(dv+1) lines
//    "x y z", u varying fastest (the Newell order).
//  - Geomview BEZ/BBP (Geomview manual, "BBP and BEZ"): header [ST]BBP or [C]BEZ<Nu><Nv><Nd>[_ST]
//    (degrees 1..6, Nd = 3, or 4 for homogeneous x y z w), then patches of (Nu+1)(Nv+1) points,
//    u fastest, each optionally followed by 4 (s, t) pairs and 4 RGBA colours, which are skipped.
//    "appearance { ... }" blocks are skipped.
//  - Wavefront OBJ, its freeform subset: v (x y z [w]), cstype [rat] bezier|bspline, deg,
//    surf s0 s1 t0 t1 v[/vt[/vn]]..., parm u|v, end. Control points of a surf are listed with u
//    varying fastest; rational points are (x, y, z) with weight w, i.e. homogeneous (w x, w y, w z,
//    w). Multi-segment Bézier surfaces take their breakpoints from parm; the global range
//    s0 s1 t0 t1 restricts the surface. Trimming loops, curves and polygonal elements are skipped
//    with a warning.
//
// Every problem is reported with file:line:column through Diagnostics; a reader collects what it
// can and returns nullopt when any error was found.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/freeform/surface.h"
#include "quadrix/scene/diagnostics.h"

namespace quadrix::import {

enum class FreeformFormat { kAuto, kNewell, kBpt, kGeomview, kObj };

std::string_view FreeformFormatName(FreeformFormat format);

struct FreeformModel {
    FreeformFormat format = FreeformFormat::kAuto;
    std::vector<freeform::Surface> surfaces;
};

// Highest degree accepted in a file (the symbolic normal field of a rational surface has degree
// 3p - 1, and the squared iso-distance 4p: beyond this the Bernstein arithmetic loses precision).
inline constexpr int kMaxFreeformDegree = 12;

// The format from the file extension (.obj, .bpt, .bez) or, for others, from the text: a Geomview
// header word, OBJ statements, commas (Newell), else BPT.
FreeformFormat DetectFreeformFormat(std::string_view fileName, std::string_view text);

std::optional<FreeformModel> ReadFreeformText(std::string_view text, const std::string& fileName,
                                              FreeformFormat format, Diagnostics& diagnostics);
std::optional<FreeformModel> ReadFreeformFile(const std::string& path, Diagnostics& diagnostics,
                                              FreeformFormat format = FreeformFormat::kAuto);

}  // namespace quadrix::import
