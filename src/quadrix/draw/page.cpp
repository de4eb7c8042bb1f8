#include "quadrix/draw/page.h"

#include <cmath>

namespace quadrix::draw {

namespace {

// The cubic Bézier with the arc's ends and end tangents on [t0, t1] (cubic Hermite
// interpolation), appended to `out` when it is within `tol` of the arc at 15 interior
// parameters, else the two halves.
void AppendCubics(const Stroke& s, double t0, double t1, double tol, int depth,
                  std::vector<Point2>& out) {
    const double h = t1 - t0;
    const Point2 p0 = s.ArcPoint(t0), p3 = s.ArcPoint(t1);
    const Point2 d0 = s.ArcTangent(t0), d3 = s.ArcTangent(t1);
    const Point2 p1{p0.x + d0.x * h / 3, p0.y + d0.y * h / 3};
    const Point2 p2{p3.x - d3.x * h / 3, p3.y - d3.y * h / 3};
    double err = 0;
    for (int k = 1; k < 16; ++k) {
        const double u = k / 16.0, w = 1 - u;
        const double b0 = w * w * w, b1 = 3 * w * w * u, b2 = 3 * w * u * u, b3 = u * u * u;
        const Point2 q = s.ArcPoint(t0 + u * h);
        err = std::fmax(err, std::hypot(b0 * p0.x + b1 * p1.x + b2 * p2.x + b3 * p3.x - q.x,
                                        b0 * p0.y + b1 * p1.y + b2 * p2.y + b3 * p3.y - q.y));
    }
    // The parametric distance bounds the distance to the arc; 0.9 leaves room for the error's
    // maximum between the samples.
    if (err <= 0.9 * tol || depth >= 40) {
        out.insert(out.end(), {p1, p2, p3});
        return;
    }
    AppendCubics(s, t0, t0 + h / 2, tol, depth + 1, out);
    AppendCubics(s, t0 + h / 2, t1, tol, depth + 1, out);
}

}  // namespace

std::vector<Point2> ConicToCubics(const Stroke& s, double tolerance) {
    std::vector<Point2> out{s.ArcPoint(s.a0)};
    AppendCubics(s, s.a0, s.a1, tolerance, 0, out);
    return out;
}

Page SingleViewPage(const Drawing& d, const std::string& title, double tolerance) {
    Page p;
    p.width = d.width;
    p.height = d.height;
    p.unit = "px";
    p.strokes = d.strokes;
    p.title = title;
    p.tolerance = tolerance;
    return p;
}

}  // namespace quadrix::draw
