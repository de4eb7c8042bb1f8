#include "quadrix/shade/shader.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <utility>

#include "quadrix/shade/phong.h"
#include "quadrix/shade/row_shading.h"
#include "quadrix/shade/shade_budget.h"
#include "quadrix/shade/shadows.h"
#include "quadrix/util/parallel.h"
#include "quadrix/util/ray_work.h"

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

PixelShader::PixelShader(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                         std::shared_ptr<const WideNodeTrees> wide)
    : scene_(scene),
      options_(options),
      model_(options.fast ? ShadingModel::kFast : options.model),
      reflection_(model_ == ShadingModel::kFast ? ShadingModel::kLambert : model_),
      viewer_(scene.projection),
      needPoint_(NeedsPoint(scene, model_) || (options.shadows && scene.projection.perspective)),
      shadows_(options.shadows),
      deviceFromWorld_(scene.projection.deviceFromWorld.Matrix()),
      color_(AnyColor(scene, options)) {
    for (const scene::Light& l : scene.lights) fixedLight_.push_back(IncidentLight(l, {}));
    // The shadow rays' box trees only when there are shadows (at 100,000 bodies they take as long
    // as reading the scene).
    if (shadows_) shadowTester_.emplace(scene, options.spatialIndex, std::move(wide));
    const std::array<double, 4>& last = deviceFromWorld_.m[3];
    const bool affine = last[0] == 0 && last[1] == 0 && last[2] == 0 && last[3] == 1;
    for (std::size_t k = 0; k < scene.lights.size(); ++k) {
        fixedRay_.emplace_back();
        // Under an affine map h = M (D, 0) has h_w = 0 and the ray is (h, ∞) whatever the point.
        if (shadows_ && affine && scene.lights[k].kind == scene::Light::Kind::kParallel) {
            fixedRay_.back() =
                DeviceShadowRay(deviceFromWorld_, Vec4(fixedLight_[k].toLight, 0.0), {}, {});
            // Every shadow ray of this light is a half-line along the same d: the box trees
            // are tested in a view along it (BoxTree::ViewAlong).
            if (fixedRay_.back()->length > 0 && fixedRay_.back()->sMax == HUGE_VAL)
                fixedRay_.back()->view = shadowTester_->AddDirection(fixedRay_.back()->d);
        }
    }
    localShading_ = !needPoint_ && model_ != ShadingModel::kFast;
    if (shadows_) {
        localShading_ = localShading_ && scene.lights.size() <= 64;
        for (std::size_t k = 0; k < scene.lights.size(); ++k)
            localShading_ = localShading_ &&
                            (scene.lights[k].kind == scene::Light::Kind::kAmbient || fixedRay_[k]);
    }
    // Fast shading: one normal per (surface, body) pair, the mean of its visible normals.
    if (model_ == ShadingModel::kFast) {
        for (std::size_t i = 0; i < frame.surface.size(); ++i)
            if (frame.surface[i] != Frame::kNone)
                meanNormal_[{frame.surface[i], frame.body[i]}] += frame.normal[i];
        for (auto& [key, n] : meanNormal_) n = Normalize(n);
    }
}

scene::Color PixelShader::Background(int y, int height) const {
    return BackgroundAt(scene_, options_, y, height);
}

ShadowOrigin PixelShader::OriginOf(std::int32_t surface, std::int32_t body) const {
    // The surface the ray starts on (shadows.h: its literal is tried first); none for a
    // freeform surface's pixel (its id is past the half-spaces: no literal to try).
    ShadowOrigin origin;
    if (body >= 0 && surface >= 0 && static_cast<std::size_t>(surface) < scene_.halfSpaces.size()) {
        origin.body = body;
        origin.halfSpace = surface;
    }
    return origin;
}

scene::Color PixelShader::At(double x, double y, std::int32_t surface, std::int32_t body,
                             double depth, const Vec3& normal, const scene::Color& background,
                             MaterialCache* cache, const ShadowReach* reach) const {
    if (surface == Frame::kNone) return background;
    Vec3 n = normal;
    if (model_ == ShadingModel::kFast) {
        // A sample may see a (surface, body) pair no pixel centre saw: its own normal then.
        auto it = meanNormal_.find({surface, body});
        if (it != meanNormal_.end()) n = it->second;
    }
    Vec3 point{0, 0, 0};
    if (needPoint_) point = viewer_.WorldPoint({x, y, depth});
    const Vec3 p{x, y, depth};
    const ShadowOrigin origin = OriginOf(surface, body);
    // The world point only tells DeviceShadowRay which side of the eye plane p is on; under
    // a parallel view (an affine map, needPoint_ may be false) any point gives the same.
    const auto blocked = [&](std::size_t k, const Incident& in) {
        if (fixedRay_[k])
            return shadowTester_->Blocked(p, *fixedRay_[k], origin,
                                          reach ? reach->light[k] : ShadowTester::kReachAll);
        const scene::Light& l = scene_.lights[k];
        const Vec4 light =
            l.kind == scene::Light::Kind::kParallel ? Vec4(in.toLight, 0.0) : Vec4(l.position, 1.0);
        return shadowTester_->Blocked(p, DeviceShadowRay(deviceFromWorld_, light, p, point),
                                      origin);
    };
    ShadowTest inShadow;
    if (shadows_) inShadow = blocked;
    return Lit(surface, body, n, point, background, cache, inShadow);
}

void PixelShader::Reach(const Frame& frame, int y, int x0, int x1, ShadowReach& reach) const {
    reach.light.assign(fixedRay_.size(), ShadowTester::kReachAll);
    if (!shadowTester_) return;
    // The starts of the run's rays: the pixel centres with the depths of the covered ones.
    const std::size_t row = frame.Index(0, y);
    double zLo = HUGE_VAL, zHi = -HUGE_VAL;
    for (int x = x0; x < x1; ++x) {
        const std::size_t i = row + static_cast<std::size_t>(x);
        if (frame.surface[i] == Frame::kNone) continue;
        const double z = frame.depth[i];
        zLo = z < zLo ? z : zLo;
        zHi = z > zHi ? z : zHi;
    }
    if (!(zLo <= zHi)) return;  // nothing covered: no rays
    ReachOfBox({x0 + 0.5, y + 0.5, zLo}, {x1 - 0.5, y + 0.5, zHi}, reach);
}

void PixelShader::ReachOfBox(const Vec3& lo, const Vec3& hi, ShadowReach& reach) const {
    reach.light.assign(fixedRay_.size(), ShadowTester::kReachAll);
    if (!shadowTester_ || !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return;
    for (std::size_t k = 0; k < fixedRay_.size(); ++k)
        if (fixedRay_[k]) reach.light[k] = shadowTester_->MayMeet(lo, hi, *fixedRay_[k]);
}

std::uint64_t PixelShader::ShadowMask(double x, double y, std::int32_t surface, std::int32_t body,
                                      double depth, const Vec3& normal,
                                      const ShadowReach* reach) const {
    // The lights PhongAt asks (phong.cpp): not ambient, lighting the normal's side; all of them
    // fixed here (LocalShading), each with its device ray.
    const Vec3 p{x, y, depth};
    const ShadowOrigin origin = OriginOf(surface, body);
    std::uint64_t mask = 0;
    for (std::size_t k = 0; k < fixedLight_.size(); ++k) {
        const Incident& in = fixedLight_[k];
        if (in.ambient) continue;
        if (!(Dot(normal, in.toLight) > 0)) continue;
        if (shadowTester_->Blocked(p, *fixedRay_[k], origin,
                                   reach ? reach->light[k] : ShadowTester::kReachAll))
            mask |= std::uint64_t{1} << k;
    }
    return mask;
}

scene::Color PixelShader::AtWithMask(std::int32_t surface, std::int32_t body, const Vec3& normal,
                                     std::uint64_t mask, const scene::Color& background,
                                     MaterialCache* cache) const {
    if (surface == Frame::kNone) return background;
    const auto blocked = [mask](std::size_t k, const Incident&) { return (mask >> k & 1) != 0; };
    return Lit(surface, body, normal, Vec3{0, 0, 0}, background, cache, blocked);
}

scene::Color PixelShader::Lit(std::int32_t surface, std::int32_t body, const Vec3& n,
                              const Vec3& point, const scene::Color& background,
                              MaterialCache* cache, const ShadowTest& inShadow) const {
    MaterialCache local;
    MaterialCache& mc = cache ? *cache : local;
    if (mc.surface != surface || mc.body != body) {
        mc.surface = surface;
        mc.body = body;
        mc.finish = scene_.SurfaceFinish(surface, body);
        mc.reflectance = ReflectanceOf(mc.finish, options_, reflection_);
        mc.base = scene_.SurfaceColor(surface, body);
    }
    const scene::Finish& finish = mc.finish;
    const Reflectance& m = mc.reflectance;
    const PhongTerms t =
        PhongAt(scene_.lights, point, n, viewer_.TowardViewer(point), m, inShadow, &fixedLight_);
    const scene::Color& base = mc.base;
    // min(1, D)·color + S (phong.h); S is 0 unless the surface is specular.
    scene::Color c{base.r * std::min(t.diffuse.r, 1.0) + t.specular.r,
                   base.g * std::min(t.diffuse.g, 1.0) + t.specular.g,
                   base.b * std::min(t.diffuse.b, 1.0) + t.specular.b};
    if (finish.opacity && *finish.opacity < 1) {
        const double a = *finish.opacity;
        c = {a * c.r + (1 - a) * background.r, a * c.g + (1 - a) * background.g,
             a * c.b + (1 - a) * background.b};
    }
    return c;
}

void StorePixel(Image& image, int x, int y, const scene::Color& c) {
    std::uint8_t* p = image.At(x, y);
    if (image.linear.size() != image.pixels.size()) image.linear.assign(image.pixels.size(), 0.0f);
    float* f = &image.linear[static_cast<std::size_t>(p - image.pixels.data())];
    if (image.channels == 3) {
        p[0] = ToByte(c.r);
        p[1] = ToByte(c.g);
        p[2] = ToByte(c.b);
        f[0] = ToUnit(c.r);
        f[1] = ToUnit(c.g);
        f[2] = ToUnit(c.b);
    } else {
        p[0] = ToByte(c.r);
        f[0] = ToUnit(c.r);
    }
}

void StoreColor(Image& image, int x, int y, const scene::Color& c) {
    if (image.linear.size() == image.pixels.size()) {
        StorePixel(image, x, y, c);
        return;
    }
    std::uint8_t* p = image.At(x, y);
    p[0] = ToByte(c.r);
    if (image.channels == 3) p[1] = ToByte(c.g), p[2] = ToByte(c.b);
}

namespace {

// The 8-bit bytes of a colour, RGB or gray, as ShadeRowKinds stores them.
struct PixelBytes {
    std::uint8_t v[3] = {0, 0, 0};
    PixelBytes() = default;
    PixelBytes(const scene::Color& c) : v{ToByte(c.r), ToByte(c.g), ToByte(c.b)} {}
};

// Row y of an 8-bit image whose shading is local (ShadeRowKinds): a pixel's colour depends only
// on its (surface, body), its normal, the row's background and, with `shadows`
// (PixelShader::LocalShading), on which lights are blocked there (ShadowMask, traced for every
// covered pixel). A pixel repeating all of those of the previous covered pixel (a plane's run)
// repeats its bytes, and every background pixel of the row gets the same bytes; only the others
// are shaded (AtWithMask: PhongAt with the shadows' answers known; At's colour without shadows).
// The Frame's depth is read for the shadow rays only.
void ShadeRowLocal(const PixelShader& shader, const Frame& frame, int y,
                   const scene::Color& background, Image& image, PixelShader::MaterialCache& cache,
                   bool shadows) {
    const std::size_t row = frame.Index(0, y);
    const std::int32_t* surface = frame.surface.data() + row;
    const std::int32_t* body = frame.body.data() + row;
    const PackedNormal* normal = frame.normal.data() + row;
    const float* depth = frame.depth.data() + row;
    const int width = frame.width;
    const bool rgb = image.channels == 3;
    std::uint8_t* out = image.At(0, y);
    const PixelBytes back(
        shader.AtWithMask(Frame::kNone, Frame::kNone, Vec3{}, 0, background, &cache));
    PixelBytes last;
    std::int32_t lastSurface = Frame::kNone, lastBody = Frame::kNone;
    PackedNormal lastNormal, decoded;
    Vec3 n = decoded;  // the normal of `decoded`'s bits, decoded once per run of them
    std::uint64_t lastMask = 0;
    PixelShader::ShadowReach reach;
    for (int x = 0; x < width; ++x) {
        if (shadows && x % PixelShader::kReachRun == 0)
            shader.Reach(frame, y, x, std::min(width, x + PixelShader::kReachRun), reach);
        const std::int32_t s = surface[x];
        const PixelBytes* bytes = &back;
        if (s != Frame::kNone) {
            const std::int32_t b = body[x];
            if (!(normal[x] == decoded)) {
                decoded = normal[x];
                n = decoded;
            }
            const std::uint64_t mask =
                shadows ? shader.ShadowMask(x + 0.5, y + 0.5, s, b, depth[x], n, &reach) : 0;
            if (s != lastSurface || b != lastBody || !(normal[x] == lastNormal) ||
                mask != lastMask) {
                lastSurface = s;
                lastBody = b;
                lastNormal = normal[x];
                lastMask = mask;
                last = PixelBytes(shader.AtWithMask(s, b, n, mask, background, &cache));
            }
            bytes = &last;
        }
        if (rgb) {
            std::uint8_t* p = out + 3 * static_cast<std::size_t>(x);
            p[0] = bytes->v[0];
            p[1] = bytes->v[1];
            p[2] = bytes->v[2];
        } else {
            out[x] = bytes->v[0];
        }
    }
}

}  // namespace

Image Shade(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
            std::shared_ptr<const WideNodeTrees> wide) {
    return ShadeRowKinds(frame, scene, options, {}, std::move(wide));
}

Image ShadeRowKinds(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                    const std::vector<std::uint8_t>& kinds,
                    std::shared_ptr<const WideNodeTrees> wide) {
    const PixelShader shader(frame, scene, options, std::move(wide));
    // The repeat of a previous pixel's bytes (below) where the shading is local
    // (PixelShader::LocalShading), and for 8-bit output only: Image::linear would need its
    // floats repeated too, which is not worth it for the one output that reads them.
    const bool local = !options.linear && shader.LocalShading();
    Image image(frame.width, frame.height, shader.Color() ? 3 : 1);
    if (options.linear) image.linear.assign(image.pixels.size(), 0.0f);
    // Rows in parallel (oneTBB): each pixel depends only on its own Frame entry, so the image
    // is the same for any thread count. A row's material lookups are cached while the
    // (surface, body) pair repeats. Only some rows (row_shading.h): those, and the rows around
    // them when the anti-aliasing's shadow-boundary test reads their shading.
    const std::uint8_t wanted =
        options.aaSamples > 1 && options.shadows ? kRowShaded | kRowHalo : kRowShaded;
    // The shading budget (shade_budget.h) of the shadow rays: one per light per pixel.
    std::uint64_t lights = 0;
    for (const scene::Light& l : scene.lights) lights += l.kind != scene::Light::Kind::kAmbient;
    ShadeBudget budget("shadows", "--no-shadows",
                       static_cast<std::uint64_t>(frame.width) *
                           static_cast<std::uint64_t>(frame.height) *
                           std::max<std::uint64_t>(1, lights));
    auto shadeRows = [&](const tbb::blocked_range<int>& rows) {
        PixelShader::MaterialCache cache;
        for (int y = rows.begin(); y < rows.end(); ++y) {
            if (!kinds.empty() && !(kinds[static_cast<std::size_t>(y)] & wanted)) continue;
            if (budget.Exhausted()) return;
            const std::uint64_t work = tRayLiterals;
            struct Spend {
                ShadeBudget& budget;
                std::uint64_t start;
                ~Spend() { budget.Spend(tRayLiterals - start); }
            } spend{budget, work};
            const scene::Color background = shader.Background(y, frame.height);
            if (local) {
                ShadeRowLocal(shader, frame, y, background, image, cache, options.shadows);
                continue;
            }
            PixelShader::ShadowReach reach;
            for (int x = 0; x < frame.width; ++x) {
                if (options.shadows && x % PixelShader::kReachRun == 0)
                    shader.Reach(frame, y, x, std::min(frame.width, x + PixelShader::kReachRun),
                                 reach);
                const std::size_t i = frame.Index(x, y);
                const scene::Color c =
                    shader.At(x + 0.5, y + 0.5, frame.surface[i], frame.body[i], frame.depth[i],
                              frame.normal[i], background, &cache, &reach);
                StoreColor(image, x, y, c);  // the floats too when options.linear made them
            }
        }
    };
    ParallelFor(tbb::blocked_range<int>(0, frame.height, 16), shadeRows);
    if (options.shadows) budget.ThrowIfExhausted(scene);
    return image;
}

}  // namespace quadrix
