// Imported (Z-up, right-handed) models — BRL-CAD databases, OpenSCAD files — are mapped into
// Quadrix space by QuadrixFromZUp: (x, y, z) → (x, z, y), a reflection (see brlcad_import.h for
// why). Views and lights of .uq files in the same render are in Quadrix space.
#pragma once

#include "quadrix/math/mat4.h"

namespace quadrix::import {

Mat4 QuadrixFromZUp();

}  // namespace quadrix::import
