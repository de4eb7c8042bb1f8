// The default light rig: the lights of a scene that declares none (issue 17, docs/language.md
// §3.7). UniQuadrix's `light default 1 0 0 -1` is fixed in world space, so every face parallel
// to z (and, for the default view, every top face) is black; the rig follows the view instead, as
// OpenSCAD's preview and BRL-CAD rt's default lighting do:
//
//   ambient    0.1
//   headlight  0.3  parallel, toward the viewer (t)
//   key light  0.6  parallel, from above, to the left and a little in front:
//                   normalize(0.5 t + up - 0.6 right)
//
// A visible surface faces the viewer (n·t > 0 for a parallel view), so the headlight lights every
// visible pixel and the ambient term keeps even grazing ones at 0.1 of their color; the key
// light, about 67° from the view direction, tells top, front and side faces apart (with the
// default view: top 0.71, front 0.54, left 0.35, right 0.19). The three intensities sum to 1 and
// |0.3 t + 0.6 k| < 0.9, so the Lambert sum never reaches the shader's saturation at 1 (which
// keeps POV-Ray's unclamped sum the same).
#pragma once

#include <vector>

#include "quadrix/math/vec.h"
#include "quadrix/scene/scene.h"

namespace quadrix::scene {

constexpr double kRigAmbient = 0.1, kRigHeadlight = 0.3, kRigKey = 0.6;

// The rig for a view with world-space unit vectors toward the viewer, screen right and screen up.
std::vector<Light> DefaultRig(const Vec3& towardViewer, const Vec3& right, const Vec3& up);

}  // namespace quadrix::scene
