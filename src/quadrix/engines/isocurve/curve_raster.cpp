#include "quadrix/engines/isocurve/curve_raster.h"

#include <algorithm>
#include <cmath>

namespace quadrix::isocurve {

using freeform::BezierCurve;

namespace {

// The homogeneous device curve M · C(t).
BezierCurve DeviceCurve(const BezierCurve& position, const Mat4& m) {
    std::vector<double> c;
    c.reserve(static_cast<std::size_t>(position.Size()) * 4);
    for (int i = 0; i < position.Size(); ++i) {
        const double* p = position.Point(i);
        Vec4 h{p[0], p[1], p[2], position.Dim() == 4 ? p[3] : 1.0};
        Vec4 d = m * h;
        c.insert(c.end(), {d.x, d.y, d.z, d.w});
    }
    return BezierCurve(4, position.Degree(), std::move(c), position.T0(), position.T1());
}

}  // namespace

CurveRasterizer::CurveRasterizer(Frame& frame, const Projection& projection, double radius)
    : frame_(frame),
      projection_(projection),
      m_(projection.deviceFromWorld.Matrix()),
      inv_(projection.deviceFromWorld.Inverse()),
      radius_(radius),
      lastCurve_(frame.depth.size(), -1),
      count_(frame.depth.size(), 0),
      owner_(frame.depth.size(), 0),
      sampleZ_(frame.depth.size(), 0.0),
      dist2_(frame.depth.size(), 0.0f),
      layerTol_(frame.depth.size(), 0.0f) {
    // Samples closer than half the radius keep the union of discs a band of half-width at least
    // radius·cos(asin(1/4)) ≈ 0.97·radius; never coarser than a pixel, never finer than 1/5.
    step_ = std::clamp(0.5 * radius_, 0.2, 1.0);
}

double CurveRasterizer::ZPerPixel(const Vec3& device, double w) const {
    // Rows of the Jacobian of p ↦ (x/w, y/w, z/w): (M_r − c_r M_3) / w, c the device point.
    double jx = 0, jz = 0;
    for (int k = 0; k < 3; ++k) {
        double a = (m_(0, k) - device.x * m_(3, k)) / w;
        double c = (m_(2, k) - device.z * m_(3, k)) / w;
        jx += a * a;
        jz += c * c;
    }
    return jx > 0 ? std::sqrt(jz / jx) : 0.0;
}

void CurveRasterizer::BeginCurve() { ++curve_; }

CurveRasterizer::Sample CurveRasterizer::Evaluate(const freeform::PowerForm& deviceCurve,
                                                  double t) const {
    double c[4];
    deviceCurve.Evaluate(t, c);
    Vec4 h{c[0], c[1], c[2], c[3]};
    // Points behind the eye (w <= 0) are not drawn; the Flattener clips quadrics the same way.
    if (!(h.w > 0)) return {t, {}, 0, false};
    Vec3 d = Dehomogenize(h);
    return {t, d, h.w, IsFinite(d)};
}

void CurveRasterizer::DrawSegment(const BezierCurve& position, const BezierCurve& normal,
                                  const freeform::Surface& surface, double fixed, bool transposed,
                                  const FrameIds& ids) {
    freeform::PowerForm device(DeviceCurve(position, m_));
    freeform::PowerForm normalForm(normal);
    // |N| below this is "zero": a degenerate point (relative to the size of N on the segment).
    double scale = 0;
    for (double c : normal.Coefficients()) scale = std::max(scale, std::fabs(c));
    normalTiny_ = 1e-9 * scale;
    // Adaptive sampling: bisect until consecutive samples are within `step` pixels.
    struct Span {
        Sample a, b;
        int depth;
    };
    const int kInitial = 4, kMaxDepth = 24;
    std::vector<Sample> initial;
    for (int i = 0; i <= kInitial; ++i)
        initial.push_back(
            Evaluate(device, i == kInitial
                                 ? position.T1()
                                 : position.T0() + (position.T1() - position.T0()) * i / kInitial));
    if (initial.front().valid) Splat(initial.front(), normalForm, surface, fixed, transposed, ids);
    std::vector<Span> stack;
    for (int i = kInitial - 1; i >= 0; --i)
        stack.push_back(
            {initial[static_cast<std::size_t>(i)], initial[static_cast<std::size_t>(i + 1)], 0});
    while (!stack.empty()) {
        Span s = stack.back();
        stack.pop_back();
        double dx = s.b.device.x - s.a.device.x, dy = s.b.device.y - s.a.device.y;
        bool close = s.a.valid && s.b.valid && dx * dx + dy * dy <= step_ * step_;
        if (close || s.depth >= kMaxDepth || (!s.a.valid && !s.b.valid && s.depth >= 6)) {
            if (s.b.valid) Splat(s.b, normalForm, surface, fixed, transposed, ids);
            continue;
        }
        Sample mid = Evaluate(device, 0.5 * (s.a.t + s.b.t));
        stack.push_back({mid, s.b, s.depth + 1});  // right half after the left one
        stack.push_back({s.a, mid, s.depth + 1});
    }
}

void CurveRasterizer::Splat(const Sample& s, const freeform::PowerForm& normal,
                            const freeform::Surface& surface, double fixed, bool transposed,
                            const FrameIds& ids) {
    ++samples_;
    double px = s.device.x, py = s.device.y;
    int x0 = static_cast<int>(std::floor(px - radius_)),
        x1 = static_cast<int>(std::ceil(px + radius_));
    int y0 = static_cast<int>(std::floor(py - radius_)),
        y1 = static_cast<int>(std::ceil(py + radius_));
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, frame_.width - 1);
    y1 = std::min(y1, frame_.height - 1);
    if (x0 > x1 || y0 > y1) return;

    // World point (the device point mapped back: cheaper than evaluating the curve again) and
    // unit normal of the surface at the sample.
    Vec3 p = Dehomogenize(inv_ * Vec4(s.device, 1.0));
    double nc[3];
    normal.Evaluate(s.t, nc);
    Vec3 n{nc[0], nc[1], nc[2]};
    if (!(Length(n) > normalTiny_)) {
        double u = transposed ? fixed : s.t, v = transposed ? s.t : fixed;
        std::optional<Vec3> limit = surface.UnitNormal(u, v);
        n = limit ? *limit : Vec3{0, 0, 0};
    }
    n = Normalize(n);
    Vec3 toward = projection_.perspective ? projection_.eye - p : projection_.towardViewer;
    if (Dot(n, toward) < 0) n = -n;

    // Device tangent plane g = M⁻ᵀ (n, −n·p): z(x, y) = z0 + sx (x − px) + sy (y − py).
    double pi[4] = {n.x, n.y, n.z, -Dot(n, p)};
    double g[4];
    for (int k = 0; k < 4; ++k)
        g[k] = inv_(0, k) * pi[0] + inv_(1, k) * pi[1] + inv_(2, k) * pi[2] + inv_(3, k) * pi[3];
    double sx = 0, sy = 0;
    if (g[2] != 0) {
        sx = -g[0] / g[2];
        sy = -g[1] / g[2];
    }
    // Slope clamp: 8 times the slope of a 45° plane at this point (device z per pixel of the
    // projection here), i.e. surfaces steeper than ~83° are extended as if at 83°.
    double zPerPixel = ZPerPixel(s.device, s.w);
    double maxSlope = 8.0 * zPerPixel;
    double slope = std::sqrt(sx * sx + sy * sy);
    if (!(slope <= maxSlope)) {
        double f = std::isfinite(slope) && slope > 0 ? maxSlope / slope : 0.0;
        sx *= f;
        sy *= f;
    }

    double r2 = radius_ * radius_;
    // Depth spread of this disc on its own layer: the clamped slope over the radius.
    float tol = static_cast<float>(radius_ * (std::sqrt(sx * sx + sy * sy) + zPerPixel));
    for (int y = y0; y <= y1; ++y) {
        double dy = y + 0.5 - py;
        for (int x = x0; x <= x1; ++x) {
            double dx = x + 0.5 - px;
            double d2 = dx * dx + dy * dy;
            if (d2 > r2) continue;
            std::size_t i = frame_.Index(x, y);
            double z = s.device.z + sx * dx + sy * dy;
            if (owner_[i] && frame_.surface[i] == ids.surface &&
                std::fabs(s.device.z - sampleZ_[i]) <= tol + layerTol_[i]) {
                // Same layer as the curve sample that holds the pixel: the sample nearer to the
                // pixel centre gives normal and depth (see the file comment).
                if (d2 < dist2_[i]) {
                    frame_.depth[i] = z;
                    frame_.normal[i] = n;
                    frame_.surface[i] = ids.surface;
                    frame_.body[i] = ids.body;
                    sampleZ_[i] = s.device.z;
                    dist2_[i] = static_cast<float>(d2);
                    layerTol_[i] = tol;
                }
            } else if (frame_.Nearer(i, z)) {
                frame_.Offer(i, z, n, ids.surface, ids.body);
                owner_[i] = 1;
                sampleZ_[i] = s.device.z;
                dist2_[i] = static_cast<float>(d2);
                layerTol_[i] = tol;
            }
            if (lastCurve_[i] != curve_) {
                lastCurve_[i] = curve_;
                if (count_[i] < UINT16_MAX) ++count_[i];
                ++pixelsDrawn_;
            }
        }
    }
}

RasterCounts CurveRasterizer::Counts() const {
    RasterCounts c;
    c.curves = curve_ + 1;
    c.samples = samples_;
    c.pixelsDrawn = pixelsDrawn_;
    for (std::uint16_t k : count_) {
        c.distinctPixels += k > 0;
        c.multiplyDrawn += k > 1;
    }
    return c;
}

}  // namespace quadrix::isocurve
