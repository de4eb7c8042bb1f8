#include "quadrix/shade/phong.h"

#include <cmath>

#include "quadrix/shade/lighting.h"

namespace quadrix {

PhongTerms PhongAt(const std::vector<scene::Light>& lights, const Vec3& point, const Vec3& normal,
                   const Vec3& towardViewer, const Reflectance& m, const ShadowTest& inShadow,
                   const std::vector<Incident>* fixed) {
    PhongTerms t;
    for (std::size_t k = 0; k < lights.size(); ++k) {
        const scene::Light& light = lights[k];
        const bool isFixed = fixed && (light.kind == scene::Light::Kind::kAmbient ||
                                       light.kind == scene::Light::Kind::kParallel);
        const Incident in = isFixed ? (*fixed)[k] : IncidentLight(light, point);
        if (in.ambient) {
            t.diffuse.r += in.rgb.r;
            t.diffuse.g += in.rgb.g;
            t.diffuse.b += in.rgb.b;
            continue;
        }
        const double nl = Dot(normal, in.toLight);
        if (!(nl > 0)) continue;  // the light is behind the surface: no diffuse, no highlight
        if (inShadow && inShadow(k, in)) continue;
        // seed 001 (6.1): only θ < π/2 contributes.
        t.diffuse.r += in.rgb.r * m.diffuse * nl;
        t.diffuse.g += in.rgb.g * m.diffuse * nl;
        t.diffuse.b += in.rgb.b * m.diffuse * nl;
        if (!(m.specular > 0)) continue;
        double c;
        if (m.blinn) {
            c = Dot(normal, Normalize(in.toLight + towardViewer));
        } else {
            const Vec3 r = normal * (2 * nl) - in.toLight;  // mirror direction of l about n
            c = Dot(r, towardViewer);
        }
        if (!(c > 0)) continue;
        const double s = m.specular * std::pow(c, m.shininess);
        t.specular.r += in.rgb.r * s;
        t.specular.g += in.rgb.g * s;
        t.specular.b += in.rgb.b * s;
    }
    return t;
}

ViewerGeometry::ViewerGeometry(const Projection& projection)
    : perspective_(projection.perspective),
      eye_(projection.eye),
      towardViewer_(Normalize(projection.towardViewer)),
      worldFromDevice_(projection.deviceFromWorld.Inverted()) {}

Vec3 ViewerGeometry::TowardViewer(const Vec3& worldPoint) const {
    if (!perspective_) return towardViewer_;
    return Normalize(eye_ - worldPoint);
}

}  // namespace quadrix
