// Flattener (seed 001 §3.3): scene hierarchy to world space, view to device space.
//
// Steps:
//  1. Depth-first traversal of instances/arrays, composing transforms (copy k of an array is
//     placed by delta^k * init; deltas accumulate) and applying the composed transform to each
//     body's half-spaces (planes p' = M^-T p, quadrics Q' = M^-T Q M^-1, DESIGN.md).
//  2. The view (defaults of §2.1.6 applied) gives viewFromWorld; parallel projection is affine,
//     perspective a projective map with the eye at the origin of a left-handed (u, v, n) frame.
//  3. Clipping: fbp adds a front and a back transparent plane to every body; perspective adds a
//     near plane (and the plane at infinity's image) so nothing behind the eye survives.
//     A section plane (FlattenOptions::section) is one more literal of every body, but opaque:
//     since (A ∪ B) ∩ P = (A ∩ P) ∪ (B ∩ P) and (A − B) ∩ P = (A ∩ P) − (B ∩ P), cutting every
//     body cuts every CSG solid, and the cut faces are the plane's own, drawn exactly by every
//     engine. Like fbp, it has no effect on auto-scaling (the window is that of the uncut scene).
//  4. Window: whh and/or whw give the window on the view plane, centred on vrp (one alone sets
//     the scale, the other follows from the image's aspect); with neither, the window is fitted
//     to the extent of the bounded solids (conservative device-space bounds), and unbounded ones
//     (a ground plane) are drawn clipped to it (window_fit.h). Pixels stay square: the window is
//     fitted inside the image and centred.
//  5. Device: x = column, y = row (row 0 at the top), z grows away from the viewer.
//  6. Bounds: every body, CSG node and solid gets conservative device-space bounds. In parallel
//     views without clip planes a body that is a translate of an earlier one gets that one's box
//     moved (flattener.cpp); the solids deciding the auto-fit window or the culling are always
//     bounded directly, so both are those of the direct bounds.
//
// Errors (user tier): unknown view, nothing bounded and no window, a view whose vectors are
// degenerate (vup parallel to vpn, zero vectors, cop on the view plane), an empty scene, a
// section plane without a normal or with a coefficient that is not finite.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/flatten/hierarchy.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix {

struct FlattenOptions {
    int width = 512;
    int height = 512;
    std::string viewName;  // empty = the last view defined (or the default view)
    // A view given directly (the viewer's camera, a turntable frame, --camera): replaces
    // viewName. Its id names it in the flat scene (FlatScene::viewName).
    std::optional<scene::View> view;
    // Fraction of the image left free around an auto-fitted scene, per side.
    double autoFitMargin = 0.02;
    // Lights to shade with instead of the scene's (uq's current light); the default parallel
    // light is added to them when they have none, as to the scene's (Scene::LightsToUse).
    std::optional<std::vector<scene::Light>> lights;
    // A section (clipping) plane in WORLD coordinates: only the part of the scene where
    // A x + B y + C z + D <= 0 is kept (a plane statement's inside, docs/language.md §3.1), and
    // the cut is drawn as a face of each solid it crosses. Its half-space is an opaque plane
    // named kSectionName (which no scene name can be), shared by every body.
    std::optional<Plane> section;
    // Bodies that are translates of another (parallel views without clip planes) reuse its box
    // moved by the shift (flattener.cpp); off only to compare with direct bounds in tests.
    bool reuseBoundsByTranslation = true;
    // Bodies whose reader gave their extent (scene::Body::extent: imported primitives) take
    // their box from it under the same conditions (flattener.cpp); off only to compare with
    // direct bounds in tests.
    bool boundsFromExtents = true;
    // Names of the half-spaces (FlatHalfSpace::name: paths such as "stack[1]/tube/outer"), which
    // pickers and the library show. A command that shows none (a one-shot render: its messages
    // name solids and bodies) leaves them empty: for a big model they are the walk's most
    // frequent allocation. Bodies and solids are always named, and so is a half-space in a
    // message of the walk.
    bool halfSpaceNames = true;
};
inline constexpr const char* kSectionName = "<section>";

// nullopt (with errors in diags) when the scene cannot be flattened. One-shot: the walk maps each
// half-space from its object space into the view with one composed transform.
std::optional<FlatScene> Flatten(const scene::Scene& scene, const FlattenOptions& options,
                                 Diagnostics& diags);

// The two stages, for callers that draw one scene from many views (the render context: the
// viewer's next frame, an animation's next camera, a turntable). What a view change invalidates
// is the view stage only:
//   FlattenWorld  step 1, independent of the view, image size, lights and section: the walk of
//                 definitions, instances, arrays and CSG (hierarchy.h) with every half-space in
//                 WORLD coordinates (rescaled, coefficient_scale.h); no clip planes, no bounds.
//   FlattenView   steps 2-6 on a kept WorldScene: each half-space mapped once more by the view's
//                 provisional map (and rescaled), the clip and section planes put in front, the
//                 bounds, the window fit, the device map and the culling.
// FlattenView(FlattenWorld) gives the same solids, bodies, ids and names as Flatten; a half-space
// of an instance is mapped twice (object → world, world → view) instead of once, so its
// coefficients can differ in the last bits (a half-space of the top scope is mapped by the
// identity first: bit for bit the same). The literal guard (HierarchyLimits::maxLiterals) is
// applied in the world stage with the most clip literals any view appends
// (kMostClipLiteralsPerBody).
struct WorldScene {
    // halfSpaces, bodies (literals index halfSpaces; bounds unset), nodes, solids and freeforms.
    FlatScene flat;
    HierarchyResult hierarchy;  // source locations (halfSpaceLocs: per world half-space)
};
inline constexpr int kMostClipLiteralsPerBody = 3;  // front/near, back/far, section

std::optional<WorldScene> FlattenWorld(const scene::Scene& scene, Diagnostics& diags);
// `recycle`: a flat scene no longer needed (the previous view's), whose half-spaces, bodies,
// nodes and solids are assigned over instead of made afresh and freed (their vectors and names
// keep their storage: for a big model the frees and allocations were a fifth of a view change).
// The result is the same either way.
std::optional<FlatScene> FlattenView(const scene::Scene& scene, const WorldScene& world,
                                     const FlattenOptions& options, Diagnostics& diags,
                                     FlatScene recycle = {});

}  // namespace quadrix
