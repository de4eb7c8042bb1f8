// Candidate curves of a hidden-line drawing (docs/drawings.md): every curve that can be part of
// the solids' boundary edges or outlines, before trimming (trim.h) and visibility (visibility.h).
//
//  1. Surfaces. Half-spaces with the same surface (equal coefficients up to a non-zero factor,
//     either sign: `top` and `!bottom_of_the_next_body`) are merged into one representative, so
//     that coincident faces give one curve, not two overlapping ones. Each representative carries
//     the union of the device-space bounds of the bodies that use it, clamped to the scene box.
//  2. Edges: for every pair of representatives whose boxes overlap, and at least one of which is
//     opaque, their intersection: plane–plane lines (conic_section.h PlanePlaneLine),
//     plane–quadric conics (PlaneQuadricCurves) and quadric–quadric curves (quartic_trace.h).
//     Pairs that are tangent along a whole line (a double line) give that line, counted apart
//     (tangentPairs): trimming decides whether it is a tangent edge (trim.h) or nothing.
//  3. Silhouettes: every opaque quadric ∩ its limb plane F x + E y + C z + J = 0 (seed 001
//     (4.11)). A quadric independent of z (a cylinder seen along its axis) has no limb plane: its
//     outline is the circle (or conic) its end faces draw, so it gives no silhouette.
#pragma once

#include <vector>

#include "quadrix/draw/curve.h"
#include "quadrix/flatten/flat_scene.h"

namespace quadrix::draw {

struct Surfaces {
    std::vector<int> rep;      // per half-space: its representative half-space (or −1: unused)
    std::vector<int> reps;     // the representatives
    std::vector<Box3> box;     // per half-space (meaningful for representatives)
    std::vector<bool> opaque;  // per half-space: some half-space of its class is opaque
};

// The scene box: the union of the solids' finite device bounds, clamped to a generous margin
// around the image (unbounded solids are drawn within it). Empty when nothing can be drawn.
Box3 SceneBox(const FlatScene& scene);

Surfaces ClassifySurfaces(const FlatScene& scene, const Box3& sceneBox);

struct ExtractionCounters {
    int lines = 0, conics = 0, silhouettes = 0, quartics = 0, tangentPairs = 0;
};

std::vector<Curve3> ExtractCurves(const FlatScene& scene, const Surfaces& surfaces,
                                  const Box3& sceneBox, ExtractionCounters& counters);

// The limb plane of a quadric for rays along z (seed 001 (4.11)); false when it does not exist
// (the quadric does not depend on z to first order: C = E = F = 0).
bool LimbPlaneOf(const Quadric& q, Plane& out);

}  // namespace quadrix::draw
