// Exact shapes shared by the importers (BRL-CAD primitives, OpenSCAD primitives and meshes): a
// Shape is a union of bodies, each body an intersection of planes, quadrics and quartics (inside
// <= 0; a literal may be complemented), in the primitive's own coordinates, plus "extent pieces"
// that bound it exactly under any affine map.
//
// Extents: every shape lists pieces (math/extent_piece.h), ellipsoids c + a·α + b·β + d·γ with
// α²+β²+γ² <= 1 (an ellipse when d = 0, a point when all are 0), whose convex hull has the same
// bounding box as the shape. Under an affine map a piece stays a piece, so the box of a transformed
// shape is exact as well: c_i ± sqrt(a_i² + b_i² + d_i²). A torus is not the hull of ellipsoids but
// a Minkowski sum (its ring circle plus a ball); `extentSums` lists such sums of pieces, whose box
// is the sum of the pieces' boxes (exact for the torus; for an elliptical torus or a pipe bend a
// containing sum).
//
// Builders. The primitives that both importers draw are built by format-neutral functions, one
// concept a file, each stating its maths: ellipsoid.h (ellipsoids and spheres), hexahedron.h
// (boxes and BRL-CAD's arb8 family), truncated_cone.h (cylinders, cones, the quartic general
// cone), torus.h (torus, elliptical torus), mesh_solid.h (closed meshes); they write their
// quadrics in the local frames of local_frame.h. brlcad/primitives.h adapts BRL-CAD's records to
// them, openscad/openscad_import.cpp calls them directly.
#pragma once

#include <string>
#include <vector>

#include "quadrix/math/extent_piece.h"
#include "quadrix/math/mat4.h"
#include "quadrix/math/plane_or_quadric.h"
#include "quadrix/math/quadric.h"
#include "quadrix/scene/scene.h"

namespace quadrix::import {

struct ShapeHalfSpace : PlaneOrQuadric {
    bool transparent = false;  // a helper plane that never touches the solid's boundary
    bool complement = false;   // the body uses the outside (a pipe's bore): literal "!"
};
using ShapeBody = std::vector<ShapeHalfSpace>;

struct Shape {
    std::vector<ShapeBody> bodies;  // union
    std::vector<ExtentPiece> extent;
    std::vector<std::vector<ExtentPiece>> extentSums;  // Minkowski sums of pieces (torus, eto)
    // Set by the builders whose pieces' hull has exactly the shape's box under every affine map
    // (an ellipsoid, a cone's end ellipses, a polytope's vertices); false where the pieces or
    // sums only contain it (a rotate-extruded profile's end discs, an elliptical torus).
    bool extentExact = false;
    bool unbounded = false;  // half-spaces
};

// What a shape builder returns: the shape, or (ok false) why its parameters bound no solid, in
// words fit for a diagnostic ("the semi-axes A, B, C are degenerate").
struct ShapeResult {
    bool ok = false;
    std::string problem;  // !ok
    Shape shape;          // ok
};

// The half-space moved by the placement `t` into the scene, as the scene model keeps imported
// half-spaces: a plane with a unit normal, a quadric scaled so that its largest coefficient is ±1
// (both without changing the set). Shared by the BRL-CAD and OpenSCAD importers.
ShapeHalfSpace Placed(const ShapeHalfSpace& h, const Transform& t);

// True when p is inside the shape (some body has every half-space <= tol).
bool ShapeContains(const Shape& shape, const Vec3& p, double tol = 0);

// Box of a bounded shape after M: its pieces and its sums of pieces.
Box3 ShapeBox(const Shape& shape, const Mat4& m);

// The extent a scene body made from the shape keeps (scene::Body::extent): its pieces after M
// when the shape is one body whose pieces are exact (extentExact, no sums) and M is affine;
// empty otherwise (the body is then bounded from its literals).
std::vector<ExtentPiece> BodyExtent(const Shape& shape, const Mat4& m);
// ShapeBox(shape, m) given BodyExtent(shape, m): the box of that placed extent where it has
// one (the same pieces mapped the same way, not mapped again).
Box3 ShapeBox(const Shape& shape, const Mat4& m, const std::vector<ExtentPiece>& bodyExtent);

// The kind and surface of a placed half-space copied into a scene half-space (plane, quadric or
// quartic); the caller sets id, position and transparency. Shared by both importers.
void SetSceneSurface(const ShapeHalfSpace& placed, scene::HalfSpace& hs);

}  // namespace quadrix::import
