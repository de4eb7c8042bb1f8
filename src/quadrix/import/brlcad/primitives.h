// BRL-CAD primitives → exact Quadrix half-spaces (FORMAT.md §6.1).
//
// Each primitive drawn exactly becomes a Shape (import/shapes/shape.h): a union of bodies, each
// body an intersection of planes, quadrics and quartics (inside <= 0; a literal may be
// complemented), in the primitive's own (BRL-CAD, millimetre) coordinates. Most primitives are one
// body; `part` is up to three (two spheres and the tangent cone frustum), a `pipe` one per
// straight run and bend (pipe_solid.h).
//
// The geometry OpenSCAD shares is not BRL-CAD's: ConvertPrimitive is a thin adapter from the
// records of database.h to the format-neutral builders of import/shapes/ — ell → ellipsoid.h,
// arb8 → hexahedron.h, tgc → truncated_cone.h (similar ends a quadric, otherwise the quartic
// general cone, census "tgc (quartic)"), tor and eto → torus.h, bot → mesh_solid.h. The
// primitives only BRL-CAD has (half, arbn, rpc, rhc, epa, ehy, hyp, part, pipe) are built here,
// their quadrics written in a local frame in which they have the textbook form (x² + y = 1
// parabola, …) and mapped to the world with shapes/local_frame.h.
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

}  // namespace quadrix::import::brlcad
