// The set of ray parameters where one half-space literal holds (DESIGN.md "Engines in more
// detail", raycast).
//
// A pixel's ray is x(t) = (x, y, t) in device space (x = i + ½, y = j + ½, t = device z, growing
// away from the viewer). Along it
//   plane   <A B C D>:  P(t) = C t + (A x + B y + D)
//   quadric <A … K>:    Q(t) = C t² + 2 (F x + E y + J) t + (A x² + B y² + 2D xy + 2G x + 2H y + K)
// (UniQuadrix coefficient order with the factor 2 on cross and linear terms, quadric.h), i.e. the
// "c z² + 2 b z + a" of DESIGN.md; the quadratic is solved by SolveQuadratic (math/quadratic.h).
//
// The literal H holds where P or Q <= 0, which on a ray is an interval, the complement of one
// (double cones, two-sheet hyperboloids, a cylinder seen sideways from outside …), everything or
// nothing. The complemented literal !H is the closure of the complement. Sets follow the
// regularised convention of math/interval_list.h: a ray that only touches a surface (a tangent ray,
// a ray through a cone's apex) gets no degenerate point interval, and a plane containing the ray
// (C = 0 and A x + B y + D = 0) holds along all of it while its complement holds nowhere.
// Non-finite coefficients along the ray (NaN, or overflow far from the origin) give the empty set
// for both H and !H: the body that uses the literal is not drawn there.
#pragma once

#include <cstdint>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/interval_list.h"

namespace quadrix::raycast {

// A half-space's coefficients regrouped for evaluation along rays parallel to z.
struct RayHalfSpace {
    bool isPlane = true;
    // Plane: P = c t + (ax x + by y + d).
    // Quadric: Q = c t² + 2 (hx x + hy y + h0) t + (x (axx x + axy y + ax) + y (byy y + by) + k0).
    double c = 0;
    double hx = 0, hy = 0, h0 = 0;                  // quadric half-linear term
    double axx = 0, axy = 0, ax = 0, byy = 0, by = 0, k0 = 0;  // quadric constant term
    double px = 0, py = 0, pd = 0;                  // plane constant term

    static RayHalfSpace From(const FlatHalfSpace& hs);
};

// What evaluating a literal cost (for RenderStats).
struct LiteralCounters {
    std::uint64_t planes = 0;
    std::uint64_t quadrics = 0;
};

// Writes into `out` the set of t where the literal holds on the ray through (x, y); finite
// endpoints carry `id`, infinite ones Interval::kNoId.
void LiteralSetOnRay(const RayHalfSpace& hs, bool complemented, double x, double y,
                     std::int32_t id, IntervalList& out, LiteralCounters& counters);

}  // namespace quadrix::raycast
