// BRL-CAD primitives → exact Quadrix half-spaces (FORMAT.md §6.1).
//
// Each primitive drawn exactly becomes a Shape: a union of bodies, each body an intersection of
// planes, quadrics and quartics (inside <= 0; a literal may be complemented), in the primitive's
// own (BRL-CAD, millimetre) coordinates. Most primitives are one body; `part` is up to three (two
// spheres and the tangent cone frustum), a `pipe` one per straight run and bend (pipe_solid.h).
// Quartics (math/quartic_surface.h): `tor` is a torus, `eto` an elliptical torus, a `tgc` whose
// end ellipses are not similar a general cone (a quartic capped by two planes).
// The quadrics are written in an affine "local" frame in which they have the textbook form
// (unit sphere, unit circular cone, x² + y = 1 parabola, ...), then mapped to the world with
// Q_world = Lᵀ Q_local L, p_world = Lᵀ p_local, L = localFromWorld (DESIGN.md transform rules).
//
// Shapes and their exact extents: import/shapes/shape.h.
#pragma once

#include <string>
#include <vector>

#include "quadrix/import/brlcad/database.h"
#include "quadrix/import/shapes/shape.h"

namespace quadrix::import::brlcad {

struct ConvertResult {
    enum class Status { kOk, kNonQuadric, kInvalid };
    Status status = Status::kOk;
    Shape shape;
    std::string censusName;  // e.g. "arb8", "tgc", "tgc (quartic)", "tor"
    std::string problem;     // kInvalid: why, for the diagnostic
};

ConvertResult ConvertPrimitive(const Primitive& prim);

// The arb8 face table of FORMAT.md §6.1 (vertex numbers 0-based): 1234 8765 1485 2673 1562 4378.
inline constexpr int kArbFaces[6][4] = {{0, 1, 2, 3}, {7, 6, 5, 4}, {0, 3, 7, 4},
                                        {1, 5, 6, 2}, {0, 4, 5, 1}, {3, 2, 6, 7}};

}  // namespace quadrix::import::brlcad
