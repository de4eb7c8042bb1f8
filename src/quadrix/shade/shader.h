// Shader (seed 001 §6.1): ambient plus Lambert parallel lights, saturating at 1.
//
//   i = min(1, Σ ambient + Σ_parallel intensity · max(0, n·l)) · color
//
// n is the Frame's world-space normal (facing the viewer), l the unit vector toward a parallel
// light. The paper shades with one parallel light (the last); Quadrix sums every parallel light,
// which is the same when there is one. Gray when no solid has a color, RGB otherwise.
// "Fast" shading (the -f option, §2.1.5) gives every (surface, body) pair one constant intensity
// computed from the mean of its visible normals: the flat look the paper used for debugging.
#pragma once

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"

namespace quadrix {

struct ShadeOptions {
    bool fast = false;
    scene::Color background{0, 0, 0};
    bool forceColor = false;  // RGB output even when every solid is white
};

Image Shade(const Frame& frame, const FlatScene& scene, const ShadeOptions& options = {});

// Intensity of a surface with world normal n under the scene's lights (before color, in [0,1]).
double LambertIntensity(const FlatScene& scene, const Vec3& n);

}  // namespace quadrix
