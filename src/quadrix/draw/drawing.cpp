#include "quadrix/draw/drawing.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "quadrix/draw/curve_extraction.h"
#include "quadrix/draw/scene_probe.h"
#include "quadrix/draw/trim.h"
#include "quadrix/draw/visibility.h"

namespace quadrix::draw {

namespace {

Point2 XY(const Vec3& p) { return {p.x, p.y}; }

Stroke ToStroke(const Curve3& c, const CurvePiece& p, bool thinTangent) {
    Stroke s;
    s.role = c.role;
    s.tangent = p.tangent && thinTangent;
    s.source = c.kind;
    s.visible = p.visible;
    s.surfaceA = c.surfaceA;
    s.surfaceB = c.surfaceB;
    if (c.kind == CurveKind::kLine) {
        s.kind = StrokeKind::kSegment;
        s.points = {XY(c.At(p.t0)), XY(c.At(p.t1))};
        return s;
    }
    if (c.kind == CurveKind::kEllipse) {
        const double det = c.u.x * c.v.y - c.u.y * c.v.x;
        const double size = c.u.x * c.u.x + c.u.y * c.u.y + c.v.x * c.v.x + c.v.y * c.v.y;
        if (std::fabs(det) > 1e-9 * size) {
            s.kind = StrokeKind::kEllipseArc;
            s.c = XY(c.o);
            s.U = XY(c.u);
            s.V = XY(c.v);
            s.a0 = p.t0;
            s.a1 = p.t1;
            return s;
        }
        // Seen edge-on: the arc's image runs along one segment, perhaps back and forth. Its
        // extent along the segment's direction d is that of d·(U cos θ + V sin θ) over the arc:
        // the ends and the interior extremes θ* = atan2(d·V, d·U) (+ kπ).
        const Point2 U = XY(c.u), V = XY(c.v);
        Point2 d = std::hypot(U.x, U.y) >= std::hypot(V.x, V.y) ? U : V;
        const double dl = std::hypot(d.x, d.y);
        if (dl > 0) {
            d = {d.x / dl, d.y / dl};
            const double du = d.x * U.x + d.y * U.y, dv = d.x * V.x + d.y * V.y;
            std::vector<double> ts{p.t0, p.t1};
            const double ts0 = std::atan2(dv, du);
            for (int k = -4; k <= 4; ++k) {
                const double t = ts0 + k * M_PI;
                if (t > p.t0 && t < p.t1) ts.push_back(t);
            }
            double lo = HUGE_VAL, hi = -HUGE_VAL;
            Point2 plo, phi;
            for (double t : ts) {
                const Point2 q = XY(c.At(t));
                const double proj = d.x * q.x + d.y * q.y;
                if (proj < lo) {
                    lo = proj;
                    plo = q;
                }
                if (proj > hi) {
                    hi = proj;
                    phi = q;
                }
            }
            s.kind = StrokeKind::kSegment;
            s.points = {plo, phi};
            return s;
        }
    }
    if (c.kind == CurveKind::kHyperbola || c.kind == CurveKind::kParabola) {
        // The image of X(t) = o + u f(t) + v g(t) is c + U f(t) + V g(t) with the same f, g:
        // kept in closed form for the writers (exact `Q` for a parabola, Béziers within the
        // page's tolerance for a hyperbola).
        s.kind =
            c.kind == CurveKind::kHyperbola ? StrokeKind::kHyperbolaArc : StrokeKind::kParabolaArc;
        s.c = XY(c.o);
        s.U = XY(c.u);
        s.V = XY(c.v);
        s.a0 = p.t0;
        s.a1 = p.t1;
        return s;
    }
    s.kind = StrokeKind::kPolyline;
    s.points.push_back(XY(c.At(p.t0)));
    for (double k = std::floor(p.t0) + 1; k < p.t1; k += 1) s.points.push_back(XY(c.At(k)));
    s.points.push_back(XY(c.At(p.t1)));
    return s;
}

Point2 StartOf(const Stroke& s) { return s.IsConicArc() ? s.ArcPoint(s.a0) : s.points.front(); }
Point2 EndOf(const Stroke& s) { return s.IsConicArc() ? s.ArcPoint(s.a1) : s.points.back(); }
Point2 MidOf(const Stroke& s) {
    if (s.IsConicArc()) return s.ArcPoint(0.5 * (s.a0 + s.a1));
    if (s.points.size() == 2)
        return {0.5 * (s.points[0].x + s.points[1].x), 0.5 * (s.points[0].y + s.points[1].y)};
    return s.points[s.points.size() / 2];
}

bool Near(const Point2& a, const Point2& b, double tol) {
    return std::fabs(a.x - b.x) <= tol && std::fabs(a.y - b.y) <= tol;
}

// Strokes that draw the same line twice — the same ends (either way round) and the same midpoint
// within 1e-6 px — are written once: the one that takes precedence is kept (drafting practice:
// visible over hidden, then silhouette over edge over tangent edge). Distinct 3-D curves have one
// image when they lie behind each other along the rays: the machined part's holes at z = ±12 seen
// from the front draw their hidden outline rulings on the same lines. Returns how many were
// dropped.
int RemoveDuplicates(std::vector<Stroke>& strokes) {
    constexpr double kTol = 1e-6;
    auto weight = [](const Stroke& s) {
        return (s.visible ? 10 : 0) + (s.role == CurveRole::kSilhouette ? 2 : (s.tangent ? 0 : 1));
    };
    struct Key {
        Point2 lo, hi, mid;
        std::size_t index;
    };
    std::vector<Key> keys;
    keys.reserve(strokes.size());
    for (std::size_t i = 0; i < strokes.size(); ++i) {
        Point2 a = StartOf(strokes[i]), b = EndOf(strokes[i]);
        if (b.x < a.x || (b.x == a.x && b.y < a.y)) std::swap(a, b);
        keys.push_back({a, b, MidOf(strokes[i]), i});
    }
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) { return a.lo.x < b.lo.x; });
    std::vector<char> drop(strokes.size(), 0);
    int dropped = 0;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (drop[keys[i].index]) continue;
        for (std::size_t j = i + 1; j < keys.size() && keys[j].lo.x - keys[i].lo.x <= 2 * kTol;
             ++j) {
            const Key &a = keys[i], &b = keys[j];
            const Stroke &sa = strokes[a.index], &sb = strokes[b.index];
            if (drop[b.index]) continue;
            // Ends may be sorted differently when they are within the tolerance in x.
            const bool ends = (Near(a.lo, b.lo, kTol) && Near(a.hi, b.hi, kTol)) ||
                              (Near(a.lo, b.hi, kTol) && Near(a.hi, b.lo, kTol));
            if (!ends || !Near(a.mid, b.mid, kTol)) continue;
            const std::size_t loser = weight(sb) > weight(sa) ? a.index : b.index;
            drop[loser] = 1;
            ++dropped;
            if (loser == a.index) break;
        }
    }
    std::size_t k = 0;
    for (std::size_t i = 0; i < strokes.size(); ++i)
        if (!drop[i]) {
            if (k != i) strokes[k] = std::move(strokes[i]);  // (a self-move empties a vector)
            ++k;
        }
    strokes.resize(k);
    return dropped;
}

// Pieces of a closed curve that meet across θ = 0 = 2π with the same visibility become one.
void MergeWrapAround(const std::vector<Curve3>& curves, std::vector<CurvePiece>& pieces) {
    std::vector<CurvePiece> out;
    std::size_t i = 0;
    while (i < pieces.size()) {
        std::size_t j = i;
        while (j < pieces.size() && pieces[j].curve == pieces[i].curve) ++j;
        const Curve3& c = curves[static_cast<std::size_t>(pieces[i].curve)];
        std::vector<CurvePiece> group(pieces.begin() + static_cast<long>(i),
                                      pieces.begin() + static_cast<long>(j));
        // Consecutive pieces with the same visibility merge too (trim splits and visibility
        // changes that cancel).
        // Slivers shorter than kSliver px in projection (a hidden edge emerging at a vertex is
        // judged visible within the depth tolerance for ~1e-5 px) join their neighbour.
        std::vector<CurvePiece> solid;
        for (const CurvePiece& p : group) {
            const bool sliver = ProjectedLength(c, p.t0, p.t1) < kSliver;
            const bool joins =
                !solid.empty() && solid.back().t1 == p.t0 && solid.back().tangent == p.tangent;
            if (sliver && joins) {
                solid.back().t1 = p.t1;
            } else if (joins && ProjectedLength(c, solid.back().t0, solid.back().t1) < kSliver) {
                const double t0 = solid.back().t0;
                solid.back() = p;
                solid.back().t0 = t0;
            } else {
                solid.push_back(p);
            }
        }
        std::vector<CurvePiece> merged;
        for (const CurvePiece& p : solid) {
            if (!merged.empty() && merged.back().t1 == p.t0 && merged.back().visible == p.visible &&
                merged.back().tangent == p.tangent)
                merged.back().t1 = p.t1;
            else
                merged.push_back(p);
        }
        if (c.Closed() && merged.size() > 1 && merged.front().t0 == c.t0 &&
            merged.back().t1 == c.t1 && merged.front().visible == merged.back().visible &&
            merged.front().tangent == merged.back().tangent) {
            merged.back().t1 = merged.front().t1 + (c.t1 - c.t0);
            merged.erase(merged.begin());
        }
        out.insert(out.end(), merged.begin(), merged.end());
        i = j;
    }
    pieces = std::move(out);
}

}  // namespace

Point2 Stroke::ArcPoint(double t) const {
    double f = 0, g = 0;
    if (kind == StrokeKind::kHyperbolaArc) {
        f = std::cosh(t);
        g = std::sinh(t);
    } else if (kind == StrokeKind::kParabolaArc) {
        f = t;
        g = t * t;
    } else {
        f = std::cos(t);
        g = std::sin(t);
    }
    return {c.x + U.x * f + V.x * g, c.y + U.y * f + V.y * g};
}

Point2 Stroke::ArcTangent(double t) const {
    double f = 0, g = 0;
    if (kind == StrokeKind::kHyperbolaArc) {
        f = std::sinh(t);
        g = std::cosh(t);
    } else if (kind == StrokeKind::kParabolaArc) {
        f = 1;
        g = 2 * t;
    } else {
        f = -std::sin(t);
        g = std::cos(t);
    }
    return {U.x * f + V.x * g, U.y * f + V.y * g};
}

Drawing MakeDrawing(const FlatScene& scene, const DrawOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Drawing d;
    d.width = scene.width;
    d.height = scene.height;
    const Box3 box = SceneBox(scene);
    if (box.Empty()) return d;
    auto lap = [last = start]() mutable {
        const auto now = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(now - last).count();
        last = now;
        return s;
    };
    const Surfaces surfaces = ClassifySurfaces(scene, box);
    ExtractionCounters ec;
    const std::vector<Curve3> curves = ExtractCurves(scene, surfaces, box, ec);
    d.stats.curveSeconds = lap();
    SceneProbe probe(scene);
    const std::vector<CurvePiece> trimmed =
        TrimToBoundary(scene, surfaces, probe, curves, options.tangentEdges != TangentEdges::kOff);
    d.stats.trimSeconds = lap();
    VisibilityCounters vc;
    std::vector<CurvePiece> pieces =
        SplitByVisibility(curves, trimmed, probe, options.visibilityStep, vc);
    d.stats.visibilitySeconds = lap();
    MergeWrapAround(curves, pieces);
    for (const CurvePiece& p : pieces) {
        if (!p.visible && !options.hidden) continue;
        d.strokes.push_back(ToStroke(curves[static_cast<std::size_t>(p.curve)], p,
                                     options.tangentEdges == TangentEdges::kThin));
    }
    d.stats.duplicates = RemoveDuplicates(d.strokes);
    d.stats.strokeSeconds = lap();
    d.stats.candidates = static_cast<int>(curves.size());
    d.stats.pieces = static_cast<int>(trimmed.size());
    d.stats.strokes = static_cast<int>(d.strokes.size());
    d.stats.lines = ec.lines;
    d.stats.conics = ec.conics;
    d.stats.silhouettes = ec.silhouettes;
    d.stats.quartics = ec.quartics;
    d.stats.tangentPairs = ec.tangentPairs;
    for (const CurvePiece& p : trimmed) d.stats.tangentPieces += p.tangent;
    d.stats.rayTests = vc.rayTests;
    d.stats.visibilityChanges = vc.changes;
    d.stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return d;
}

void TransformDrawing(Drawing& d, double s, double dx, double dy) {
    auto map = [&](Point2& p) {
        p.x = s * p.x + dx;
        p.y = s * p.y + dy;
    };
    for (Stroke& st : d.strokes) {
        map(st.c);
        st.U.x *= s;
        st.U.y *= s;
        st.V.x *= s;
        st.V.y *= s;
        for (Point2& p : st.points) map(p);
    }
}

}  // namespace quadrix::draw
