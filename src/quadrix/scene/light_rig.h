// The default light rig: the lights of a scene that declares none (issue 17, docs/language.md
// §3.7). UniQuadrix's `light default 1 0 0 -1` is fixed in world space, so every face parallel
// to z (and, for the default view, every top face) is black; the rig follows the view instead, as
// OpenSCAD's preview and BRL-CAD rt's default lighting do:
//
//   ambient    0.2
//   headlight  0.5  parallel, toward the viewer (t)
//   key light  0.3  parallel, from above left and in front: normalize(t + up - 0.5 right)
//
// A visible surface faces the viewer (n·t > 0 for a parallel view), so the headlight lights every
// visible pixel and the ambient term keeps even grazing ones at 0.2 of their color. The three
// intensities sum to 1, and the headlight and key light are 45° or more apart, so the Lambert sum
// never reaches the shader's saturation at 1 (which keeps POV-Ray's unclamped sum the same).
#pragma once

#include <vector>

#include "quadrix/math/vec.h"
#include "quadrix/scene/scene.h"

namespace quadrix::scene {

constexpr double kRigAmbient = 0.2, kRigHeadlight = 0.5, kRigKey = 0.3;

// The rig for a view with world-space unit vectors toward the viewer, screen right and screen up.
std::vector<Light> DefaultRig(const Vec3& towardViewer, const Vec3& right, const Vec3& up);

}  // namespace quadrix::scene
