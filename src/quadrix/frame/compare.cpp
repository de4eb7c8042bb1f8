#include "quadrix/frame/compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace quadrix {

namespace {

// True when the reference shows more than one surface id (background counts as one) in the 3×3
// neighbourhood of (x, y).
bool OnEdge(const Frame& ref, int x, int y) {
    const std::int32_t s = ref.surface[ref.Index(x, y)];
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int u = x + dx, v = y + dy;
            if (u < 0 || v < 0 || u >= ref.width || v >= ref.height) continue;
            if (ref.surface[ref.Index(u, v)] != s) return true;
        }
    return false;
}

double AngleDegrees(const Vec3& a, const Vec3& b) {
    const double c = std::clamp(Dot(a, b) / std::sqrt(Dot(a, a) * Dot(b, b)), -1.0, 1.0);
    return std::acos(c) * 180.0 / M_PI;
}

}  // namespace

double FrameComparison::SameSurfaceShare() const {
    return coveredBoth ? static_cast<double>(sameSurface) / static_cast<double>(coveredBoth) : 1.0;
}

std::string FrameComparison::Summary() const {
    if (sizeMismatch) return "the frames differ in size";
    std::string s = fmt::format(
        "{}x{}: covered in both {}, only in A {}, only in the reference {}; same surface {:.4f}% "
        "of common pixels, same solid {}; off-edge differences {}\n"
        "depth error (same surface): max {:.3g}, mean {:.3g}, p99.9 {:.3g} device z ({} over the "
        "tolerance); normal error max {:.3g} degrees\n",
        width, height, coveredBoth, onlyA, onlyReference, 100 * SameSurfaceShare(), sameSolid,
        offEdgeDifferences, maxDepthError, meanDepthError, p999DepthError, depthOverTolerance,
        maxNormalErrorDegrees);
    if (!firstDifference.empty()) s += "first off-edge difference: " + firstDifference + "\n";
    return s;
}

FrameComparison CompareFrames(const Frame& a, const Frame& ref, const CompareOptions& options) {
    FrameComparison c;
    c.width = ref.width;
    c.height = ref.height;
    if (a.width != ref.width || a.height != ref.height) {
        c.sizeMismatch = true;
        return c;
    }
    std::vector<double> errors, intensityErrors;
    double sum = 0, intensitySum = 0;
    double depthLo = HUGE_VAL, depthHi = -HUGE_VAL;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            const std::size_t i = ref.Index(x, y);
            const bool ca = a.surface[i] != Frame::kNone, cr = ref.surface[i] != Frame::kNone;
            const bool differs = ca != cr || (ca && a.surface[i] != ref.surface[i]);
            if (cr) {
                depthLo = std::fmin(depthLo, ref.depth[i]);
                depthHi = std::fmax(depthHi, ref.depth[i]);
            }
            if (ca && cr) {
                ++c.coveredBoth;
                c.sameSolid += a.Solid(i) == ref.Solid(i);
                if (a.surface[i] == ref.surface[i]) {
                    ++c.sameSurface;
                    c.sameSurfaceOtherBody += a.body[i] != ref.body[i];
                    const double e = std::fabs(a.depth[i] - ref.depth[i]);
                    c.maxDepthError = std::fmax(c.maxDepthError, e);
                    c.depthOverTolerance += e > options.depthTolerance;
                    sum += e;
                    errors.push_back(e);
                    c.maxNormalErrorDegrees = std::fmax(c.maxNormalErrorDegrees,
                                                        AngleDegrees(a.normal[i], ref.normal[i]));
                    if (options.intensity) {
                        const double d = std::fabs(options.intensity(a.normal[i]) -
                                                   options.intensity(ref.normal[i]));
                        c.maxIntensityError = std::fmax(c.maxIntensityError, d);
                        intensitySum += d;
                        intensityErrors.push_back(d);
                    }
                } else {
                    ++c.surfaceDiffers;
                }
            } else if (ca) {
                ++c.onlyA;
            } else if (cr) {
                ++c.onlyReference;
            }
            if (differs && !OnEdge(ref, x, y)) {
                ++c.offEdgeDifferences;
                c.offEdgeCoverageDifferences += ca != cr;
                if (c.firstDifference.empty())
                    c.firstDifference = fmt::format(
                        "pixel ({}, {}): surface {} vs {}, solid {} vs {}, depth {:.17g} vs "
                        "{:.17g}",
                        x, y, a.surface[i], ref.surface[i], a.Solid(i), ref.Solid(i), a.depth[i],
                        ref.depth[i]);
            }
        }
    if (depthHi > depthLo) c.referenceDepthRange = depthHi - depthLo;
    if (!errors.empty()) {
        c.meanDepthError = sum / static_cast<double>(errors.size());
        const auto k = static_cast<std::ptrdiff_t>(0.999 * static_cast<double>(errors.size() - 1));
        std::nth_element(errors.begin(), errors.begin() + k, errors.end());
        c.p999DepthError = errors[static_cast<std::size_t>(k)];
    }
    if (!intensityErrors.empty()) {
        c.meanIntensityError = intensitySum / static_cast<double>(intensityErrors.size());
        const auto k =
            static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(intensityErrors.size() - 1));
        std::nth_element(intensityErrors.begin(), intensityErrors.begin() + k,
                         intensityErrors.end());
        c.p99IntensityError = intensityErrors[static_cast<std::size_t>(k)];
    }
    return c;
}

std::string FirstBitDifference(const Frame& a, const Frame& b) {
    if (a.width != b.width || a.height != b.height)
        return fmt::format("sizes differ: {}x{} vs {}x{}", a.width, a.height, b.width, b.height);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const std::size_t i = a.Index(x, y);
            if (a.depth[i] != b.depth[i] || !(a.normal[i] == b.normal[i]) ||
                a.surface[i] != b.surface[i] || a.body[i] != b.body[i] || a.Solid(i) != b.Solid(i))
                return fmt::format(
                    "pixel ({}, {}): depth {:.17g} vs {:.17g}, surface {} vs {}, body {} vs {}, "
                    "solid {} vs {}",
                    x, y, a.depth[i], b.depth[i], a.surface[i], b.surface[i], a.body[i], b.body[i],
                    a.Solid(i), b.Solid(i));
        }
    return {};
}

Image FrameDiffImage(const Frame& a, const Frame& ref, const CompareOptions& options) {
    Image img(ref.width, ref.height, 3);
    if (a.width != ref.width || a.height != ref.height) return img;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            const std::size_t i = ref.Index(x, y);
            const bool ca = a.surface[i] != Frame::kNone, cr = ref.surface[i] != Frame::kNone;
            const int full = OnEdge(ref, x, y) ? 128 : 255;
            std::uint8_t* p = img.At(x, y);
            auto set = [&](int r, int g, int b) {
                p[0] = static_cast<std::uint8_t>(r);
                p[1] = static_cast<std::uint8_t>(g);
                p[2] = static_cast<std::uint8_t>(b);
            };
            if (!ca && !cr) {
                set(0, 0, 0);
            } else if (ca && !cr) {
                set(full, 0, 0);
            } else if (!ca) {
                set(0, 0, full);
            } else if (a.surface[i] != ref.surface[i]) {
                set(full, full, 0);
            } else {
                const double e = std::fabs(a.depth[i] - ref.depth[i]);
                const int g = e > options.depthTolerance ? 230 : 90;
                set(g, g, g);
            }
        }
    return img;
}

}  // namespace quadrix
