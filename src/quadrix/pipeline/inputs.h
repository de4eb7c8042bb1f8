// Stage 1 of the render context: the input dispatcher, which reads a list of files of mixed
// formats into one Scene.
//
// Format by extension, then by content (docs/import.md):
//   .uq (and anything not recognised)      UniQuadrix language (lang::Reader)
//   .asc .g-ascii .cg .comgeom             BRL-CAD ASCII v4 / v5 / COMGEOM deck (content decides)
//   .g                                     BRL-CAD binary database, format v5 (brlcad/g_format.h)
//   .csg .scad                             OpenSCAD CSG subset
//   .obj .bpt .bez .bbp .teaset            freeform models (import/freeform; drawn by isocurves)
// A file with an unknown extension whose first line looks like a BRL-CAD database (or that starts
// with the v5 binary header 76 01 .. 35) is read as one. Imported models are mapped into Quadrix
// space (import/model_space.h); every file is read through the bounded reader (io/bounded_read.h).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "quadrix/import/brlcad/brlcad_import.h"
#include "quadrix/lang/reader.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix {

using import::ImportOptions;
using import::ImportReport;

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
    // ... outside view statements: the geometry may differ from clock to clock (false when the
    // clock only moves the camera).
    bool clockOutsideViews = false;
    // When `clock` is in view statements only: every view and redef view statement read, in
    // order (lang::Reader::ViewStatements), which another clock re-reads on their own
    // (RenderContext::ReadAtClock).
    std::vector<lang::ViewStatement> viewStatements;
};

// Reads every path ("-" = standard input, always UniQuadrix) into `scene`. Returns false when
// errors were added to diags. A --top name that no imported file defines is an error.
bool ReadSceneInputs(const std::vector<std::string>& paths, const InputOptions& options,
                     scene::Scene& scene, Diagnostics& diags, InputReport& report);

}  // namespace quadrix
