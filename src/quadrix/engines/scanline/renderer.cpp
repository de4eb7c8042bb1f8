#include "quadrix/engines/scanline/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
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
    // The edge's FACE STACK (§5.2), carried from row to row: the show-faces immediately to the
    // right of the edge on the CSL, nearest first. Only edges of face-stack bodies take part
    // (`stackEdge`); the others are mere breakpoints ("transparent" for the stacks).
    std::vector<int> stack;
    bool stackEdge = false;
    // x is not finite on this row (a conic leg traced just past its end): the edge takes no
    // part in the stacks until it is found again, when its stack is derived afresh.
    bool lost = false;
    // Pass three must derive `stack` again from the left neighbour's stack (⊕ this edge's
    // faces): the band's first row, or where passes one and two could not carry the stack (a
    // vertex fallback, a change of S0, a lost conic leg found again) — DeriveEdge.
    bool derive = false;
    // `stack` still holds a set that was right for this edge (so that the derived set can be
    // compared with it); false when it was given away in a swap or never set.
    bool carriedValid = true;
    // After deriving, mark the next stack edge for derivation too: always when !carriedValid,
    // else when the derived set differs from the carried one (the change runs on to the right
    // until a derived stack equals the carried one).
    bool propagate = false;
    bool found = false;  // pass two only: x finite again after being lost
    // The swap rule's state (SwapLeft): the edge moved left past another in pass one or two and
    // handed its stack over; its own stack is its left neighbour's ⊕ its faces, derived when its
    // move ends (pass two) or never (pass one: it is deleted next to CE).
    bool pending = false;
    int startRow = -1;  // the row it entered the AEL (its x is already on that row)
    // Faces still to be toggled in `stack` (pass one and pass two keep the stacks as sets; the
    // faces that enter are put in depth order in pass three, where the crossing's P and Q on
    // the CSL are known: ResolveToggles).
    std::vector<int> toggles;
    // On its last row, when that row's centre is the edge's top end (snapped, SnapToRow): the
    // edge stays a breakpoint (BuildEsl's closed range) but no longer toggles faces — the
    // half-open rule [yBottom, yTop) that makes a vertex exactly on a row centre toggle its
    // faces once, through the edges that leave it downwards.
    bool ending = false;
};

double SortKey(double x) { return std::isfinite(x) ? x : HUGE_VAL; }

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
    int root = -1;  // its tree pruned to the operands present in the span (ScanRenderer::PNode)
};
// A node of a pruned CSG tree: a leaf (body, template index or −1 = exact) or an operation on
// pKids_[first, first + count).
struct PNode {
    bool leaf = false;
    int body = -1, tmpl = -1;
    scene::CsgOp op = scene::CsgOp::kUnion;
    std::size_t first = 0, count = 0;
};
// A CSG operand's template kept across spans: per interval its two ends (the evaluator's tag,
// −1 for an infinite end, and the sheet), valid on row `row` while `passed` own crossings lie left.
struct CachedEnd {
    int tag = -1, sheet = 0;
};
struct CachedTemplate {
    int row = -1, passed = -1;
    std::vector<std::array<CachedEnd, 2>> ends;
};
struct SpanLeaf {
    int unit = -1, leaf = -1, tmpl = -1;
};
// A body whose bounds reach an image side: its coverage of that side's pixel is evaluated per
// row (it may have no crossing on the row and still cover it).
struct SideBody {
    int body = -1;
    bool left = false, right = false;
    int y0 = 0, y1 = -1;
};
constexpr double kRangeMargin = 1e-3;  // px: exact pixels take operands this near their range

// Inclusive pixel range of the centres i + ½ inside [lo, hi], clipped to [0, n) (as the
// engine's units are made).
void PixelRange(double lo, double hi, int n, int& a, int& b) {
    double fa = std::ceil(lo - 0.5), fb = std::floor(hi - 0.5);
    a = static_cast<int>(std::clamp(std::isnan(fa) ? 0.0 : fa, 0.0, static_cast<double>(n)));
    b = static_cast<int>(std::clamp(std::isnan(fb) ? n - 1.0 : fb, -1.0, n - 1.0));
}

// The Edge Start List: per row, the edges (index, last row) that start there.
std::vector<std::vector<std::pair<int, int>>> BuildEsl(const std::vector<ShowEdge>& edges, int h) {
    std::vector<std::vector<std::pair<int, int>>> esl(static_cast<std::size_t>(std::max(h, 0)));
    for (std::size_t e = 0; e < edges.size(); ++e) {
        const ShowEdge& s = edges[e];
        if (s.horizontal) continue;  // never active: it only links its vertices (§5.4)
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

// §5.4's vertices. A stack edge toggles its faces on the rows whose centre lies in the half-open
// [yBottom, yTop) (ActiveEdge::ending); the scan line of row j takes the vertices with
// y in (j − ½, j + ½] (VertexBand): there the edges toggling up to row j − 1 finish and those
// toggling from row j start. An edge whose two ends lie in one band toggles on no row: it "lies
// completely within the scan line" and only links its two vertices (pass one recurses through
// it). Ends of different edges are one vertex when they lie in one band within kVertexTol in x
// and y (a vertex shared by two i-lines is computed on each; merging two distinct vertices is
// harmless, since the toggles of each cancel around it, so do those of the two together).
struct RVertex {
    double x = 0, y = 0;
    int band = 0;
    std::vector<int> finishing;  // toggling edges whose top end is here
    std::vector<int> starting;   // toggling edges whose bottom end is here
    std::vector<int> inBand;     // edges with both ends in this band
};
struct VertexTable {
    std::vector<RVertex> vertices;
    std::vector<int> bottom, top;            // per edge: the vertex of each end (−1: none)
    std::vector<char> toggling;              // per edge: a stack edge whose ends are in two bands
    std::vector<std::vector<int>> startsAt;  // per row: vertices with starting edges, x order
};
constexpr double kVertexTol = 1e-3;  // px

int VertexBand(double y) { return static_cast<int>(std::ceil(SnapToRow(y) - 0.5)); }

// x of an edge's end; a conic leg at its VEXTRM may round to no root: the insert line's x.
double EndX(const ShowEdge& s, double y, bool top) {
    if (s.horizontal) return top ? s.xTop : s.xBottom;
    double x = s.XAt(y);
    if (!std::isfinite(x) && s.conic && s.shape.a != 0)
        x = -(s.shape.c * y + s.shape.d) / (2 * s.shape.a);
    return std::isfinite(x) ? x : HUGE_VAL;
}

// The vertex table of the stack bodies' show-edges (`stack[b]`: drawn from face stacks).
VertexTable BuildVertices(const std::vector<ShowEdge>& edges, const std::vector<char>& stack,
                          int h) {
    VertexTable vt;
    const std::size_t n = edges.size();
    vt.bottom.assign(n, -1);
    vt.top.assign(n, -1);
    vt.toggling.assign(n, 0);
    vt.startsAt.resize(static_cast<std::size_t>(std::max(h, 0)));
    struct End {
        int band;
        double x, y;
        int edge;
        bool isTop;
    };
    std::vector<End> ends;
    for (std::size_t e = 0; e < n; ++e) {
        const ShowEdge& s = edges[e];
        if (s.body < 0 || static_cast<std::size_t>(s.body) >= stack.size() ||
            !stack[static_cast<std::size_t>(s.body)])
            continue;
        const double yb = SnapToRow(s.yBottom), yt = SnapToRow(s.yTop);
        if (!(yb <= yt)) continue;
        const int bb = VertexBand(yb), bt = VertexBand(yt);
        if (s.horizontal && bb != bt) continue;  // (its y rounds across a band: links nothing)
        vt.toggling[e] = bb < bt;
        if (bb >= 0 && bb < h)
            ends.push_back({bb, EndX(s, s.yBottom, false), yb, static_cast<int>(e), false});
        if (bt >= 0 && bt < h)
            ends.push_back({bt, EndX(s, s.yTop, true), yt, static_cast<int>(e), true});
    }
    std::sort(ends.begin(), ends.end(), [](const End& p, const End& q) {
        return p.band < q.band || (p.band == q.band && p.x < q.x);
    });
    std::size_t bandFirst = 0;  // first vertex of the current band
    for (std::size_t i = 0; i < ends.size(); ++i) {
        const End& p = ends[i];
        if (i == 0 || p.band != ends[i - 1].band) bandFirst = vt.vertices.size();
        int v = -1;
        for (std::size_t k = vt.vertices.size(); k-- > bandFirst;) {  // recent ones, x order
            const RVertex& c = vt.vertices[k];
            if (p.x - c.x > kVertexTol) break;
            if (std::fabs(p.y - c.y) <= kVertexTol) {
                v = static_cast<int>(k);
                break;
            }
        }
        if (v < 0) {
            v = static_cast<int>(vt.vertices.size());
            vt.vertices.push_back({p.x, p.y, p.band, {}, {}, {}});
        }
        RVertex& vx = vt.vertices[static_cast<std::size_t>(v)];
        const auto e = static_cast<std::size_t>(p.edge);
        (p.isTop ? vt.top : vt.bottom)[e] = v;
        if (!vt.toggling[e]) {
            if (vx.inBand.empty() || vx.inBand.back() != p.edge) vx.inBand.push_back(p.edge);
        } else {
            (p.isTop ? vx.finishing : vx.starting).push_back(p.edge);
        }
    }
    // Vertices were made in x order within each band.
    for (std::size_t v = 0; v < vt.vertices.size(); ++v)
        if (!vt.vertices[v].starting.empty())
            vt.startsAt[static_cast<std::size_t>(vt.vertices[v].band)].push_back(
                static_cast<int>(v));
    return vt;
}

class ScanRenderer {
  public:
    ScanRenderer(const FlatScene& scene, std::vector<ShowEdge>& edges,
                 const std::vector<ShowFace>& faces, const std::vector<Unit>& units,
                 const std::vector<bool>& pixelBody, const std::vector<bool>& stackBody,
                 const VertexTable& vt, const RenderSettings& settings, Frame& frame,
                 RendererCounters& c)
        : scene_(scene),
          vt_(vt),
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
        markP_.assign(faces.size(), 0);
        markT_.assign(faces.size(), 0);
        for (char u : useStack_) stackOn_ = stackOn_ || u;
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
        vertexRow_.assign(vt.vertices.size(), -1);
        inBandRow_.assign(edges.size(), -1);
        PrepareCsg(scene, units, pixelBody);
    }

    // Tables for the row and span work (UpdateActiveUnits, the per-row body ranges, pruned
    // CSG trees): parents and child positions of tree nodes, each body's leaves, the bodies
    // per unit that are refused or may cover an image side, the units sorted on y0.
    void PrepareCsg(const FlatScene& scene, const std::vector<Unit>& units,
                    const std::vector<bool>& pixelBody) {
        const std::size_t nn = scene.nodes.size(), nb = scene.bodies.size();
        parent_.assign(nn, -1);
        childPos_.assign(nn, 0);
        for (std::size_t n = 0; n < nn; ++n) {
            const FlatCsgNode& node = scene.nodes[n];
            if (node.isLeaf) continue;
            for (std::size_t c = 0; c < node.children.size(); ++c) {
                const int ch = node.children[c];
                if (ch < 0 || static_cast<std::size_t>(ch) >= nn) continue;
                parent_[static_cast<std::size_t>(ch)] = static_cast<int>(n);
                childPos_[static_cast<std::size_t>(ch)] = static_cast<int>(c);
            }
        }
        touchGen_.assign(nn, 0);
        leafPNode_.assign(nn, -1);
        touchedKids_.assign(nn, {});
        bodyLeaves_.assign(nb, {});
        unitPixelBodies_.assign(units.size(), {});
        unitSideBodies_.assign(units.size(), {});
        unitStamp_.assign(units.size(), 0);
        const int w = frame_.width;
        std::size_t depth = 1;
        for (std::size_t u = 0; u < units.size(); ++u) {
            const Unit& unit = units[u];
            if (unit.kind == Unit::Kind::kBody) {
                const auto b = static_cast<std::size_t>(unit.body);
                if (pixelBody[b]) {
                    unitPixelBodies_[u].push_back(unit.body);
                } else if (!useStack_[b] && (unit.x0 == 0 || unit.x1 == w - 1)) {
                    unitSideBodies_[u].push_back(
                        {unit.body, unit.x0 == 0, unit.x1 == w - 1, unit.y0, unit.y1});
                }
                continue;
            }
            // The tree's leaves (depth-first), each body's bounds for the side checks.
            std::vector<std::pair<int, std::size_t>> todo{{unit.node, 1}};
            while (!todo.empty()) {
                auto [n, d] = todo.back();
                todo.pop_back();
                if (n < 0 || static_cast<std::size_t>(n) >= nn) continue;
                depth = std::max(depth, d);
                const FlatCsgNode& node = scene.nodes[static_cast<std::size_t>(n)];
                if (!node.isLeaf) {
                    for (int c : node.children) todo.push_back({c, d + 1});
                    continue;
                }
                if (node.body < 0 || static_cast<std::size_t>(node.body) >= nb) continue;
                const auto b = static_cast<std::size_t>(node.body);
                bodyLeaves_[b].push_back({static_cast<int>(u), n});
                if (pixelBody[b]) {
                    unitPixelBodies_[u].push_back(node.body);
                    continue;
                }
                const Box3& box = scene.bodies[b].bounds;
                if (box.Empty()) continue;
                int x0, x1, y0, y1;
                PixelRange(box.lo.x, box.hi.x, w, x0, x1);
                PixelRange(box.lo.y, box.hi.y, frame_.height, y0, y1);
                if (x1 < x0 || y1 < y0) continue;
                if (x0 == 0 || x1 == w - 1)
                    unitSideBodies_[u].push_back({node.body, x0 == 0, x1 == w - 1, y0, y1});
            }
        }
        pool_.resize(2 * depth + 4);
        unitsByY_.resize(units.size());
        for (std::size_t u = 0; u < units.size(); ++u) unitsByY_[u] = static_cast<int>(u);
        std::stable_sort(unitsByY_.begin(), unitsByY_.end(), [&](int p, int q) {
            return units[static_cast<std::size_t>(p)].y0 < units[static_cast<std::size_t>(q)].y0;
        });
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
        ownPassed_.assign(nb, 0);
        tmplCache_.assign(nb, {});
        activeUnits_.clear();
        unitPos_ = 0;
        for (int j = j0; j < j1; ++j) Row(j, j == j0);
    }

    void Start(ActiveEdge& a, double y) {
        const ShowEdge& s = edges_[static_cast<std::size_t>(a.edge)];
        a.stackEdge = stackOn_ && useStack_[static_cast<std::size_t>(s.body)];
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
        bandStartRow_ = bandStart;
        // Pass one (the vertices of the CSL, §5.4: finishing edges leave, starting stack edges
        // enter with their stacks) and pass two (x on the CSL, x order by adjacent swaps), with
        // the face stacks carried through both.
        if (stackOn_ && !bandStart)
            PassOne(j);
        else
            DropFinishingEdges(j);
        TraceAndSort(j);
        // The other starting edges (of CSG operands and refused bodies, and stack edges that
        // toggle on no row; at a band's first row every edge that started on an earlier row and
        // is still active): merged into x order without swaps. At a band's first row every
        // stack is derived in pass three from the left neighbour's (MarkFresh).
        starting_.clear();
        for (int r = bandStart ? 0 : j; r <= j; ++r) {
            for (auto [e, last] : (*esl_)[static_cast<std::size_t>(r)]) {
                if (last < j) continue;
                if (stackOn_ && !bandStart && vt_.toggling[static_cast<std::size_t>(e)])
                    continue;  // entered in pass one
                ActiveEdge a;
                a.edge = e;
                a.startRow = j;
                a.lastRow = last;
                Start(a, yc);
                Trace(a, true);
                a.lost = !std::isfinite(a.x);
                a.ending = EndsOnRow(a, j);
                MarkFresh(a);
                starting_.push_back(std::move(a));
            }
        }
        if (!starting_.empty()) {  // merged in: O(AEL + starting), not a swap per edge passed
            std::stable_sort(starting_.begin(), starting_.end(),
                             [](const ActiveEdge& p, const ActiveEdge& q) {
                                 return SortKey(p.x) < SortKey(q.x);
                             });
            merged_.clear();
            merged_.reserve(ael_.size() + starting_.size());
            std::size_t p = 0, q = 0;
            while (p < ael_.size() || q < starting_.size()) {
                const bool takeOld =
                    q == starting_.size() ||
                    (p < ael_.size() && SortKey(ael_[p].x) <= SortKey(starting_[q].x));
                merged_.push_back(std::move(takeOld ? ael_[p++] : starting_[q++]));
            }
            ael_.swap(merged_);
        }
        // Per-body x ranges on this row: the crossings of the body's show-edges, opened toward
        // an image side when the body covers that side's pixel; refused bodies: their unit's
        // bounds. Only bodies met on this row are touched (rowBodies_): the work per row grows
        // with the active edges, not with the bodies of the scene or the operands of a tree.
        const int w = frame_.width;
        UpdateActiveUnits(j);
        rowBodies_.clear();
        breaks_.clear();
        breakBody_.clear();
        for (const ActiveEdge& a : ael_) {
            if (!std::isfinite(a.x)) continue;
            breaks_.push_back(a.x);
            const int b = edges_[static_cast<std::size_t>(a.edge)].body;
            breakBody_.push_back(b);
            TouchBody(b, j);
            lo_[static_cast<std::size_t>(b)] = std::min(lo_[static_cast<std::size_t>(b)], a.x);
            hi_[static_cast<std::size_t>(b)] = std::max(hi_[static_cast<std::size_t>(b)], a.x);
        }
        for (int u : activeUnits_) {
            const Unit& unit = units_[static_cast<std::size_t>(u)];
            for (int b : unitPixelBodies_[static_cast<std::size_t>(u)]) {
                TouchBody(b, j);
                auto k = static_cast<std::size_t>(b);
                lo_[k] = std::min(lo_[k], static_cast<double>(unit.x0));
                hi_[k] = std::max(hi_[k], unit.x1 + 1.0);
            }
            for (const SideBody& sb : unitSideBodies_[static_cast<std::size_t>(u)]) {
                if (j < sb.y0 || j > sb.y1) continue;
                const auto k = static_cast<std::size_t>(sb.body);
                const bool touched = rangeRow_[k] == j;
                if (sb.left && (!touched || lo_[k] > -HUGE_VAL)) {
                    ++c_.sideEvaluations;
                    if (SideCovered(sb.body, 0.5, yc)) {
                        TouchBody(sb.body, j);
                        lo_[k] = -HUGE_VAL;
                        hi_[k] = std::max(hi_[k], 0.5);
                    }
                }
                if (sb.right && (rangeRow_[k] != j || hi_[k] < HUGE_VAL)) {
                    ++c_.sideEvaluations;
                    if (SideCovered(sb.body, w - 0.5, yc)) {
                        TouchBody(sb.body, j);
                        hi_[k] = HUGE_VAL;
                        lo_[k] = std::min(lo_[k], w - 0.5);
                    }
                }
            }
        }
        std::sort(rowBodies_.begin(), rowBodies_.end(), [&](int p, int q) {
            return lo_[static_cast<std::size_t>(p)] < lo_[static_cast<std::size_t>(q)] ||
                   (lo_[static_cast<std::size_t>(p)] == lo_[static_cast<std::size_t>(q)] && p < q);
        });
        sweepPos_ = 0;
        spanBodies_.clear();
        if (stackOn_) SeedStack(yc);
        // Pass three: spans between crossings.
        std::size_t k = 0;
        int i = 0;
        while (i < w) {
            const double xc = i + 0.5;
            const bool straddle = stackOn_ && ApplyEdgesBefore(xc, yc);
            while (k < breaks_.size() && breaks_[k] < xc - kOnEdge)
                ++ownPassed_[static_cast<std::size_t>(breakBody_[k++])];
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
        // The walk goes on past the image's right side: every stack must be consistent (and
        // verified) before it is carried to the next row.
        if (stackOn_) ApplyEdgesBefore(HUGE_VAL, yc);
    }

    // First touch of body b on row j: its x range starts empty and it joins rowBodies_.
    void TouchBody(int b, int j) {
        const auto k = static_cast<std::size_t>(b);
        if (rangeRow_[k] == j) return;
        rangeRow_[k] = j;
        lo_[k] = HUGE_VAL;
        hi_[k] = -HUGE_VAL;
        ownPassed_[k] = 0;
        rowBodies_.push_back(b);
    }

    // The units whose bounds hold row j, kept by a sweep over the units sorted on y0 (a band
    // starts it at its first row), so that a row costs the units active there, not all units.
    void UpdateActiveUnits(int j) {
        while (unitPos_ < unitsByY_.size() &&
               units_[static_cast<std::size_t>(unitsByY_[unitPos_])].y0 <= j) {
            const int u = unitsByY_[unitPos_++];
            const Unit& unit = units_[static_cast<std::size_t>(u)];
            if (unit.y1 >= j && unit.x1 >= unit.x0) activeUnits_.push_back(u);
        }
        std::size_t keep = 0;
        for (int u : activeUnits_)
            if (units_[static_cast<std::size_t>(u)].y1 >= j) activeUnits_[keep++] = u;
        activeUnits_.resize(keep);
    }

    // Whether the body's set on the ray has any finite endpoint or covers it (for the x range we
    // need where the body is, not where it is visible: a CSG operand matters where it is).
    bool SideCovered(int body, double x, double y) {
        IntervalList l;
        eval_.BodySet(body, x, y, l);
        return !l.empty();
    }

    // The sweep of pass three over rowBodies_ (sorted on lo): spanBodies_ holds the bodies whose
    // x range meets the pixel centres i0 + ½ … i1 + ½. Spans come left to right, so each body
    // enters once and leaves once per row.
    void SweepTo(int i0, int i1) {
        while (sweepPos_ < rowBodies_.size() &&
               lo_[static_cast<std::size_t>(rowBodies_[sweepPos_])] <= i1 + 0.5)
            spanBodies_.push_back(rowBodies_[sweepPos_++]);
        std::size_t keep = 0;
        for (int b : spanBodies_)
            if (hi_[static_cast<std::size_t>(b)] >= i0 + 0.5) spanBodies_[keep++] = b;
        spanBodies_.resize(keep);
    }

    bool EvaluateUnit(int u, double x, double y, RayEvaluator::Hit& hit) {
        const Unit& unit = units_[static_cast<std::size_t>(u)];
        if (unit.kind != Unit::Kind::kCsg) return eval_.Body(unit.body, x, y, hit);
        if (!settings_.csgTemplates) return eval_.Node(unit.node, x, y, hit);  // csg=pixels
        // The tree pruned to the operands whose x range on this row holds x (the others are
        // empty on this ray), each evaluated exactly.
        pruneLeaves_.clear();
        for (int b : rowBodies_) {
            const auto k = static_cast<std::size_t>(b);
            if (lo_[k] > x + kRangeMargin) break;  // sorted on lo
            if (hi_[k] < x - kRangeMargin) continue;
            for (auto [lu, leaf] : bodyLeaves_[k])
                if (lu == u) pruneLeaves_.push_back({leaf, -1});
        }
        // Appended after the span's pruned trees (an exact pixel inside a span), then dropped.
        const std::size_t nodes = pNodes_.size(), kids = pKids_.size();
        const int root = BuildPruned(unit.node, pruneLeaves_);
        bool found = false;
        if (root >= 0) {
            IntervalList& l = Pool(0);
            bool broken = false;
            EvalPruned(root, 1, x, y, l, broken, true);
            found = eval_.First(l, hit);
        }
        pNodes_.resize(nodes);
        pKids_.resize(kids);
        return found;
    }

    bool RowActive(int u, int j) const {
        const Unit& unit = units_[static_cast<std::size_t>(u)];
        return j >= unit.y0 && j <= unit.y1 && unit.x1 >= unit.x0;
    }

    // UnitWinsTie: does a hit of unit u on half-space hs win an exact depth tie (at depth t, pixel
    // centre (x, y)) against one of unit v on half-space hv? Raycast's rules (renderer.h, Unit):
    // the lower solid; within a union of bodies the union's interval fold, which is opened by its
    // left operand's start and closed by its right operand's end on a tie, so the lower unit for
    // entries and the higher one for exits (a body's exit is visible where a transparent plane
    // clips it). Only called on exact ties, so the facing test costs nothing elsewhere.
    bool UnitWinsTie(int u, int hs, int v, int hv, double x, double y, double t) const {
        if (v < 0) return true;
        if (u == v) return false;
        const Unit& a = units_[static_cast<std::size_t>(u)];
        const Unit& b = units_[static_cast<std::size_t>(v)];
        if (a.solid != b.solid) return a.solid < b.solid;
        if (a.kind == Unit::Kind::kBody && b.kind == Unit::Kind::kBody &&
            IsExit(a.body, hs, x, y, t) && IsExit(b.body, hv, x, y, t))
            return u > v;
        return u < v;
    }
    // Is the point at depth t of half-space hs on the ray through (x, y) where body leaves the
    // literal (its ray function grows through zero, or falls for a complemented literal)?
    bool IsExit(int body, int hs, double x, double y, double t) const {
        if (body < 0 || static_cast<std::size_t>(body) >= scene_.bodies.size()) return false;
        bool complemented = false;
        for (const FlatLiteral& l : scene_.bodies[static_cast<std::size_t>(body)].literals)
            if (l.halfSpace == hs) complemented = l.complemented;
        const raycast::RayHalfSpace& r = eval_.Ray(hs);
        const double slope =
            r.isPlane ? r.c : r.c * (t - r.z0) + r.hx * (x - r.x0) + r.hy * (y - r.y0) + r.h0;
        return (slope > 0) != complemented;
    }

    void ExactPixel(int i, int j) {
        ++c_.exactPixels;
        const double x = i + 0.5, y = j + 0.5;
        RayEvaluator::Hit best;
        int bestSolid = -1, bestUnit = -1;
        for (int u : activeUnits_) {
            const Unit& unit = units_[static_cast<std::size_t>(u)];
            if (i < unit.x0 || i > unit.x1) continue;
            RayEvaluator::Hit hit;
            if (EvaluateUnit(u, x, y, hit) &&
                (hit.t < best.t || (hit.t == best.t && UnitWinsTie(u, hit.halfSpace, bestUnit,
                                                                   best.halfSpace, x, y, hit.t)))) {
                best = hit;
                bestSolid = unit.solid;
                bestUnit = u;
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
        return SheetDepth(f, SolveQuadratic(r.c, f.h, f.k));
    }
    // The depth of f's sheet from the roots of its quadric on the current ray.
    static double SheetDepth(const StackFace& f, const QuadraticRoots& roots) {
        const raycast::RayHalfSpace& r = *f.ray;
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

    // The template of one CSG operand body in this span (see renderer.h); its index. A body's
    // interval structure holds from one of its own crossings to the next (every boundary of
    // its faces is one of its show-edges), not only within one span: spans are also cut by the
    // crossings of other bodies. So the structure read at one span's sample (which faces bound
    // which intervals) is kept per body and reused, with the faces re-seeked to the span's
    // first pixel, until the row passes another crossing of the body (ownPassed_).
    int BuildTemplate(int body, int i0, int sample, double y) {
        const auto k = static_cast<std::size_t>(body);
        BodyTemplate t;
        t.body = body;
        t.first = tIntervals_.size();
        if (pixelBody_[k]) {
            t.exact = true;
        } else {
            const int row = static_cast<int>(std::floor(y));
            CachedTemplate& cache = tmplCache_[k];
            if (cache.row != row || cache.passed != ownPassed_[k]) {
                ++c_.csgTemplateBodies;
                cache.row = row;
                cache.passed = ownPassed_[k];
                cache.ends.clear();
                IntervalList l;
                eval_.BodySet(body, sample + 0.5, y, l);
                for (const Interval& v : l) {
                    std::array<CachedEnd, 2> ends;
                    for (int end = 0; end < 2; ++end) {
                        const double tv = end == 0 ? v.lo : v.hi;
                        const int id = end == 0 ? v.loId : v.hiId;
                        if (id < 0 || !std::isfinite(tv)) continue;  // an infinite end
                        const int hs = eval_.TagHalfSpace(id);
                        ends[static_cast<std::size_t>(end)] = {id,
                                                               MakeFace(hs, tv, sample, y).sheet};
                    }
                    cache.ends.push_back(ends);
                }
            } else {
                ++c_.csgTemplateReuses;
            }
            for (const std::array<CachedEnd, 2>& ends : cache.ends) {
                TemplateInterval ti;
                for (int end = 0; end < 2; ++end) {
                    const CachedEnd& ce = ends[static_cast<std::size_t>(end)];
                    if (ce.tag < 0) continue;
                    StackFace f;
                    f.halfSpace = eval_.TagHalfSpace(ce.tag);
                    f.ray = &eval_.Ray(f.halfSpace);
                    f.sheet = ce.sheet;
                    SeekFace(f, i0, y);
                    (end == 0 ? ti.lo : ti.hi) = static_cast<int>(tFaces_.size());
                    (end == 0 ? ti.loTag : ti.hiTag) = ce.tag;
                    tFaces_.push_back(f);
                }
                tIntervals_.push_back(ti);
            }
        }
        t.count = tIntervals_.size() - t.first;
        templates_.push_back(t);
        return static_cast<int>(templates_.size()) - 1;
    }

    // The set of template t at the current pixel (depths from the span shader's conics).
    // `broken` when the template does not hold here (a root vanished, the order changed).
    void TemplateSet(int tmpl, IntervalList& out, bool& broken) {
        out.clear();
        const BodyTemplate& t = templates_[static_cast<std::size_t>(tmpl)];
        double prevLo = -HUGE_VAL;
        for (std::size_t k = t.first; k < t.first + t.count; ++k) {
            const TemplateInterval& ti = tIntervals_[k];
            double lo = ti.lo < 0 ? -HUGE_VAL : tFaces_[static_cast<std::size_t>(ti.lo)].depth;
            double hi = ti.hi < 0 ? HUGE_VAL : tFaces_[static_cast<std::size_t>(ti.hi)].depth;
            if (std::isnan(lo) || std::isnan(hi) || lo < prevLo) {
                broken = true;
                return;
            }
            prevLo = lo;
            out.Append(lo, ti.lo < 0 ? Interval::kNoId : ti.loTag, hi,
                       ti.hi < 0 ? Interval::kNoId : ti.hiTag);
        }
    }

    // ---- CSG trees pruned to the operands present (per span, or per exact pixel) ----
    //
    // A leaf whose body's x range on the row misses the span (or the pixel) has an empty set
    // there, and ∅ is the identity of union and of the subtrahends of a difference and absorbs
    // intersections and minuends. So the tree is rebuilt over the leaves present only: each
    // present leaf marks its ancestors (stopping at one already marked), and the marked nodes
    // are assembled bottom-up with their present children in the original order (the interval
    // operations then run on the same operands in the same order as the full tree's: the same
    // result, bit for bit). The cost is the present leaves × the tree depth, not the tree size:
    // a union of 10,000 spheres costs per span the few spheres the span meets.
    int BuildPruned(int root, const std::vector<std::pair<int, int>>& leaves) {
        if (++pruneGen_ == 0) {
            std::fill(touchGen_.begin(), touchGen_.end(), 0);
            pruneGen_ = 1;
        }
        for (auto [leaf, tmpl] : leaves) {
            const auto l = static_cast<std::size_t>(leaf);
            if (touchGen_[l] == pruneGen_) continue;  // a leaf listed twice
            touchGen_[l] = pruneGen_;
            leafPNode_[l] = static_cast<int>(pNodes_.size());
            PNode pn;
            pn.leaf = true;
            pn.body = scene_.nodes[l].body;
            pn.tmpl = tmpl;
            pNodes_.push_back(pn);
            int c = leaf;
            for (int p = parent_[l]; p >= 0; c = p, p = parent_[static_cast<std::size_t>(p)]) {
                const auto pk = static_cast<std::size_t>(p);
                if (touchGen_[pk] == pruneGen_) {
                    touchedKids_[pk].push_back(c);
                    break;
                }
                touchGen_[pk] = pruneGen_;
                touchedKids_[pk].assign(1, c);
            }
        }
        if (touchGen_[static_cast<std::size_t>(root)] != pruneGen_) return -1;
        return Assemble(root);
    }

    int Assemble(int node) {
        const auto nk = static_cast<std::size_t>(node);
        const FlatCsgNode& n = scene_.nodes[nk];
        if (n.isLeaf) return leafPNode_[nk];
        std::vector<int>& kids = touchedKids_[nk];
        std::sort(kids.begin(), kids.end(), [&](int p, int q) {
            return childPos_[static_cast<std::size_t>(p)] < childPos_[static_cast<std::size_t>(q)];
        });
        std::vector<int> built;
        built.reserve(kids.size());
        if (n.op == scene::CsgOp::kIntersection) {
            if (kids.size() != n.children.size()) return -1;  // an operand is empty: ∅
            for (int k : kids) {
                const int r = Assemble(k);
                if (r < 0) return -1;
                built.push_back(r);
            }
        } else if (n.op == scene::CsgOp::kUnion) {
            for (int k : kids)
                if (const int r = Assemble(k); r >= 0) built.push_back(r);
            if (built.empty()) return -1;
        } else {  // difference: the minuend must be present; absent subtrahends drop out
            if (kids.empty() || kids.front() != n.children.front()) return -1;
            for (std::size_t i = 0; i < kids.size(); ++i) {
                const int r = Assemble(kids[i]);
                if (i == 0 && r < 0) return -1;
                if (r >= 0) built.push_back(r);
            }
        }
        if (built.size() == 1) return built.front();
        PNode pn;
        pn.op = n.op;
        pn.first = pKids_.size();
        pn.count = built.size();
        pKids_.insert(pKids_.end(), built.begin(), built.end());
        pNodes_.push_back(pn);
        return static_cast<int>(pNodes_.size()) - 1;
    }

    IntervalList& Pool(std::size_t i) { return pool_[i]; }

    // The set of pruned node pn on the ray through (x, y): template leaves from the span's
    // templates (exact leaves, or all leaves with `exact`, by the interval code of raycast),
    // combined as RayEvaluator::TreeSet does. Scratch lists come from pool_ by depth.
    void EvalPruned(int pn, std::size_t depth, double x, double y, IntervalList& out, bool& broken,
                    bool exact) {
        const PNode& p = pNodes_[static_cast<std::size_t>(pn)];
        if (p.leaf) {
            if (exact || p.tmpl < 0)
                eval_.BodySet(p.body, x, y, out);
            else
                TemplateSet(p.tmpl, out, broken);
            return;
        }
        out.clear();
        IntervalList& operand = Pool(2 * depth);
        IntervalList& tmp = Pool(2 * depth + 1);
        for (std::size_t i = 0; i < p.count; ++i) {
            if (i > 0 && out.empty() && p.op != scene::CsgOp::kUnion) return;
            const int kid = pKids_[p.first + i];
            if (i == 0) {
                EvalPruned(kid, depth + 1, x, y, out, broken, exact);
                if (broken) return;
                continue;
            }
            EvalPruned(kid, depth + 1, x, y, operand, broken, exact);
            if (broken) return;
            CombineOperand(p.op, out, operand, tmp);
        }
    }

    // The CSG unit's visible point at pixel i from its pruned tree and templates; false when
    // nothing is visible. Where a template does not hold, the pruned tree is evaluated exactly.
    bool CsgPixel(const CsgSpanUnit& cu, int i, double y, RayEvaluator::Hit& hit) {
        ++c_.csgPixels;
        bool broken = false;
        IntervalList& l = Pool(0);
        EvalPruned(cu.root, 1, i + 0.5, y, l, broken, false);
        if (broken) {
            ++c_.csgFallbackPixels;
            broken = false;
            EvalPruned(cu.root, 1, i + 0.5, y, l, broken, true);
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
        // The bodies whose x range meets the span, from the row's sweep (not all bodies).
        SweepTo(i0, i1);
        if (++spanGen_ == 0) {
            std::fill(unitStamp_.begin(), unitStamp_.end(), 0);
            spanGen_ = 1;
        }
        pNodes_.clear();
        pKids_.clear();
        spanLeaves_.clear();
        for (int b : spanBodies_) {
            const auto k = static_cast<std::size_t>(b);
            const int u = bodyUnit_[k];
            if (u >= 0 && RowActive(u, j)) {  // a body drawn on its own
                const Unit& unit = units_[static_cast<std::size_t>(u)];
                if (pixelBody_[k]) {
                    perPixel_.push_back(u);
                } else if (!useStack_[k]) {  // stack bodies: TakeStackFaces below
                    RayEvaluator::Hit hit;
                    ++c_.sampleEvaluations;
                    if (eval_.Body(b, sample + 0.5, y, hit)) {
                        StackFace f = MakeFace(hit.halfSpace, hit.t, sample, y);
                        f.unit = u;
                        f.body = hit.body;
                        f.solid = unit.solid;
                        if (settings_.fastShading)
                            f.fastNormal = Normal(f.halfSpace, sample + 0.5, y, hit.t);
                        InsertFace(f, sample + 0.5, y);
                    }
                }
            }
            int tmpl = -2;  // one template per body and span, built when a CSG leaf needs it
            for (auto [lu, leaf] : bodyLeaves_[k]) {
                if (!RowActive(lu, j)) continue;
                if (!settings_.csgTemplates) {  // csg=pixels: the whole tree per pixel
                    if (unitStamp_[static_cast<std::size_t>(lu)] != spanGen_) {
                        unitStamp_[static_cast<std::size_t>(lu)] = spanGen_;
                        perPixel_.push_back(lu);
                    }
                    continue;
                }
                if (tmpl == -2) tmpl = BuildTemplate(b, i0, sample, y);
                spanLeaves_.push_back({lu, leaf, tmpl});
            }
        }
        // Per CSG unit present: its tree pruned to the leaves present.
        std::sort(spanLeaves_.begin(), spanLeaves_.end(),
                  [](const SpanLeaf& p, const SpanLeaf& q) { return p.unit < q.unit; });
        for (std::size_t a = 0; a < spanLeaves_.size();) {
            std::size_t e = a;
            pruneLeaves_.clear();
            for (; e < spanLeaves_.size() && spanLeaves_[e].unit == spanLeaves_[a].unit; ++e)
                pruneLeaves_.push_back({spanLeaves_[e].leaf, spanLeaves_[e].tmpl});
            const int u = spanLeaves_[a].unit;
            const int root = BuildPruned(units_[static_cast<std::size_t>(u)].node, pruneLeaves_);
            if (root >= 0) csgUnits_.push_back({u, root});
            a = e;
        }
        if (stackOn_) TakeStackFaces(sample, y);
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
                // Strictly nearer wins; exact ties by raycast's rule (UnitWinsTie).
                if (f.depth < bestT ||
                    (f.depth == bestT && best >= 0 &&
                     UnitWinsTie(f.unit, f.halfSpace, stack_[static_cast<std::size_t>(best)].unit,
                                 stack_[static_cast<std::size_t>(best)].halfSpace, i + 0.5, y,
                                 f.depth))) {
                    best = static_cast<int>(s);
                    bestT = f.depth;
                }
            }
            if (stackOn_ && stackHead_ == 0 && best > 0) ++c_.interpenetrationPixels;
            if (fallback) {
                ++c_.rootFallbackPixels;
                ExactPixel(i, j);
            } else {
                // Units evaluated per pixel (refused bodies, CSG solids) compete with the stack.
                RayEvaluator::Hit ph;
                int phSolid = -1, phUnit = -1;
                // Template faces: the two ends of an operand's interval are often the two
                // sheets of one quadric, with the same incremental state: one solve for both.
                for (std::size_t k = 0; k < tFaces_.size(); ++k) {
                    StackFace& f = tFaces_[k];
                    if (f.ray->isPlane) {
                        f.depth = FaceDepth(f);
                        continue;
                    }
                    const StackFace* g = k > 0 ? &tFaces_[k - 1] : nullptr;
                    if (!(g && g->ray == f.ray && g->h == f.h && g->k == f.k))
                        lastRoots_ = SolveQuadratic(f.ray->c, f.h, f.k);
                    ++c_.depthCalcs;
                    f.depth = SheetDepth(f, lastRoots_);
                }
                auto offer = [&](const RayEvaluator::Hit& hit, int u) {
                    if (hit.t < ph.t ||
                        (hit.t == ph.t &&
                         UnitWinsTie(u, hit.halfSpace, phUnit, ph.halfSpace, i + 0.5, y, hit.t))) {
                        ph = hit;
                        phSolid = units_[static_cast<std::size_t>(u)].solid;
                        phUnit = u;
                    }
                };
                for (int u : perPixel_) {
                    const Unit& unit = units_[static_cast<std::size_t>(u)];
                    if (i < unit.x0 || i > unit.x1) continue;
                    ++c_.perPixelUnitPixels;
                    RayEvaluator::Hit hit;
                    if (EvaluateUnit(u, i + 0.5, y, hit)) offer(hit, u);
                }
                for (const CsgSpanUnit& cu : csgUnits_) {
                    RayEvaluator::Hit hit;
                    if (CsgPixel(cu, i, y, hit)) offer(hit, cu.unit);
                }
                if (ph.halfSpace >= 0 &&
                    (best < 0 || ph.t < bestT ||
                     (ph.t == bestT &&
                      UnitWinsTie(phUnit, ph.halfSpace, stack_[static_cast<std::size_t>(best)].unit,
                                  stack_[static_cast<std::size_t>(best)].halfSpace, i + 0.5, y,
                                  ph.t)))) {
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

    // Insertion into stack `st` in depth order: below every face it is not in front of,
    // scanning from the head. Bodies of different solids may interpenetrate without a show-edge
    // (the paper's scenes had none), so the order between faces of DIFFERENT bodies can go stale;
    // the order among one body's faces cannot (their crossings are i-lines, hence show-edges).
    // So the face is also kept below every face of its own body that is in front of it: each
    // body's first face on a stack is then that body's visible face whatever the others do.
    void InsertInto(std::vector<int>& st, int f, double xe, double xq, double y) {
        std::size_t pos = st.size();
        for (std::size_t s = 0; s < st.size(); ++s) {
            if (CompareAt(f, st[s], xe, xq, y) < 0) {
                pos = s;
                break;
            }
        }
        const int body = faces_[static_cast<std::size_t>(f)].body;
        for (std::size_t s = pos + 1; s < st.size(); ++s) {
            const int g = st[s];
            if (faces_[static_cast<std::size_t>(g)].body == body && CompareAt(f, g, xe, xq, y) > 0)
                pos = s + 1;
        }
        st.insert(st.begin() + static_cast<std::ptrdiff_t>(pos), f);
        c_.stackMaxDepth = std::max<std::uint64_t>(c_.stackMaxDepth, st.size());
    }

    static bool Contains(const std::vector<int>& st, int f) {
        return std::find(st.begin(), st.end(), f) != st.end();
    }
    static bool SameSet(const std::vector<int>& a, const std::vector<int>& b) {
        if (a.size() != b.size()) return false;
        for (int f : a)
            if (!Contains(b, f)) return false;
        return true;
    }

    // ---- carrying the stacks from row to row (pass one, pass two) ----

    void MarkFresh(ActiveEdge& a) {
        a.derive = true;
        a.carriedValid = false;
        a.propagate = true;
    }
    void MarkCheck(ActiveEdge& a) {
        a.derive = true;
        a.propagate = true;
    }
    bool Participates(const ActiveEdge& a) const { return a.stackEdge && !a.lost && !a.ending; }
    // The edge's top end lies on the centre of its last row j (see ActiveEdge::ending).
    bool EndsOnRow(const ActiveEdge& a, int j) const {
        return a.lastRow == j &&
               SnapToRow(edges_[static_cast<std::size_t>(a.edge)].yTop) <= j + 0.5;
    }

    // ---- pass one: the vertices of the CSL (§5.4) ----
    //
    // The AEL comes from pass two of row j − 1: sorted on x at that row, every stack its left
    // neighbour's ⊕ its faces. Pass one walks it with the current-edge pointer CE (ce_), copying
    // the edges it passes to the new AEL, and processes the vertices of scan line j (VertexBand):
    // the top vertex of CE when CE finishes, and before that every vertex with starting edges
    // (vt_.startsAt[j], x order) that lies left of CE. A vertex is processed in three steps
    // (ProcessVertex): (1) its finishing edges leave the AEL — one that is not CE is first moved
    // next to CE by successive swaps, each applying the swap rule of pass two to the edge passed
    // (SwapLeft; counted in stackDeletionSwaps), then deleted; (2) its edges lying within the
    // scan line are taken and their other vertices processed recursively; (3) its remaining
    // starting edges are inserted at CE, each stack derived from its left neighbour's and the
    // edge's two faces. Around a vertex (or a group of vertices linked by edges within the scan
    // line) the finishing edges and the starting ones toggle the same faces, so the stack right
    // of the inserted edges is the one right of the deleted edges: nothing further right changes.
    // When they do not (parity_ not empty: an end missing from the vertex table, a conic leg
    // lost to rounding), the next stack edge is derived again in pass three and the change is
    // carried on from there (the fallback, stackVertexFallbacks).
    void PassOne(int j) {
        old_.swap(ael_);
        ael_.clear();
        gone_.assign(old_.size(), 0);
        lastPart_ = -1;
        markOut_ = false;
        ce_ = 0;
        const std::vector<int>& sv = vt_.startsAt[static_cast<std::size_t>(j)];
        std::size_t q = 0;
        for (;;) {
            while (ce_ < old_.size() && gone_[ce_]) ++ce_;
            while (q < sv.size() && vertexRow_[static_cast<std::size_t>(sv[q])] == j) ++q;
            const bool haveCe = ce_ < old_.size();
            if (q < sv.size() && (!haveCe || vt_.vertices[static_cast<std::size_t>(sv[q])].x <
                                                 CeX(old_[ce_], sv[q], j))) {
                ProcessComponent(sv[q], j);
                continue;
            }
            if (!haveCe) break;
            const int v = FinishingVertex(old_[ce_], j);
            if (v >= 0 && vertexRow_[static_cast<std::size_t>(v)] != j) {
                ProcessComponent(v, j);
                continue;
            }
            ActiveEdge& a = old_[ce_++];
            if (v >= 0) {  // its vertex was processed without it (not expected): fallback
                if (Participates(a)) {
                    ++c_.stackVertexFallbacks;
                    markOut_ = true;
                }
                a.ending = true;
            }
            if (a.lastRow < j) continue;  // finishing edges of other bodies and lost ones leave
            Emit(std::move(a));
        }
        old_.clear();
    }

    // Where CE is at the height of vertex v (the next one with starting edges): its own top
    // vertex's x if it finishes on this scan line, else x on its show-edge at v's y (the AEL's
    // x are on row j − 1, up to a row below v).
    double CeX(const ActiveEdge& a, int v, int j) const {
        const int top = FinishingVertex(a, j);
        if (top >= 0) return vt_.vertices[static_cast<std::size_t>(top)].x;
        const double yv = vt_.vertices[static_cast<std::size_t>(v)].y;
        const ShowEdge& s = edges_[static_cast<std::size_t>(a.edge)];
        if (!(yv >= s.yBottom && yv <= s.yTop)) return SortKey(a.x);
        const double x = s.XAt(yv);
        return std::isfinite(x) ? x : SortKey(a.x);
    }

    // The vertex v of scan line j where a toggling stack edge finishes, or −1.
    int FinishingVertex(const ActiveEdge& a, int j) const {
        if (!a.stackEdge) return -1;
        const auto e = static_cast<std::size_t>(a.edge);
        if (!vt_.toggling[e]) return -1;
        const int v = vt_.top[e];
        return v >= 0 && vt_.vertices[static_cast<std::size_t>(v)].band == j ? v : -1;
    }

    // Appends an edge to the new AEL (pass one); the first stack edge after a fallback is
    // marked for derivation.
    void Emit(ActiveEdge&& a) {
        ael_.push_back(std::move(a));
        ActiveEdge& b = ael_.back();
        if (!Participates(b)) return;
        if (markOut_) {
            MarkCheck(b);
            markOut_ = false;
        }
        lastPart_ = static_cast<std::ptrdiff_t>(ael_.size()) - 1;
    }

    // A vertex and, recursively, those linked to it by edges within the scan line; then step
    // (3) for all of them: their starting edges enter at CE in x order on row j.
    void ProcessComponent(int v, int j) {
        const double y = j + 0.5;
        parity_.clear();
        starts_.clear();
        ProcessVertex(v, j, 0);
        newEdges_.clear();
        for (int e : starts_) {
            ActiveEdge a;
            a.edge = e;
            const double last =
                std::floor(SnapToRow(edges_[static_cast<std::size_t>(e)].yTop) - 0.5);
            a.lastRow = static_cast<int>(std::min(last, frame_.height - 1.0));
            a.startRow = j;
            Start(a, y);
            Trace(a, true);
            a.lost = !std::isfinite(a.x);
            a.ending = EndsOnRow(a, j);
            newEdges_.push_back(std::move(a));
        }
        std::stable_sort(
            newEdges_.begin(), newEdges_.end(),
            [](const ActiveEdge& p, const ActiveEdge& q) { return SortKey(p.x) < SortKey(q.x); });
        for (std::size_t k = 0; k < newEdges_.size(); ++k) {
            ActiveEdge& a = newEdges_[k];
            if (Participates(a)) {
                ToggleParity(a);
                const ActiveEdge* left =
                    lastPart_ >= 0 ? &ael_[static_cast<std::size_t>(lastPart_)] : nullptr;
                if (left && left->derive) {
                    MarkFresh(a);  // its left neighbour is re-derived in pass three
                } else {
                    DeriveFrom(a, left);
                }
            } else {
                MarkFresh(a);  // lost: derived afresh when found
            }
            Emit(std::move(a));
        }
        if (!parity_.empty()) {
            ++c_.stackVertexFallbacks;
            markOut_ = true;
        }
    }

    // Steps (1) and (2) of §5.4 for vertex v; step (3) is collected in starts_.
    void ProcessVertex(int v, int j, int depth) {
        vertexRow_[static_cast<std::size_t>(v)] = j;
        ++c_.stackVertices;
        if (depth > 0) ++c_.stackVertexRecursions;
        const RVertex& vx = vt_.vertices[static_cast<std::size_t>(v)];
        // The finishing edges' places in the AEL, left to right (CE first when it is one).
        found_.clear();
        for (int e : vx.finishing) {
            std::size_t i = ce_;
            while (i < old_.size() && (gone_[i] || old_[i].edge != e)) ++i;
            if (i < old_.size()) found_.push_back(i);  // else: not in the AEL (lost, dropped)
        }
        std::sort(found_.begin(), found_.end());
        for (std::size_t i : found_) {
            // (1) Moved left next to CE by successive swaps: each edge X passed takes the
            // finishing edge's stack, or toggles its faces (the swap rule of pass two).
            for (std::size_t k = i; k-- > ce_;)
                if (!gone_[k] && SwapLeft(old_[i], old_[k])) ++c_.stackDeletionSwaps;
            // ... and deleted. An edge whose top is this row's centre stays a breakpoint for
            // this row (ActiveEdge::ending) but no longer takes part in the stacks.
            ActiveEdge& r = old_[i];
            if (Participates(r)) ToggleParity(r);
            gone_[i] = 1;
            r.pending = false;
            if (r.lastRow >= j) {
                r.ending = true;
                Emit(std::move(r));
            }
        }
        // (2) Edges lying within the scan line: their other vertex, recursively.
        for (int h : vx.inBand) {
            const auto he = static_cast<std::size_t>(h);
            if (inBandRow_[he] == j) continue;
            inBandRow_[he] = j;
            const int o = vt_.bottom[he] == v ? vt_.top[he] : vt_.bottom[he];
            if (o >= 0 && vertexRow_[static_cast<std::size_t>(o)] != j)
                ProcessVertex(o, j, depth + 1);
        }
        // (3) The starting edges (inserted by ProcessComponent).
        for (int e : vx.starting) starts_.push_back(e);
    }

    // The faces a vertex component toggles: finishing edges' and starting edges' (they cancel
    // when the component is complete).
    void ToggleParity(const ActiveEdge& a) { AddToggles(parity_, a); }

    // a's stack from its left neighbour's (S0 when `left` is null) ⊕ a's faces, as a set: the
    // faces to toggle wait in a.toggles for pass three (ResolveToggles).
    void DeriveFrom(ActiveEdge& a, const ActiveEdge* left) {
        ++c_.stackDerivations;
        if (left) {
            a.stack.assign(left->stack.begin(), left->stack.end());
            a.toggles.assign(left->toggles.begin(), left->toggles.end());
        } else {
            a.stack.assign(seed_.begin(), seed_.end());
            a.toggles.clear();
        }
        AddToggles(a.toggles, a);
        a.carriedValid = true;
        a.pending = false;
    }

    // Adds edge a's faces to a list of faces to toggle (two toggles of one face cancel).
    void AddToggles(std::vector<int>& t, const ActiveEdge& a) const {
        for (int f : edges_[static_cast<std::size_t>(a.edge)].faces) {
            if (f < 0) continue;
            auto it = std::find(t.begin(), t.end(), f);
            if (it != t.end())
                t.erase(it);
            else
                t.push_back(f);
        }
    }

    // Pass three, at a's crossing: the faces waiting in a.toggles leave a's stack or enter it in
    // depth order (§5.5.1 at the crossing and at Q).
    void ResolveToggles(ActiveEdge& a, double xq, double y) {
        for (int f : a.toggles) {
            auto it = std::find(a.stack.begin(), a.stack.end(), f);
            if (it != a.stack.end()) {
                a.stack.erase(it);
                ++c_.stackDeriveDeletes;
            } else {
                InsertInto(a.stack, f, a.x, xq, y);
                ++c_.stackDeriveInserts;
            }
        }
        a.toggles.clear();
    }

    // The swap rule (§5.3), for pass two's sort and pass one's deletion swaps: edge e moves left
    // past its neighbour x. The region right of x is now the one that was right of e: x takes
    // e's stack as it is (depth order included). e's own stack is then its new left
    // neighbour's ⊕ its faces (`pending`); if e moves on past another edge, that edge takes this
    // stack, which is its own ⊕ e's faces: they are toggled in its stack in place. True when a
    // stack changed (both edges take part in the stacks).
    bool SwapLeft(ActiveEdge& e, ActiveEdge& x) {
        if (!Participates(e) || !Participates(x)) return false;
        if (e.derive) {  // e's stack is not valid (a fallback): x is derived again too
            x.derive = true;
            x.carriedValid = false;
            x.propagate = x.propagate || e.propagate;
            e.pending = false;
            return true;
        }
        if (!e.pending) {
            std::swap(x.stack, e.stack);
            std::swap(x.toggles, e.toggles);
            x.carriedValid = true;  // x keeps any derive mark it had
            e.pending = true;
        } else {
            AddToggles(x.toggles, e);
        }
        return true;
    }

    // Without face stacks: finishing edges leave the AEL.
    void DropFinishingEdges(int j) {
        std::size_t keep = 0;
        for (std::size_t i = 0; i < ael_.size(); ++i) {
            if (ael_[i].lastRow < j) continue;
            if (keep != i) ael_[keep] = std::move(ael_[i]);
            ++keep;
        }
        ael_.resize(keep);
    }

    // Pass two: x on the new CSL (conic edges by differences; edges that entered in pass one are
    // there already), then x order by adjacent swaps (insertion sort) with the swap rule: the
    // mover's own stack is derived from its new left neighbour's when its move ends. Edges whose
    // x stops being finite ("lost") leave the structure like finishing edges and "found" ones
    // re-enter like new ones, both by derivation in pass three (a fallback: a leg traced past
    // its VEXTRM by rounding).
    void TraceAndSort(int j) {
        bool pending = false;
        for (ActiveEdge& a : ael_) {
            if (a.startRow == j) continue;
            const bool wasLost = a.lost;
            Trace(a, false);
            const bool lost = !std::isfinite(a.x);
            if (!a.stackEdge) {
                a.lost = lost;
                continue;
            }
            if (lost && !wasLost) {
                a.lost = true;
                pending = true;
            } else if (!lost && wasLost) {
                a.found = true;  // stays transparent during the sort; fresh after it
            } else if (!lost && pending) {
                MarkCheck(a);
                pending = false;
            }
        }
        const std::size_t n = ael_.size();
        for (std::size_t i = 1; i < n; ++i) {
            std::size_t k = i;
            while (k > 0 && SortKey(ael_[k - 1].x) > SortKey(ael_[k].x)) {
                std::swap(ael_[k - 1], ael_[k]);  // the mover is now at k − 1, the edge passed at k
                if (SwapLeft(ael_[k - 1], ael_[k])) ++c_.stackSwapUpdates;
                --k;
                ++c_.edgeSwaps;
            }
            if (ael_[k].pending) ResolvePending(k);
        }
        for (ActiveEdge& a : ael_) {
            if (!a.found) continue;
            a.found = false;
            a.lost = false;
            MarkFresh(a);
        }
    }

    // The mover's stack at the end of its move: its left neighbour's ⊕ its faces.
    void ResolvePending(std::size_t k) {
        ActiveEdge& a = ael_[k];
        a.pending = false;
        if (a.derive) return;  // derived in pass three
        const ActiveEdge* left = nullptr;
        for (std::size_t p = k; p-- > 0;)
            if (Participates(ael_[p])) {
                left = &ael_[p];
                break;
            }
        if (left && left->derive) {
            MarkFresh(a);
            return;
        }
        DeriveFrom(a, left);
    }

    // ---- pass three: walking the AEL with the carried stacks ----

    // The stack left of every crossing of the row (S0): empty except for faces of bodies that
    // reach the image's left side, which may be unbounded to the left (a half-space, a
    // paraboloid); their faces there are the finite opaque endpoints of the body on the ray at
    // xs, found by one exact evaluation per such body and row. A body can leave or enter S0
    // without any show-edge (a horizontal boundary far left), so S0 is evaluated on every row;
    // when it changed, the first stack edge is derived again.
    void SeedStack(double y) {
        seedPrev_.swap(seed_);
        seed_.clear();
        aelPos_ = 0;
        cur_ = &seed_;
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
                            SheetOf(f) != sheet || Contains(seed_, f))
                            continue;
                        InsertInto(seed_, f, xs, xs + 0.5, y);
                    }
                }
            }
        }
        markNext_ = !SameSet(seed_, seedPrev_);
        closedAdd_.clear();
        closedDrop_.clear();
        shown_ = cur_;
    }

    // Pass three up to x: every AEL edge with a crossing left of x is walked. Crossings closer
    // than kCluster to their neighbour form one event (a vertex on the CSL, or edges meeting
    // just off it): the event's faces are checked together at Q, half-way from its last
    // crossing to the next one (at most ½ px on), so that the face test at Q is never made in a
    // sliver narrower than its own error estimate. True when an event straddles x (the pixel
    // is then evaluated exactly: it lies within kCluster of a crossing).
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
            ApplyEvent(aelPos_, end, xq, y);
            aelPos_ = end;
        }
        return straddle;
    }

    // One event (crossings [b, e) of the AEL): derive the stacks marked in pass one/two from
    // the left neighbour's, then verify the event's resulting stack.
    void ApplyEvent(std::size_t b, std::size_t e, double xq, double y) {
        const std::vector<int>* before = cur_;
        std::size_t last = e;
        bool ending = false;
        for (std::size_t k = b; k < e; ++k) {
            ActiveEdge& a = ael_[k];
            ending = ending || (a.stackEdge && !a.lost && a.ending);
            if (!Participates(a)) continue;
            if (markNext_) {
                MarkCheck(a);
                markNext_ = false;
            }
            // Q of an edge inside the event lies in its own (narrow) region, up to the next
            // crossing: its stack is carried to rows where that region is wide.
            const double q = k + 1 < e ? 0.5 * (a.x + ael_[k + 1].x) : xq;
            if (!a.toggles.empty()) ResolveToggles(a, q, y);
            if (a.derive) DeriveEdge(a, *cur_, q, y);
            cur_ = &a.stack;
            last = k;
        }
        if (last != e) {
            if (settings_.checkStacks) VerifyEvent(*before, b, e, last, xq, y);
            cur_ = &ael_[last].stack;
        }
        if (ending && settings_.checkStacks) UpdateClosedRowFaces(b, e, xq, y);
        if (last != e || ending) ShowStack(ael_[e - 1].x, xq, y);
    }

    // Edges whose top end lies exactly on this row's centre no longer toggle (half-open rule,
    // ActiveEdge::ending), which is right for the carried stacks: below the row the boundary
    // has ended. But raycast's half-spaces are closed, so on the row itself a face bounded there
    // may still be on its body's boundary: a box whose bottom side y = j + ½ is an edge-on plane
    // covers row j. The face test at Q decides these faces for this row only: they are shown in
    // the span stacks (`shown_`) without entering the carried ones (closedRowFaces counts them).
    void UpdateClosedRowFaces(std::size_t b, std::size_t e, double xq, double y) {
        for (std::size_t k = b; k < e; ++k) {
            const ActiveEdge& a = ael_[k];
            if (!(a.stackEdge && !a.lost && a.ending)) continue;
            for (int f : edges_[static_cast<std::size_t>(a.edge)].faces) {
                if (f < 0) continue;
                const bool present = PresentAt(f, xq, y);
                const bool carried = Contains(*cur_, f);
                auto add = std::find(closedAdd_.begin(), closedAdd_.end(), f);
                auto drop = std::find(closedDrop_.begin(), closedDrop_.end(), f);
                if (add != closedAdd_.end()) closedAdd_.erase(add);
                if (drop != closedDrop_.end()) closedDrop_.erase(drop);
                if (present == carried) continue;
                ++c_.closedRowFaces;
                (present ? closedAdd_ : closedDrop_).push_back(f);
            }
        }
    }

    // The stack the spans after this event are drawn from: the carried one, adjusted by the
    // closed-row faces when there are any on this row.
    void ShowStack(double xe, double xq, double y) {
        if (closedAdd_.empty() && closedDrop_.empty()) {
            shown_ = cur_;
            return;
        }
        showBuf_.clear();
        for (int f : *cur_)
            if (!Contains(closedDrop_, f)) showBuf_.push_back(f);
        for (int f : closedAdd_)
            if (!Contains(showBuf_, f)) InsertInto(showBuf_, f, xe, xq, y);
        shown_ = &showBuf_;
    }

    // Pass three's derivation (the REBUILD, used where pass one and two cannot carry the
    // stacks): the stack of edge a from its left neighbour's stack `prev` — the faces of a that
    // are on prev leave, the others enter in depth order (§5.5.1 at the crossing and at Q); a
    // show-edge's two faces change sides at it. Used for every stack at a band's first row, and
    // afterwards only for marked edges: after a vertex fallback (PassOne), when S0 changed
    // (SeedStack), and for conic legs lost to rounding and found again (TraceAndSort). With
    // `propagate`, a derived set that differs from the carried one marks the next stack edge,
    // so the change is carried right until a derived stack equals the carried one.
    void DeriveEdge(ActiveEdge& a, const std::vector<int>& prev, double xq, double y) {
        ++c_.stackDerivations;
        if (!bandStartRow_) ++c_.stackRebuilds;
        a.toggles.clear();
        derived_.assign(prev.begin(), prev.end());
        const ShowEdge& e = edges_[static_cast<std::size_t>(a.edge)];
        for (int f : e.faces) {
            if (f < 0) continue;
            auto it = std::find(derived_.begin(), derived_.end(), f);
            if (it != derived_.end()) {
                derived_.erase(it);
                ++c_.stackDeriveDeletes;
            } else {
                InsertInto(derived_, f, a.x, xq, y);
                ++c_.stackDeriveInserts;
            }
        }
        const bool changed = !a.carriedValid || !SameSet(derived_, a.stack);
        if (a.propagate && changed) markNext_ = true;
        if (changed) ++c_.stackDerivationsChanged;
        a.stack.swap(derived_);
        a.derive = false;
        a.carriedValid = true;
        a.propagate = false;
    }

    // The verifier. After an event whose stack edges are [b, e) (the last one `last`), the stack
    // must be the stack before the event with the event's faces toggled (structure), and each
    // toggled face must be on it exactly when the face test at Q finds the face on its body's
    // boundary there (geometry). A structural mismatch (a vertex whose change was not carried
    // on) is counted in stackRepairs, a face the test overrules in stackCorrections; both are
    // corrected: the stack is rebuilt from `before` with the faces the test finds, and the next
    // stack edge is derived again. Then the faces that entered are checked against the
    // nearest faces of their own body on the stack (order, §5.5.1; stackOrderCorrections).
    // The faces entering/leaving at the event are counted as face_stack_inserts/deletes.
    void VerifyEvent(const std::vector<int>& before, std::size_t b, std::size_t e, std::size_t last,
                     double xq, double y) {
        std::vector<int>& t = ael_[last].stack;
        const double xe = ael_[last].x;
        if (++gen_ == 0) {  // stamp overflow: clear the marks
            std::fill(markP_.begin(), markP_.end(), 0);
            std::fill(markT_.begin(), markT_.end(), 0);
            gen_ = 1;
        }
        for (int f : before) markP_[static_cast<std::size_t>(f)] = gen_;
        for (int f : t) markT_[static_cast<std::size_t>(f)] = gen_;
        auto inP = [&](int f) { return markP_[static_cast<std::size_t>(f)] == gen_; };
        auto inT = [&](int f) { return markT_[static_cast<std::size_t>(f)] == gen_; };
        toggles_.clear();
        for (std::size_t k = b; k < e; ++k) {
            if (!Participates(ael_[k])) continue;
            for (int f : edges_[static_cast<std::size_t>(ael_[k].edge)].faces) {
                if (f < 0) continue;
                auto it = std::find_if(toggles_.begin(), toggles_.end(),
                                       [&](const std::pair<int, bool>& p) { return p.first == f; });
                if (it == toggles_.end())
                    toggles_.push_back({f, true});
                else
                    it->second = !it->second;
            }
        }
        auto toggled = [&](int f) {
            return std::any_of(toggles_.begin(), toggles_.end(),
                               [&](const std::pair<int, bool>& p) { return p.first == f; });
        };
        bool structural = true;
        for (int f : t) structural = structural && (toggled(f) || inP(f));
        for (int f : before) structural = structural && (toggled(f) || inT(f));
        for (auto [f, odd] : toggles_) structural = structural && (inT(f) == (inP(f) != odd));
        bool geometric = true;
        present_.clear();
        for (auto [f, odd] : toggles_) {
            const bool p = PresentAt(f, xq, y);
            present_.push_back(p);
            if (p != inT(f)) {
                geometric = false;
                ++c_.stackCorrections;
            }
        }
        if (!structural) ++c_.stackRepairs;
        if (!structural || !geometric) {
            // Rebuild from the stack before the event: it was verified at its own event.
            derived_.assign(before.begin(), before.end());
            for (std::size_t k = 0; k < toggles_.size(); ++k) {
                const int f = toggles_[k].first;
                auto it = std::find(derived_.begin(), derived_.end(), f);
                if (it != derived_.end() && !present_[k]) derived_.erase(it);
                if (it == derived_.end() && present_[k]) InsertInto(derived_, f, xe, xq, y);
            }
            t.swap(derived_);
            markNext_ = true;
        }
        for (int f : t)
            if (!inP(f)) ++c_.stackInserts;
        for (int f : before)
            if (!Contains(t, f)) ++c_.stackDeletes;
        // Order: each entering face against the nearest faces of its own body above and below.
        // A misplaced face is inserted again (InsertInto leaves it in order with its own body's
        // faces) and the scan restarts, a bounded number of times.
        int retries = static_cast<int>(t.size());
        for (std::size_t s = 0; s < t.size(); ++s) {
            const int f = t[s];
            if (inP(f)) continue;
            const int body = faces_[static_cast<std::size_t>(f)].body;
            bool ok = true;
            for (std::size_t r = s; r-- > 0;) {
                if (faces_[static_cast<std::size_t>(t[r])].body != body) continue;
                ok = CompareAt(t[r], f, xe, xq, y) <= 0;
                break;
            }
            for (std::size_t r = s + 1; ok && r < t.size(); ++r) {
                if (faces_[static_cast<std::size_t>(t[r])].body != body) continue;
                ok = CompareAt(f, t[r], xe, xq, y) <= 0;
                break;
            }
            if (ok || retries-- <= 0) continue;
            ++c_.stackOrderCorrections;

            t.erase(t.begin() + static_cast<std::ptrdiff_t>(s));
            InsertInto(t, f, xe, xq, y);
            s = static_cast<std::size_t>(-1);  // rescan from the head
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
        const std::vector<OrientedLiteral>& lits = bodyLiterals_[static_cast<std::size_t>(sf.body)];
        // ∂/∂z of the face's own HSI: the body lies along the ray on the side where it is < 0.
        double gz = 0;
        for (const OrientedLiteral& l : lits) {
            if (l.halfSpace != sf.halfSpace) continue;
            const Quadric& q = l.quadric;
            gz = l.isPlane ? l.plane.c : q.F() * x + q.E() * y + q.C() * z + q.J();
            break;
        }
        for (const OrientedLiteral& l : lits) {
            if (l.halfSpace == sf.halfSpace) continue;
            const double v = l.isPlane ? l.plane.Evaluate(p) : l.quadric.Evaluate(p);
            const double e = l.isPlane ? PlaneErrorEstimate(l.plane, p, pointError)
                                       : QuadricErrorEstimate(l.quadric, p, pointError);
            if (l.zFree) {
                if (!(v <= e)) return false;
                continue;
            }
            if (v < -e) continue;
            if (v > e || gz == 0) return false;
            // The point lies ON this HSI's surface: Q is on an edge of the face that runs along
            // the CSL (a row exactly on a horizontal edge). The face is there when the body goes
            // on along the ray from it (raycast's interval has a length: the front face at a
            // box's slanted top edge), not when the body only touches the ray there (zero
            // thickness: the base edge of a pyramid).
            const double step = (gz > 0 ? -1e-6 : 1e-6) * (1 + std::fabs(z));
            const Vec3 p2{x, y, z + step};
            const double v2 = l.isPlane ? l.plane.Evaluate(p2) : l.quadric.Evaluate(p2);
            const double e2 = l.isPlane ? PlaneErrorEstimate(l.plane, p2, pointError)
                                        : QuadricErrorEstimate(l.quadric, p2, pointError);
            if (!(v2 < -e2)) return false;
        }
        return true;
    }

    // The span's faces from the stack: per stack body its first (nearest) face, in stack order,
    // so stack_[0] is the head when no exactly evaluated unit shares the span.
    void TakeStackFaces(int sample, double y) {
        stackHead_ = stack_.empty() ? 0 : -1;
        ++c_.stackSpans;
        c_.stackDepthSum += shown_->size();
        taken_.clear();
        for (int f : *shown_) {
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
        const bool head = !shown_->empty();
        if (!head && best.halfSpace < 0) return;
        ++c_.verifySpans;
        bool same = head && best.halfSpace >= 0;
        if (same) {
            const FaceRef h = RefOf(shown_->front());
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
    const VertexTable& vt_;
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
    std::vector<ActiveEdge> starting_, merged_;  // starting edges of a row, merge scratch
    // Pass one (§5.4): the AEL of row j − 1 being walked (old_, CE = ce_, gone_: deleted), the
    // new AEL's last stack edge, a fallback mark for the next stack edge emitted, per vertex and
    // per within-the-line edge the row it was processed on, a component's starting edges and the
    // faces its finishing and starting edges toggle.
    std::vector<ActiveEdge> old_, newEdges_;
    std::vector<char> gone_;
    std::size_t ce_ = 0;
    std::ptrdiff_t lastPart_ = -1;
    bool markOut_ = false;
    bool bandStartRow_ = false;  // the row is a band's first: every stack is derived
    std::vector<int> vertexRow_, inBandRow_, starts_, parity_;
    std::vector<std::size_t> found_;         // ProcessVertex: places of the finishing edges in old_
    QuadraticRoots lastRoots_;               // Span: roots shared by consecutive faces
    std::vector<double> lo_, hi_;            // per body: x range on the current row
    std::vector<int> breakBody_;             // per crossing in breaks_: its body
    std::vector<int> ownPassed_;             // per body: its crossings left of the current pixel
    std::vector<CachedTemplate> tmplCache_;  // per CSG operand body (BuildTemplate)
    std::vector<int> rangeRow_;              // the row lo_/hi_ were reset for
    std::vector<int> activeUnits_;
    std::vector<int> unitsByY_;  // units sorted on y0 (UpdateActiveUnits)
    std::size_t unitPos_ = 0;
    std::vector<int> rowBodies_;   // bodies met on this row, sorted on lo_ (per-row ranges)
    std::size_t sweepPos_ = 0;     // SweepTo: next of rowBodies_ to enter
    std::vector<int> spanBodies_;  // SweepTo: bodies whose range meets the current span
    // CSG: tree parents and child positions, per body its leaves (unit, node), per unit its
    // refused bodies and side bodies; pruned trees (BuildPruned) and their scratch.
    std::vector<int> parent_, childPos_;
    std::vector<std::vector<std::pair<int, int>>> bodyLeaves_;
    std::vector<std::vector<int>> unitPixelBodies_;
    std::vector<std::vector<SideBody>> unitSideBodies_;
    std::vector<std::uint32_t> touchGen_, unitStamp_;
    std::uint32_t pruneGen_ = 0, spanGen_ = 0;
    std::vector<int> leafPNode_;
    std::vector<std::vector<int>> touchedKids_;
    std::vector<PNode> pNodes_;
    std::vector<int> pKids_;
    std::vector<SpanLeaf> spanLeaves_;
    std::vector<std::pair<int, int>> pruneLeaves_;  // (leaf node, template index or −1)
    std::vector<IntervalList> pool_;
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
    bool stackOn_ = false;                                    // some body is drawn from face stacks
    // Pass three: the stack right of the last walked stack edge (or seed_), nearest first.
    const std::vector<int>* cur_ = &seed_;
    // The stack the spans are drawn from: *cur_, or showBuf_ = *cur_ adjusted by the faces of
    // edges ending on this row's centre that the face test keeps (closedAdd_) or drops.
    const std::vector<int>* shown_ = &seed_;
    std::vector<int> showBuf_, closedAdd_, closedDrop_;
    std::vector<int> seed_, seedPrev_;           // S0 on this row and on the previous one
    bool markNext_ = false;                      // derive the next stack edge walked
    std::vector<int> derived_;                   // scratch stack
    std::vector<std::pair<int, bool>> toggles_;  // an event's faces, odd number of crossings
    std::vector<char> present_;                  // the face test at Q for toggles_
    std::vector<std::uint32_t> markP_, markT_;   // per show-face: on the stack before / after
    std::uint32_t gen_ = 0;                      // stamp of markP_ / markT_
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
    csgTemplateReuses += o.csgTemplateReuses;
    rootFallbackPixels += o.rootFallbackPixels;
    stackInserts += o.stackInserts;
    stackDeletes += o.stackDeletes;
    stackMaxDepth = std::max(stackMaxDepth, o.stackMaxDepth);
    stackDepthSum += o.stackDepthSum;
    stackSpans += o.stackSpans;
    stackSeedEvaluations += o.stackSeedEvaluations;
    stackTieBreaks += o.stackTieBreaks;
    stackCorrections += o.stackCorrections;
    stackRepairs += o.stackRepairs;
    closedRowFaces += o.closedRowFaces;
    stackOrderCorrections += o.stackOrderCorrections;
    stackSwapUpdates += o.stackSwapUpdates;
    stackDerivations += o.stackDerivations;
    stackDerivationsChanged += o.stackDerivationsChanged;
    stackDeriveInserts += o.stackDeriveInserts;
    stackDeriveDeletes += o.stackDeriveDeletes;
    stackVertices += o.stackVertices;
    stackVertexRecursions += o.stackVertexRecursions;
    stackDeletionSwaps += o.stackDeletionSwaps;
    stackVertexFallbacks += o.stackVertexFallbacks;
    stackRebuilds += o.stackRebuilds;
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
    // Bodies drawn from face stacks (as ScanRenderer's useStack_): their edges make §5.4's
    // vertices.
    std::vector<char> stack(scene.bodies.size(), 0);
    for (const Unit& unit : units) {
        if (unit.kind != Unit::Kind::kBody || unit.body < 0) continue;
        const auto b = static_cast<std::size_t>(unit.body);
        stack[b] = settings.faceStacks && b < stackBody.size() && stackBody[b] && !pixelBody[b];
    }
    const VertexTable vt = BuildVertices(edges, stack, h);
    constexpr int kBand = 32;  // rows per task; fixed, so results never depend on threads
    const int bands = (h + kBand - 1) / kBand;
    std::mutex mutex;
    auto run = [&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1),
                          [&](const tbb::blocked_range<int>& r) {
                              for (int b = r.begin(); b < r.end(); ++b) {
                                  RendererCounters local;
                                  ScanRenderer(scene, edges, faces, units, pixelBody, stackBody, vt,
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
