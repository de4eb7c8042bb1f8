#include "quadrix/draw/drawing.h"

#include <chrono>
#include <cmath>

#include "quadrix/draw/curve_extraction.h"
#include "quadrix/draw/scene_probe.h"
#include "quadrix/draw/trim.h"
#include "quadrix/draw/visibility.h"

namespace quadrix::draw {

namespace {

Point2 XY(const Vec3& p) { return {p.x, p.y}; }

// Adaptive polyline of c on [t0, t1]: halves until the midpoint of each chord is within `tol`
// of the curve's midpoint (in projection), at least 8 chords.
void Flatten(const Curve3& c, double t0, double t1, double tol, std::vector<Point2>& out,
             int depth) {
    const Vec3 a = c.At(t0), b = c.At(t1), m = c.At(0.5 * (t0 + t1));
    const double dx = 0.5 * (a.x + b.x) - m.x, dy = 0.5 * (a.y + b.y) - m.y;
    if (depth >= 3 && (std::hypot(dx, dy) <= tol || depth > 24)) {
        out.push_back(XY(b));
        return;
    }
    Flatten(c, t0, 0.5 * (t0 + t1), tol, out, depth + 1);
    Flatten(c, 0.5 * (t0 + t1), t1, tol, out, depth + 1);
}

Stroke ToStroke(const Curve3& c, const CurvePiece& p, double tol, bool thinTangent) {
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
    s.kind = StrokeKind::kPolyline;
    if (c.kind == CurveKind::kPolyline) {
        s.points.push_back(XY(c.At(p.t0)));
        for (double k = std::floor(p.t0) + 1; k < p.t1; k += 1) s.points.push_back(XY(c.At(k)));
        s.points.push_back(XY(c.At(p.t1)));
        return s;
    }
    s.points.push_back(XY(c.At(p.t0)));
    Flatten(c, p.t0, p.t1, tol, s.points, 0);
    return s;
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
    const double ct = std::cos(t), st = std::sin(t);
    return {c.x + U.x * ct + V.x * st, c.y + U.y * ct + V.y * st};
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
                                     options.chordTolerance,
                                     options.tangentEdges == TangentEdges::kThin));
    }
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
