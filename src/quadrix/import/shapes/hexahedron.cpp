// Hexahedra from eight vertices (hexahedron.h).
#include "quadrix/import/shapes/hexahedron.h"

#include <cmath>
#include <vector>

namespace quadrix::import {

namespace {

// The plane of one face through its first three distinct, non-collinear vertices, inside towards
// the centroid; nullopt when the face has no such three or the centroid lies on the plane.
std::optional<ShapeHalfSpace> FacePlane(const std::array<Vec3, 8>& v, const int (&face)[4],
                                        const Vec3& centre) {
    std::vector<Vec3> pts;
    for (int k : face) {
        const Vec3& x = v[k];
        bool dup = false;
        for (const Vec3& q : pts) dup = dup || Length(x - q) < kHexahedronTol;
        if (dup) continue;
        if (pts.size() == 2) {
            Vec3 n = Cross(pts[1] - pts[0], x - pts[0]);
            if (Length(n) < kHexahedronTol * (Length(pts[1] - pts[0]) + Length(x - pts[0])))
                continue;
        }
        pts.push_back(x);
        if (pts.size() == 3) break;
    }
    if (pts.size() < 3) return std::nullopt;
    Vec3 n = Normalize(Cross(pts[1] - pts[0], pts[2] - pts[0]));
    double d = -Dot(n, pts[0]);
    double side = Dot(n, centre) + d;
    if (std::fabs(side) < kHexahedronTol) return std::nullopt;  // the centre lies on it: flat
    if (side > 0) {
        n = -n;
        d = -d;
    }
    ShapeHalfSpace h;
    h.plane = Plane{n.x, n.y, n.z, d};
    return h;
}

}  // namespace

ShapeResult HexahedronShape(const std::array<Vec3, 8>& vertices) {
    ShapeResult r;
    Vec3 centre;
    for (const Vec3& v : vertices) centre += v * 0.125;
    ShapeBody body;
    for (const auto& face : kHexahedronFaces)
        if (auto h = FacePlane(vertices, face, centre)) body.push_back(*h);
    if (body.size() < 4) {
        r.problem = "its vertices do not span a solid";
        return r;
    }
    bool convex = true;
    for (const Vec3& v : vertices)
        for (const ShapeHalfSpace& h : body)
            convex = convex && h.plane.Evaluate(v) <= kHexahedronTol;
    if (!convex) {  // bounded by the box of its vertices (hexahedron.h)
        Box3 box;
        for (const Vec3& v : vertices) box.Extend(v);
        for (int axis = 0; axis < 3; ++axis) {
            ShapeHalfSpace lo, hi;
            Vec3 n;
            n[axis] = 1;
            hi.plane = Plane{n.x, n.y, n.z, -box.hi[axis]};
            lo.plane = Plane{-n.x, -n.y, -n.z, box.lo[axis]};
            body.push_back(hi);
            body.push_back(lo);
        }
    }
    r.ok = true;
    r.shape.bodies.push_back(std::move(body));
    for (const Vec3& v : vertices) r.shape.extent.push_back({v, {}, {}, {}});
    // The vertices are the solid's corners when it is convex and every face's vertices lie on
    // its plane to rounding (a face twisted within kHexahedronTol has a corner elsewhere).
    double reach = 0;
    for (const Vec3& v : vertices) reach = std::fmax(reach, Length(v));
    bool planar = convex;
    for (const auto& face : kHexahedronFaces)
        if (auto h = planar ? FacePlane(vertices, face, centre) : std::nullopt)
            for (int k : face)
                planar = planar && std::fabs(h->plane.Evaluate(vertices[k])) <= 1e-12 * reach;
    r.shape.extentExact = planar;
    return r;
}

ShapeResult BoxShape(const Vec3& lo, const Vec3& hi) {
    return HexahedronShape({Vec3{lo.x, lo.y, lo.z}, Vec3{hi.x, lo.y, lo.z}, Vec3{hi.x, hi.y, lo.z},
                            Vec3{lo.x, hi.y, lo.z}, Vec3{lo.x, lo.y, hi.z}, Vec3{hi.x, lo.y, hi.z},
                            Vec3{hi.x, hi.y, hi.z}, Vec3{lo.x, hi.y, hi.z}});
}

}  // namespace quadrix::import
