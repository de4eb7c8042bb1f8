// Exact point and ray queries on a FlatScene for the hidden-line drawer (docs/drawings.md).
//
// Two questions are asked of the scene, both in DEVICE space (flat_scene.h: rays along +z, z grows
// away from the viewer):
//  - Inside(p): point membership in the union of every solid. A body holds at p when each of its
//    literals does (H: value <= 0, !H: value >= 0); CSG nodes combine the booleans. Used on points
//    a small offset away from a curve, never on a surface, so the closed/open question of the
//    boundary does not arise.
//  - FirstOpaqueHit(x, y): the depth of the visible point on the ray through (x, y): per solid,
//    the set of t where the ray is inside is computed as raycast computes it (each literal's set by
//    eval::LiteralOnRay, bodies intersect, CSG trees combine regularised interval lists,
//    math/interval_list.h); the visible point of a solid is its first finite endpoint on an opaque
//    surface (transparent half-spaces and clipping planes bound but are not drawn), and the nearest
//    solid wins. This is raycast's visible-point rule on an arbitrary ray (not only pixel centres),
//    written as a small recursive evaluator because raycast's own is private to its tiles.
//    One difference: curves lie ON surfaces, so their rays often lie exactly in a plane seen
//    edge-on (or on a cylinder seen along its axis); where such a surface's value on the ray is
//    zero to within rounding (1e-11 relative), the literal is taken to contain the ray (H holds
//    along all of it, !H nowhere: raycast's rule for an exact zero), so that visibility along an
//    edge does not flicker with the sign of rounding errors.
//
// Not thread-safe (scratch lists are members); one probe per thread.
#pragma once

#include <deque>
#include <vector>

#include "quadrix/eval/ray_literal.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/interval_list.h"

namespace quadrix::draw {

class SceneProbe {
  public:
    explicit SceneProbe(const FlatScene& scene);

    // Point membership in the union of all solids.
    bool Inside(const Vec3& p) const;
    // Device z of the nearest opaque boundary point on the ray through (x, y); +inf when none.
    double FirstOpaqueHit(double x, double y);
    // The set of t inside solid `s` on the ray through (x, y) (endpoint ids = half-space index).
    void SolidOnRay(int s, double x, double y, IntervalList& out);

    const FlatScene& scene() const { return scene_; }
    bool Opaque(int halfSpace) const {
        const FlatHalfSpace& h = scene_.halfSpaces[static_cast<std::size_t>(halfSpace)];
        return !h.transparent && !h.isClip;
    }

  private:
    bool InsideNode(int node, const Vec3& p) const;
    bool InsideBody(int body, const Vec3& p) const;
    void NodeOnRay(int node, double x, double y, std::size_t depth, IntervalList& out);
    void BodyOnRay(int body, double x, double y, IntervalList& out);
    IntervalList& Scratch(std::size_t depth, int which);

    const FlatScene& scene_;
    std::vector<eval::RayHalfSpace> rays_;
    std::deque<IntervalList> scratch_;  // 3 lists per recursion depth (deque: stable references)
    IntervalList solidList_, literalList_, tmp_;
};

}  // namespace quadrix::draw
