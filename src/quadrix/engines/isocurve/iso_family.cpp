#include "quadrix/engines/isocurve/iso_family.h"

#include <algorithm>
#include <cmath>

namespace quadrix::isocurve {

using freeform::BezierCurve;

IsoFamily::IsoFamily(const freeform::Surface& surface, Constant constant)
    : constant_(constant), oriented_(constant == Constant::kV ? surface : surface.Transposed()) {
    for (const freeform::BSplineSurface& strip : oriented_.Net().SplitIntoUSpans()) {
        breaks_.push_back(strip.U0());
        stripRows_.push_back(strip.RowsAsCurveInV());
    }
    breaks_.push_back(oriented_.U1());
}

const std::vector<BezierCurve>& IsoFamily::Curve(double fixed) {
    auto it = cache_.find(fixed);
    if (it != cache_.end()) return it->second;
    std::vector<BezierCurve> segs;
    int dim = oriented_.Net().Dim(), p = oriented_.Net().DegreeU();
    for (std::size_t k = 0; k < stripRows_.size(); ++k)
        segs.emplace_back(dim, p, stripRows_[k].Evaluate(fixed), breaks_[k], breaks_[k + 1]);
    return cache_.emplace(fixed, std::move(segs)).first->second;
}

std::vector<BezierCurve> RestrictSegments(const std::vector<BezierCurve>& segs, double a,
                                          double b) {
    std::vector<BezierCurve> out;
    for (const BezierCurve& s : segs) {
        double lo = std::max(a, s.T0()), hi = std::min(b, s.T1());
        if (!(lo < hi)) continue;
        out.push_back(lo == s.T0() && hi == s.T1() ? s : s.Restricted(lo, hi));
    }
    return out;
}

std::vector<BezierCurve> IsoFamily::Pieces(double fixed, double a, double b) {
    return RestrictSegments(Curve(fixed), a, b);
}

std::vector<BezierCurve> IsoFamily::NormalPieces(double fixed, double a, double b) const {
    return RestrictSegments(oriented_.NormalPatches().IsoCurveAtV(fixed), a, b);
}

namespace {

// |C'(t)| for a Euclidean (dim 3) or homogeneous (dim 4) curve: C = P / w,
// C' = (P' w − P w') / w².
double Speed(const BezierCurve& c, const BezierCurve& d, double t) {
    double p[4], q[4];
    c.Evaluate(t, p);
    d.Evaluate(t, q);
    if (c.Dim() == 3) return std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    double w = p[3], w2 = w * w, s = 0;
    for (int k = 0; k < 3; ++k) {
        double v = (q[k] * w - p[k] * q[3]) / w2;
        s += v * v;
    }
    return std::sqrt(s);
}

}  // namespace

double ArcLength(const BezierCurve& segment) {
    // 5-point Gauss–Legendre on 8 equal sub-intervals.
    static const double kX[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                 0.9061798459386640};
    static const double kW[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                 0.4786286704993665, 0.2369268850561891};
    BezierCurve d = segment.Derivative();
    const int kParts = 8;
    double h = (segment.T1() - segment.T0()) / kParts, sum = 0;
    for (int i = 0; i < kParts; ++i) {
        double mid = segment.T0() + (i + 0.5) * h;
        for (int k = 0; k < 5; ++k) sum += kW[k] * Speed(segment, d, mid + 0.5 * h * kX[k]);
    }
    return 0.5 * h * sum;
}

}  // namespace quadrix::isocurve
