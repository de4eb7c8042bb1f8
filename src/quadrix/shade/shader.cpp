#include "quadrix/shade/shader.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace quadrix {

double LambertIntensity(const FlatScene& scene, const Vec3& n) {
    double sum = 0;
    for (const scene::Light& l : scene.lights) {
        if (l.kind == scene::Light::Kind::kAmbient) {
            sum += l.intensity;
        } else {
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

bool AnyColor(const FlatScene& scene, const ShadeOptions& options) {
    if (options.forceColor) return true;
    auto gray = [](const scene::Color& c) { return c.r == c.g && c.g == c.b; };
    if (!gray(options.background)) return true;
    for (const FlatBody& b : scene.bodies)
        if (!(b.color == scene::Color{})) return true;
    for (const FlatFreeform& f : scene.freeforms)
        if (!(f.color == scene::Color{})) return true;
    return false;
}

}  // namespace

Image Shade(const Frame& frame, const FlatScene& scene, const ShadeOptions& options) {
    const bool color = AnyColor(scene, options);
    Image image(frame.width, frame.height, color ? 3 : 1);

    // Fast shading: one normal per (surface, body) pair, the mean of its visible normals.
    std::map<std::pair<int, int>, Vec3> meanNormal;
    if (options.fast) {
        for (std::size_t i = 0; i < frame.surface.size(); ++i)
            if (frame.surface[i] != Frame::kNone)
                meanNormal[{frame.surface[i], frame.body[i]}] += frame.normal[i];
        for (auto& [key, n] : meanNormal) n = Normalize(n);
    }

    // Rows in parallel (oneTBB): each pixel depends only on its own Frame entry, so the image
    // is the same for any thread count.
    auto shadeRows = [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < frame.width; ++x) {
                const std::size_t i = frame.Index(x, y);
                scene::Color c = options.background;
                if (frame.surface[i] != Frame::kNone) {
                    const Vec3 n = options.fast
                                       ? meanNormal.find({frame.surface[i], frame.body[i]})->second
                                       : frame.normal[i];
                    const double intensity = LambertIntensity(scene, n);
                    const scene::Color base = scene.SurfaceColor(frame.surface[i], frame.body[i]);
                    c = {base.r * intensity, base.g * intensity, base.b * intensity};
                }
                std::uint8_t* p = image.At(x, y);
                if (color) {
                    p[0] = ToByte(c.r);
                    p[1] = ToByte(c.g);
                    p[2] = ToByte(c.b);
                } else {
                    p[0] = ToByte(c.r);
                }
            }
    };
    tbb::parallel_for(tbb::blocked_range<int>(0, frame.height, 16), shadeRows);
    return image;
}

}  // namespace quadrix
