// The hexahedron given by its eight vertices as an exact Shape (shape.h): BRL-CAD's arb8 and,
// with repeated vertices, arb4..arb7 (tetrahedra, pyramids, wedges); OpenSCAD's cube (BoxShape).
//
// Vertex order and faces (FORMAT.md §6.1, 1-based): 1234 8765 1485 2673 1562 4378, i.e. the base
// 1234, the top 5678 above it, and the four sides (kHexahedronFaces, 0-based).
//
// Maths. The solid is the intersection of its face planes (one body of up to six planes):
//   - a face's plane passes through its first three distinct, non-collinear vertices v0, v1, v2
//     (librt's rt_arb_add_pnt): n = unit((v1 − v0) × (v2 − v0)), plane <n, −n·v0>, turned so that
//     the centroid c (the mean of the eight vertices) is inside, n·c − n·v0 < 0;
//   - a face with fewer than three such vertices is dropped (an arb4..arb7 repeats vertices), and
//     so is a plane through the centroid (a flat hexahedron); fewer than four planes left bound no
//     solid: refused;
//   - a concave or twisted hexahedron (a vertex outside some face plane) is, as in librt, the
//     intersection of its face planes, which can reach far beyond its vertices; librt only finds
//     it along rays through the bounding box, so six more planes bound it by the box of its
//     vertices (x <= max x, −x <= −min x, …). A convex hexahedron has no such planes.
// For the box [lo, hi] these are its six faces with unit normals, <1, 0, 0, −hi.x> (x <= hi.x),
// <−1, 0, 0, lo.x> (x >= lo.x) and likewise in y and z.
// Extent: the eight vertices (pieces that are points): exact under any affine map.
// Tolerance: vertices closer than kHexahedronTol are the same vertex, three vertices whose cross
// product is below it (relative to the edges) are collinear; it is librt's bn_tol.dist, 0.0005
// model units (millimetres in BRL-CAD and, by convention, in OpenSCAD; FORMAT.md §8).
#pragma once

#include <array>

#include "quadrix/import/shapes/shape.h"
#include "quadrix/math/vec.h"

namespace quadrix::import {

inline constexpr double kHexahedronTol = 0.0005;

// The face table (vertex numbers 0-based): 1234 8765 1485 2673 1562 4378.
inline constexpr int kHexahedronFaces[6][4] = {{0, 1, 2, 3}, {7, 6, 5, 4}, {0, 3, 7, 4},
                                               {1, 5, 6, 2}, {0, 4, 5, 1}, {3, 2, 6, 7}};

ShapeResult HexahedronShape(const std::array<Vec3, 8>& vertices);

// The axis-aligned box [lo, hi]: the hexahedron of its corners, base z = lo.z counter-clockwise
// from lo seen from above, then the top.
ShapeResult BoxShape(const Vec3& lo, const Vec3& hi);

}  // namespace quadrix::import
