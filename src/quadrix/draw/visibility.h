// Visibility of trimmed curve pieces (docs/drawings.md), decided by exact ray casts toward the
// viewer, not by a raster.
//
// A point p of a curve is visible when nothing opaque lies in front of it on its ray:
// SceneProbe::FirstOpaqueHit(p.x, p.y) >= p.z − τ, with τ = 1e-7 · max(image side, |p.z|)
// device units (p lies on the boundary itself, so the hit is p up to the rounding of the ray's
// roots, about 1e-13 of the depth, or 1e-7 at a silhouette where the ray is tangent: there the
// root error is the square root of the rounding). Along a piece the predicate is sampled every
// `step` pixels of projected length (default 0.5 px), and wherever two neighbouring samples
// differ the change point is found by bisection on the ray test down to the last bit of the
// parameter (60 halvings). An occluder narrower than `step` in projection can be missed: that is
// the only sampling in the drawer, and it is stated, not hidden.
#pragma once

#include <vector>

#include "quadrix/draw/curve.h"
#include "quadrix/draw/scene_probe.h"
#include "quadrix/draw/trim.h"

namespace quadrix::draw {

bool PointVisible(SceneProbe& probe, const Vec3& p);

struct VisibilityCounters {
    long long rayTests = 0;
    int changes = 0;
};

// Splits every piece where its visibility changes; sets CurvePiece::visible.
std::vector<CurvePiece> SplitByVisibility(const std::vector<Curve3>& curves,
                                          const std::vector<CurvePiece>& pieces, SceneProbe& probe,
                                          double step, VisibilityCounters& counters);

}  // namespace quadrix::draw
