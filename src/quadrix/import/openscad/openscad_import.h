// OpenSCAD CSG files (`openscad -o model.csg`) and the same subset in .scad → scene::Scene,
// exactly: sphere, cylinder (cones with r1/r2), cube, multmatrix/translate/rotate/scale/mirror,
// union/difference/intersection/group and color become quadrics, planes and CSG solids.
// polyhedron, linear_extrude and rotate_extrude of 2D polygons become planes (and cones),
// $fn/$fa/$fs make a circle a polygon where OpenSCAD's author asked for one (polygon_solids.h).
// Anything else (hull, minkowski, text, twisted extrusions, ...) is an error naming it and its
// line; with --allow-missing it is left out with a warning (docs/import.md). A .scad beyond this
// literal subset (variables, modules, loops) is evaluated by OpenSCAD first (scad_source.h).
//
// Coordinates: OpenSCAD is right-handed with Z up; the model is mapped into Quadrix space with
// QuadrixFromZUp, as BRL-CAD models are.
#pragma once

#include <string>
#include <string_view>

#include "quadrix/import/import_report.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix::import {

bool ImportOpenScad(std::string_view text, const std::string& file, const ImportOptions& options,
                    scene::Scene& scene, Diagnostics& diags, ImportReport& report);

// Whether `text` parses as the subset (syntax only; nothing is built). Errors go to diags.
bool ParsesAsOpenScadSubset(std::string_view text, const std::string& file, Diagnostics& diags);

}  // namespace quadrix::import
