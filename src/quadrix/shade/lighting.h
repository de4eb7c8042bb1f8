// Light arriving at a world point from one scene::Light (scene.h; docs/language.md §3.7):
//
//   ambient   no direction; I = intensity · color
//   parallel  l = normalize(direction); I = intensity · color
//   point     l = normalize(position - p); I = intensity · color (no distance fall-off, as
//             POV-Ray's default fade_power 0)
//   spot      as point, times the spot factor of the angle θ between the spot axis
//             a = normalize(aim - position) and the ray from the light to p:
//               1 for θ <= cone, 0 for θ >= falloff, and between them the smoothstep
//               s²(3 - 2s) of s = (cos θ - cos falloff)/(cos cone - cos falloff),
//             which is continuous with a continuous derivative at both ends.
#pragma once

#include "quadrix/math/vec.h"
#include "quadrix/scene/scene.h"

namespace quadrix {

struct Incident {
    bool ambient = false;
    Vec3 toLight;      // unit, world space (not for ambient)
    scene::Color rgb;  // intensity · color after the spot factor
};

// The light from `light` at world point `p`; intensity 0 outside a spot's cone.
Incident IncidentLight(const scene::Light& light, const Vec3& p);

// The spot factor for cos θ (see above); exposed for tests.
double SpotFactor(double cosTheta, double coneDegrees, double falloffDegrees);

}  // namespace quadrix
