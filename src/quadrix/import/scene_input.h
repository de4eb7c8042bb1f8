// The input dispatcher: reads a list of files of mixed formats into one Scene.
//
// Format by extension, then by content (docs/import.md):
//   .uq (and anything not recognised)      UniQuadrix language (lang::Reader)
//   .asc .g-ascii .cg .comgeom             BRL-CAD ASCII v4 / v5 / COMGEOM deck (content decides)
//   .g                                     BRL-CAD binary database, format v5 (brlcad/g_format.h)
//   .csg .scad                             OpenSCAD CSG subset
//   .obj .bpt .bez .bbp .teaset            freeform models (import/freeform; drawn by isocurves)
// A file with an unknown extension whose first line looks like a BRL-CAD database (or that starts
// with the v5 binary header 76 01 .. 35) is read as one.
//
// Imported (Z-up, right-handed) models are mapped into Quadrix space by QuadrixFromZUp:
// (x, y, z) → (x, z, y). Views and lights of .uq files in the same render are in Quadrix space.
//
// Views like rt (FORMAT.md §9.4): MakeAzElView and MakeRtView build orthographic scene::Views in
// Quadrix space from rt's parameters, which are given in the model's own coordinates.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "quadrix/import/brlcad/brlcad_import.h"
#include "quadrix/math/mat4.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix::import {

// (x, y, z) → (x, z, y): BRL-CAD / OpenSCAD model space to Quadrix space (a reflection; see
// brlcad_import.h for why).
Mat4 QuadrixFromZUp();

enum class InputFormat { kUniQuadrix, kBrlcad, kOpenScad, kFreeform };

// The format a path will be read as (extension first, then the first bytes of `text`).
InputFormat DetectInputFormat(const std::string& path, std::string_view text);

struct InputOptions {
    ImportOptions import;  // --top, --strict
    double clock = 0;      // `clock` in UniQuadrix files (docs/language.md §3.14)
};

struct InputReport {
    std::vector<std::pair<std::string, ImportReport>> imports;  // (path, report) per imported file
    Box3 importedBounds;  // union of the imported models' bounds (Quadrix space)
    // A UniQuadrix input wrote a number with `clock` (docs/language.md §3.14): the scene depends
    // on InputOptions::clock.
    bool usesClock = false;
};

// Reads every path ("-" = standard input, always UniQuadrix) into `scene`. Returns false when
// errors were added to diags. A --top name that no imported file defines is an error.
bool ReadSceneInputs(const std::vector<std::string>& paths, const InputOptions& options,
                     scene::Scene& scene, Diagnostics& diags, InputReport& report);

// rt's explicit orthographic view (FORMAT.md §9.4), in MODEL coordinates: rows 0-2 of `viewrot`
// are the view's X (right), Y (up) and Z (toward the viewer) axes; the image spans `viewsize`
// across its width; pixel (i, j from the bottom) samples eye + (-vs/2 + i·cell) X +
// (-vs/2 + j·cell) Y, cell = viewsize/width, along -Z. Nothing behind the eye plane is drawn.
struct RtView {
    double viewsize = 0;
    Vec3 eye;
    Mat4 viewrot = Mat4::Identity();
};

// The view (id "rt") reproducing rt's frame pixel for pixel on a width×height image.
scene::View MakeRtView(const RtView& rt, int width, int height);

// rt's azimuth/elevation (degrees) in model coordinates: the viewer sits along
// (cos el cos az, cos el sin az, sin el), model Z projects to screen up. When `modelBox` (Quadrix
// space) is finite the view is fitted like rt: centred on the box, viewsize = its diagonal (or
// `viewsize` when given); otherwise the Flattener's auto-fit frames the scene.
RtView AzElRtView(double azimuth, double elevation, const Box3& modelBox,
                  std::optional<double> viewsize);
scene::View MakeAzElView(double azimuth, double elevation, const Box3& modelBox,
                         std::optional<double> viewsize, int width, int height);

// Reads rt's view commands (`viewsize s;` `eye_pt x y z;` `viewrot m0 .. m15;` `ae az el;`)
// from text, as rt reads them on standard input. Errors name file:line:column.
std::optional<RtView> ParseRtViewScript(std::string_view text, const std::string& file,
                                        Diagnostics& diags);

// Lights for a view made from rt parameters when the scene has none: rt's 40 % ambient plus a
// light at the eye (FORMAT.md §9.2-9.4).
void AddRtLights(scene::Scene& scene, const scene::View& view);

}  // namespace quadrix::import
