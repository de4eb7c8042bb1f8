// Shadow rays through the CSG (issue 17, deliverable 3): is the segment from a shaded surface
// point toward a light blocked by a solid of the scene?
//
// The shadow ray is a device-space line p + s·d in an arbitrary direction (not along z as the
// engines' rays), so each literal is evaluated along it directly, the same way raycast does along
// z (engines/raycast/ray_literal.h):
//   plane    P(p + s d) = (n·d) s + P(p)
//   quadric  Q(p + s d) = (dᵀA d) s² + 2 ((A p + b)·d) s + Q(p)      (A, b: quadric.h)
// solved by SolveQuadratic (math/quadratic.h); the literal's set is where the polynomial is <= 0
// (regularised: tangent rays give no point interval), the complemented literal its closed
// complement. Bodies intersect their literals (transparent ones bound too, and the clip planes
// the Flattener appends keep clipped-away geometry from casting shadows), CSG nodes combine their
// children's interval lists (math/interval_list.h), and the point is in shadow when some solid's
// set meets s in (ε, sMax). ε = 1e-4 pixel along the ray keeps a surface from shadowing itself
// where the ray leaves it (the set's end at s ≈ 0 carries the rounding of the hit point).
//
// Limits: parallel projections only (the device map of a perspective view is projective, so a
// world segment toward a light at infinity is not a device segment; Shade() skips shadows there);
// only solids the Flattener kept (those whose bounds meet the image) cast shadows; every solid is
// tested per shadow ray behind a bounding-box test, and so is every CSG node (no spatial index),
// so the cost grows with the number of solids.
#pragma once

#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/interval_list.h"

namespace quadrix {

class ShadowTester {
  public:
    explicit ShadowTester(const FlatScene& scene) : scene_(scene) {}

    // True when a solid's set meets p + s·d for some s in (ε/|d|, sMax), p and d in device space.
    bool Blocked(const Vec3& p, const Vec3& d, double sMax) const;

    // The set of s where a half-space literal holds on the line (exposed for tests).
    static IntervalList LiteralOnLine(const FlatHalfSpace& h, bool complemented, const Vec3& p,
                                      const Vec3& d);

  private:
    // The node's set on the line; exact on (s0, s1), where children whose boxes the segment
    // misses are taken as ∅.
    IntervalList Node(int node, const Vec3& p, const Vec3& d, double s0, double s1) const;
    const FlatScene& scene_;
};

}  // namespace quadrix
