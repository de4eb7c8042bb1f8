#include "quadrix/draw/trim.h"

#include <algorithm>
#include <cmath>

#include "quadrix/math/quadratic.h"

namespace quadrix::draw {

namespace {

Vec3 GradientOf(const FlatHalfSpace& h, const Vec3& p) {
    return h.isPlane ? h.plane.Normal() : h.quadric.Gradient(p);
}

Box3 CurveBox(const Curve3& c) {
    Box3 b;
    if (c.kind == CurveKind::kPolyline) {
        for (const Vec3& p : c.points) b.Extend(p);
        return b;
    }
    if (c.kind == CurveKind::kLine) {
        b.Extend(c.At(c.t0));
        b.Extend(c.At(c.t1));
        return b;
    }
    if (c.kind == CurveKind::kEllipse) {
        const Vec3 r{std::hypot(c.u.x, c.v.x), std::hypot(c.u.y, c.v.y), std::hypot(c.u.z, c.v.z)};
        b.Extend(c.o - r);
        b.Extend(c.o + r);
        return b;
    }
    for (int i = 0; i <= 64; ++i) b.Extend(c.At(c.t0 + (c.t1 - c.t0) * i / 64));
    const Vec3 pad = b.Size() * 0.05;  // sampled: widen a little
    b.lo -= pad;
    b.hi += pad;
    return b;
}

// Does surface h contain the curve (to `tol` device px at 16 points)? At a mitred joint the
// bisecting plane meets both tubes in one ellipse, so three surfaces share it.
bool ContainsCurve(const FlatHalfSpace& h, const Curve3& c, double tol) {
    for (int i = 0; i <= 16; ++i) {
        const Vec3 p = c.At(c.t0 + (c.t1 - c.t0) * (i + 0.37) / 17.37);
        const Vec3 g = GradientOf(h, p);
        const double gl = Length(g);
        if (!(gl > 0) || !(std::fabs(h.Evaluate(p)) <= tol * gl)) return false;
    }
    return true;
}

bool Overlap(const Box3& a, const Box3& b) {
    return !(a.hi.x < b.lo.x || b.hi.x < a.lo.x || a.hi.y < b.lo.y || b.hi.y < a.lo.y ||
             a.hi.z < b.lo.z || b.hi.z < a.lo.z);
}

}  // namespace

std::vector<double> CurveBreaks(const Curve3& c, const FlatHalfSpace& s) {
    std::vector<double> out;
    auto keep = [&](double t) {
        if (t > c.t0 && t < c.t1 && std::isfinite(t)) out.push_back(t);
    };
    if (c.kind == CurveKind::kLine) {
        if (s.isPlane) {
            const double du = Dot(s.plane.Normal(), c.u);
            if (du != 0) keep(-s.plane.Evaluate(c.o) / du);
        } else {
            // Q(o + t u) = (uᵀA u) t² + 2 (Q o)·u t + Q(o): with the homogeneous gradient.
            const Mat4 q = s.quadric.Matrix();
            const Vec4 u4(c.u, 0), o4(c.o, 1);
            const double a = Dot(u4, q * u4), h = Dot(u4, q * o4), k = Dot(o4, q * o4);
            const QuadraticRoots r = SolveQuadratic(a, h, k);
            if (r.kind == RootKind::kTwo || r.kind == RootKind::kSingle) {
                keep(r.t0);
                if (r.kind == RootKind::kTwo) keep(r.t1);
            }
        }
        std::sort(out.begin(), out.end());
        return out;
    }
    int n = 96;
    if (c.kind == CurveKind::kPolyline) n = static_cast<int>(c.points.size()) - 1;
    if (n < 1) return out;
    auto param = [&](int i) { return c.t0 + (c.t1 - c.t0) * i / n; };
    double tp = param(0), vp = s.Evaluate(c.At(tp));
    for (int i = 1; i <= n; ++i) {
        const double t = param(i), v = s.Evaluate(c.At(t));
        if ((vp < 0) != (v < 0) && std::isfinite(v) && std::isfinite(vp)) {
            double lo = tp, hi = t, vlo = vp;
            for (int k = 0; k < 100; ++k) {
                const double mid = 0.5 * (lo + hi);
                if (mid <= lo || mid >= hi) break;
                const double vm = s.Evaluate(c.At(mid));
                if ((vm < 0) == (vlo < 0)) {
                    lo = mid;
                    vlo = vm;
                } else {
                    hi = mid;
                }
            }
            keep(0.5 * (lo + hi));
        }
        tp = t;
        vp = v;
    }
    std::sort(out.begin(), out.end());
    return out;
}

namespace {

// The local structure around a curve point when a third surface passes through the curve (see
// trim.h): membership on a circle of radius eps in the curve's normal plane, transitions located
// by bisection on the angle. Two antipodal transitions are one smooth face through the point.
bool CircleTest(const SceneProbe& probe, const Vec3& p, const Vec3& ga, const Vec3& gb,
                double eps) {
    const Vec3 t = Normalize(Cross(ga, gb));
    const Vec3 n1 = Normalize(ga), n2 = Cross(t, n1);
    auto inside = [&](double phi) {
        return probe.Inside(p + (n1 * std::cos(phi) + n2 * std::sin(phi)) * eps);
    };
    constexpr int kSteps = 48;
    std::vector<double> transitions;
    bool prev = inside(0);
    for (int k = 1; k <= kSteps; ++k) {
        const double phi = 2 * M_PI * k / kSteps;
        const bool cur = inside(phi);
        if (cur != prev) {
            double lo = 2 * M_PI * (k - 1) / kSteps, hi = phi;
            for (int i = 0; i < 30; ++i) {
                const double mid = 0.5 * (lo + hi);
                (inside(mid) == prev ? lo : hi) = mid;
            }
            transitions.push_back(0.5 * (lo + hi));
        }
        prev = cur;
    }
    if (transitions.empty()) return false;
    if (transitions.size() != 2) return true;
    return std::fabs(transitions[1] - transitions[0] - M_PI) > 1e-3;
}

}  // namespace

bool OnBoundary(const FlatScene& scene, const SceneProbe& probe, const Curve3& c, double t,
                double eps, bool shared) {
    const Vec3 p = c.At(t);
    const FlatHalfSpace& A = scene.halfSpaces[static_cast<std::size_t>(c.surfaceA)];
    const Vec3 ga = GradientOf(A, p);
    const double la = Length(ga);
    if (!(la > 0) || !std::isfinite(la)) return false;
    if (c.role == CurveRole::kSilhouette) {
        const Vec3 d = ga * (eps / la);
        return probe.Inside(p + d) != probe.Inside(p - d);
    }
    const FlatHalfSpace& B = scene.halfSpaces[static_cast<std::size_t>(c.surfaceB)];
    const Vec3 gb = GradientOf(B, p);
    const double lb = Length(gb);
    if (!(lb > 0) || !std::isfinite(lb)) return false;
    const double sinAngle = Length(Cross(ga, gb)) / (la * lb);
    if (!(sinAngle > 1e-4)) return false;  // tangent: a smooth join
    if (shared) return CircleTest(probe, p, ga, gb, eps);
    const double aa = Dot(ga, ga), ab = Dot(ga, gb), bb = Dot(gb, gb);
    const double det = aa * bb - ab * ab;
    bool m[2][2];
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            const double ra = (i ? 1 : -1) * la * eps, rb = (j ? 1 : -1) * lb * eps;
            const double alpha = (ra * bb - rb * ab) / det, beta = (rb * aa - ra * ab) / det;
            m[i][j] = probe.Inside(p + ga * alpha + gb * beta);
        }
    const bool onlyA = m[0][0] == m[0][1] && m[1][0] == m[1][1];
    const bool onlyB = m[0][0] == m[1][0] && m[0][1] == m[1][1];
    return !onlyA && !onlyB;
}

namespace {

// A closed curve without breaks: an edge when OnBoundary says so at t = π (its midpoint) and at
// one of its two golden sections (a midpoint that says "not an edge" is kept as it was). Its
// midpoint is a point of symmetry (an ellipse's vertex), which is where it may touch a surface it
// does not cross (a tangency the breaks miss), and one sample there would classify the whole
// curve by the tangency (gallery/name: a tube's cap ellipse tangent to the next tube was drawn
// whole, or not, depending on the last bits of the bounds).
bool WholeCurveOnBoundary(const FlatScene& scene, const SceneProbe& probe, const Curve3& c,
                          double eps, bool shared) {
    constexpr double kGolden = 0.381966011250105;  // (3 - √5) / 2
    const double t0 = c.t0, t1 = c.t1;
    const bool mid = OnBoundary(scene, probe, c, 0.5 * (t0 + t1), eps, shared);
    if (!mid) return false;
    const bool a = OnBoundary(scene, probe, c, t0 + kGolden * (t1 - t0), eps, shared);
    if (a) return true;
    return OnBoundary(scene, probe, c, t1 - kGolden * (t1 - t0), eps, shared);
}

}  // namespace

std::vector<CurvePiece> TrimToBoundary(const FlatScene& scene, const Surfaces& surfaces,
                                       const SceneProbe& probe, const std::vector<Curve3>& curves) {
    std::vector<CurvePiece> out;
    const double eps = 1e-7 * std::max({scene.width, scene.height, 1});
    const double containTol = 1e-9 * std::max({scene.width, scene.height, 1});
    for (std::size_t ci = 0; ci < curves.size(); ++ci) {
        const Curve3& c = curves[ci];
        const Box3 cb = CurveBox(c);
        std::vector<double> ts{c.t0, c.t1};
        bool shared = false;
        for (int r : surfaces.reps) {
            if (r == c.surfaceA || r == c.surfaceB) continue;
            if (!Overlap(cb, surfaces.box[static_cast<std::size_t>(r)])) continue;
            const FlatHalfSpace& h = scene.halfSpaces[static_cast<std::size_t>(r)];
            if (ContainsCurve(h, c, containTol)) {
                shared = true;  // its sign along the curve is rounding noise: no breaks
                continue;
            }
            auto b = CurveBreaks(c, h);
            ts.insert(ts.end(), b.begin(), b.end());
        }
        std::sort(ts.begin(), ts.end());
        const double minLen = 1e-12 * (std::fabs(c.t1 - c.t0) + 1);
        std::size_t first = out.size();
        for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
            if (!(ts[i + 1] - ts[i] > minLen)) continue;
            const bool whole = c.Closed() && ts.size() == 2;
            if (!(whole ? WholeCurveOnBoundary(scene, probe, c, eps, shared)
                        : OnBoundary(scene, probe, c, 0.5 * (ts[i] + ts[i + 1]), eps, shared)))
                continue;
            if (out.size() > first &&
                (out.back().t1 == ts[i] || ProjectedLength(c, out.back().t1, ts[i]) < kSliver)) {
                out.back().t1 = ts[i + 1];  // consecutive pieces merge, tiny gaps close
            } else {
                out.push_back({static_cast<int>(ci), ts[i], ts[i + 1], true});
            }
        }
        if (c.Closed() && out.size() > first) {  // a tiny gap across t0 = t1 closes too
            if (out[first].t0 != c.t0 && ProjectedLength(c, c.t0, out[first].t0) < kSliver)
                out[first].t0 = c.t0;
            if (out.back().t1 != c.t1 && ProjectedLength(c, out.back().t1, c.t1) < kSliver)
                out.back().t1 = c.t1;
        }
    }
    return out;
}

}  // namespace quadrix::draw
