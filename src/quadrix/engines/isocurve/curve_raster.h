// Drawing isocurves into a Frame as thick curves with exact normals (seed 002 §3.1).
//
// A curve segment is given in world coordinates (polynomial, or homogeneous when rational) with
// its normal field N(t) (iso_family.h). Its device image is exact: the homogeneous control points
// are mapped by Projection::deviceFromWorld (4×4, projective for perspective), so the device curve
// is the rational curve M·C(t), evaluated directly instead of being approximated by a polyline
// (the seed's hardware compromise). The curve is sampled so that consecutive samples are at most
// `step` pixels apart on the screen, and each sample splats a disc of radius `radius` pixels:
//   - depth: the device z of the sample, extended over the disc along the device-space tangent
//     plane (the world tangent plane (n, −n·p) maps to the device covector M⁻ᵀ(n, −n·p), which is
//     exact for projective maps), with the slope clamped near silhouettes;
//   - normal: N(t)/|N(t)| in world space, turned toward the viewer (two-sided: the tea-set files
//     disagree on orientation, testdata/SOURCES.md); at degenerate points, where N vanishes, the
//     surface's limit normal (Surface::UnitNormal).
// Which sample a pixel keeps: against anything else in the Frame (quadric solids, other layers of
// the surface) the nearer depth wins, as Frame::Offer does, so freeform curves and quadric solids
// compose by depth in one Frame (DESIGN.md "unit of composition"). Between two curve samples of
// the same surface and layer — their centre depths differ by less than the depth spread of their
// discs — the sample nearer to the pixel centre wins instead: a tangent plane lies in front of a
// convex surface, so "nearest depth" would let the steep, extrapolated discs of samples near a
// silhouette cover the pixels of the samples that actually lie there, with their normals.
// Different surfaces (e.g. the teapot's spout entering its body) still meet by depth, so their
// intersection curve is placed by the tangent planes.
//
// For the statistics of item 5 the rasterizer also counts, per pixel, how many distinct curves
// drew it (one curve counts once however many of its samples touch the pixel).
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/freeform/bezier_curve.h"
#include "quadrix/freeform/power_form.h"
#include "quadrix/freeform/surface.h"

namespace quadrix::isocurve {

// The ids a surface's pixels carry (its solid is its body's, from the Frame's table: frame.h).
struct FrameIds {
    std::int32_t surface = 0, body = 0;
};

struct RasterCounts {
    long long curves = 0;
    long long samples = 0;
    long long pixelsDrawn = 0;     // Σ over curves of the pixels each curve touched
    long long distinctPixels = 0;  // pixels touched by at least one curve
    long long multiplyDrawn = 0;   // pixels touched by two curves or more
    double Redundancy() const {
        return distinctPixels ? static_cast<double>(pixelsDrawn) / distinctPixels : 0.0;
    }
};

class CurveRasterizer {
  public:
    CurveRasterizer(Frame& frame, const Projection& projection, double radius);

    // Starts a new curve (for the per-curve pixel counts).
    void BeginCurve();
    // One segment of the current curve: `position` in world coordinates (dim 3, or 4 =
    // homogeneous), `normal` the normal field along it (dim 3, same interval). `surface` and
    // (t ↦ (u, v)) give the limit normal where N vanishes: u = t, v = fixed when !transposed.
    void DrawSegment(const freeform::BezierCurve& position, const freeform::BezierCurve& normal,
                     const freeform::Surface& surface, double fixed, bool transposed,
                     const FrameIds& ids);

    // Final counts (walks the per-pixel counters).
    RasterCounts Counts() const;
    double Radius() const { return radius_; }

  private:
    struct Sample {
        double t;
        Vec3 device;  // x, y in pixels, device z
        double w;     // homogeneous weight of the device point
        bool valid;
    };
    Sample Evaluate(const freeform::PowerForm& deviceCurve, double t) const;
    // Device z of a 45° plane over one pixel at a device point (the local z/xy scale).
    double ZPerPixel(const Vec3& device, double w) const;
    void Splat(const Sample& s, const freeform::PowerForm& normal, const freeform::Surface& surface,
               double fixed, bool transposed, const FrameIds& ids);

    Frame& frame_;
    const Projection& projection_;
    Mat4 m_, inv_;
    double radius_, step_;
    double normalTiny_ = 0;
    std::int32_t curve_ = -1;
    std::vector<std::int32_t> lastCurve_;
    std::vector<std::uint16_t> count_;
    // Per pixel: written by a curve sample, that sample's centre depth, its squared distance to
    // the pixel centre, and the depth spread of its disc.
    std::vector<std::uint8_t> owner_;
    std::vector<double> sampleZ_;
    std::vector<float> dist2_;
    std::vector<float> layerTol_;
    long long samples_ = 0, pixelsDrawn_ = 0;
};

}  // namespace quadrix::isocurve
