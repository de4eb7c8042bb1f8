#include "quadrix/shade/shader.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "quadrix/shade/phong.h"
#include "quadrix/shade/shadows.h"

namespace quadrix {

double LambertIntensity(const FlatScene& scene, const Vec3& n) {
    double sum = 0;
    for (const scene::Light& l : scene.lights) {
        if (l.kind == scene::Light::Kind::kAmbient) {
            sum += l.intensity;
        } else if (l.kind == scene::Light::Kind::kParallel) {
            double c = Dot(n, Normalize(l.direction));
            if (c > 0) sum += l.intensity * c;  // seed 001 (6.1): only θ < π/2 contributes
        }
    }
    return std::min(sum, 1.0);
}

namespace {

std::uint8_t ToByte(double v) {
    // Round to nearest (halves up) without a libm call: v·255 + ½ is in (0.5, 255.5) here and
    // the conversion truncates. NaN fails the first test and gives 0.
    if (!(v > 0)) return 0;
    if (v >= 1) return 255;
    return static_cast<std::uint8_t>(v * 255.0 + 0.5);
}

float ToUnit(double v) { return v > 0 ? (v < 1 ? static_cast<float>(v) : 1.0f) : 0.0f; }

bool Gray(const scene::Color& c) { return c.r == c.g && c.g == c.b; }

bool AnyColor(const FlatScene& scene, const ShadeOptions& options) {
    if (options.forceColor) return true;
    if (options.background) {
        if (!Gray(*options.background)) return true;
    } else if (!Gray(scene.background) || !Gray(scene.backgroundBottom)) {
        return true;
    }
    for (const scene::Light& l : scene.lights)
        if (!Gray(l.color)) return true;
    for (const FlatBody& b : scene.bodies)
        if (!(b.color == scene::Color{})) return true;
    for (const FlatFreeform& f : scene.freeforms)
        if (!(f.color == scene::Color{})) return true;
    return false;
}

// The background of row y (a vertical gradient, or one color).
scene::Color BackgroundAt(const FlatScene& scene, const ShadeOptions& options, int y, int height) {
    if (options.background) return *options.background;
    const scene::Color& a = scene.background;
    const scene::Color& b = scene.backgroundBottom;
    if (a == b) return a;
    const double t = height > 1 ? (y + 0.5) / height : 0.5;
    return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

// Whether the shader needs the world point of each pixel: for point and spot lights, and for
// highlights under perspective (the direction to the eye varies).
bool NeedsPoint(const FlatScene& scene, ShadingModel model) {
    for (const scene::Light& l : scene.lights)
        if (l.kind == scene::Light::Kind::kPoint || l.kind == scene::Light::Kind::kSpot)
            return true;
    if (!scene.projection.perspective) return false;
    if (model == ShadingModel::kPhong || model == ShadingModel::kBlinnPhong) return true;
    for (const FlatBody& b : scene.bodies)
        if (b.finish.specular && *b.finish.specular > 0) return true;
    for (const FlatFreeform& f : scene.freeforms)
        if (f.finish.specular && *f.finish.specular > 0) return true;
    return false;
}

// The reflectance of a surface under a model: the finish's properties, else the model's.
Reflectance ReflectanceOf(const scene::Finish& f, const ShadeOptions& o, ShadingModel model) {
    Reflectance r;
    const bool phong = model == ShadingModel::kPhong || model == ShadingModel::kBlinnPhong;
    r.diffuse = f.diffuse.value_or(phong ? o.phongDiffuse : 1.0);
    r.specular = f.specular.value_or(phong ? o.phongSpecular : 0.0);
    r.shininess = f.shininess.value_or(phong ? o.phongShininess : 24.0);
    r.blinn = model != ShadingModel::kPhong;
    return r;
}

}  // namespace

Image Shade(const Frame& frame, const FlatScene& scene, const ShadeOptions& options) {
    const ShadingModel model = options.fast ? ShadingModel::kFast : options.model;
    const bool color = AnyColor(scene, options);
    Image image(frame.width, frame.height, color ? 3 : 1);
    if (options.linear) image.linear.assign(image.pixels.size(), 0.0f);
    const ViewerGeometry viewer(scene.projection);
    const bool needPoint = NeedsPoint(scene, model);
    const bool shadows = options.shadows && !scene.projection.perspective;
    const ShadowTester shadowTester(scene);
    std::vector<Incident> fixedLight;
    for (const scene::Light& l : scene.lights) fixedLight.push_back(IncidentLight(l, {}));
    const Mat4& deviceFromWorld = scene.projection.deviceFromWorld.Matrix();

    // Fast shading: one normal per (surface, body) pair, the mean of its visible normals.
    std::map<std::pair<int, int>, Vec3> meanNormal;
    if (model == ShadingModel::kFast) {
        for (std::size_t i = 0; i < frame.surface.size(); ++i)
            if (frame.surface[i] != Frame::kNone)
                meanNormal[{frame.surface[i], frame.body[i]}] += frame.normal[i];
        for (auto& [key, n] : meanNormal) n = Normalize(n);
    }
    const ShadingModel reflection = model == ShadingModel::kFast ? ShadingModel::kLambert : model;

    // Only ambient and parallel lights, no shadows: every light's incidence is fixed, and the
    // terms are those of PhongAt (same operations, same order) without its per-light dispatch.
    const bool fixedOnly = !needPoint && !shadows;
    const Vec3 towardViewerFixed = viewer.TowardViewer({0, 0, 0});
    const bool keepLinear = options.linear;

    // Rows in parallel (oneTBB): each pixel depends only on its own Frame entry, so the image
    // is the same for any thread count. A row's pixels mostly repeat the previous pixel's
    // (surface, body): its material (color, finish, reflectance) is looked up once per run.
    auto shadeRows = [&](const tbb::blocked_range<int>& rows) {
        std::int32_t lastSurface = Frame::kNone, lastBody = Frame::kNone;
        scene::Finish finish;
        Reflectance m;
        scene::Color base;
        for (int y = rows.begin(); y < rows.end(); ++y) {
            const scene::Color background = BackgroundAt(scene, options, y, frame.height);
            const std::uint8_t bg[3] = {ToByte(background.r), ToByte(background.g),
                                        ToByte(background.b)};
            const float bgf[3] = {ToUnit(background.r), ToUnit(background.g),
                                  ToUnit(background.b)};
            const std::size_t row = frame.Index(0, y);
            std::uint8_t* prow = image.At(0, y);
            float* frow = keepLinear ? &image.linear[row * image.channels] : nullptr;
            for (int x = 0; x < frame.width; ++x) {
                const std::size_t i = row + static_cast<std::size_t>(x);
                std::uint8_t* p = prow + static_cast<std::size_t>(x) * image.channels;
                const std::int32_t surface = frame.surface[i];
                if (surface == Frame::kNone) {
                    p[0] = bg[0];
                    if (color) p[1] = bg[1], p[2] = bg[2];
                    if (frow) {
                        float* f = frow + static_cast<std::size_t>(x) * image.channels;
                        f[0] = bgf[0];
                        if (color) f[1] = bgf[1], f[2] = bgf[2];
                    }
                    continue;
                }
                const std::int32_t bodyIndex = frame.body[i];
                if (surface != lastSurface || bodyIndex != lastBody) {
                    lastSurface = surface;
                    lastBody = bodyIndex;
                    finish = scene.SurfaceFinish(surface, bodyIndex);
                    m = ReflectanceOf(finish, options, reflection);
                    base = scene.SurfaceColor(surface, bodyIndex);
                }
                const Vec3 n = model == ShadingModel::kFast
                                   ? meanNormal.find({surface, bodyIndex})->second
                                   : frame.normal[i];
                PhongTerms t;
                if (fixedOnly) {
                    for (const Incident& in : fixedLight) {
                        if (in.ambient) {
                            t.diffuse.r += in.rgb.r;
                            t.diffuse.g += in.rgb.g;
                            t.diffuse.b += in.rgb.b;
                            continue;
                        }
                        const double nl = Dot(n, in.toLight);
                        if (!(nl > 0)) continue;
                        t.diffuse.r += in.rgb.r * m.diffuse * nl;
                        t.diffuse.g += in.rgb.g * m.diffuse * nl;
                        t.diffuse.b += in.rgb.b * m.diffuse * nl;
                        if (!(m.specular > 0)) continue;
                        double c;
                        if (m.blinn) {
                            c = Dot(n, Normalize(in.toLight + towardViewerFixed));
                        } else {
                            const Vec3 r = n * (2 * nl) - in.toLight;
                            c = Dot(r, towardViewerFixed);
                        }
                        if (!(c > 0)) continue;
                        const double sp = m.specular * std::pow(c, m.shininess);
                        t.specular.r += in.rgb.r * sp;
                        t.specular.g += in.rgb.g * sp;
                        t.specular.b += in.rgb.b * sp;
                    }
                } else {
                    Vec3 point{0, 0, 0};
                    if (needPoint) point = viewer.WorldPoint({x + 0.5, y + 0.5, frame.depth[i]});
                    ShadowTest inShadow;
                    if (shadows) {
                        const Vec3 dp{x + 0.5, y + 0.5, frame.depth[i]};
                        inShadow = [&, dp](std::size_t k, const Incident& in) {
                            const scene::Light& l = scene.lights[k];
                            if (l.kind == scene::Light::Kind::kParallel)
                                return shadowTester.Blocked(
                                    dp, deviceFromWorld.MapVector(in.toLight), HUGE_VAL);
                            return shadowTester.Blocked(
                                dp, deviceFromWorld.MapPoint(l.position) - dp, 1.0);
                        };
                    }
                    t = PhongAt(scene.lights, point, n, viewer.TowardViewer(point), m, inShadow,
                                &fixedLight);
                }
                // min(1, D)·color + S (phong.h); S is 0 unless the surface is specular.
                scene::Color c = {base.r * std::min(t.diffuse.r, 1.0) + t.specular.r,
                                  base.g * std::min(t.diffuse.g, 1.0) + t.specular.g,
                                  base.b * std::min(t.diffuse.b, 1.0) + t.specular.b};
                if (finish.opacity && *finish.opacity < 1) {
                    const double a = *finish.opacity;
                    c = {a * c.r + (1 - a) * background.r, a * c.g + (1 - a) * background.g,
                         a * c.b + (1 - a) * background.b};
                }
                if (color) {
                    p[0] = ToByte(c.r);
                    p[1] = ToByte(c.g);
                    p[2] = ToByte(c.b);
                } else {
                    p[0] = ToByte(c.r);
                }
                if (frow) {
                    float* f = frow + static_cast<std::size_t>(x) * image.channels;
                    f[0] = ToUnit(c.r);
                    if (color) f[1] = ToUnit(c.g), f[2] = ToUnit(c.b);
                }
            }
        }
    };
    tbb::parallel_for(tbb::blocked_range<int>(0, frame.height, 16), shadeRows);
    return image;
}

}  // namespace quadrix
