// A .scad source file → Scene: read directly when it is in the literal CSG subset our reader
// takes (openscad_import.h), else evaluated by the OpenSCAD program (openscad_program.h) and its
// CSG output read instead (docs/import.md "OpenSCAD").
//
//   1. Our parser tries the file. When it parses, the file is imported directly (exact positions,
//      no OpenSCAD needed). Only the syntax decides: an unsupported primitive in a file that
//      parses is an error of the importer, not a reason to run OpenSCAD.
//   2. Otherwise (variables, modules, functions, loops, expressions, include/use, ...) the file
//      is evaluated with `openscad -o model.csg` and the CSG text is imported.
//   3. Without OpenSCAD: our parser's errors, and an error naming what to install.
//
// Positions of an evaluated file. The CSG tree has no source positions, so every diagnostic and
// every scene element (Csg, Body, HalfSpace, CsgNode locations; the Csg ids "name@line") of the
// import is mapped back by the name of the statement at its CSG position:
//   - the name is called exactly once in the .scad (outside comments and strings): that call's
//     line and column, with its source line — "model.scad:7:5";
//   - otherwise (a module called from several places, a loop, a library module): the .scad file
//     without a line, and the message says so: "(evaluated by OpenSCAD: CSG line 12
//     'cylinder(...)'; 'cylinder' is called at lines 3, 9)". Ids become "name@csgN".
#pragma once

#include <string>
#include <string_view>

#include "quadrix/import/import_report.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix::import {

bool ImportScadSource(std::string_view text, const std::string& path, const ImportOptions& options,
                      scene::Scene& scene, Diagnostics& diags, ImportReport& report);

}  // namespace quadrix::import
