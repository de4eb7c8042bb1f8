#include "quadrix/shade/lighting.h"

#include <cmath>

namespace quadrix {

double SpotFactor(double cosTheta, double coneDegrees, double falloffDegrees) {
    const double cosCone = std::cos(coneDegrees * M_PI / 180);
    const double cosFall = std::cos(falloffDegrees * M_PI / 180);
    if (cosTheta >= cosCone) return 1;
    if (cosTheta <= cosFall) return 0;
    const double s = (cosTheta - cosFall) / (cosCone - cosFall);  // cone > falloff in cosine
    return s * s * (3 - 2 * s);
}

Incident IncidentLight(const scene::Light& light, const Vec3& p) {
    Incident in;
    double k = light.intensity;
    switch (light.kind) {
        case scene::Light::Kind::kAmbient:
            in.ambient = true;
            break;
        case scene::Light::Kind::kParallel:
            in.toLight = Normalize(light.direction);
            break;
        case scene::Light::Kind::kPoint:
        case scene::Light::Kind::kSpot: {
            const Vec3 d = light.position - p;
            const double len = Length(d);
            in.toLight = len > 0 ? d / len : Vec3{0, 0, 0};
            if (light.kind == scene::Light::Kind::kSpot) {
                const Vec3 axis = Normalize(light.aim - light.position);
                k *= SpotFactor(-Dot(in.toLight, axis), light.coneDegrees, light.falloffDegrees);
            }
            break;
        }
    }
    in.rgb = {k * light.color.r, k * light.color.g, k * light.color.b};
    return in;
}

}  // namespace quadrix
