#include "quadrix/engines/patch/phong.h"

#include <algorithm>
#include <cmath>

namespace quadrix::patch {
namespace {

std::uint8_t ToByte(double v) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

}  // namespace

PhongTerms PhongAt(const FlatScene& scene, const Vec3& normal, const Vec3& towardViewer,
                   const PhongOptions& options) {
    PhongTerms t;
    for (const scene::Light& light : scene.lights) {
        if (light.kind == scene::Light::Kind::kAmbient) {
            t.diffuse += light.intensity;
            continue;
        }
        const Vec3 l = Normalize(light.direction);
        const double nl = Dot(normal, l);
        if (nl <= 0) continue;  // the light is behind the surface: no diffuse, no highlight
        t.diffuse += light.intensity * options.diffuse * nl;
        const Vec3 r = normal * (2 * nl) - l;  // mirror direction of l about n
        const double rv = Dot(r, towardViewer);
        if (rv > 0)
            t.specular += light.intensity * options.specular * std::pow(rv, options.shininess);
    }
    t.diffuse = std::min(t.diffuse, 1.0);
    return t;
}

Vec3 TowardViewer(const FlatScene& scene, const Vec3& devicePoint) {
    if (!scene.projection.perspective) return Normalize(scene.projection.towardViewer);
    const Vec3 world = scene.projection.deviceFromWorld.Inverted().MapPoint(devicePoint);
    return Normalize(scene.projection.eye - world);
}

Image PhongShade(const Frame& frame, const FlatScene& scene, const PhongOptions& options) {
    Image image(frame.width, frame.height, 3);
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            const std::size_t i = frame.Index(x, y);
            scene::Color c = options.background;
            if (frame.surface[i] != Frame::kNone) {
                scene::Color base;
                base = scene.SurfaceColor(frame.surface[i], frame.body[i]);
                const Vec3 p{x + 0.5, y + 0.5, frame.depth[i]};
                const PhongTerms t =
                    PhongAt(scene, frame.normal[i], TowardViewer(scene, p), options);
                c = {base.r * t.diffuse + t.specular, base.g * t.diffuse + t.specular,
                     base.b * t.diffuse + t.specular};
            }
            std::uint8_t* px = image.At(x, y);
            px[0] = ToByte(c.r);
            px[1] = ToByte(c.g);
            px[2] = ToByte(c.b);
        }
    return image;
}

}  // namespace quadrix::patch
