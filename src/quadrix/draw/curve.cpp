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
            return points[i] + (points[i + 1] - points[i]) * f;
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
