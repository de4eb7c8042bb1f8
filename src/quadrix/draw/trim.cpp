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

// Angles in [0, 2π) where membership changes on the circle p + r (n1 cos φ + n2 sin φ), located
// by bisection (48 directions, 30 halvings each).
std::vector<double> CircleTransitions(const SceneProbe& probe, const Vec3& p, const Vec3& n1,
                                      const Vec3& n2, double r) {
    auto inside = [&](double phi) {
        return probe.Inside(p + (n1 * std::cos(phi) + n2 * std::sin(phi)) * r);
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
    return transitions;
}

// Two transitions nearly opposite (within `tol` rad): one smooth sheet crosses the circle.
bool OneSheet(const std::vector<double>& tr, double tol) {
    return tr.size() == 2 && std::fabs(tr[1] - tr[0] - M_PI) <= tol;
}

// The local structure around a curve point when a third surface passes through the curve (see
// trim.h): membership on a circle of radius eps in the curve's normal plane. Two antipodal
// transitions are one smooth face through the point: kNone here (the caller asks TangentJoin).
BoundaryKind CircleTest(const SceneProbe& probe, const Vec3& p, const Vec3& ga, const Vec3& gb,
                        double eps) {
    const Vec3 t = Normalize(Cross(ga, gb));
    const Vec3 n1 = Normalize(ga), n2 = Cross(t, n1);
    const std::vector<double> tr = CircleTransitions(probe, p, n1, n2, eps);
    if (tr.empty() || OneSheet(tr, 1e-3)) return BoundaryKind::kNone;
    return BoundaryKind::kEdge;
}

// A tangent edge at p (trim.h, "Tangent edges")? `tangentDir` is the curve's direction at p,
// `surfaces` the surfaces through p (the curve's two, then those containing the curve).
bool TangentJoin(const FlatScene& scene, const SceneProbe& probe, const Vec3& p,
                 const Vec3& tangentDir, const Vec3& ga, const std::vector<int>& surfaces,
                 int curveA, int curveB, double delta) {
    const double tl = Length(tangentDir);
    if (!(tl > 0) || !std::isfinite(tl)) return false;
    const Vec3 t = tangentDir / tl;
    Vec3 n1 = ga - t * Dot(ga, t);
    if (!(Length(n1) > 0)) return false;
    n1 = Normalize(n1);
    const Vec3 n2 = Cross(t, n1);
    const std::vector<double> tr = CircleTransitions(probe, p, n1, n2, delta);
    if (!OneSheet(tr, 0.1)) return false;
    int owner[2] = {-1, -1};
    for (int k = 0; k < 2; ++k) {
        const Vec3 q = p + (n1 * std::cos(tr[static_cast<std::size_t>(k)]) +
                            n2 * std::sin(tr[static_cast<std::size_t>(k)])) *
                               delta;
        double best = HUGE_VAL;
        for (int s : surfaces) {
            const FlatHalfSpace& h = scene.halfSpaces[static_cast<std::size_t>(s)];
            const double gl = Length(GradientOf(h, q));
            if (!(gl > 0)) continue;
            const double dist = std::fabs(h.Evaluate(q)) / gl;
            if (dist < best) {
                best = dist;
                owner[k] = s;
            }
        }
    }
    if (owner[0] < 0 || owner[1] < 0 || owner[0] == owner[1]) return false;
    // One curve keeps a join that several carry (trim.h): the curve of the two faces' surfaces
    // when it is extracted in closed form (a plane is one of them: the double line), else one
    // on the lower-numbered face's surface.
    if ((curveA == owner[0] && curveB == owner[1]) || (curveA == owner[1] && curveB == owner[0]))
        return true;
    if (scene.halfSpaces[static_cast<std::size_t>(owner[0])].isPlane ||
        scene.halfSpaces[static_cast<std::size_t>(owner[1])].isPlane)
        return false;
    const int low = std::min(owner[0], owner[1]);
    return curveA == low || curveB == low;
}

}  // namespace

BoundaryKind OnBoundary(const FlatScene& scene, const SceneProbe& probe, const Curve3& c, double t,
                        double eps, const std::vector<int>& shared) {
    const Vec3 p = c.At(t);
    const FlatHalfSpace& A = scene.halfSpaces[static_cast<std::size_t>(c.surfaceA)];
    const Vec3 ga = GradientOf(A, p);
    const double la = Length(ga);
    if (!(la > 0) || !std::isfinite(la)) return BoundaryKind::kNone;
    if (c.role == CurveRole::kSilhouette) {
        const Vec3 d = ga * (eps / la);
        return probe.Inside(p + d) != probe.Inside(p - d) ? BoundaryKind::kEdge
                                                          : BoundaryKind::kNone;
    }
    const FlatHalfSpace& B = scene.halfSpaces[static_cast<std::size_t>(c.surfaceB)];
    const Vec3 gb = GradientOf(B, p);
    const double lb = Length(gb);
    if (!(lb > 0) || !std::isfinite(lb)) return BoundaryKind::kNone;
    // δ of the tangent test: 1e-3 of the image's larger side (eps is 1e-7 of it).
    const double delta = eps * 1e4;
    auto tangentJoin = [&] {
        std::vector<int> surfaces{c.surfaceA, c.surfaceB};
        surfaces.insert(surfaces.end(), shared.begin(), shared.end());
        return TangentJoin(scene, probe, p, c.Derivative(t), ga, surfaces, c.surfaceA, c.surfaceB,
                           delta)
                   ? BoundaryKind::kTangent
                   : BoundaryKind::kNone;
    };
    const double sinAngle = Length(Cross(ga, gb)) / (la * lb);
    if (!(sinAngle > kTangentSin)) return tangentJoin();
    if (!shared.empty()) {
        const BoundaryKind k = CircleTest(probe, p, ga, gb, eps);
        return k == BoundaryKind::kEdge ? k : tangentJoin();
    }
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
    return !onlyA && !onlyB ? BoundaryKind::kEdge : BoundaryKind::kNone;
}

namespace {

// A closed curve without breaks: classified as at t = π (its midpoint) when one of its two
// golden sections is on the boundary too, else not at all (a midpoint off the boundary is kept
// as it was). Its midpoint is a point of symmetry (an ellipse's vertex), which is where it may
// touch a surface it does not cross (a tangency the breaks miss), and one sample there would
// classify the whole curve by the tangency (gallery/name: a tube's cap ellipse tangent to the
// next tube was drawn whole, or not, depending on the last bits of the bounds).
BoundaryKind WholeCurveKind(const FlatScene& scene, const SceneProbe& probe, const Curve3& c,
                            double eps, const std::vector<int>& shared) {
    constexpr double kGolden = 0.381966011250105;  // (3 - √5) / 2
    const double t0 = c.t0, t1 = c.t1;
    const BoundaryKind mid = OnBoundary(scene, probe, c, 0.5 * (t0 + t1), eps, shared);
    if (mid == BoundaryKind::kNone) return mid;
    if (OnBoundary(scene, probe, c, t0 + kGolden * (t1 - t0), eps, shared) != BoundaryKind::kNone)
        return mid;
    if (OnBoundary(scene, probe, c, t1 - kGolden * (t1 - t0), eps, shared) != BoundaryKind::kNone)
        return mid;
    return BoundaryKind::kNone;
}

}  // namespace

std::vector<CurvePiece> TrimToBoundary(const FlatScene& scene, const Surfaces& surfaces,
                                       const SceneProbe& probe, const std::vector<Curve3>& curves,
                                       bool keepTangent) {
    std::vector<CurvePiece> out;
    const double eps = 1e-7 * std::max({scene.width, scene.height, 1});
    const double containTol = 1e-9 * std::max({scene.width, scene.height, 1});
    for (std::size_t ci = 0; ci < curves.size(); ++ci) {
        const Curve3& c = curves[ci];
        const Box3 cb = CurveBox(c);
        std::vector<double> ts{c.t0, c.t1};
        std::vector<int> shared;
        for (int r : surfaces.reps) {
            if (r == c.surfaceA || r == c.surfaceB) continue;
            if (!cb.Overlaps(surfaces.box[static_cast<std::size_t>(r)])) continue;
            const FlatHalfSpace& h = scene.halfSpaces[static_cast<std::size_t>(r)];
            if (ContainsCurve(h, c, containTol)) {
                shared.push_back(r);  // its sign along the curve is rounding noise: no breaks
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
            const BoundaryKind kind =
                c.Closed() && ts.size() == 2
                    ? WholeCurveKind(scene, probe, c, eps, shared)
                    : OnBoundary(scene, probe, c, 0.5 * (ts[i] + ts[i + 1]), eps, shared);
            if (kind == BoundaryKind::kNone) continue;
            const bool tangent = kind == BoundaryKind::kTangent;
            if (!keepTangent && tangent) continue;
            if (out.size() > first && out.back().tangent == tangent &&
                (out.back().t1 == ts[i] || ProjectedLength(c, out.back().t1, ts[i]) < kSliver)) {
                out.back().t1 = ts[i + 1];  // consecutive pieces merge, tiny gaps close
            } else {
                out.push_back({static_cast<int>(ci), ts[i], ts[i + 1], true, tangent});
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
