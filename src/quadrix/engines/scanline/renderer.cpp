#include "quadrix/engines/scanline/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "quadrix/math/interval_list.h"
#include "quadrix/math/quadratic.h"

namespace quadrix::scanline {

// ---------------------------------------------------------------- exact ray evaluation

RayEvaluator::RayEvaluator(const FlatScene& scene) : scene_(scene) {
    // The same re-centring points as raycast (its SceneTables::ReferencePoints), so the two
    // engines solve bit-identical quadratics.
    Vec3 anchor{std::round(0.5 * scene.width), std::round(0.5 * scene.height), 0};
    halfSpaces_.reserve(scene.halfSpaces.size());
    for (const FlatHalfSpace& hs : scene.halfSpaces) {
        Vec3 ref = hs.isPlane ? anchor : raycast::RayHalfSpace::Centre(hs.quadric).value_or(anchor);
        halfSpaces_.push_back(raycast::RayHalfSpace::From(hs, ref));
    }
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        bodyFirstTag_.push_back(static_cast<int>(tags_.size()));
        bool valid = true;
        for (const FlatLiteral& lit : scene.bodies[b].literals)
            valid = valid && lit.halfSpace >= 0 &&
                    static_cast<std::size_t>(lit.halfSpace) < scene.halfSpaces.size();
        if (!valid) continue;  // a body naming a missing half-space is empty (as in raycast)
        for (const FlatLiteral& lit : scene.bodies[b].literals) {
            const FlatHalfSpace& hs = scene.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
            tags_.push_back({lit.halfSpace, static_cast<int>(b), lit.complemented,
                             !hs.transparent && !hs.isClip});
        }
    }
    bodyFirstTag_.push_back(static_cast<int>(tags_.size()));
}

void RayEvaluator::BodySet(int body, double x, double y, IntervalList& out) {
    out.clear();
    int first = bodyFirstTag_[static_cast<std::size_t>(body)];
    int last = bodyFirstTag_[static_cast<std::size_t>(body) + 1];
    IntervalList lit, tmp;
    for (int t = first; t < last; ++t) {
        const Tag& tag = tags_[static_cast<std::size_t>(t)];
        raycast::RaySet s =
            raycast::LiteralOnRay(halfSpaces_[static_cast<std::size_t>(tag.halfSpace)],
                                  tag.complemented, x, y, t, literalCounters_);
        if (s.count == 0) {
            out.clear();
            return;
        }
        if (t == first) {
            for (int i = 0; i < s.count; ++i)
                out.Append(s.piece[i].lo, s.piece[i].loId, s.piece[i].hi, s.piece[i].hiId);
        } else if (s.count == 1) {
            ClipTo(out, s.piece[0]);
        } else {
            lit.clear();
            for (int i = 0; i < s.count; ++i)
                lit.Append(s.piece[i].lo, s.piece[i].loId, s.piece[i].hi, s.piece[i].hiId);
            Intersection(out, lit, tmp);
            std::swap(out, tmp);
        }
        if (out.empty()) return;
    }
}

bool RayEvaluator::First(const IntervalList& l, Hit& hit) const {
    for (const Interval& v : l) {
        for (auto [t, id] : {std::pair{v.lo, v.loId}, std::pair{v.hi, v.hiId}}) {
            if (id >= 0 && std::isfinite(t) && tags_[static_cast<std::size_t>(id)].opaque) {
                hit.t = t;
                hit.halfSpace = tags_[static_cast<std::size_t>(id)].halfSpace;
                hit.body = tags_[static_cast<std::size_t>(id)].body;
                return true;
            }
        }
    }
    return false;
}

bool RayEvaluator::Body(int body, double x, double y, Hit& hit) {
    IntervalList l;
    BodySet(body, x, y, l);
    return First(l, hit);
}

bool RayEvaluator::Node(int node, double x, double y, Hit& hit) {
    IntervalList l;
    TreeSet(
        node, [&](int body, IntervalList& out) { BodySet(body, x, y, out); }, l);
    return First(l, hit);
}

// ---------------------------------------------------------------- depth comparisons (§5.5.1)

bool FaceDerivatives(const FlatScene& scene, const FaceRef& f, double x, double y, double& z,
                     double& dz, double& d2z) {
    const FlatHalfSpace& hs = scene.halfSpaces[static_cast<std::size_t>(f.halfSpace)];
    if (hs.isPlane) {
        const Plane& p = hs.plane;
        if (p.c == 0) return false;
        z = -(p.a * x + p.b * y + p.d) / p.c;
        dz = -p.a / p.c;
        d2z = 0;
        return true;
    }
    const Quadric& q = hs.quadric;
    QuadraticRoots r = SolveQuadratic(
        q.C(), q.F() * x + q.E() * y + q.J(),
        q.A() * x * x + q.B() * y * y + 2 * q.D() * x * y + 2 * q.G() * x + 2 * q.H() * y + q.K());
    if (r.kind == RootKind::kNone || r.kind == RootKind::kAll) return false;
    z = (f.sheet == 1 && r.kind == RootKind::kTwo) ? r.t1 : r.t0;
    // F = Q(x, y, z): F_x = 2(A x + D y + F z + G), F_z = 2(F x + E y + C z + J),
    // F_xx = 2A, F_xz = 2F, F_zz = 2C (the common factor 2 cancels).
    double fx = q.A() * x + q.D() * y + q.F() * z + q.G();
    double fz = q.F() * x + q.E() * y + q.C() * z + q.J();
    if (fz == 0) return false;  // on the limb: dz/dx is infinite
    dz = -fx / fz;
    d2z = -(q.A() + 2 * q.F() * dz + q.C() * dz * dz) / fz;
    return true;
}

int CompareFaces(const FlatScene& scene, const FaceRef& f, const FaceRef& g, double x, double y,
                 double tolerance) {
    double zf, sf, cf, zg, sg, cg;
    bool hf = FaceDerivatives(scene, f, x, y, zf, sf, cf);
    bool hg = FaceDerivatives(scene, g, x, y, zg, sg, cg);
    if (!hf || !hg) return hf ? -1 : (hg ? 1 : 0);
    auto tol = [&](double a, double b) {
        return tolerance * (1 + std::max(std::fabs(a), std::fabs(b)));
    };
    if (std::fabs(zf - zg) > tol(zf, zg)) return zf < zg ? -1 : 1;
    // Case (a): equal at P; compare at Q one pixel on.
    double qf, qg, s1, s2, c1, c2;
    if (FaceDerivatives(scene, f, x + 1, y, qf, s1, c1) &&
        FaceDerivatives(scene, g, x + 1, y, qg, s2, c2) && std::fabs(qf - qg) > tol(qf, qg))
        return qf < qg ? -1 : 1;
    // Case (b): equal again: the lesser slope is in front.
    if (std::fabs(sf - sg) > tol(sf, sg)) return sf < sg ? -1 : 1;
    // Case (c): tangent faces: the smaller rate of change of slope is in front.
    if (std::fabs(cf - cg) > tol(cf, cg)) return cf < cg ? -1 : 1;
    return 0;
}

// ---------------------------------------------------------------- renderer

namespace {

constexpr double kOnEdge = 1e-6;  // pixels: crossings this close to a centre → exact pixel

struct ActiveEdge {
    int edge = -1;
    int lastRow = 0;
    double x = 0;
    double br = 0, cr = 0, dcr = 0;  // conic: (5.3) at the current row and ΔC_r
    double dx = 0;                   // linear: dx/dy
};

double SortKey(double x) { return std::isnan(x) ? HUGE_VAL : x; }

// An edge end within 1e-9 (relative) of a row centre j + ½ is put exactly on it: the vertex
// shared by two edges is computed separately for each (different i-lines, different rounding),
// and the half-open toggle rule of the face stacks needs both ends on the same side of the CSL.
double SnapToRow(double y) {
    const double r = std::round(y - 0.5) + 0.5;
    return std::fabs(y - r) <= 1e-9 * (1 + std::fabs(y)) ? r : y;
}

// One show-face on a span's stack, with its incremental state along the span.
struct StackFace {
    int unit = -1;
    int halfSpace = -1, body = -1, solid = -1;
    int sheet = 0;
    const raycast::RayHalfSpace* ray = nullptr;
    double h = 0, k = 0, dk = 0;  // quadric: c z'² + 2 h z' + k = 0 at the current pixel
    double planeE = 0;            // plane: px x + py y + pd at the current pixel
    double depth = HUGE_VAL;      // at the current pixel (NaN: no root)
    Vec3 fastNormal;
    int g0 = -1, g1 = -1;  // shading interval cache
    Vec3 n0, n1;
};

struct TemplateInterval {
    int lo = -1, hi = -1;        // indices of endpoint faces; −1 = infinite end
    int loTag = -1, hiTag = -1;  // the evaluator's tags of the endpoints
};
struct BodyTemplate {
    int body = -1;
    bool exact = false;  // refused body: evaluated per pixel
    std::size_t first = 0, count = 0;
};
struct CsgSpanUnit {
    int unit = -1;
    std::size_t firstTemplate = 0, templateCount = 0;
};

// The Edge Start List: per row, the edges (index, last row) that start there.
std::vector<std::vector<std::pair<int, int>>> BuildEsl(const std::vector<ShowEdge>& edges, int h) {
    std::vector<std::vector<std::pair<int, int>>> esl(static_cast<std::size_t>(std::max(h, 0)));
    for (std::size_t e = 0; e < edges.size(); ++e) {
        const ShowEdge& s = edges[e];
        // Rows whose centre j + ½ lies in the CLOSED range [yBottom, yTop]: a row exactly on a
        // horizontal boundary keeps the edges that end there, so the bodies they bound stay
        // candidates on that row (raycast's closed half-spaces decide it at the sample pixel).
        // Crossings are breakpoints, not parity toggles, so the duplicate crossing at a vertex
        // shared by two edges is harmless.
        double first = std::ceil(SnapToRow(s.yBottom) - 0.5);
        double last = std::floor(SnapToRow(s.yTop) - 0.5);
        first = std::max(first, 0.0);
        last = std::min(last, static_cast<double>(h - 1));
        if (!(first <= last)) continue;
        esl[static_cast<std::size_t>(first)].push_back(
            {static_cast<int>(e), static_cast<int>(last)});
    }
    return esl;
}

class ScanRenderer {
  public:
    ScanRenderer(const FlatScene& scene, std::vector<ShowEdge>& edges,
                 const std::vector<ShowFace>& faces, const std::vector<Unit>& units,
                 const std::vector<bool>& pixelBody, const std::vector<bool>& stackBody,
                 const RenderSettings& settings, Frame& frame, RendererCounters& c)
        : scene_(scene),
          edges_(edges),
          faces_(faces),
          units_(units),
          pixelBody_(pixelBody),
          settings_(settings),
          frame_(frame),
          c_(c),
          eval_(scene) {
        const std::size_t nb = scene.bodies.size();
        bodyUnit_.assign(nb, -1);
        bodyFaces_.assign(nb, {});
        useStack_.assign(nb, 0);
        for (std::size_t u = 0; u < units.size(); ++u) {
            const Unit& unit = units[u];
            if (unit.kind != Unit::Kind::kBody) continue;
            auto b = static_cast<std::size_t>(unit.body);
            bodyUnit_[b] = static_cast<int>(u);
            useStack_[b] =
                settings.faceStacks && b < stackBody.size() && stackBody[b] && !pixelBody[b];
        }
        for (std::size_t f = 0; f < faces.size(); ++f) {
            auto b = static_cast<std::size_t>(faces[f].body);
            if (b < nb) bodyFaces_[b].push_back(static_cast<int>(f));
        }
        inStack_.assign(faces.size(), 0);
        bodyLiterals_.resize(nb);
        for (std::size_t b = 0; b < nb; ++b) {
            if (!useStack_[b]) continue;
            for (const FlatLiteral& lit : scene.bodies[b].literals) {
                const FlatHalfSpace& hs = scene.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
                OrientedLiteral o;
                o.halfSpace = lit.halfSpace;
                o.isPlane = hs.isPlane;
                o.plane = hs.plane;
                o.quadric = hs.quadric;
                o.zFree = hs.isPlane ? PlaneIsEdgeOn(hs.plane)
                                     : QuadricIsViewCylinder(hs.quadric,
                                                             std::max(scene.width, scene.height));
                if (lit.complemented) {  // !h: −h <= 0
                    o.plane = {-hs.plane.a, -hs.plane.b, -hs.plane.c, -hs.plane.d};
                    for (double& v : o.quadric.k) v = -v;
                }
                bodyLiterals_[b].push_back(o);
            }
        }
        bodyTaken_.assign(nb, 0);
    }

    // Rows [j0, j1): a band. Bands are independent (each starts its AEL from the ESL), so they
    // run in parallel; results do not depend on the thread count, only on the fixed band size.
    void Run(const std::vector<std::vector<std::pair<int, int>>>& esl, int j0, int j1) {
        const int w = frame_.width, h = frame_.height;
        if (w <= 0 || h <= 0) return;
        esl_ = &esl;
        const std::size_t nb = scene_.bodies.size();
        lo_.assign(nb, HUGE_VAL);
        hi_.assign(nb, -HUGE_VAL);
        rangeRow_.assign(nb, -1);
        for (int j = j0; j < j1; ++j) Row(j, j == j0);
    }

    void Start(ActiveEdge& a, double y) {
        const ShowEdge& s = edges_[static_cast<std::size_t>(a.edge)];
        if (s.conic) {
            const Conic2& k = s.shape;
            a.br = k.c * y + k.d;
            a.cr = (k.b * y + k.e) * y + k.f;
            a.dcr = k.b * (2 * y + 1) + k.e;
        } else {
            a.dx = -s.line.b / s.line.a;
            a.x = s.XAt(y);
        }
        ++c_.edgesStarted;
    }

    // Pass two for one edge: x on the CSL. Conic edges by differences (§5.5.2).
    void Trace(ActiveEdge& a, bool first) {
        const ShowEdge& s = edges_[static_cast<std::size_t>(a.edge)];
        if (!s.conic) {
            if (!first) a.x += a.dx;
            return;
        }
        if (!first) {
            a.br += s.shape.c;
            a.cr += a.dcr;
            a.dcr += 2 * s.shape.b;
        }
        const double A = s.shape.a, B = a.br, C = a.cr;
        double disc = B * B - 4 * A * C;
        if (disc < 0) {
            if (disc < -(64 * kUnit) * (B * B + 4 * std::fabs(A * C))) {
                a.x = std::numeric_limits<double>::quiet_NaN();
                return;
            }
            disc = 0;
        }
        const double r = std::sqrt(disc), q = -0.5 * (B + (B >= 0 ? r : -r));
        const double minus = B >= 0 ? q / A : C / q, plus = B >= 0 ? C / q : q / A;
        a.x = s.leg < 0 ? minus : plus;
    }

    void Row(int j, bool bandStart) {
        const double yc = j + 0.5;
        // Pass one: finishing edges leave, starting edges enter (at a band's first row, every
        // edge that started on an earlier row and is still active).
        std::size_t keep = 0;
        for (ActiveEdge& a : ael_)
            if (a.lastRow >= j) ael_[keep++] = a;
        ael_.resize(keep);
        for (int r = bandStart ? 0 : j; r <= j; ++r) {
            for (auto [e, last] : (*esl_)[static_cast<std::size_t>(r)]) {
                if (last < j) continue;
                ActiveEdge a;
                a.edge = e;
                a.lastRow = last;
                Start(a, yc);
                Trace(a, true);
                ael_.push_back(a);
            }
        }
        // Pass two: advance the others and keep x order (insertion sort, swaps counted).
        for (std::size_t i = 0; i < keep; ++i) Trace(ael_[i], false);
        for (std::size_t i = 1; i < ael_.size(); ++i) {
            ActiveEdge a = ael_[i];
            std::size_t k = i;
            while (k > 0 && SortKey(ael_[k - 1].x) > SortKey(a.x)) {
                ael_[k] = ael_[k - 1];
                --k;
                ++c_.edgeSwaps;
            }
            ael_[k] = a;
        }
        // Per-body x ranges on this row: the crossings of the body's show-edges, opened toward
        // an image side when the body covers that side's pixel; refused bodies: their bounds.
        const int w = frame_.width;
        activeUnits_.clear();
        for (std::size_t u = 0; u < units_.size(); ++u) {
            const Unit& unit = units_[u];
            if (j < unit.y0 || j > unit.y1 || unit.x1 < unit.x0) continue;
            activeUnits_.push_back(static_cast<int>(u));
            ForBodies(unit, [&](int b) {
                auto k = static_cast<std::size_t>(b);
                rangeRow_[k] = j;
                lo_[k] = pixelBody_[k] ? unit.x0 : HUGE_VAL;
                hi_[k] = pixelBody_[k] ? unit.x1 + 1.0 : -HUGE_VAL;
            });
        }
        breaks_.clear();
        for (const ActiveEdge& a : ael_) {
            if (!std::isfinite(a.x)) continue;
            breaks_.push_back(a.x);
            auto b = static_cast<std::size_t>(edges_[static_cast<std::size_t>(a.edge)].body);
            if (rangeRow_[b] != j) continue;
            lo_[b] = std::min(lo_[b], a.x);
            hi_[b] = std::max(hi_[b], a.x);
        }
        for (int u : activeUnits_) {
            const Unit& unit = units_[static_cast<std::size_t>(u)];
            ForBodies(unit, [&](int b) {
                auto k = static_cast<std::size_t>(b);
                if (pixelBody_[k] || useStack_[k]) return;  // stack bodies: SeedStack
                if (unit.x0 == 0 && lo_[k] > -HUGE_VAL) {
                    ++c_.sideEvaluations;
                    if (SideCovered(b, 0.5, yc)) lo_[k] = -HUGE_VAL;
                }
                if (unit.x1 == w - 1 && hi_[k] < HUGE_VAL) {
                    ++c_.sideEvaluations;
                    if (SideCovered(b, w - 0.5, yc)) hi_[k] = HUGE_VAL;
                }
            });
        }
        if (settings_.faceStacks) SeedStack(yc);
        // Pass three: spans between crossings.
        std::size_t k = 0;
        int i = 0;
        while (i < w) {
            const double xc = i + 0.5;
            const bool straddle = settings_.faceStacks && ApplyEdgesBefore(xc, yc);
            while (k < breaks_.size() && breaks_[k] < xc - kOnEdge) ++k;
            if (straddle || (k < breaks_.size() && breaks_[k] <= xc + kOnEdge)) {
                ExactPixel(i, j);
                ++i;
                continue;
            }
            int end = w - 1;
            if (k < breaks_.size()) {
                // Clamped before the cast: a crossing may lie far outside the image.
                end =
                    static_cast<int>(std::ceil(std::min(breaks_[k], w + 1.0) - kOnEdge - 0.5)) - 1;
                end = std::min(w - 1, end);
            }
            end = std::max(end, i);
            Span(i, end, j);
            i = end + 1;
        }
    }

    template <class Fn>
    static void ForBodies(const Unit& unit, Fn&& fn) {
        if (unit.kind == Unit::Kind::kBody) {
            fn(unit.body);
        } else {
            for (int b : unit.bodies) fn(b);
        }
    }

    // Whether the body's set on the ray has any finite endpoint or covers it (for the x range we
    // need where the body is, not where it is visible: a CSG operand matters where it is).
    bool SideCovered(int body, double x, double y) {
        IntervalList l;
        eval_.BodySet(body, x, y, l);
        return !l.empty();
    }

    bool Overlaps(const Unit& unit, int i0, int i1) const {
        bool any = false;
        ForBodies(unit, [&](int b) {
            auto k = static_cast<std::size_t>(b);
            any = any || (lo_[k] <= i1 + 0.5 && hi_[k] >= i0 + 0.5);
        });
        return any;
    }

    bool EvaluateUnit(const Unit& unit, double x, double y, RayEvaluator::Hit& hit) {
        return unit.kind == Unit::Kind::kCsg ? eval_.Node(unit.node, x, y, hit)
                                             : eval_.Body(unit.body, x, y, hit);
    }

    void ExactPixel(int i, int j) {
        ++c_.exactPixels;
        const double x = i + 0.5, y = j + 0.5;
        RayEvaluator::Hit best;
        int bestSolid = -1;
        for (int u : activeUnits_) {
            const Unit& unit = units_[static_cast<std::size_t>(u)];
            if (i < unit.x0 || i > unit.x1) continue;
            RayEvaluator::Hit hit;
            if (EvaluateUnit(unit, x, y, hit) &&
                (hit.t < best.t || (hit.t == best.t && unit.solid < bestSolid))) {
                best = hit;
                bestSolid = unit.solid;
            }
        }
        if (best.halfSpace < 0) return;
        Write(i, j, best.t, scene_.WorldNormal(best.halfSpace, {x, y, best.t}), best.halfSpace,
              best.body, bestSolid);
    }

    void Write(int i, int j, double t, const Vec3& n, int hs, int body, int solid) {
        std::size_t idx = frame_.Index(i, j);
        frame_.depth[idx] = t;
        frame_.normal[idx] = n;
        frame_.surface[idx] = hs;
        frame_.body[idx] = body;
        frame_.solid[idx] = solid;
        ++c_.covered;
    }

    // The face state at pixel i (x = i + ½) on row y.
    void SeekFace(StackFace& f, int i, double y) {
        const raycast::RayHalfSpace& r = *f.ray;
        const double x = i + 0.5;
        if (r.isPlane) {
            f.planeE = r.px * x + r.py * y + r.pd;
            return;
        }
        const double dx = x - r.x0, dy = y - r.y0;
        f.h = r.hx * dx + r.hy * dy + r.h0;
        f.k = dx * (r.axx * dx + r.axy * dy + r.ax) + dy * (r.byy * dy + r.by) + r.k0;
        f.dk = r.axx * (2 * dx + 1) + r.axy * dy + r.ax;
    }
    void AdvanceFace(StackFace& f) {
        const raycast::RayHalfSpace& r = *f.ray;
        if (r.isPlane) {
            f.planeE += r.px;
            return;
        }
        f.h += r.hx;
        f.k += f.dk;
        f.dk += 2 * r.axx;
    }
    // Depth from the current state (NaN when the sheet has no point here).
    double FaceDepth(const StackFace& f) {
        ++c_.depthCalcs;
        const raycast::RayHalfSpace& r = *f.ray;
        if (r.isPlane) return r.c != 0 ? -f.planeE / r.c : std::numeric_limits<double>::quiet_NaN();
        QuadraticRoots roots = SolveQuadratic(r.c, f.h, f.k);
        switch (roots.kind) {
            case RootKind::kTwo:
                return r.z0 + (f.sheet == 1 ? roots.t1 : roots.t0);
            case RootKind::kSingle:
            case RootKind::kDouble:
                return r.z0 + roots.t0;
            default:
                return std::numeric_limits<double>::quiet_NaN();
        }
    }
    // Exact depth of the face at pixel i (for the shading-interval grid).
    double FaceDepthAt(const StackFace& f, int i, double y) {
        StackFace g = f;
        SeekFace(g, i, y);
        return FaceDepth(g);
    }

    Vec3 Normal(int hs, double x, double y, double t) {
        ++c_.normals;
        return scene_.WorldNormal(hs, {x, y, t});
    }

    Vec3 ShadedNormal(StackFace& f, int i, int i0, int i1, int delta, double y, double t) {
        if (settings_.fastShading) return f.fastNormal;
        if (delta <= 1) return Normal(f.halfSpace, i + 0.5, y, t);
        int g0 = i0 + ((i - i0) / delta) * delta, g1 = std::min(g0 + delta, i1);
        if (g1 == g0) return Normal(f.halfSpace, i + 0.5, y, t);
        if (f.g0 != g0 || f.g1 != g1) {
            // Moving on by one interval: the old right end is the new left end.
            bool reuse = f.g1 == g0;
            double t0 = reuse ? 0 : FaceDepthAt(f, g0, y), t1 = FaceDepthAt(f, g1, y);
            if (!std::isfinite(t0) || !std::isfinite(t1)) return Normal(f.halfSpace, i + 0.5, y, t);
            f.n0 = reuse ? f.n1 : Normal(f.halfSpace, g0 + 0.5, y, t0);
            f.n1 = Normal(f.halfSpace, g1 + 0.5, y, t1);
            f.g0 = g0;
            f.g1 = g1;
        }
        if (i == g0) return f.n0;
        double s = static_cast<double>(i - g0) / (g1 - g0);
        Vec3 n = f.n0 * (1 - s) + f.n1 * s;
        double len = Length(n);
        return len > 0 ? n / len : f.n0;
    }

    // A show-face from an interval endpoint (tag, t) found at pixel `sample` of row y.
    StackFace MakeFace(int halfSpace, double t, int sample, double y) {
        return MakeFaceAt(halfSpace, t, sample + 0.5, y);
    }
    StackFace MakeFaceAt(int halfSpace, double t, double x, double y) {
        StackFace f;
        f.halfSpace = halfSpace;
        f.ray = &eval_.Ray(halfSpace);
        if (!f.ray->isPlane) {  // which sheet: the root nearer to the endpoint
            const raycast::RayHalfSpace& r = *f.ray;
            const double dx = x - r.x0, dy = y - r.y0;
            QuadraticRoots roots = SolveQuadratic(
                r.c, r.hx * dx + r.hy * dy + r.h0,
                dx * (r.axx * dx + r.axy * dy + r.ax) + dy * (r.byy * dy + r.by) + r.k0);
            if (roots.kind == RootKind::kTwo &&
                std::fabs(t - (r.z0 + roots.t1)) < std::fabs(t - (r.z0 + roots.t0)))
                f.sheet = 1;
        }
        return f;
    }

    // The template of one CSG operand body in this span (see renderer.h).
    void BuildTemplate(const Unit& unit, int body, int i0, int i1, int sample, double y) {
        BodyTemplate t;
        t.body = body;
        t.first = tIntervals_.size();
        auto k = static_cast<std::size_t>(body);
        if (pixelBody_[k]) {
            t.exact = true;
        } else if (lo_[k] <= i1 + 0.5 && hi_[k] >= i0 + 0.5) {
            ++c_.csgTemplateBodies;
            IntervalList l;
            eval_.BodySet(body, sample + 0.5, y, l);
            for (const Interval& v : l) {
                TemplateInterval ti;
                for (int end = 0; end < 2; ++end) {
                    double tv = end == 0 ? v.lo : v.hi;
                    int id = end == 0 ? v.loId : v.hiId;
                    if (id < 0 || !std::isfinite(tv)) continue;
                    StackFace f = MakeFace(eval_.TagHalfSpace(id), tv, sample, y);
                    f.solid = unit.solid;
                    SeekFace(f, i0, y);
                    (end == 0 ? ti.lo : ti.hi) = static_cast<int>(tFaces_.size());
                    (end == 0 ? ti.loTag : ti.hiTag) = id;
                    tFaces_.push_back(f);
                }
                tIntervals_.push_back(ti);
            }
        }
        t.count = tIntervals_.size() - t.first;
        templates_.push_back(t);
    }

    // The CSG unit's visible point at pixel i from its templates; false when nothing is visible.
    // `exact` is set when a template could not be used here (then the tree was evaluated exactly).
    bool CsgPixel(const CsgSpanUnit& cu, int i, double y, RayEvaluator::Hit& hit) {
        const Unit& unit = units_[static_cast<std::size_t>(cu.unit)];
        ++c_.csgPixels;
        bool broken = false;
        auto leaf = [&](int body, IntervalList& out) {
            out.clear();
            const BodyTemplate* t = nullptr;
            for (std::size_t k = cu.firstTemplate; k < cu.firstTemplate + cu.templateCount; ++k)
                if (templates_[k].body == body) t = &templates_[k];
            if (!t || t->exact) {
                eval_.BodySet(body, i + 0.5, y, out);
                return;
            }
            double prevLo = -HUGE_VAL;
            for (std::size_t k = t->first; k < t->first + t->count; ++k) {
                const TemplateInterval& ti = tIntervals_[k];
                double lo = ti.lo < 0 ? -HUGE_VAL : tFaces_[static_cast<std::size_t>(ti.lo)].depth;
                double hi = ti.hi < 0 ? HUGE_VAL : tFaces_[static_cast<std::size_t>(ti.hi)].depth;
                if (std::isnan(lo) || std::isnan(hi) || lo < prevLo) {
                    broken = true;  // order changed or a root vanished: the template does not hold
                    return;
                }
                prevLo = lo;
                out.Append(lo, ti.lo < 0 ? Interval::kNoId : ti.loTag, hi,
                           ti.hi < 0 ? Interval::kNoId : ti.hiTag);
            }
        };
        IntervalList l;
        eval_.TreeSet(unit.node, leaf, l);
        if (broken) {
            ++c_.csgFallbackPixels;
            return eval_.Node(unit.node, i + 0.5, y, hit);
        }
        return eval_.First(l, hit);
    }

    void Span(int i0, int i1, int j) {
        ++c_.spans;
        const double y = j + 0.5;
        stack_.clear();
        perPixel_.clear();
        csgUnits_.clear();
        templates_.clear();
        tIntervals_.clear();
        tFaces_.clear();
        const int sample = (i0 + i1) / 2;
        for (int u : activeUnits_) {
            const Unit& unit = units_[static_cast<std::size_t>(u)];
            if (!Overlaps(unit, i0, i1)) continue;
            if (unit.kind == Unit::Kind::kCsg) {
                if (!settings_.csgTemplates) {
                    perPixel_.push_back(u);
                    continue;
                }
                CsgSpanUnit cu{u, templates_.size(), 0};
                for (int b : unit.bodies) BuildTemplate(unit, b, i0, i1, sample, y);
                cu.templateCount = templates_.size() - cu.firstTemplate;
                csgUnits_.push_back(cu);
                continue;
            }
            if (pixelBody_[static_cast<std::size_t>(unit.body)]) {
                perPixel_.push_back(u);
                continue;
            }
            if (useStack_[static_cast<std::size_t>(unit.body)]) continue;  // below
            RayEvaluator::Hit hit;
            ++c_.sampleEvaluations;
            if (!eval_.Body(unit.body, sample + 0.5, y, hit)) continue;
            StackFace f = MakeFace(hit.halfSpace, hit.t, sample, y);
            f.unit = u;
            f.body = hit.body;
            f.solid = unit.solid;
            if (settings_.fastShading) f.fastNormal = Normal(f.halfSpace, sample + 0.5, y, hit.t);
            InsertFace(f, sample + 0.5, y);
        }
        if (settings_.faceStacks) TakeStackFaces(sample, y);
        if (stack_.empty() && perPixel_.empty() && csgUnits_.empty()) {
            ++c_.emptySpans;
            return;
        }
        for (StackFace& f : stack_) SeekFace(f, i0, y);
        const int delta = std::max(1, std::min((i1 - i0) / 16 + 1, settings_.shadeInterval));
        for (int i = i0; i <= i1; ++i) {
            int best = -1;
            double bestT = HUGE_VAL;
            bool fallback = false;
            for (std::size_t s = 0; s < stack_.size(); ++s) {
                StackFace& f = stack_[s];
                f.depth = FaceDepth(f);
                if (std::isnan(f.depth)) {
                    fallback = true;
                    continue;
                }
                // Strictly nearer wins; exact ties go to the lower solid, then stack order.
                if (f.depth < bestT || (f.depth == bestT && best >= 0 &&
                                        f.solid < stack_[static_cast<std::size_t>(best)].solid)) {
                    best = static_cast<int>(s);
                    bestT = f.depth;
                }
            }
            if (settings_.faceStacks && stackHead_ == 0 && best > 0) ++c_.interpenetrationPixels;
            if (fallback) {
                ++c_.rootFallbackPixels;
                ExactPixel(i, j);
            } else {
                // Units evaluated per pixel (refused bodies, CSG solids) compete with the stack.
                RayEvaluator::Hit ph;
                int phSolid = -1;
                for (StackFace& f : tFaces_) f.depth = FaceDepth(f);
                auto offer = [&](const RayEvaluator::Hit& hit, int solid) {
                    if (hit.t < ph.t || (hit.t == ph.t && solid < phSolid)) {
                        ph = hit;
                        phSolid = solid;
                    }
                };
                for (int u : perPixel_) {
                    const Unit& unit = units_[static_cast<std::size_t>(u)];
                    if (i < unit.x0 || i > unit.x1) continue;
                    ++c_.perPixelUnitPixels;
                    RayEvaluator::Hit hit;
                    if (EvaluateUnit(unit, i + 0.5, y, hit)) offer(hit, unit.solid);
                }
                for (const CsgSpanUnit& cu : csgUnits_) {
                    RayEvaluator::Hit hit;
                    if (CsgPixel(cu, i, y, hit))
                        offer(hit, units_[static_cast<std::size_t>(cu.unit)].solid);
                }
                if (ph.halfSpace >= 0 &&
                    (best < 0 || ph.t < bestT ||
                     (ph.t == bestT && phSolid < stack_[static_cast<std::size_t>(best)].solid))) {
                    Write(i, j, ph.t, Normal(ph.halfSpace, i + 0.5, y, ph.t), ph.halfSpace, ph.body,
                          phSolid);
                } else if (best >= 0) {
                    StackFace& f = stack_[static_cast<std::size_t>(best)];
                    Write(i, j, bestT, ShadedNormal(f, i, i0, i1, delta, y, bestT), f.halfSpace,
                          f.body, f.solid);
                }
            }
            for (StackFace& f : stack_) AdvanceFace(f);
            for (StackFace& f : tFaces_) AdvanceFace(f);
        }
    }

    // ------------------------------------------------------------ face stacks (§5.2–5.5)

    int SheetOf(int face) const {
        return faces_[static_cast<std::size_t>(face)].sheet == Sheet::kBack ? 1 : 0;
    }
    FaceRef RefOf(int face) const {
        return {faces_[static_cast<std::size_t>(face)].halfSpace, SheetOf(face)};
    }

    // Is show-face f in front of g at the crossing P = (xe, y)? (§5.5.1.) The lesser depth at P
    // decides; equal within the scene's depth tolerance (or a face without a point at P, e.g. a
    // limb crossing rounded just outside the sheet), case (a): depth at Q, the point half-way to
    // the next crossing (at most ½ pixel on — the scan-line analogue of "where E meets the next
    // scan line", since our stacks are swept along the CSL); equal again, case (b): the lesser
    // slope dz/dx at Q; then case (c): the lesser rate d²z/dx² at Q. −1: f in front, +1: g in
    // front, 0: coincident (order unimportant, f goes below).
    int CompareAt(int f, int g, double xe, double xq, double y) {
        const FaceRef fr = RefOf(f), gr = RefOf(g);
        double zf, sf, cf, zg, sg, cg;
        auto tol = [&](double a, double b) {
            return scene_.depthTolerance * (1 + std::max(std::fabs(a), std::fabs(b)));
        };
        ++c_.depthCalcs;
        if (FaceDerivatives(scene_, fr, xe, y, zf, sf, cf) &&
            FaceDerivatives(scene_, gr, xe, y, zg, sg, cg) && std::fabs(zf - zg) > tol(zf, zg))
            return zf < zg ? -1 : 1;
        ++c_.stackTieBreaks;
        const bool hf = FaceDerivatives(scene_, fr, xq, y, zf, sf, cf);
        const bool hg = FaceDerivatives(scene_, gr, xq, y, zg, sg, cg);
        if (!hf || !hg) return hf ? -1 : (hg ? 1 : 0);  // a face without a point at Q is behind
        if (std::fabs(zf - zg) > tol(zf, zg)) return zf < zg ? -1 : 1;  // (a)
        if (std::fabs(sf - sg) > tol(sf, sg)) return sf < sg ? -1 : 1;  // (b)
        if (std::fabs(cf - cg) > tol(cf, cg)) return cf < cg ? -1 : 1;  // (c)
        return 0;
    }

    // Insertion in depth order: below every face it is not in front of, scanning from the head.
    // Bodies of different solids may interpenetrate without a show-edge (the paper's scenes had
    // none), so the order between faces of DIFFERENT bodies can go stale along the CSL; the
    // order among one body's faces cannot (their crossings are i-lines, hence show-edges). So
    // the face is also kept below every face of its own body that is in front of it: each
    // body's first face on the stack is then that body's visible face whatever the others do.
    void InsertStackFace(int f, double xe, double xq, double y) {
        ++c_.stackInserts;
        std::size_t pos = fstack_.size();
        for (std::size_t s = 0; s < fstack_.size(); ++s) {
            if (CompareAt(f, fstack_[s], xe, xq, y) < 0) {
                pos = s;
                break;
            }
        }
        const int body = faces_[static_cast<std::size_t>(f)].body;
        for (std::size_t s = pos + 1; s < fstack_.size(); ++s) {
            const int g = fstack_[s];
            if (faces_[static_cast<std::size_t>(g)].body == body && CompareAt(f, g, xe, xq, y) > 0)
                pos = s + 1;
        }
        fstack_.insert(fstack_.begin() + static_cast<std::ptrdiff_t>(pos), f);
        inStack_[static_cast<std::size_t>(f)] = 1;
        c_.stackMaxDepth = std::max<std::uint64_t>(c_.stackMaxDepth, fstack_.size());
    }

    // The stack left of every crossing of the row: empty except for faces of bodies that reach
    // the image's left side, which may be unbounded to the left (a half-space, a paraboloid);
    // their faces there are the finite opaque endpoints of the body on the ray at xs, found by
    // one exact evaluation per such body and row.
    void SeedStack(double y) {
        for (int f : fstack_) inStack_[static_cast<std::size_t>(f)] = 0;
        fstack_.clear();
        aelPos_ = 0;
        double first = HUGE_VAL;
        for (const ActiveEdge& a : ael_)
            if (std::isfinite(a.x)) {
                first = a.x;
                break;
            }
        const double xs = std::min(first, 0.5) - 1;
        IntervalList l;
        for (int u : activeUnits_) {
            const Unit& unit = units_[static_cast<std::size_t>(u)];
            if (unit.kind != Unit::Kind::kBody || unit.x0 != 0) continue;
            const auto b = static_cast<std::size_t>(unit.body);
            if (!useStack_[b]) continue;
            ++c_.stackSeedEvaluations;
            eval_.BodySet(unit.body, xs, y, l);
            for (const Interval& v : l) {
                for (auto [t, id] : {std::pair{v.lo, v.loId}, std::pair{v.hi, v.hiId}}) {
                    if (id < 0 || !std::isfinite(t)) continue;
                    const int hs = eval_.TagHalfSpace(id);
                    const int sheet = MakeFaceAt(hs, t, xs, y).sheet;
                    for (int f : bodyFaces_[b]) {
                        if (faces_[static_cast<std::size_t>(f)].halfSpace != hs ||
                            SheetOf(f) != sheet || inStack_[static_cast<std::size_t>(f)])
                            continue;
                        InsertStackFace(f, xs, xs + 0.5, y);
                    }
                }
            }
        }
    }

    // Pass three up to x: every AEL edge with a crossing left of x updates the stack. Crossings
    // closer than kCluster to their neighbour form one event (a vertex on the CSL, or edges
    // meeting just off it): their faces are decided together at Q, half-way from the event's
    // last crossing to the next one (at most ½ px on), so that the face test at Q is never made
    // in a sliver narrower than its own error estimate. True when an event straddles x (the
    // pixel is then evaluated exactly: it lies within kCluster of a crossing).
    bool ApplyEdgesBefore(double x, double y) {
        constexpr double kCluster = 1e-4;  // pixels
        bool straddle = false;
        const std::size_t n = ael_.size();
        while (aelPos_ < n && std::isfinite(ael_[aelPos_].x) && ael_[aelPos_].x < x) {
            std::size_t end = aelPos_ + 1;
            while (end < n && std::isfinite(ael_[end].x) &&
                   ael_[end].x - ael_[end - 1].x < kCluster)
                ++end;
            const double last = ael_[end - 1].x;
            straddle = straddle || last >= x;
            double next = last + 1;
            if (end < n && std::isfinite(ael_[end].x)) next = std::min(next, ael_[end].x);
            const double xq = 0.5 * (last + next);
            for (std::size_t k = aelPos_; k < end; ++k) ApplyEdge(k, xq, y);
            aelPos_ = end;
        }
        return straddle;
    }

    // An edge's show-faces change sides at its crossing: each one on the stack leaves it, each
    // one off it is inserted in depth order. Half-open rows (renderer.h): an edge toggles on the
    // rows whose centre lies in [yBottom, yTop).
    void ApplyEdge(std::size_t idx, double xq, double y) {
        const ActiveEdge& a = ael_[idx];
        const ShowEdge& e = edges_[static_cast<std::size_t>(a.edge)];
        if (!useStack_[static_cast<std::size_t>(e.body)]) return;
        const bool toggles = SnapToRow(e.yBottom) <= y && y < SnapToRow(e.yTop);
        for (int f : e.faces) {
            if (f < 0) continue;
            const bool on = inStack_[static_cast<std::size_t>(f)] != 0;
            const bool present = PresentAt(f, xq, y);
            if ((present != on) != toggles) {
                ++c_.stackCorrections;
                if (std::getenv("SCAN_DEBUG"))
                    std::fprintf(stderr, "corr body %d iline %d (%d,%d) y %.3f x %.4f yb %.6f yt %.6f face %d hs %d on %d present %d toggles %d\n",
                                 e.body, e.iline, 0, 0, y, a.x, e.yBottom, e.yTop, f,
                                 faces_[static_cast<std::size_t>(f)].halfSpace, on, present, toggles);
            }
            if (on && !present) {
                ++c_.stackDeletes;
                fstack_.erase(std::find(fstack_.begin(), fstack_.end(), f));
                inStack_[static_cast<std::size_t>(f)] = 0;
            } else if (!on && present) {
                InsertStackFace(f, a.x, xq, y);
            }
        }
    }

    // Is show-face f on its body's boundary at (x, y): does its sheet have a point there that
    // lies DEFINITELY inside every other HSI of the body (value < −E of zero test (4))? Q is at
    // least kCluster / 2 from every crossing, so a face that is there has a margin far above E;
    // a face that only touches the body (a row exactly on a horizontal edge where the body has
    // zero thickness, e.g. the base edge of a pyramid) is not there, as in raycast, whose
    // interval [t, t] of zero length draws nothing. HSBs that contain the view direction
    // (edge-on planes, view-axis cylinders) are tested closed instead (value <= E): a row on
    // such a boundary is inside the body along the whole ray, as in raycast.
    bool PresentAt(int f, double x, double y) const {
        const ShowFace& sf = faces_[static_cast<std::size_t>(f)];
        const FlatHalfSpace& hs = scene_.halfSpaces[static_cast<std::size_t>(sf.halfSpace)];
        double z;
        if (hs.isPlane) {
            if (hs.plane.c == 0) return false;
            z = -(hs.plane.a * x + hs.plane.b * y + hs.plane.d) / hs.plane.c;
        } else {
            const Quadric& q = hs.quadric;
            QuadraticRoots r = SolveQuadratic(q.C(), q.F() * x + q.E() * y + q.J(),
                                              q.A() * x * x + q.B() * y * y + 2 * q.D() * x * y +
                                                  2 * q.G() * x + 2 * q.H() * y + q.K());
            const bool back = sf.sheet == Sheet::kBack;
            switch (r.kind) {
                case RootKind::kTwo:
                    z = back ? r.t1 : r.t0;
                    break;
                case RootKind::kDouble:
                    z = r.t0;
                    break;
                case RootKind::kSingle:  // C = 0: one root, the front face's (as FaceDepth)
                    if (back) return false;
                    z = r.t0;
                    break;
                default:
                    return false;
            }
        }
        if (!std::isfinite(z)) return false;
        const Vec3 p{x, y, z};
        // The face point comes from one plane or quadratic solve (relative error ~1e-15 away
        // from a double root); 1e-9 (1 + |z|) px leaves a wide margin and still resolves Q,
        // which lies at least kCluster / 2 from every crossing.
        const double pointError = 1e-9 * (1 + std::fabs(z));
        for (const OrientedLiteral& l : bodyLiterals_[static_cast<std::size_t>(sf.body)]) {
            if (l.halfSpace == sf.halfSpace) continue;
            const double v = l.isPlane ? l.plane.Evaluate(p) : l.quadric.Evaluate(p);
            const double e = l.isPlane ? PlaneErrorEstimate(l.plane, p, pointError)
                                       : QuadricErrorEstimate(l.quadric, p, pointError);
            if (l.zFree ? !(v <= e) : !(v < -e)) return false;
        }
        return true;
    }

    // The span's faces from the stack: per stack body its first (nearest) face, in stack order,
    // so stack_[0] is the head when no exactly evaluated unit shares the span.
    void TakeStackFaces(int sample, double y) {
        stackHead_ = stack_.empty() ? 0 : -1;
        ++c_.stackSpans;
        c_.stackDepthSum += fstack_.size();
        taken_.clear();
        for (int f : fstack_) {
            const ShowFace& sf = faces_[static_cast<std::size_t>(f)];
            const auto b = static_cast<std::size_t>(sf.body);
            if (bodyTaken_[b]) continue;
            bodyTaken_[b] = 1;
            taken_.push_back(sf.body);
            const int u = bodyUnit_[b];
            StackFace face;
            face.halfSpace = sf.halfSpace;
            face.sheet = SheetOf(f);
            face.ray = &eval_.Ray(sf.halfSpace);
            face.unit = u;
            face.body = sf.body;
            face.solid = units_[static_cast<std::size_t>(u)].solid;
            if (settings_.fastShading) {
                const double t = FaceDepthAt(face, sample, y);
                face.fastNormal =
                    std::isfinite(t) ? Normal(face.halfSpace, sample + 0.5, y, t) : Vec3{0, 0, -1};
            }
            stack_.push_back(face);
        }
        for (int b : taken_) bodyTaken_[static_cast<std::size_t>(b)] = 0;
        if (settings_.verify) Verify(sample, y);
    }

    // verify=on: the stack head against the nearest exact hit of the stack bodies at the sample.
    void Verify(int sample, double y) {
        RayEvaluator::Hit best;
        for (int u : activeUnits_) {
            const Unit& unit = units_[static_cast<std::size_t>(u)];
            if (unit.kind != Unit::Kind::kBody || !useStack_[static_cast<std::size_t>(unit.body)])
                continue;
            if (sample < unit.x0 || sample > unit.x1) continue;
            RayEvaluator::Hit hit;
            if (eval_.Body(unit.body, sample + 0.5, y, hit) && hit.t < best.t) best = hit;
        }
        const bool head = !fstack_.empty();
        if (!head && best.halfSpace < 0) return;
        ++c_.verifySpans;
        bool same = head && best.halfSpace >= 0;
        if (same) {
            const FaceRef h = RefOf(fstack_.front());
            same = h.halfSpace == best.halfSpace &&
                   h.sheet == MakeFace(best.halfSpace, best.t, sample, y).sheet;
        }
        if (!same) ++c_.verifyMismatchSpans;
        // Per body: its first face on the stack against its exact visible face.
        for (int u : activeUnits_) {
            const Unit& unit = units_[static_cast<std::size_t>(u)];
            if (unit.kind != Unit::Kind::kBody || !useStack_[static_cast<std::size_t>(unit.body)])
                continue;
            if (sample < unit.x0 || sample > unit.x1) continue;
            RayEvaluator::Hit hit;
            const bool exact = eval_.Body(unit.body, sample + 0.5, y, hit);
            const StackFace* mine = nullptr;
            for (const StackFace& sf : stack_)
                if (sf.body == unit.body) mine = &sf;
            if (!exact && !mine) continue;
            ++c_.verifyBodies;
            if (!exact || !mine || mine->halfSpace != hit.halfSpace ||
                mine->sheet != MakeFace(hit.halfSpace, hit.t, sample, y).sheet)
                ++c_.verifyBodyMismatches;
        }
    }

    // Face stack insertion in depth order with the §5.5.1 tie-breaks.
    void InsertFace(const StackFace& f, double x, double y) {
        ++c_.faceInserts;
        std::size_t pos = stack_.size();
        FaceRef fr{f.halfSpace, f.sheet};
        for (std::size_t s = 0; s < stack_.size(); ++s) {
            FaceRef gr{stack_[s].halfSpace, stack_[s].sheet};
            double zf, zg, d1, d2, c1, c2;
            bool ok = FaceDerivatives(scene_, fr, x, y, zf, d1, c1) &&
                      FaceDerivatives(scene_, gr, x, y, zg, d2, c2);
            int cmp;
            if (ok && zf != zg) {
                cmp = zf < zg ? -1 : 1;
            } else {
                ++c_.tieBreaks;
                cmp = CompareFaces(scene_, fr, gr, x, y, scene_.depthTolerance);
            }
            if (cmp < 0) {
                pos = s;
                break;
            }
        }
        stack_.insert(stack_.begin() + static_cast<std::ptrdiff_t>(pos), f);
    }

    const FlatScene& scene_;
    std::vector<ShowEdge>& edges_;
    const std::vector<ShowFace>& faces_;
    const std::vector<Unit>& units_;
    const std::vector<bool>& pixelBody_;
    const RenderSettings& settings_;
    Frame& frame_;
    RendererCounters& c_;
    RayEvaluator eval_;

    const std::vector<std::vector<std::pair<int, int>>>* esl_ = nullptr;
    std::vector<ActiveEdge> ael_;
    std::vector<double> lo_, hi_;  // per body: x range on the current row
    std::vector<int> rangeRow_;    // the row lo_/hi_ were reset for
    std::vector<int> activeUnits_;
    std::vector<double> breaks_;
    std::vector<StackFace> stack_;
    std::vector<int> perPixel_;
    std::vector<CsgSpanUnit> csgUnits_;
    std::vector<BodyTemplate> templates_;
    std::vector<TemplateInterval> tIntervals_;
    std::vector<StackFace> tFaces_;

    // Face stacks.
    struct OrientedLiteral {
        int halfSpace = -1;
        bool isPlane = true;
        bool zFree = false;  // contains the view direction (zero tests (1), (2))
        Plane plane;
        Quadric quadric;
    };
    std::vector<std::vector<OrientedLiteral>> bodyLiterals_;  // stack bodies: "<= 0 inside"
    std::vector<int> bodyUnit_;                               // body → its kBody unit
    std::vector<std::vector<int>> bodyFaces_;                 // body → its show-faces
    std::vector<char> useStack_;                              // body drawn from the face stacks
    std::vector<int> fstack_;    // the current edge's face stack, nearest first
    std::vector<char> inStack_;  // per show-face
    std::vector<char> bodyTaken_;
    std::vector<int> taken_;
    std::size_t aelPos_ = 0;  // pass three: the next AEL edge to apply
    int stackHead_ = -1;      // index of the stack head in stack_ (−1: mixed with exact units)
};

}  // namespace

void RendererCounters::Add(const RendererCounters& o) {
    edgesStarted += o.edgesStarted;
    edgeSwaps += o.edgeSwaps;
    spans += o.spans;
    emptySpans += o.emptySpans;
    faceInserts += o.faceInserts;
    depthCalcs += o.depthCalcs;
    sampleEvaluations += o.sampleEvaluations;
    sideEvaluations += o.sideEvaluations;
    exactPixels += o.exactPixels;
    perPixelUnitPixels += o.perPixelUnitPixels;
    normals += o.normals;
    covered += o.covered;
    tieBreaks += o.tieBreaks;
    csgPixels += o.csgPixels;
    csgTemplateBodies += o.csgTemplateBodies;
    csgFallbackPixels += o.csgFallbackPixels;
    rootFallbackPixels += o.rootFallbackPixels;
    stackInserts += o.stackInserts;
    stackDeletes += o.stackDeletes;
    stackMaxDepth = std::max(stackMaxDepth, o.stackMaxDepth);
    stackDepthSum += o.stackDepthSum;
    stackSpans += o.stackSpans;
    stackSeedEvaluations += o.stackSeedEvaluations;
    stackTieBreaks += o.stackTieBreaks;
    stackCorrections += o.stackCorrections;
    interpenetrationPixels += o.interpenetrationPixels;
    verifySpans += o.verifySpans;
    verifyMismatchSpans += o.verifyMismatchSpans;
    verifyBodies += o.verifyBodies;
    verifyBodyMismatches += o.verifyBodyMismatches;
}

void RenderScanlines(const FlatScene& scene, std::vector<ShowEdge>& edges,
                     const std::vector<ShowFace>& faces, const std::vector<Unit>& units,
                     const std::vector<bool>& pixelBody, const std::vector<bool>& stackBody,
                     const RenderSettings& settings, Frame& frame, RendererCounters& counters) {
    const int h = frame.height;
    if (frame.width <= 0 || h <= 0) return;
    const auto esl = BuildEsl(edges, h);
    constexpr int kBand = 32;  // rows per task; fixed, so results never depend on threads
    const int bands = (h + kBand - 1) / kBand;
    std::mutex mutex;
    auto run = [&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1),
                          [&](const tbb::blocked_range<int>& r) {
                              for (int b = r.begin(); b < r.end(); ++b) {
                                  RendererCounters local;
                                  ScanRenderer(scene, edges, faces, units, pixelBody, stackBody,
                                               settings, frame, local)
                                      .Run(esl, b * kBand, std::min(h, (b + 1) * kBand));
                                  std::lock_guard<std::mutex> lock(mutex);
                                  counters.Add(local);
                              }
                          });
    };
    if (settings.threads > 0) {
        tbb::task_arena arena(settings.threads);
        arena.execute(run);
    } else {
        run();
    }
}

}  // namespace quadrix::scanline
