// The picture defaults (docs/shading.md "Defaults"): what a picture gets unless told otherwise —
// `quadrix render`, and every frame of an animation, a turntable or a batch job alike:
//   - shadows, when the scene declares a light that can cast one (not the default rig);
//   - anti-aliasing, kDefaultAaSamples samples per edge pixel (box filter);
// both only for scenes of at most kPictureDefaultBodies bodies (the cost of their rays, which the
// box trees of math/box_tree.h bound); asked for explicitly they are still done. They depend on the
// flat scene (its lights and bodies), so they are applied after flattening, frame by frame.
#pragma once

#include <cstddef>
#include <string>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/shade/shader.h"

namespace quadrix {

// --aa's default: samples per edge pixel (measured on the machined part, docs/shading.md).
constexpr int kDefaultAaSamples = 4;
// Scenes with more bodies get neither default shadows nor default anti-aliasing (their cost).
// With the box trees of the shadow and sample rays (math/box_tree.h) 10,000 spheres − a cylinder
// at 640×360 take 0.85 s with shadows and 1.5 s with --aa 4 (docs/shading.md), so only scenes
// beyond what was measured are left out.
constexpr std::size_t kPictureDefaultBodies = 20000;
// Nor scenes with a body of more literals: the box trees skip solids and CSG children, never the
// literals of one body, so every sample or shadow ray that meets it evaluates all of them (one
// body of 10⁵ literals: 17 s of anti-aliasing at 64×64, docs/performance.md). Asked for
// explicitly they are done under the shading budget (shade_budget.h).
constexpr std::size_t kPictureDefaultLiterals = 1024;

// Which of the options the request leaves to the defaults.
struct PictureDefaults {
    // Shadows when the scene declares lights; false: --no-shadows (or shadows given as asked).
    bool shadows = true;
    // kDefaultAaSamples; false: the request's aaSamples stand (--aa N, --aa off).
    bool antialiasing = true;
};

// Whether the scene declares a light that can cast a shadow (not the default rig).
bool DeclaresLights(const FlatScene& flat);

// Sets options.shadows and options.aaSamples where `defaults` leaves them open. Returns a note
// ("... bodies: no default shadows ...") when the scene is too big for the defaults, else empty.
std::string ApplyPictureDefaults(const FlatScene& flat, const PictureDefaults& defaults,
                                 ShadeOptions& options);

// --aa's value ("off", "4", "16", "64" or "default") → samples (0 = off); error or empty.
std::string ParseAaSamples(const std::string& text, int& samples);

}  // namespace quadrix
