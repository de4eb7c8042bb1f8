#include "quadrix/draw/curve.h"

#include <algorithm>
#include <cmath>

namespace quadrix::draw {

Vec3 Curve3::At(double t) const {
    switch (kind) {
        case CurveKind::kLine:
            return o + u * t;
        case CurveKind::kEllipse:
            return o + u * std::cos(t) + v * std::sin(t);
        case CurveKind::kHyperbola:
            return o + u * std::cosh(t) + v * std::sinh(t);
        case CurveKind::kParabola:
            return o + u * t + v * (t * t);
        case CurveKind::kPolyline: {
            if (points.empty()) return {};
            if (points.size() == 1) return points[0];
            const double last = static_cast<double>(points.size() - 1);
            const double c = std::clamp(t, 0.0, last);
            std::size_t i = static_cast<std::size_t>(std::floor(c));
            if (i >= points.size() - 1) i = points.size() - 2;
            const double f = c - static_cast<double>(i);
            Vec3 p = points[i] + (points[i + 1] - points[i]) * f;
            if (project && f > 0) {
                Vec3 q = p;
                if (ProjectOntoBoth(onA, onB, q, 1e-12 * (1 + Length(p)))) p = q;
            }
            return p;
        }
    }
    return {};
}

Vec3 Curve3::Derivative(double t) const {
    switch (kind) {
        case CurveKind::kLine:
            return u;
        case CurveKind::kEllipse:
            return v * std::cos(t) - u * std::sin(t);
        case CurveKind::kHyperbola:
            return u * std::sinh(t) + v * std::cosh(t);
        case CurveKind::kParabola:
            return u + v * (2 * t);
        case CurveKind::kPolyline: {
            if (points.size() < 2) return {};
            const double last = static_cast<double>(points.size() - 1);
            std::size_t i = static_cast<std::size_t>(std::floor(std::clamp(t, 0.0, last)));
            if (i >= points.size() - 1) i = points.size() - 2;
            return points[i + 1] - points[i];
        }
    }
    return {};
}

bool ProjectOntoBoth(const Quadric& a, const Quadric& b, Vec3& p, double tol) {
    for (int it = 0; it < 30; ++it) {
        const double fa = a.Evaluate(p), fb = b.Evaluate(p);
        const Vec3 ga = a.Gradient(p), gb = b.Gradient(p);
        const double aa = Dot(ga, ga), ab = Dot(ga, gb), bb = Dot(gb, gb);
        const double det = aa * bb - ab * ab;
        if (!(det > 1e-20 * aa * bb)) return false;
        // Δ = α ga + β gb with ga·Δ = −fa, gb·Δ = −fb.
        const double alpha = (-fa * bb + fb * ab) / det, beta = (-fb * aa + fa * ab) / det;
        const Vec3 d = ga * alpha + gb * beta;
        p += d;
        if (!IsFinite(p)) return false;
        if (Length(d) <= tol) return true;
    }
    return false;
}

double ProjectedLength(const Curve3& c, double t0, double t1) {
    double len = 0;
    Vec3 prev = c.At(t0);
    const int n = c.kind == CurveKind::kLine ? 1 : 64;
    for (int i = 1; i <= n; ++i) {
        const Vec3 p = c.At(t0 + (t1 - t0) * i / n);
        len += std::hypot(p.x - prev.x, p.y - prev.y);
        prev = p;
    }
    return len;
}

const char* ToString(CurveKind k) {
    switch (k) {
        case CurveKind::kLine:
            return "line";
        case CurveKind::kEllipse:
            return "ellipse";
        case CurveKind::kHyperbola:
            return "hyperbola";
        case CurveKind::kParabola:
            return "parabola";
        case CurveKind::kPolyline:
            return "polyline";
    }
    return "?";
}

}  // namespace quadrix::draw
