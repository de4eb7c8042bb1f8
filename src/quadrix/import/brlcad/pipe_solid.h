// The BRL-CAD `pipe` as an exact Shape (primitives.h): straight runs are cones (cylinders when the
// diameters do not change) and bends are torus sections, each with its bore subtracted.
//
// Input (FORMAT.md §3.1, binary g_format.h): points P0 … Pn−1, each with an outer diameter od, an
// inner diameter id (0: a solid rod) and a bend radius R. The layout, as librt lays a pipe out:
//
//   walking from P0 with the current point X = P0 and diameters (od, id) of P0, for each interior
//   point Pi (previous X, next Pi+1):
//     n1 = unit(X − Pi), n2 = unit(Pi+1 − Pi), θ = π − acos(n1·n2) (the deflection), and the
//     tangent distance t = Ri·tan(θ/2). A duplicate point (X = Pi) is skipped. Collinear points
//     (or Ri = 0, t = 0) end a straight run at Pi. Otherwise the run X → S = Pi + t·n1 tapers from
//     X's diameters to Pi's, and the bend from S to E = Pi + t·n2 has Pi's diameters: the torus of
//     major radius Ri about the axis n = unit(n1 × n2) through the centre C (at distance Ri from
//     S and E, on the bisector of n1 and n2), cut by the two planes through C perpendicular to the
//     pipe at S and at E. Then X = E with Pi's diameters.
//   the last run goes from X to Pn−1 (diameters of X, then Pn−1's).
//
// Each run or bend is one body: outer surface ∩ !(inner surface) ∩ its two joint planes. A joint
// plane is computed once and used with opposite signs by the two pieces that meet there, so the
// seam is exact (no crack, no double hit); at the ends the joint planes are the flat end caps (the
// annulus). Rejected, as librt's rt_pipe_ck rejects them: fewer than 2 points, od <= 0, id < 0 or
// id >= od, a bend whose radius is smaller than its outer radius (a self-intersecting torus) or
// that turns by 180°, bends that overlap on a run (t_i + t_i+1 > |Pi+1 − Pi|).
//
// Extent: the end circles of every run (exact) and, for each bend, balls of the outer radius at the
// corners of a tangent polygon around its arc (sub-arcs of at most 22.5°), a box within ~2% of the
// bend radius of the exact one.
#pragma once

#include <string>
#include <vector>

#include "quadrix/import/brlcad/database.h"
#include "quadrix/import/brlcad/primitives.h"

namespace quadrix::import::brlcad {

struct PipePiece {
    enum class Kind { kRun, kBend };
    Kind kind = Kind::kRun;
    Vec3 a, b;  // start and end on the centre line
    // Outer and inner radii at a and at b (a bend has the same at both ends).
    double ro0 = 0, ri0 = 0, ro1 = 0, ri1 = 0;
    // kBend: the centre C, the unit normal of the bend plane, the bend radius and the angle.
    Vec3 centre, normal;
    double bend = 0, angle = 0;
};

struct PipeLayout {
    bool ok = false;
    std::string problem;  // when !ok
    int point = -1;       // when !ok: the point the problem is at (0-based), -1 for the whole pipe
    std::vector<PipePiece> pieces;
};

PipeLayout LayOutPipe(const std::vector<Primitive::PipePoint>& points);

// The Shape of a laid-out pipe; ok = false with `problem` when a bend's torus cannot be built.
struct PipeShape {
    bool ok = false;
    std::string problem;
    Shape shape;
};
PipeShape PipeToShape(const PipeLayout& layout);

}  // namespace quadrix::import::brlcad
