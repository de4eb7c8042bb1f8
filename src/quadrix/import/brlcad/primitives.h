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
// Exact extents: every shape also lists "extent pieces", ellipsoids c + a·α + b·β + d·γ with
// α²+β²+γ² <= 1 (an ellipse when d = 0, a point when all are 0), whose convex hull has the same
// bounding box as the primitive. Under an affine map a piece stays a piece, so the box of a
// transformed primitive is exact as well: c_i ± sqrt(a_i² + b_i² + d_i²). A torus is not the
// hull of ellipsoids but a Minkowski sum (its ring circle plus a ball); `extentSums` lists such
// sums of pieces, whose box is the sum of the pieces' boxes (exact for the torus; for the eto and
// the pipe's bends a containing sum, so the box is conservative there).
#pragma once

#include <string>
#include <vector>

#include "quadrix/import/brlcad/database.h"
#include "quadrix/math/mat4.h"
#include "quadrix/math/plane_or_quadric.h"
#include "quadrix/math/quadric.h"
#include "quadrix/scene/scene.h"

namespace quadrix::import::brlcad {

struct ShapeHalfSpace : PlaneOrQuadric {
    bool transparent = false;  // a helper plane that never touches the solid's boundary
    bool complement = false;   // the body uses the outside (a pipe's bore): literal "!"
};
using ShapeBody = std::vector<ShapeHalfSpace>;

struct ExtentPiece {
    Vec3 c, a, b, d;
};

struct Shape {
    std::vector<ShapeBody> bodies;  // union
    std::vector<ExtentPiece> extent;
    std::vector<std::vector<ExtentPiece>> extentSums;  // Minkowski sums of pieces (torus, eto)
    bool unbounded = false;                            // half-spaces
};

struct ConvertResult {
    enum class Status { kOk, kNonQuadric, kInvalid };
    Status status = Status::kOk;
    Shape shape;
    std::string censusName;  // e.g. "arb8", "tgc", "tgc (quartic)", "tor"
    std::string problem;     // kInvalid: why, for the diagnostic
};

ConvertResult ConvertPrimitive(const Primitive& prim);

// The half-space moved by the placement `t` into the scene, as the scene model keeps imported
// half-spaces: a plane with a unit normal, a quadric scaled so that its largest coefficient is ±1
// (both without changing the set). Shared by the BRL-CAD and OpenSCAD importers.
ShapeHalfSpace Placed(const ShapeHalfSpace& h, const Transform& t);

// True when p is inside the shape (some body has every half-space <= tol).
bool ShapeContains(const Shape& shape, const Vec3& p, double tol = 0);

// Box of a piece after the affine map M (normalised so that M(3,3) = 1 and row 3 = 0 0 0 1).
Box3 PieceBox(const ExtentPiece& piece, const Mat4& m);
// Box of a bounded shape after M: its pieces and its sums of pieces.
Box3 ShapeBox(const Shape& shape, const Mat4& m);

// The kind and surface of a placed half-space copied into a scene half-space (plane, quadric or
// quartic); the caller sets id, position and transparency. Shared by both importers.
void SetSceneSurface(const ShapeHalfSpace& placed, scene::HalfSpace& hs);

// The arb8 face table of FORMAT.md §6.1 (vertex numbers 0-based): 1234 8765 1485 2673 1562 4378.
inline constexpr int kArbFaces[6][4] = {{0, 1, 2, 3}, {7, 6, 5, 4}, {0, 3, 7, 4},
                                        {1, 5, 6, 2}, {0, 4, 5, 1}, {3, 2, 6, 7}};

}  // namespace quadrix::import::brlcad
