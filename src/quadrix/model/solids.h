// Solids by their dimensions (seed 001 §7.2.3: "a front end ... to specify spheres, cylinders, and
// other quadric surfaces [by] half-axes, center coordinates, and orientation angles"): each solid
// becomes the plain half-spaces the core language would write, so every engine sees ordinary HSBs.
//
// A SolidShape is the list of half-spaces whose intersection is the solid. Surfaces are named by
// a suffix appended to the solid's id: "" for the curved surface (so that `!id` in a body is the
// complement of the infinite quadric, a drilled hole), "#0"/"#1" for the planes that cap an axial
// solid at its `from` and `to` ends, "#x0".."#z1" for the faces of a box (low and high face of
// its own x, y and z axes).
//
// Coefficients follow DESIGN.md: plane <A B C D> with Ax+By+Cz+D <= 0 inside and (A, B, C) the
// outward normal; quadric xᵀQx <= 0 inside. Circular sections are written monic in the section
// coordinates (x² + y² − r² for a cylinder, as docs/language.md's table), elliptic ones as
// x²/a² + y²/b² − 1, so simple cases give the coefficients a user would write by hand.
//
// These functions assume valid dimensions (positive radii, distinct end points, ...); the
// language checks them first and reports errors with their positions (lang/stmt_solids.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "quadrix/math/mat4.h"
#include "quadrix/math/plane_or_quadric.h"
#include "quadrix/math/quadric.h"

namespace quadrix::model {

struct SolidSurface : PlaneOrQuadric {
    std::string suffix;  // appended to the solid's id
    bool isCap = false;  // an end plane of an axial solid (made transparent by =open)

    SolidSurface Transformed(const Transform& t) const;
};

struct SolidShape {
    std::vector<SolidSurface> surfaces;  // the solid is their intersection

    SolidShape Transformed(const Transform& t) const;
    bool Contains(const Vec3& p) const;
};

// An orthonormal, positively oriented frame (u × v = w) along the segment from → to: w is the
// unit axis, u a unit vector across it, v = w × u. Local coordinates (x, y, z) are measured along
// u, v, w from `from`, so the solid's axis is the local z axis and `to` is at z = length.
struct AxisFrame {
    Vec3 origin, u, v, w;
    double length = 0;

    // The transform mapping local coordinates to world ones (rigid; inverse exact up to rounding).
    Transform WorldFromLocal() const;
};

// nullopt when from and to coincide, or when `uHint` is (nearly) parallel to the axis. Without a
// hint, u is the world axis least aligned with w, made perpendicular to w (exact for axes along
// the world axes: a segment along y gets u = +x, v = −z).
std::optional<AxisFrame> MakeAxisFrame(const Vec3& from, const Vec3& to,
                                       const std::optional<Vec3>& uHint = std::nullopt);

// A cross-section's half-axes: a along u, b along v (a == b: circular).
struct Section {
    double a = 1, b = 1;
    bool Circular() const { return a == b; }
};

// Sphere of radius r about `centre`: <1 1 1 0 0 0 −cx −cy −cz |c|²−r²>.
SolidShape MakeSphere(const Vec3& centre, double r);
// Ellipsoid about the origin with half-axes a, b, c along x, y, z: <1/a² 1/b² 1/c² 0 ... −1>.
SolidShape MakeEllipsoid(double a, double b, double c);
// Cylinder along the frame's axis from z = 0 to z = length, capped by planes "#0" and "#1".
SolidShape MakeCylinder(const AxisFrame& frame, Section s);
// Cone frustum: section s0 at `from`, s1 at `to` (same shape: s0.a·s1.b == s1.a·s0.b; one may be
// zero, an apex). The surface is the double cone through both sections; the caps keep one nappe.
// Equal sections give a cylinder.
SolidShape MakeCone(const AxisFrame& frame, Section s0, Section s1);
// Axis-aligned box between two corners (any order; coordinates must differ).
SolidShape MakeBox(const Vec3& corner0, const Vec3& corner1);
// Paraboloid with its apex at `from`, opening toward `to`, where its section is s; capped by "#1".
SolidShape MakeParaboloid(const AxisFrame& frame, Section s);
// Hyperboloid of one sheet, symmetric about the middle of from → to: section s at both caps,
// waist (the narrowest section, at the middle) waistRatio·s, 0 < waistRatio < 1.
SolidShape MakeHyperboloid1(const AxisFrame& frame, Section s, double waistRatio);
// Hyperboloid of two sheets, symmetric about the middle of from → to: the sheets' vertices are
// `gap` apart about the middle (0 < gap < length), each sheet opens toward its cap, where its
// section is s. The solid is the two cups inside the sheets between the caps.
SolidShape MakeHyperboloid2(const AxisFrame& frame, Section s, double gap);
// The half-space through `point` whose outward normal is `normal`: <n, −n·p> (n as given).
SolidShape MakeHalfSpace(const Vec3& point, const Vec3& normal);

// Quartic solids (math/quartic_surface.h; valid parameters as QuarticSurface's constructors
// check them, which return the reason otherwise). The curved surface has suffix "".
// Torus about `axis` through `center`, major radius R, minor r (0 < r < R).
SolidShape MakeTorus(const QuarticSurface& torus);
// Elliptical torus (BRL-CAD eto).
SolidShape MakeEllipticalTorus(const QuarticSurface& eto);
// General truncated cone (BRL-CAD tgc, non-similar ends): the quartic "" and its caps "#0" (base,
// T >= 0) and "#1" (top, T <= 1), as MakeCylinder's.
SolidShape MakeGeneralCone(const QuarticSurface& cone);

}  // namespace quadrix::model
