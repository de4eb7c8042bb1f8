// The reflection models of the shader, per pixel from the Frame's normal (seed 000 §1.3 and
// §1.6: "Shading (true Phong shading can be used [9]) and Z-buffer operations are
// post-processed"; the patch processor's post-shading unit, generalised to every engine's Frame).
//
// World space throughout. n is the Frame's unit normal (facing the viewer), v the unit vector
// toward the viewer, and for each light l the unit vector toward it and I its intensity times its
// color (per channel) at the shaded point (lighting.h):
//
//   diffuse  D = Σ_ambient I + Σ_other I · kd · max(0, n·l)
//   specular S = Σ_other [n·l > 0] · I · ks · max(0, r·v)^shininess,   r = 2(n·l)n - l   (Phong)
//            S = Σ_other [n·l > 0] · I · ks · max(0, n·h)^shininess,   h = (l+v)/|l+v|   (Blinn)
//
// and the shader forms min(1, D) · color + S (the white highlight of plastic). With kd = 1 and
// ks = 0 this is UniQuadrix's Lambert shader (seed 001 §6.1, shade/shader.h). The sums are in
// linear light and evaluated left to right in exactly this order, so that the Lambert case is
// bit-identical to the historical shader (multiplications by 1 are exact).
#pragma once

#include <cstddef>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/vec.h"
#include "quadrix/scene/scene.h"
#include "quadrix/shade/lighting.h"
#include "quadrix/util/function_ref.h"

namespace quadrix {

struct Reflectance {
    double diffuse = 1;     // kd
    double specular = 0;    // ks
    double shininess = 24;  // the exponent
    bool blinn = false;     // Blinn–Phong's half vector instead of Phong's mirror direction
};

// Per-channel sums, before color and saturation.
struct PhongTerms {
    scene::Color diffuse{0, 0, 0};
    scene::Color specular{0, 0, 0};
};

// Whether light k (an index into the lights) is blocked before it reaches the point. A reference
// to the caller's test (util/function_ref.h): the shader makes one per pixel.
using ShadowTest = FunctionRef<bool(std::size_t light, const Incident& incident)>;

// The terms at world point `point` (needed by point and spot lights only). A light for which
// `inShadow` (when given) says true contributes nothing but is asked only where n·l > 0.
// `fixed`, when given, holds IncidentLight(lights[k], ·) for the ambient and parallel lights
// (which do not depend on the point), computed once per picture.
PhongTerms PhongAt(const std::vector<scene::Light>& lights, const Vec3& point, const Vec3& normal,
                   const Vec3& towardViewer, const Reflectance& reflectance,
                   const ShadowTest& inShadow = {}, const std::vector<Incident>* fixed = nullptr);

// The viewer's side of a scene: the unit vector toward the viewer from a world point, and the
// world point seen at a device point. Precomputes the inverse of the device map once.
class ViewerGeometry {
  public:
    explicit ViewerGeometry(const Projection& projection);
    Vec3 WorldPoint(const Vec3& devicePoint) const {
        return worldFromDevice_.MapPoint(devicePoint);
    }
    // Projection::towardViewer for a parallel projection; the direction to the eye for a
    // perspective one.
    Vec3 TowardViewer(const Vec3& worldPoint) const;

  private:
    bool perspective_;
    Vec3 eye_, towardViewer_;
    Transform worldFromDevice_;
};

}  // namespace quadrix
