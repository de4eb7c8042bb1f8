// Export to POV-Ray (Persistence of Vision 3.7) scene text.
//
// The export is written in DEVICE space with an orthographic camera looking along +z: the flat
// scene's planes and quadrics are exported with their device-space coefficients, so POV-Ray
// traces exactly the rays our engines trace (pixel centres, z away from the viewer), for parallel
// and perspective views alike (a perspective view is a projective map, and the image of a quadric
// under it is still a quadric). POV-Ray's space is left-handed with y up; device y runs down, so
// the whole scene is wrapped in `scale <1,-1,1>`.
//
// Mapping (our convention → POV-Ray):
//   plane  A x + B y + C z + D <= 0          → plane { <A,B,C>, -D/|(A,B,C)| }
//   quadric <A B C D E F G H J K>            → quadric { <A,B,C>, <2D,2F,2E>, <2G,2H,2J>, K }
//   complemented literal                     → the object with `inverse`
//   body: opaque literals                    → intersection { … }
//         transparent literals (and clips)   → clipped_by { intersection { … } } (bound, not drawn)
//   CSG union / intersection / difference    → union / intersection / difference
//   (∪ aᵢ) − S, a union of more than 8 operands minus at most 4 subtrahends
//                                            → union { difference { aᵢ S } … } (the same set):
//     POV-Ray bounds a difference by its minuend only, so a ray into the union's box tested
//     every operand; written ∪ (aᵢ − S) each operand is bounded on its own (10,000 spheres − a
//     drill: 47 s → about 2 s in POV-Ray at 1280 × 720). The walk writes both forms of such a
//     solid this way (flatten/hierarchy.h groups ∪ (aᵢ − S) into (∪ aᵢ) − S for Quadrix).
// Lights: ambient lights sum into global ambient_light; parallel lights become `parallel` light
// sources far away in their (device-space) direction; point and spot lights are placed at their
// device-space positions (spot: radius/falloff = cone/falloff, tightness 0). The default rig of a
// scene without lights is exported as the three lights it is. Colors are linear with
// `assumed_gamma 1.0`; rendered with `File_Gamma=sRGB` POV-Ray writes the sRGB-encoded picture
// Quadrix writes. Shading therefore matches for parallel views; for perspective views
// device-space normals differ from world normals (coverage and depth are still exact). Finishes
// map to `finish { diffuse kd specular ks roughness 1/shininess }` (POV-Ray's Blinn highlight);
// opacity to `rgbt` transmit (POV-Ray then shows what is behind, Quadrix the background). The
// background is `background`, or for a gradient an emitting plane behind every solid.
// Mask mode writes every solid as unlit white for coverage comparisons.
#pragma once

#include <string>

#include "quadrix/flatten/flat_scene.h"

namespace quadrix {

struct PovExportOptions {
    bool mask = false;  // white, ambient 1, no lights: coverage masks
    // Solids cast shadows in POV-Ray. Off by default (the union is `no_shadow`), as Quadrix's
    // shader without ShadeOptions::shadows: the export reproduces Quadrix's picture.
    bool shadows = false;
};

std::string ExportPov(const FlatScene& scene, const PovExportOptions& options = {});

}  // namespace quadrix
