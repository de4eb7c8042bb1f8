// A closed polygon mesh (BRL-CAD bot, OpenSCAD polyhedron) → the exact solid it bounds, as a union
// of convex bodies of planes (a Shape of shape.h), with no approximation.
//
// Method. A closed mesh is the intersection of its face planes only when it is convex, so:
//   1. The faces are oriented consistently (a breadth-first walk across shared edges; a face
//      listed the other way round is flipped), and each connected piece is turned so that its
//      signed volume is positive (outward normals). A mesh with an edge not shared by exactly two
//      faces, or that cannot be oriented (a Möbius-like strip), bounds no solid: refused.
//   2. Convex (every vertex on the inner side of every face plane, within the tolerance): one body,
//      the distinct face planes.
//   3. Otherwise a solid-leaf BSP tree (Thibault & Naylor, SIGGRAPH '87) of the face polygons:
//      a node takes the plane of one of its polygons (the candidate, among a few, that splits the
//      fewest), the others go to its front or back (straddlers are split). A side with no polygon
//      left is a cell entirely inside (back) or outside (front) the solid: the splitting polygon,
//      which lies inside the cell, has the solid just behind it. Every inside cell is convex, the
//      intersection of the half-spaces on its path from the root, so the solid is the union of
//      these cells. Neighbouring cells share a plane with opposite signs, coefficient for
//      coefficient, so the ray parameters of a seam are bit-identical on both sides.
// Tolerance: one per mesh, 1e-9 × the diagonal of its box (STYLE.md "one scale-derived tolerance").
// Faces with more than three vertices are fanned into triangles (correct for convex faces, which
// is what BRL-CAD and OpenSCAD write; a non-convex face must be split by the author).
#pragma once

#include <string>
#include <vector>

#include "quadrix/import/shapes/shape.h"
#include "quadrix/math/vec.h"

namespace quadrix::import {

struct MeshSolid {
    bool ok = false;
    std::string problem;  // !ok: why the mesh bounds no solid (for the diagnostic)
    Shape shape;          // ok: union of convex bodies, extent = the vertices
    bool convex = false;
};

// Limits: at most this many BSP cells (inside cells kept) before giving up with a problem.
inline constexpr std::size_t kMaxMeshCells = 200'000;

MeshSolid MeshToSolid(const std::vector<Vec3>& vertices,
                      const std::vector<std::vector<int>>& faces);

// A plate-mode bot (BRL-CAD mode 3, every face centred): the union over faces of the triangular
// prism of thickness t_i along the face normal, centred on the face.
MeshSolid PlatesToSolid(const std::vector<Vec3>& vertices,
                        const std::vector<std::array<int, 3>>& faces,
                        const std::vector<double>& thickness);

}  // namespace quadrix::import
