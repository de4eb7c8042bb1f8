// Ellipsoids and spheres (ellipsoid.h).
#include "quadrix/import/shapes/ellipsoid.h"

#include "quadrix/import/shapes/local_frame.h"

namespace quadrix::import {

ShapeResult EllipsoidShape(const Vec3& centre, const Vec3& a, const Vec3& b, const Vec3& c) {
    ShapeResult r;
    LocalFrame f(centre, a, b, c);
    if (!f.ok()) {
        r.problem = "the semi-axes A, B, C are degenerate";
        return r;
    }
    r.ok = true;
    r.shape.bodies.push_back({f.Quad(DiagonalQuadric(1, 1, 1, -1))});
    r.shape.extent.push_back({centre, a, b, c});
    r.shape.extentExact = true;
    return r;
}

ShapeResult SphereShape(const Vec3& centre, double r) {
    return EllipsoidShape(centre, {r, 0, 0}, {0, r, 0}, {0, 0, r});
}

}  // namespace quadrix::import
