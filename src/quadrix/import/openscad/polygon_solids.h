// OpenSCAD's polygonal solids as exact plane/quadric Shapes (shapes/shape.h): what a model
// gets when $fn makes a circle a polygon, and the extrusions of 2D polygons.
//
// Fragments. OpenSCAD draws a circle of radius r with n = get_fragments_from_r(r) sides:
//   r < 1e-5 → 3;  $fn > 0 → max($fn, 3);  else ceil(max(min(360/$fa, 2πr/$fs), 5))
// with vertices at angles 360°·i/n (OpenSCAD manual, "$fa, $fs and $fn"). Quadrix draws the exact
// circle unless the polygon is what the author asked for: PolygonSides returns n when
// n <= kMaxPolygonSides and either $fn > 0 or $fa/$fs differ from OpenSCAD's defaults (12°, 2 mm);
// OpenSCAD's own .csg export writes "$fn = 0, $fa = 12, $fs = 2" on every primitive, which stays an
// exact circle. So cylinder(r=10, h=6, $fn=6) is a hexagonal prism, $fn=64 an exact cylinder.
//
// Polygons → convex pieces: a trapezoidal decomposition. The y values of all vertices (and of
// edge crossings, so that self-intersecting outlines work) cut the plane into slabs; inside a slab
// no edges cross, so the edges spanning it sorted by x pair up (even-odd rule, which is how
// OpenSCAD reads a polygon with several paths: holes) into trapezoids, each the intersection of 4
// half-planes. Neighbouring slabs share their cut line with opposite signs (exact seams).
//
// linear_extrude(height h, center, scale s, twist 0): a trapezoid a·x + b·y + c <= 0 (each edge)
// extruded with the section scaled by σ(z) = 1 + (s − 1)(z − z0)/h about the z axis is
// a·x + b·y + c·σ(z) <= 0 — still a plane, so a scaled extrusion of a polygon is planes too.
//
// rotate_extrude (angle 360) of a polygon in the half-plane x >= 0, x = radius, y = height: a
// trapezoid between heights z0, z1 with edges x = L(z) (right) and x = M(z) (left), both linear
// and >= 0 on [z0, z1], revolves to z0 <= z <= z1, r² − L(z)² <= 0 (a cone, a cylinder when L is
// constant) and r² − M(z)² >= 0 (the complement of a cone, dropped when M ≡ 0): on [z0, z1],
// r <= L ⟺ r² <= L² because L >= 0 there, and the same for M.
//
// rotate_extrude with n fragments (n = PolygonSides of the profile's largest x; OpenSCAD 2021.01
// puts the vertices at θ_i = 180° + 360°·i/n): each profile vertex (x, z) sweeps the n-gon of
// radius x, and between θ_i and θ_i+1 the face swept by a profile edge joins two parallel chords,
// so it is planar. With u = x·cos φ + y·sin φ, φ the wedge's bisector, a chord at radius r lies on
// u = r·cos(180°/n); a trapezoid of the profile in wedge i is z0 <= z <= z1, the two half-planes
// of the wedge through the z axis, u <= cos(180°/n)·L(z) and u >= cos(180°/n)·M(z) (dropped when
// M ≡ 0): planes only, n bodies per trapezoid.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "quadrix/import/shapes/shape.h"

namespace quadrix::import::scad {

inline constexpr int kMaxPolygonSides = 12;

struct Specials {
    double fn = 0, fa = 12, fs = 2;
};

// OpenSCAD's fragment count for radius r.
int Fragments(double r, const Specials& s);
// n when the circle of radius r is drawn as an n-gon (see above), nullopt for the exact circle.
std::optional<int> PolygonSides(double r, const Specials& s);

struct Pt2 {
    double x = 0, y = 0;
};
using Ring = std::vector<Pt2>;

struct Trapezoid {
    double y0 = 0, y1 = 0;
    // Edges as x = p + q·y: left (smaller x) and right.
    double pl = 0, ql = 0, pr = 0, qr = 0;
};
// Even-odd decomposition of the rings (any orientation, holes allowed).
std::vector<Trapezoid> Trapezoids(const std::vector<Ring>& rings);

// The OpenSCAD n-gon of radius r about the origin (vertex i at 360°·i/n).
Ring RegularPolygon(double r, int n);

// Polyhedral forms of the round primitives, in the primitive's own coordinates.
Shape PolygonalCylinder(double r1, double r2, double z0, double h, int n);
std::optional<Shape> PolygonalSphere(double r, int n);

// Extrusions; an empty optional with *problem set when the profile cannot be used.
Shape LinearExtrude(const std::vector<Ring>& rings, double z0, double h, double scale);
// rotate_extrude: exact (cones) unless `specials` make its circle an n-gon (PolygonSides of the
// profile's largest radius), then n planar wedges as OpenSCAD draws them.
std::optional<Shape> RotateExtrude(const std::vector<Ring>& rings, const Specials& specials,
                                   std::string* problem);

}  // namespace quadrix::import::scad
