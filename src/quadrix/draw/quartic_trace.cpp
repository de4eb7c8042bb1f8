#include "quadrix/draw/quartic_trace.h"

#include <algorithm>
#include <cmath>

#include "quadrix/draw/conic_section.h"

namespace quadrix::draw {

namespace {

bool InBox(const Box3& b, const Vec3& p) {
    return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z &&
           p.z <= b.hi.z;
}

bool Project(const Quadric& a, const Quadric& b, Vec3& p, double tol) {
    return ProjectOntoBoth(a, b, p, tol);
}

Vec3 TangentAt(const Quadric& a, const Quadric& b, const Vec3& p) {
    return Cross(a.Gradient(p), b.Gradient(p));
}

double DistanceToPolyline(const std::vector<Vec3>& pts, const Vec3& p) {
    double best = HUGE_VAL;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const Vec3 d = pts[i + 1] - pts[i];
        const double dd = Dot(d, d);
        double t = dd > 0 ? std::clamp(Dot(p - pts[i], d) / dd, 0.0, 1.0) : 0.0;
        best = std::fmin(best, Length(pts[i] + d * t - p));
    }
    if (pts.size() == 1) best = Length(pts[0] - p);
    return best;
}

// Follows the curve from `start` along `dir` (±1 times the tangent). Returns the points after
// `start`; `closed` when it came back to the start.
std::vector<Vec3> Follow(const Quadric& a, const Quadric& b, const Box3& box, const Vec3& start,
                         double dir, double tol, double hMax, bool& closed) {
    std::vector<Vec3> pts;
    closed = false;
    Vec3 p = start;
    Vec3 t = Normalize(TangentAt(a, b, p) * dir);
    double h = hMax * 0.25;
    double travelled = 0;
    const double ptol = 1e-10 * (1 + Length(start));
    for (int step = 0; step < 200000; ++step) {
        if (Length(t) == 0) return pts;  // singular point
        Vec3 q = p + t * h;
        if (!Project(a, b, q, ptol)) {
            if (h < 1e-6 * hMax) return pts;
            h *= 0.5;
            continue;
        }
        Vec3 tq = Normalize(TangentAt(a, b, q));
        if (Dot(tq, t) < 0) tq = -tq;
        const double turn = std::acos(std::clamp(Dot(tq, t), -1.0, 1.0));
        if (turn * h > 8 * tol && h > 1e-6 * hMax) {
            h *= 0.5;
            continue;
        }
        travelled += Length(q - p);
        // Closed loop: back within one step of the start, after going some way.
        if (travelled > 4 * h && Length(q - start) < 1.5 * h) {
            closed = true;
            return pts;
        }
        pts.push_back(q);
        if (!InBox(box, q)) return pts;
        p = q;
        t = tq;
        if (turn * h < 2 * tol) h = std::fmin(h * 1.5, hMax);
    }
    return pts;
}

// Points strictly between p and q on the curve such that every chord's midpoint is within tol.
void Refine(const Quadric& a, const Quadric& b, const Vec3& p, const Vec3& q, double tol, int depth,
            std::vector<Vec3>& out) {
    const Vec3 m = (p + q) * 0.5;
    Vec3 c = m;
    if (depth > 20 || !Project(a, b, c, 1e-12 * (1 + Length(m))) || Length(c - m) <= tol) return;
    Refine(a, b, p, c, tol, depth + 1, out);
    out.push_back(c);
    Refine(a, b, c, q, tol, depth + 1, out);
}

}  // namespace

std::vector<Curve3> TraceQuadricQuadric(const Quadric& a, const Quadric& b, const Box3& box,
                                        double chordTolerance) {
    std::vector<Curve3> out;
    if (box.Empty() || !box.Finite()) return out;
    const Vec3 size = box.Size();
    const double diag = Length(size);
    if (!(diag > 0)) return out;
    const double hMax = std::fmax(diag / 64, 10 * chordTolerance);
    std::vector<Vec3> seeds;
    constexpr int kSlices = 24, kSamples = 64;
    for (int axis = 0; axis < 3; ++axis)
        for (int s = 0; s < kSlices; ++s) {
            const double c = box.lo[axis] + size[axis] * (s + 0.5) / kSlices;
            Plane slice{axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0, -c};
            for (const Curve3& conic : PlaneQuadricCurves(slice, a, box)) {
                double prevT = conic.t0;
                double prevV = b.Evaluate(conic.At(prevT));
                for (int i = 1; i <= kSamples; ++i) {
                    const double t = conic.t0 + (conic.t1 - conic.t0) * i / kSamples;
                    const double v = b.Evaluate(conic.At(t));
                    if ((prevV < 0) != (v < 0)) {
                        double lo = prevT, hi = t, vlo = prevV;
                        for (int k = 0; k < 80 && lo != hi; ++k) {
                            const double mid = 0.5 * (lo + hi);
                            const double vm = b.Evaluate(conic.At(mid));
                            if ((vm < 0) == (vlo < 0)) {
                                lo = mid;
                                vlo = vm;
                            } else {
                                hi = mid;
                            }
                        }
                        seeds.push_back(conic.At(0.5 * (lo + hi)));
                    }
                    prevT = t;
                    prevV = v;
                }
            }
        }
    std::vector<std::vector<Vec3>> traced;
    for (Vec3 seed : seeds) {
        if (!Project(a, b, seed, 1e-10 * (1 + Length(seed)))) continue;
        bool skip = false;
        for (const auto& pl : traced)
            if (DistanceToPolyline(pl, seed) < 2 * hMax) {
                skip = true;
                break;
            }
        if (skip) continue;
        bool closed = false;
        std::vector<Vec3> fwd = Follow(a, b, box, seed, 1, chordTolerance, hMax, closed);
        std::vector<Vec3> pts;
        if (closed) {
            pts.push_back(seed);
            pts.insert(pts.end(), fwd.begin(), fwd.end());
            // The closing chord was not checked by Follow's step control: split it until its
            // midpoints are within the tolerance of the curve.
            const Vec3 last = pts.back();
            std::vector<Vec3> closing;
            Refine(a, b, last, seed, chordTolerance, 0, closing);
            pts.insert(pts.end(), closing.begin(), closing.end());
            pts.push_back(seed);
        } else {
            bool closed2 = false;
            std::vector<Vec3> back = Follow(a, b, box, seed, -1, chordTolerance, hMax, closed2);
            pts.assign(back.rbegin(), back.rend());
            pts.push_back(seed);
            pts.insert(pts.end(), fwd.begin(), fwd.end());
        }
        if (pts.size() < 2) continue;
        traced.push_back(pts);
        Curve3 c;
        c.kind = CurveKind::kPolyline;
        c.points = std::move(pts);
        c.t0 = 0;
        c.t1 = static_cast<double>(c.points.size() - 1);
        c.project = true;
        c.onA = a;
        c.onB = b;
        out.push_back(std::move(c));
    }
    return out;
}

}  // namespace quadrix::draw
