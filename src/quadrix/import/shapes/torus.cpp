// Tori and elliptical tori (torus.h).
#include "quadrix/import/shapes/torus.h"

#include <cmath>
#include <string>

#include "quadrix/import/shapes/local_frame.h"
#include "quadrix/math/quartic_surface.h"

namespace quadrix::import {

namespace {

ShapeResult OneQuartic(const QuarticSurface& q) {
    ShapeResult r;
    r.ok = true;
    ShapeHalfSpace h;
    h.SetQuartic(q);
    r.shape.bodies.push_back({h});
    return r;
}

}  // namespace

ShapeResult TorusShape(const Vec3& centre, const Vec3& axis, double R, double r) {
    std::string why;
    auto q = QuarticSurface::Torus(centre, axis, R, r, &why);
    if (!q) return {false, why, {}};
    ShapeResult s = OneQuartic(*q);
    const Vec3 n = Normalize(axis), e1 = AnyPerpendicular(n), e2 = Cross(n, e1);
    s.shape.extentSums.push_back(
        {{centre, e1 * R, e2 * R, {}}, {{}, {r, 0, 0}, {0, r, 0}, {0, 0, r}}});
    return s;
}

ShapeResult EllipticalTorusShape(const Vec3& centre, const Vec3& axis, double r, const Vec3& c,
                                 double rd) {
    std::string why;
    auto q = QuarticSurface::EllipticalTorus(centre, axis, r, c, rd, &why);
    if (!q) return {false, why, {}};
    ShapeResult s = OneQuartic(*q);
    const Vec3 n = Normalize(axis), e1 = AnyPerpendicular(n), e2 = Cross(n, e1);
    const double lc = Length(c);
    const double cz = Dot(c, n), crho = Length(c - n * cz);
    // The meridian ellipse's half extents along the radius and along the axis.
    const double er = std::sqrt(crho * crho + rd * rd * cz * cz / (lc * lc));
    const double ez = std::sqrt(cz * cz + rd * rd * crho * crho / (lc * lc));
    s.shape.extentSums.push_back(
        {{centre, e1 * r, e2 * r, {}}, {{}, e1 * er, e2 * er, {}}, {{}, n * ez, {}, {}}});
    return s;
}

}  // namespace quadrix::import
