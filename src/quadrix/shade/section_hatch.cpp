#include "quadrix/shade/section_hatch.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "quadrix/shade/row_shading.h"
#include "quadrix/util/parallel.h"

namespace quadrix {

namespace {

double Component(const Vec3& v, int i) { return i == 0 ? v.x : i == 1 ? v.y : v.z; }

Vec3 Axis(int i) { return {i == 0 ? 1.0 : 0.0, i == 1 ? 1.0 : 0.0, i == 2 ? 1.0 : 0.0}; }

// The plane's canonical unit normal and axes (file comment).
void PlaneAxes(const Plane& plane, SectionHatch& hatch) {
    Vec3 n = Normalize(plane.Normal());
    int largest = 0, least = 0;
    for (int i = 1; i < 3; ++i) {
        if (std::fabs(Component(n, i)) > std::fabs(Component(n, largest))) largest = i;
        if (std::fabs(Component(n, i)) < std::fabs(Component(n, least))) least = i;
    }
    if (Component(n, largest) < 0) n = -n;
    const Vec3 a = Axis(least);
    hatch.normal = n;
    hatch.e1 = Normalize(a - n * Dot(a, n));
    hatch.e2 = Cross(n, hatch.e1);
}

// h = N/D on the device plane as functions of the pixel position (X, Y): the world point of the
// plane under (X, Y) is the dehomogenised worldFromDevice · (X, Y, z(X, Y), 1), affine in X and
// Y before the division, so h is a ratio of two affine functions (a homography).
struct Ratio {
    double n0 = 0, nx = 0, ny = 0, d0 = 1, dx = 0, dy = 0;
};

Ratio HatchRatio(const Mat4& worldFromDevice, const Plane& device, const Vec3& across) {
    const double a = device.a / device.c, b = device.b / device.c, d = device.d / device.c;
    const Vec4 v0 = worldFromDevice * Vec4{0, 0, -d, 1};
    const Vec4 vx = worldFromDevice * Vec4{1, 0, -a, 0};
    const Vec4 vy = worldFromDevice * Vec4{0, 1, -b, 0};
    auto dot = [&](const Vec4& v) { return across.x * v.x + across.y * v.y + across.z * v.z; };
    return {dot(v0), dot(vx), dot(vy), v0.w, vx.w, vy.w};
}

std::uint8_t Byte(double v) {
    if (!(v > 0)) return 0;
    if (v >= 1) return 255;
    return static_cast<std::uint8_t>(v * 255.0 + 0.5);
}

void Paint(Image& image, std::size_t pixel, const scene::Color& c) {
    const std::size_t at = pixel * static_cast<std::size_t>(image.channels);
    const bool linear = image.linear.size() == image.pixels.size();
    const double rgb[3] = {c.r, c.g, c.b};
    for (int k = 0; k < image.channels; ++k) {
        image.pixels[at + k] = Byte(rgb[k]);
        if (linear) image.linear[at + k] = static_cast<float>(std::clamp(rgb[k], 0.0, 1.0));
    }
}

}  // namespace

std::optional<SectionHatch> SectionHatchOf(const FlatScene& scene, double spacingPixels) {
    if (!scene.section || scene.sectionHalfSpace < 0 ||
        scene.sectionHalfSpace >= static_cast<int>(scene.halfSpaces.size()))
        return std::nullopt;
    const Plane& device = scene.halfSpaces[static_cast<std::size_t>(scene.sectionHalfSpace)].plane;
    if (device.c == 0 || !device.AllFinite() || !(spacingPixels > 0)) return std::nullopt;
    SectionHatch hatch;
    hatch.halfSpace = scene.sectionHalfSpace;
    PlaneAxes(*scene.section, hatch);
    // The pixel size where the image centre's ray meets the plane.
    const Mat4& worldFromDevice = scene.projection.deviceFromWorld.Inverse();
    const double cx = 0.5 * scene.width, cy = 0.5 * scene.height;
    const double cz = -(device.a * cx + device.b * cy + device.d) / device.c;
    const Vec3 p = worldFromDevice.MapPoint({cx, cy, cz});
    const Vec3 q = worldFromDevice.MapPoint({cx + 1, cy, cz});
    hatch.pixelSize = Length(q - p);
    if (!std::isfinite(hatch.pixelSize) || !(hatch.pixelSize > 0)) return std::nullopt;
    hatch.spacing = std::exp2(std::round(std::log2(spacingPixels * hatch.pixelSize)));
    if (!std::isfinite(hatch.spacing) || !(hatch.spacing > 0)) return std::nullopt;
    return hatch;
}

Vec3 HatchAcross(const SectionHatch& hatch, int solid) {
    const double r = 1 / std::sqrt(2.0);
    return solid >= 0 && solid % 2 == 1 ? (hatch.e1 + hatch.e2) * r : (hatch.e2 - hatch.e1) * r;
}

bool OnHatchLine(const SectionHatch& hatch, double h, double w) {
    // t = h / s (exact: s is a power of two) and the nearest whole number to it, by truncation
    // rather than a libm call (the hatch step's inner loop); |t| >= 2^52 is farther than any
    // picture's pixels from the plane's origin in units of a line spacing, and not hatched.
    const double t = h * (1 / hatch.spacing);
    if (!(std::fabs(t) < 0x1p52)) return false;
    const double u = t + 0.5;
    double k = static_cast<double>(static_cast<std::int64_t>(u));
    if (k > u) k -= 1;  // floor(t + ½) for negative t too
    return std::fabs(t - k) * hatch.spacing < 0.5 * std::min(w, hatch.spacing / 3);
}

std::size_t HatchSection(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                         Image& image) {
    return HatchSectionRowKinds(frame, scene, options, image, {});
}

std::size_t HatchSectionRowKinds(const Frame& frame, const FlatScene& scene,
                                 const ShadeOptions& options, Image& image,
                                 const std::vector<std::uint8_t>& rows) {
    if (!options.hatch || image.width != frame.width || image.height != frame.height) return 0;
    const std::optional<SectionHatch> hatch = SectionHatchOf(scene, options.hatchSpacing);
    if (!hatch) return 0;
    const Mat4& worldFromDevice = scene.projection.deviceFromWorld.Inverse();
    const Plane& device = scene.halfSpaces[static_cast<std::size_t>(hatch->halfSpace)].plane;
    const Ratio family[2] = {HatchRatio(worldFromDevice, device, HatchAcross(*hatch, 0)),
                             HatchRatio(worldFromDevice, device, HatchAcross(*hatch, 1))};
    std::atomic<std::size_t> count{0};
    ParallelFor(tbb::blocked_range<int>(0, frame.height, 16), [&](const auto& range) {
        std::size_t local = 0;
        for (int y = range.begin(); y < range.end(); ++y) {
            if (!rows.empty() && rows[static_cast<std::size_t>(y)] != kRowShaded) continue;
            const double Y = y + 0.5;
            for (int x = 0; x < frame.width; ++x) {
                const std::size_t i = frame.Index(x, y);
                if (frame.surface[i] != hatch->halfSpace) continue;
                const Ratio& r = family[frame.Solid(i) >= 0 && frame.Solid(i) % 2 == 1];
                const double X = x + 0.5;
                const double D = r.d0 + r.dx * X + r.dy * Y;
                const double h = (r.n0 + r.nx * X + r.ny * Y) / D;
                // ∂h/∂X = (nx − h·dx)/D, likewise for Y: h's change per pixel (scene scales
                // are far from where the squares overflow).
                const double gx = (r.nx - h * r.dx) / D, gy = (r.ny - h * r.dy) / D;
                if (!OnHatchLine(*hatch, h, kLineWidthPixels * std::sqrt(gx * gx + gy * gy)))
                    continue;
                Paint(image, i, options.hatchColor);
                ++local;
            }
        }
        count += local;
    });
    return count.load();
}

}  // namespace quadrix
