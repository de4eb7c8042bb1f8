#include "quadrix/engines/pixelpowers/compiler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <utility>

namespace quadrix::pixelpowers {

Vec3 RaycastReferencePoint(const FlatScene& scene, std::size_t h) {
    // Same rule as raycast's SceneTables::ReferencePoint.
    Vec3 anchor{std::round(0.5 * scene.width), std::round(0.5 * scene.height), 0};
    const FlatHalfSpace& hs = scene.halfSpaces[h];
    return hs.isPlane ? anchor : eval::RayHalfSpace::Centre(hs.quadric).value_or(anchor);
}

namespace {

constexpr std::uint8_t kF1 = 0, kF2 = 1, kF3 = 2;
using Coeffs = std::array<double, 6>;  // A x² + B xy + C y² + D x + E y + F

// A quadric along the rays of its pixels (DESIGN.md "Depth of a quadric at a pixel"):
// Q = c z² + 2 b(x,y) z + a(x,y), roots z = L ± sqrt(Δ)/|c| with L = −b/c, Δ = b² − c a.
struct RayForm {
    double c = 0;
    Coeffs b{}, a{};  // b uses only D E F (linear)
};

RayForm RayFormOf(const Quadric& q) {
    RayForm r;
    r.c = q.C();
    r.b = {0, 0, 0, q.F(), q.E(), q.J()};
    r.a = {q.A(), 2 * q.D(), q.B(), 2 * q.G(), 2 * q.H(), q.K()};
    return r;
}

Coeffs Discriminant(const RayForm& r) {
    const double bx = r.b[3], by = r.b[4], b0 = r.b[5];
    Coeffs b2{bx * bx, 2 * bx * by, by * by, 2 * bx * b0, 2 * by * b0, b0 * b0};
    Coeffs d;
    for (int i = 0; i < 6; ++i) d[static_cast<std::size_t>(i)] = b2[i] - r.c * r.a[i];
    return d;
}

double Eval(const Coeffs& q, double x, double y) {
    return q[0] * x * x + q[1] * x * y + q[2] * y * y + q[3] * x + q[4] * y + q[5];
}

// The maximum of Q(x, y) over the pixel centres' rectangle [x0+½, x1−½] × [y0+½, y1−½] of
// `rect`: a quadratic attains it at a corner, at the vertex of an edge's parabola, or at the
// interior stationary point, so the maximum over those candidates is exact (up to rounding).
double MaxOverRect(const Coeffs& q, const PixelRect& rect) {
    const double xa = rect.x0 + 0.5, xb = rect.x1 - 0.5, ya = rect.y0 + 0.5, yb = rect.y1 - 0.5;
    double m = -HUGE_VAL;
    auto consider = [&](double x, double y) {
        if (x >= xa && x <= xb && y >= ya && y <= yb) m = std::max(m, Eval(q, x, y));
    };
    const double A = q[0], B = q[1], C = q[2], D = q[3], E = q[4];
    for (double y : {ya, yb}) {
        consider(xa, y);
        consider(xb, y);
        if (A != 0) consider(-(B * y + D) / (2 * A), y);  // vertex of the edge's parabola in x
    }
    for (double x : {xa, xb}) {
        if (C != 0) consider(x, -(B * x + E) / (2 * C));
    }
    double det = 4 * A * C - B * B;  // ∇Q = 0: [2A B; B 2C] (x y) = −(D E)
    if (det != 0) consider((B * E - 2 * C * D) / det, (B * D - 2 * A * E) / det);
    return m;
}

// Tangent points u_i of sqrt so that min_i T_i(v²) − v <= e for v in [0, vmax], where
// T_u(Δ) = u/2 + Δ/(2u) is the tangent of sqrt at Δ = u² (sqrt is concave, so every tangent lies
// above it and the minimum over tangents is the best: the envelope of seed 004 §III step 2).
// The error of T_u at v is (u − v)²/(2u): T_u covers [u − sqrt(2ue), u + sqrt(2ue)], and the first
// point u0 = 2e covers [0, 4e].
std::vector<double> TangentPoints(double vmax, double e, int maxStrips, bool& capped) {
    std::vector<double> u;
    capped = false;
    double covered = 0;
    double t = 2 * e;
    while (true) {
        u.push_back(t);
        covered = t + std::sqrt(2 * t * e);
        if (covered >= vmax) break;
        if (static_cast<int>(u.size()) >= maxStrips) {
            capped = true;
            break;
        }
        // Next u with u − sqrt(2ue) = covered: w = sqrt(u) solves w² − sqrt(2e) w − covered = 0.
        double w = 0.5 * (std::sqrt(2 * e) + std::sqrt(2 * e + 4 * covered));
        t = w * w;
    }
    return u;
}

class Compiler {
  public:
    Compiler(const FlatScene& scene, const CompileOptions& options, Program& program,
             CompileStats& stats)
        : scene_(scene), options_(options), program_(program), stats_(stats) {}

    void Run() {
        program_ = Program{};
        stats_ = CompileStats{};
        boxes_ = csg::BodyBoxes(scene_);
        SetDepthWords();
        std::set<int> bodies, halfSpaces;
        for (std::size_t s = 0; s < scene_.solids.size(); ++s) {
            csg::Tree tree = csg::TreeOfSolid(scene_, static_cast<int>(s));
            csg::NormalizeOptions no;
            no.maxProducts = options_.maxProducts;
            no.boxes = boxes_;
            // A solid's own bounds bound every product of it.
            const Box3& sb = scene_.solids[s].bounds;
            csg::NormalForm nf = csg::Normalize(tree, no);
            Accumulate(nf.stats);
            const std::string who = SolidName(s);
            if (!nf.ok) {
                stats_.errors.push_back(who + " not drawn: " + nf.error);
                stats_.undrawnSolids.push_back(static_cast<int>(s));
                continue;
            }
            std::size_t most = 0;
            for (const csg::Product& p : nf.products) {
                std::size_t n = 0;
                for (const csg::Factor& f : p)
                    if (ValidBody(f.primitive)) n += Body(f.primitive).literals.size();
                most = std::max(most, n);
            }
            if (most > options_.maxLiterals) {
                stats_.errors.push_back(
                    who + " not drawn: a product of " + std::to_string(most) +
                    " literals passes max-literals = " + std::to_string(options_.maxLiterals) +
                    " (paring costs ~literals^2 per product)");
                stats_.undrawnSolids.push_back(static_cast<int>(s));
                continue;
            }
            const std::size_t cappedMark = stats_.stripsCapped;
            products_ = &nf.products;
            const std::size_t codeMark = program_.code.size(), blockMark = program_.blocks.size(),
                              patchMark = program_.patches.size();
            bool tooBig = false;
            for (const csg::Product& p : nf.products) {
                if (program_.code.size() > options_.maxInstructions) {
                    tooBig = true;
                    break;
                }
                for (const csg::Factor& f : p) {
                    bodies.insert(f.primitive);
                    if (ValidBody(f.primitive))
                        for (const FlatLiteral& l : Body(f.primitive).literals)
                            halfSpaces.insert(l.halfSpace);
                }
                CompileProduct(p, static_cast<std::int32_t>(s), sb);
            }
            for (std::size_t g = exitGroups_.size(); g-- > 0;)
                program_.blocks.insert(program_.blocks.end(), exitGroups_[g].begin(),
                                       exitGroups_[g].end());
            exitGroups_.clear();
            if (tooBig || program_.code.size() > options_.maxInstructions) {
                program_.code.resize(codeMark);
                program_.blocks.resize(blockMark);
                program_.patches.resize(patchMark);
                stats_.errors.push_back(
                    who + " not drawn: the program would pass max-instructions = " +
                    std::to_string(options_.maxInstructions) + " with it (" +
                    std::to_string(codeMark) + " instructions before it, " +
                    std::to_string(nf.products.size()) +
                    " products); simplify the tree or raise --engine-opt max-instructions");
                stats_.undrawnSolids.push_back(static_cast<int>(s));
            } else if (stats_.stripsCapped > cappedMark) {
                stats_.warnings.push_back(
                    who + ": " + std::to_string(stats_.stripsCapped - cappedMark) +
                    " sheet(s) needed more than max-strips = " +
                    std::to_string(options_.maxStrips) +
                    " parabolic strips; its depth error may exceed the tolerance");
            }
        }
        stats_.primitives = bodies.size();
        stats_.halfSpaces = halfSpaces.size();
        stats_.patches = program_.blocks.size();
    }

  private:
    std::string SolidName(std::size_t s) const {
        const std::string& n = scene_.solids[s].name;
        return n.empty() ? "solid #" + std::to_string(s) : "solid '" + n + "'";
    }

    // Fixed-point depth words over the z range of the solids' bounds (seed 004 §III: ZTEMP and
    // ZMIN are 20–30 bit registers). The range must be finite to place the words.
    void SetDepthWords() {
        if (options_.depthBits <= 0) return;
        // The hull of the solids' bounds, tightened by the hull of the bodies' boxes (either may
        // be the unbounded default; every drawn depth lies in both).
        double lo = HUGE_VAL, hi = -HUGE_VAL, bodyLo = HUGE_VAL, bodyHi = -HUGE_VAL;
        for (const FlatSolid& solid : scene_.solids) {
            if (solid.bounds.Empty()) continue;
            lo = std::min(lo, solid.bounds.lo.z);
            hi = std::max(hi, solid.bounds.hi.z);
        }
        for (const Box3& box : boxes_) {
            if (box.Empty()) continue;
            bodyLo = std::min(bodyLo, box.lo.z);
            bodyHi = std::max(bodyHi, box.hi.z);
        }
        lo = std::max(lo, bodyLo);
        hi = std::min(hi, bodyHi);
        if (!(std::isfinite(lo) && std::isfinite(hi))) {
            if (lo <= hi)
                stats_.warnings.push_back(
                    "depth-bits ignored: the solids' depth range is unbounded, so fixed-point "
                    "depth words cannot be placed (depths stay doubles)");
            return;
        }
        // A small margin so that depths on the bounds themselves do not clamp.
        double span = hi - lo, margin = 1e-3 * (span + 1);
        program_.depthOrigin = lo - margin;
        program_.depthStep = (span + 2 * margin) / (std::ldexp(1.0, options_.depthBits) - 1);
        program_.depthBits = options_.depthBits;
    }

    void Accumulate(const csg::NormalFormStats& s) {
        csg::NormalFormStats& t = stats_.normalForm;
        t.treePrimitives += s.treePrimitives;
        t.treeOperators += s.treeOperators;
        t.products += s.products;
        t.factors += s.factors;
        t.terms += s.terms;
        t.prunedProducts += s.prunedProducts;
        t.prunedFactors += s.prunedFactors;
        t.prunedSubtrahends += s.prunedSubtrahends;
        t.contradictions += s.contradictions;
        t.duplicates += s.duplicates;
    }

    const FlatBody& Body(int b) const { return scene_.bodies[static_cast<std::size_t>(b)]; }

    // raycast treats a body with a missing half-space, or without literals, as empty.
    bool ValidBody(int b) const {
        if (b < 0 || static_cast<std::size_t>(b) >= scene_.bodies.size()) return false;
        const FlatBody& body = Body(b);
        if (body.literals.empty()) return false;
        for (const FlatLiteral& l : body.literals)
            if (l.halfSpace < 0 ||
                static_cast<std::size_t>(l.halfSpace) >= scene_.halfSpaces.size())
                return false;
        return true;
    }

    std::int32_t LiteralIndex(const FlatLiteral& l) {
        auto key = std::make_pair(l.halfSpace, l.complemented);
        auto it = literalIndex_.find(key);
        if (it != literalIndex_.end()) return it->second;
        const FlatHalfSpace& hs = scene_.halfSpaces[static_cast<std::size_t>(l.halfSpace)];
        MachineLiteral m;
        m.ray = eval::RayHalfSpace::From(
            hs, RaycastReferencePoint(scene_, static_cast<std::size_t>(l.halfSpace)));
        m.complemented = l.complemented;
        m.isPlane = hs.isPlane;
        program_.literals.push_back(m);
        auto index = static_cast<std::int32_t>(program_.literals.size() - 1);
        literalIndex_.emplace(key, index);
        return index;
    }

    // Pixels whose centres lie in the box's xy range, clipped to the image.
    PixelRect RectOf(const Box3& b) const {
        auto lo = [](double v, int n) {
            if (std::isnan(v)) return 0;
            double c = std::ceil(v - 0.5);
            return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(n)));
        };
        auto hi = [](double v, int n) {
            if (std::isnan(v)) return n;
            double c = std::floor(v - 0.5) + 1;
            return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(n)));
        };
        if (b.Empty()) return {};
        return {lo(b.lo.x, scene_.width), lo(b.lo.y, scene_.height), hi(b.hi.x, scene_.width),
                hi(b.hi.y, scene_.height)};
    }

    bool Opaque(const FlatLiteral& l) const {
        const FlatHalfSpace& hs = scene_.halfSpaces[static_cast<std::size_t>(l.halfSpace)];
        return !hs.transparent && !hs.isClip;
    }

    // True when a plane literal holds over the whole box (all eight corners inside), so that it
    // bounds nothing there: the Flattener's clipping planes behind the eye, far from the solids.
    bool HoldsOver(const FlatLiteral& l, const Box3& b) const {
        const FlatHalfSpace& hs = scene_.halfSpaces[static_cast<std::size_t>(l.halfSpace)];
        if (!hs.isPlane || !b.Finite()) return false;
        for (int c = 0; c < 8; ++c) {
            Vec3 p{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z};
            double v = hs.plane.Evaluate(p);
            if (!(l.complemented ? v > 0 : v < 0)) return false;
        }
        return true;
    }

    Box3 BoxOf(int body) const { return boxes_[static_cast<std::size_t>(body)]; }

    void CompileProduct(const csg::Product& p, std::int32_t solid, const Box3& solidBox) {
        for (const csg::Factor& f : p)
            if (!f.subtracted && !ValidBody(f.primitive)) return;  // an empty ∩ factor
        Box3 productBox = solidBox.Empty() ? Box3{} : Box3::Everything();
        for (const csg::Factor& f : p)
            if (!f.subtracted) productBox = productBox.Intersected(BoxOf(f.primitive));
        // Exit terms are needed where the first opaque boundary point on a ray may be one where
        // the product is left: after a transparent surface (a clipping plane), or when the ray
        // starts inside the product (a box unbounded toward the viewer).
        bool exits = !(productBox.lo.z > -HUGE_VAL);
        for (const csg::Factor& f : p)
            if (ValidBody(f.primitive))
                for (const FlatLiteral& l : Body(f.primitive).literals)
                    exits = exits || (!Opaque(l) && !HoldsOver(l, productBox));
        struct Term {
            std::size_t i;
            Box3 box;
            PixelRect rect;
            std::vector<csg::Factor> paring;
        };
        std::vector<Term> terms;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const csg::Factor& xi = p[i];
            if (!ValidBody(xi.primitive)) continue;  // an empty − factor draws nothing
            Box3 termBox = productBox.Intersected(BoxOf(xi.primitive));
            PixelRect rect = RectOf(termBox);
            if (termBox.Empty() || rect.Empty()) {
                ++stats_.prunedTerms;
                continue;
            }
            ++stats_.terms;
            std::vector<csg::Factor> paring;
            for (std::size_t j = 0; j < p.size(); ++j) {
                if (j == i) continue;
                const csg::Factor& y = p[j];
                if (y.subtracted &&
                    (!ValidBody(y.primitive) || termBox.Intersected(BoxOf(y.primitive)).Empty())) {
                    ++stats_.prunedParings;
                    continue;
                }
                paring.push_back(y);
            }
            terms.push_back({i, termBox, rect, std::move(paring)});
        }
        // Display theorem: front (entry) face for ∩ factors, back (exit) face for − ones;
        // with `exits`, also the opposite faces (raycast draws the first opaque endpoint).
        auto emitTerm = [&](const Term& t, int face) {
            const csg::Factor& xi = p[t.i];
            const FlatBody& body = Body(xi.primitive);
            bool exitFace = xi.subtracted != (face == 1);
            for (std::size_t k = 0; k < body.literals.size(); ++k) {
                const FlatLiteral& lit = body.literals[k];
                if (!Opaque(lit)) continue;  // never drawn (raycast: not opaque)
                PixelRect patchRect = PlaneFaceRect(body, k, t.box, t.rect);
                if (patchRect.Empty()) {
                    ++stats_.prunedPatches;
                    continue;
                }
                EmitPatch(xi.primitive, k, exitFace, face == 1, t.paring,
                          exits ? Others(p, t.box) : std::vector<const csg::Product*>{}, patchRect,
                          solid);
            }
        };
        // Exact ties, as raycast's left fold ((X0 ∩ X1) − X2 …, math/interval_list.h) breaks
        // them. A tie of the product's entries goes to the later factor (an intersection is
        // opened by its right operand's start on a tie, a difference reopened at the
        // subtrahend's exit; within a body the later literal's start opens it): entry terms in
        // factor order, whose ZTESTs let a patch win a tie against the patches of this product
        // drawn before it (tieFrom_) and against no other (a union is opened by its left
        // operand, and the lower solid wins). A tie of exits goes to the later − factor (a
        // difference closed at the subtrahend's start) and else to the earlier ∩ factor (an
        // intersection closed by its left operand's end): exit terms − factors last first, then
        // ∩ factors first first, with strict ZTESTs; they are set aside and appended after the
        // solid's entries in reverse product order (a union is closed by its right operand's end
        // on a tie; Run).
        tieFrom_ = static_cast<std::int32_t>(program_.patches.size());
        for (const Term& t : terms) emitTerm(t, 0);
        tieFrom_ = -1;
        if (!exits) return;
        const std::size_t exitMark = program_.blocks.size();
        for (std::size_t n = terms.size(); n-- > 0;)
            if (p[terms[n].i].subtracted) emitTerm(terms[n], 1);
        for (const Term& t : terms)
            if (!p[t.i].subtracted) emitTerm(t, 1);
        exitGroups_.emplace_back(program_.blocks.begin() + static_cast<std::ptrdiff_t>(exitMark),
                                 program_.blocks.end());
        program_.blocks.resize(exitMark);
    }

    Instruction& Emit(Opcode op, std::uint8_t a, std::uint8_t b = 0, std::int32_t arg = -1) {
        Instruction in;
        in.op = op;
        in.a = a;
        in.b = b;
        in.arg = arg;
        program_.code.push_back(in);
        return program_.code.back();
    }
    void EmitQ(Opcode op, std::uint8_t a, const Coeffs& q) {
        Instruction& in = Emit(op, a);
        for (int i = 0; i < 6; ++i) in.q[i] = q[static_cast<std::size_t>(i)];
    }

    // The other products of the solid that may meet `box` (for exit terms: a boundary point of
    // one product inside another is no boundary of their union).
    std::vector<const csg::Product*> Others(const csg::Product& p, const Box3& box) const {
        std::vector<const csg::Product*> out;
        for (const csg::Product& q : *products_) {
            if (&q == &p) continue;
            Box3 b = box;
            bool valid = true;
            for (const csg::Factor& f : q) {
                if (f.subtracted) continue;
                valid = valid && ValidBody(f.primitive);
                if (valid) b = b.Intersected(BoxOf(f.primitive));
            }
            if (valid && !b.Empty()) out.push_back(&q);
        }
        return out;
    }

    // The screen rectangle of a plane patch: the polygon cut from the plane by the term box and
    // the body's other plane literals (quadric literals only shrink the face, so ignoring them is
    // conservative), widened by a rounding margin. Quadric patches keep `rect`.
    PixelRect PlaneFaceRect(const FlatBody& body, std::size_t k, const Box3& box,
                            const PixelRect& rect) const {
        const FlatHalfSpace& hs =
            scene_.halfSpaces[static_cast<std::size_t>(body.literals[k].halfSpace)];
        if (!hs.isPlane || !box.Finite() || !hs.plane.AllFinite()) return rect;
        Vec3 n = hs.plane.Normal();
        double nn = Dot(n, n);
        if (!(nn > 0)) return rect;
        // A square on the plane around the box centre's projection, larger than the box.
        Vec3 centre = box.Center();
        Vec3 p0 = centre - n * (hs.plane.Evaluate(centre) / nn);
        Vec3 u =
            Normalize(Cross(n, std::fabs(n.x) < std::fabs(n.y) ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
        Vec3 v = Normalize(Cross(n, u));
        double half = Length(box.Size()) + Length(p0 - centre) + 1;
        std::vector<Vec3> poly = {p0 + (u + v) * half, p0 + (v - u) * half, p0 - (u + v) * half,
                                  p0 + (u - v) * half};
        // Clip by a half-space  g·x + e <= 0  (Sutherland–Hodgman).
        auto clip = [&](const Vec3& g, double e) {
            std::vector<Vec3> out;
            for (std::size_t i = 0; i < poly.size(); ++i) {
                const Vec3& a = poly[i];
                const Vec3& b = poly[(i + 1) % poly.size()];
                double fa = Dot(g, a) + e, fb = Dot(g, b) + e;
                if (fa <= 0) out.push_back(a);
                if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
                    double t = fa / (fa - fb);
                    out.push_back(a + (b - a) * t);
                }
            }
            poly.swap(out);
        };
        for (std::size_t axis = 0; axis < 3 && !poly.empty(); ++axis) {
            Vec3 g{0, 0, 0};
            g[axis] = 1;
            clip(g, -box.hi[axis]);
            if (!poly.empty()) clip(g * -1.0, box.lo[axis]);
        }
        for (std::size_t m = 0; m < body.literals.size() && !poly.empty(); ++m) {
            if (m == k) continue;
            const FlatLiteral& l = body.literals[m];
            const FlatHalfSpace& o = scene_.halfSpaces[static_cast<std::size_t>(l.halfSpace)];
            if (!o.isPlane || !o.plane.AllFinite()) continue;
            double sgn = l.complemented ? -1.0 : 1.0;
            clip(o.plane.Normal() * sgn, o.plane.d * sgn);
        }
        if (poly.empty()) return {};
        Box3 b;
        for (const Vec3& p : poly) b.Extend(p);
        // Rounding of the clipped vertices is far below this margin (coordinates ~ image size).
        double margin = 1e-6 * (1 + Length(b.Size()) + Length(b.Center()));
        b.lo = b.lo - Vec3{margin, margin, margin};
        b.hi = b.hi + Vec3{margin, margin, margin};
        return RectOf(b).Intersected(rect);
    }

    // `productExit`: the patch's points are exits of the product (face 1), else entries; for a −
    // factor that is the opposite of `exitFace`, the sheet of the factor's own literal.
    void EmitPatch(int bodyIndex, std::size_t k, bool exitFace, bool productExit,
                   const std::vector<csg::Factor>& paring,
                   const std::vector<const csg::Product*>& others, const PixelRect& rect,
                   std::int32_t solid) {
        const FlatBody& body = Body(bodyIndex);
        const FlatLiteral& lit = body.literals[k];
        Block block;
        block.rect = rect;
        currentRect_ = rect;
        block.first = static_cast<std::int32_t>(program_.code.size());
        // Scan conversion and depth: F1 = the sheet exists here, ZTEMP = its depth.
        if (!EmitSheet(lit, exitFace, rect)) {
            program_.code.resize(static_cast<std::size_t>(block.first));
            return;  // this literal has no such sheet anywhere
        }
        // Early depth test: ZMIN does not change within a block, so dropping hidden pixels now
        // gives the same result as the final test and spares them the paring.
        Emit(Opcode::kZTest, kF1, 0, tieFrom_);
        // The patch is the part of the sheet inside the primitive's other literals. The tests
        // are one-sided (InsideMode): a point at depth z is an entry (exit) of the product iff
        // every other factor holds, or for a − factor does not hold, just beyond (before) z, which
        // is what the regularised interval sets of raycast give on coincident surfaces (a door
        // exactly as thick as its wall leaves nothing; `body (s p !p)` is empty). The sheet is an
        // entry (exit) of the primitive itself where its other literals hold beyond (before) it.
        const std::uint8_t ownSide = exitFace ? kInsideBefore : kInsideAfter;
        for (std::size_t m = 0; m < body.literals.size(); ++m)
            if (m != k) EmitInside(body.literals[m], kF1, ownSide);
        const std::uint8_t side = productExit ? kInsideBefore : kInsideAfter;
        // CSG operation: pare with the other factors of the product.
        for (const csg::Factor& y : paring) {
            const FlatBody& other = Body(y.primitive);
            if (!y.subtracted) {
                for (const FlatLiteral& l : other.literals) EmitInside(l, kF1, side);
            } else {
                Emit(Opcode::kFlagCopy, kF2, kF1);
                for (const FlatLiteral& l : other.literals) EmitInside(l, kF2, side);
                Emit(Opcode::kFlagAndNot, kF1, kF2);
            }
        }
        // With exit terms: keep only points outside the solid's other products (F2 = inside Q,
        // F3 = inside a − factor of Q). An entry (exit) of this product is one of the union iff
        // Q does not hold just before (beyond) it, so Q is tested on the other side; a boundary
        // point shared by two products (the same literal's root, the same double) is kept where
        // the union changes there. The root unit does these tests for quadrics in both modes:
        // approximate depths err outward (near sheets nearer, far sheets farther), so shared
        // boundaries stay outside; planes in approx mode by the QEE (EmitRootUnitInside).
        const std::uint8_t otherSide = productExit ? kInsideAfter : kInsideBefore;
        for (const csg::Product* q : others) {
            Emit(Opcode::kFlagCopy, kF2, kF1);
            for (const csg::Factor& y : *q) {
                if (!ValidBody(y.primitive)) continue;
                const FlatBody& other = Body(y.primitive);
                if (!y.subtracted) {
                    for (const FlatLiteral& l : other.literals)
                        EmitRootUnitInside(l, kF2, otherSide);
                } else {
                    Emit(Opcode::kFlagCopy, kF3, kF2);
                    for (const FlatLiteral& l : other.literals)
                        EmitRootUnitInside(l, kF3, otherSide);
                    Emit(Opcode::kFlagAndNot, kF2, kF3);
                }
            }
            Emit(Opcode::kFlagAndNot, kF1, kF2);
        }
        // Z-buffer merge (the union of terms, seed 004 §II.a) and COLOR.
        Emit(Opcode::kZTest, kF1, 0, tieFrom_);
        // Shading (seed 004 §III step 4) on the pixels about to be written.
        bool machineNormal = options_.paperShading && EmitShading(lit, exitFace, rect);
        stats_.shadedPatches += machineNormal;
        program_.patches.push_back({lit.halfSpace, bodyIndex, solid, machineNormal});
        Emit(Opcode::kZWrite, kF1, 0, static_cast<std::int32_t>(program_.patches.size() - 1));
        block.count = static_cast<std::int32_t>(program_.code.size()) - block.first;
        program_.blocks.push_back(block);
    }

    // Loads the entry (or exit) sheet of literal `lit` into ZTEMP, F1 = where it exists. Returns
    // false when it exists nowhere.
    bool EmitSheet(const FlatLiteral& lit, bool exitFace, const PixelRect& rect) {
        std::int32_t li = LiteralIndex(lit);
        const FlatHalfSpace& hs = scene_.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
        if (hs.isPlane) {
            // The host knows a plane's facing (seed 003 §3: patches are split into front and
            // back after the eye transformation): inside C z + e <= 0 is z >= r (entered there)
            // when C < 0, z <= r (left there) when C > 0; a complement flips; C = 0 (seen
            // edge-on) has no sheet.
            const Plane& pl = hs.plane;
            if (pl.c == 0) return false;
            bool entry = (pl.c < 0) != lit.complemented;
            if (entry == exitFace) return false;
        }
        if (options_.mode == DepthMode::kExact) {
            Emit(Opcode::kRoot, kF1, exitFace ? 1 : 0, li);
            return true;
        }
        if (hs.isPlane) {
            const Plane& pl = hs.plane;
            if (!pl.AllFinite()) {
                Emit(Opcode::kRoot, kF1, exitFace ? 1 : 0, li);
                return true;
            }
            Emit(Opcode::kFlagSet, kF1);
            EmitQ(Opcode::kZLoad, kF1, {0, 0, 0, -pl.a / pl.c, -pl.b / pl.c, -pl.d / pl.c});
            return true;
        }
        RayForm r = RayFormOf(hs.quadric);
        if (r.c == 0 || !hs.quadric.AllFinite()) {  // linear along rays: z = −a / 2b
            ++stats_.extendedFallbacks;
            Emit(Opcode::kRoot, kF1, exitFace ? 1 : 0, li);
            return true;
        }
        // With c > 0 the inside is [L − s, L + s] (entered at the near sheet); with c < 0 it is
        // outside that; a complement flips entry and exit.
        bool nearSheet = (!exitFace) == ((r.c > 0) != lit.complemented);
        Coeffs disc = Discriminant(r);
        std::vector<Coeffs> sheets = Strips(r, disc, nearSheet, rect);
        if (sheets.empty()) return false;
        Emit(Opcode::kFlagSet, kF1);
        EmitQ(Opcode::kQeeKeepPositive, kF1, disc);
        EmitQ(Opcode::kZLoad, kF1, sheets[0]);
        for (std::size_t i = 1; i < sheets.size(); ++i)
            EmitQ(nearSheet ? Opcode::kZMax : Opcode::kZMin, kF1, sheets[i]);
        return true;
    }

    // The parabolic strips z_i = L ∓ T_i(Δ)/|c| of a quadric's near (−) or far (+) sheet over
    // `rect` (seed 004 §III step 2). Empty when Δ <= 0 over the whole rectangle.
    std::vector<Coeffs> Strips(const RayForm& r, const Coeffs& disc, bool nearSheet,
                               const PixelRect& rect) {
        double maxDisc = MaxOverRect(disc, rect);
        if (!(maxDisc > 0)) return {};
        double ac = std::fabs(r.c);
        double e = std::max(options_.tolerance, 1e-9) * ac;  // tolerance in sqrt(Δ) units
        bool capped = false;
        std::vector<double> us =
            TangentPoints(std::sqrt(maxDisc) * 1.01, e, options_.maxStrips, capped);
        stats_.stripsCapped += capped;
        stats_.strips += us.size();
        double sign = nearSheet ? -1 : 1;
        std::vector<Coeffs> out;
        for (double u : us) {
            // z = −b/c + sign (u/2 + Δ/(2u)) / |c|
            Coeffs z;
            for (int i = 0; i < 6; ++i) {
                auto k = static_cast<std::size_t>(i);
                z[k] = -r.b[k] / r.c + sign * disc[k] / (2 * u * ac);
            }
            z[5] += sign * 0.5 * u / ac;
            out.push_back(z);
        }
        return out;
    }

    // The paper's shading of a patch (seed 004 §III step 4), as three kNLoad broadcasts: the
    // components of the world-space approximate normal a(x, y). Returns false (exact normal at
    // scan-out) when the approximation does not apply.
    //
    // Derivation (re-derived; the OCR'd text reads "shade = (L + sqrt Q)/sqrt W"). The world
    // normal is the pull-back n = (Mᵀ g)_xyz of the device gradient g = Q p, p = (x, y, z, 1), M =
    // deviceFromWorld (FlatScene::WorldNormal), so each component is linear in (x, y, z):
    // n_j = K_j0 x + K_j1 y + K_j2 z + K_j3. On a sheet z = L ± sqrt(Δ)/|c| this is
    // "linear + k·sqrt(Δ)", and n·l / |n| is the paper's (L + sqrt Q)/sqrt W with W = |n|². The
    // paper replaces sqrt(Δ) by ONE parabolic cylinder s + tΔ over the patch and sqrt W by a
    // constant w0. Because n_j is linear in z, that is n_j evaluated at z_s = L ± (s + tΔ)/|c|, a
    // quadratic in (x, y) per component: a = φ n(x, y, z_s)/w0, φ = ±1 turning it to the viewer.
    //   s, t: the minimax line of sqrt over [Δlo, Δhi] (Δ's range over the rectangle, clamped at
    //   0): with α = sqrt Δlo, β = sqrt Δhi, t = 1/(α+β) (the secant slope) and s raised by half
    //   the secant's largest gap, s = αβ/(α+β) + (β−α)²/(8(α+β)); error ±(β−α)²/(8(α+β)), half
    //   that of the best single tangent (the z-buffer step's strips must be tangents to form an
    //   envelope; a lone shading cylinder need not be).
    //   w0: the midrange of |n| sampled on the exact sheet over the rectangle (minimises the
    //   largest relative error of a constant; exact for spheres and circular cylinders under a
    //   parallel view, whose world gradient has constant length on the surface).
    bool EmitShading(const FlatLiteral& lit, bool exitFace, const PixelRect& rect) {
        const FlatHalfSpace& hs = scene_.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
        const Mat4& m = scene_.projection.deviceFromWorld.Matrix();
        auto pull = [&](const double g[4], std::size_t j) {
            return m.m[0][j] * g[0] + m.m[1][j] * g[1] + m.m[2][j] * g[2] + m.m[3][j] * g[3];
        };
        if (hs.isPlane) {
            const Plane& pl = hs.plane;
            if (!pl.AllFinite()) return false;
            double sgn = pl.c > 0 ? -1.0 : 1.0;  // facing the viewer: g.z <= 0
            double g[4] = {sgn * pl.a, sgn * pl.b, sgn * pl.c, sgn * pl.d};
            Vec3 n{pull(g, 0), pull(g, 1), pull(g, 2)};
            double w = Length(n);
            if (!(w > 0) || !std::isfinite(w)) return false;
            for (std::size_t j = 0; j < 3; ++j)
                EmitNLoad(static_cast<std::uint8_t>(j), {0, 0, 0, 0, 0, n[j] / w});
            return true;
        }
        RayForm r = RayFormOf(hs.quadric);
        if (r.c == 0 || !hs.quadric.AllFinite()) {
            ++stats_.shadingFallbacks;
            return false;
        }
        const bool nearSheet = (!exitFace) == ((r.c > 0) != lit.complemented);
        const double sigma = nearSheet ? -1 : 1, ac = std::fabs(r.c);
        // g.z = c z + b = sigma·sign(c)·sqrt(Δ) on the sheet; WorldNormal flips g when g.z > 0.
        const double phi = sigma * r.c > 0 ? -1 : 1;
        Coeffs disc = Discriminant(r);
        double dHi = MaxOverRect(disc, rect);
        if (!(dHi > 0) || !std::isfinite(dHi)) return false;
        Coeffs neg;
        for (std::size_t i = 0; i < 6; ++i) neg[i] = -disc[i];
        double dLo = std::max(0.0, -MaxOverRect(neg, rect));
        const double alpha = std::sqrt(dLo), beta = std::sqrt(dHi);
        const double t = 1 / (alpha + beta);
        const double s = alpha * beta * t + (beta - alpha) * (beta - alpha) * t / 8;
        // K_j: n_j = Σ_i M_ij (Q p)_i.
        const Mat4 q = hs.quadric.Matrix();
        double k[3][4];
        for (std::size_t j = 0; j < 3; ++j)
            for (std::size_t col = 0; col < 4; ++col) {
                double g[4] = {q.m[0][col], q.m[1][col], q.m[2][col], q.m[3][col]};
                k[j][col] = pull(g, j);
            }
        // Denominator: midrange of |n| on the exact sheet, sampled on a grid over the rectangle.
        double wMin = HUGE_VAL, wMax = 0;
        for (int pass = 0; pass < 2 && !(wMax > 0); ++pass) {
            const int nx = std::min(9, rect.x1 - rect.x0), ny = std::min(9, rect.y1 - rect.y0);
            for (int iy = 0; iy < ny; ++iy)
                for (int ix = 0; ix < nx; ++ix) {
                    double x = rect.x0 + 0.5 +
                               (nx > 1 ? (rect.x1 - rect.x0 - 1) * double(ix) / (nx - 1) : 0);
                    double y = rect.y0 + 0.5 +
                               (ny > 1 ? (rect.y1 - rect.y0 - 1) * double(iy) / (ny - 1) : 0);
                    double d = Eval(disc, x, y);
                    if (d < 0 && pass == 0) continue;  // second pass: the silhouette's z
                    double z = -r.b[3] / r.c * x - r.b[4] / r.c * y - r.b[5] / r.c +
                               sigma * std::sqrt(std::max(d, 0.0)) / ac;
                    Vec3 n{k[0][0] * x + k[0][1] * y + k[0][2] * z + k[0][3],
                           k[1][0] * x + k[1][1] * y + k[1][2] * z + k[1][3],
                           k[2][0] * x + k[2][1] * y + k[2][2] * z + k[2][3]};
                    double w = Length(n);
                    if (!std::isfinite(w)) continue;
                    wMin = std::min(wMin, w);
                    wMax = std::max(wMax, w);
                }
        }
        const double w0 = 0.5 * (wMin + wMax);
        if (!(w0 > 0) || !std::isfinite(w0)) return false;
        // z_s = L + sigma (s + tΔ)/|c|.
        Coeffs zs;
        for (std::size_t i = 0; i < 6; ++i) zs[i] = -r.b[i] / r.c + sigma * t * disc[i] / ac;
        zs[5] += sigma * s / ac;
        const double sqrtErr = (beta - alpha) * (beta - alpha) * t / 8;
        double kz = 0;
        for (std::size_t j = 0; j < 3; ++j) {
            Coeffs a;
            for (std::size_t i = 0; i < 6; ++i) a[i] = k[j][2] * zs[i];
            a[3] += k[j][0];
            a[4] += k[j][1];
            a[5] += k[j][3];
            for (double& v : a) v *= phi / w0;
            EmitNLoad(static_cast<std::uint8_t>(j), a);
            kz += k[j][2] * k[j][2];
        }
        stats_.shadingDenominatorSpread =
            std::max(stats_.shadingDenominatorSpread, (wMax - wMin) / (wMax + wMin));
        stats_.shadingSqrtBound =
            std::max(stats_.shadingSqrtBound, std::sqrt(kz) * sqrtErr / (ac * w0));
        return true;
    }

    void EmitNLoad(std::uint8_t axis, const Coeffs& q) {
        Instruction& in = Emit(Opcode::kNLoad, kF1, axis);
        for (int i = 0; i < 6; ++i) in.q[i] = q[static_cast<std::size_t>(i)];
    }

    // Approx mode: planes are tested by the QEE as in EmitInside (the same formula as a plane
    // sheet's ZLOAD, so a plane shared by two products compares equal to itself), quadrics by
    // the root unit.
    void EmitRootUnitInside(const FlatLiteral& lit, std::uint8_t f, std::uint8_t mode) {
        if (options_.mode != DepthMode::kExact) {
            const FlatHalfSpace& hs = scene_.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
            if (hs.isPlane && hs.plane.AllFinite()) {
                EmitInside(lit, f, mode);
                return;
            }
            ++stats_.extendedFallbacks;
        }
        Emit(Opcode::kInside, f, mode, LiteralIndex(lit));
    }

    // F[f] ∧= (ZTEMP inside literal `lit` in the sense of `mode`, an InsideMode), on pixels where
    // F[f] is set. f is F1 or F2 (F3 is scratch here). The approximate machine tests planes
    // one-sidedly too (ZLT/ZGT; its plane depths are those of the plane's own ZLOAD), and its
    // quadric strip tests at the strict end.
    void EmitInside(const FlatLiteral& lit, std::uint8_t f, std::uint8_t mode) {
        std::int32_t li = LiteralIndex(lit);
        const FlatHalfSpace& hs = scene_.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
        if (options_.mode == DepthMode::kExact) {
            Emit(Opcode::kInside, f, mode, li);
            return;
        }
        if (hs.isPlane) {
            const Plane& pl = hs.plane;
            if (!pl.AllFinite()) {
                Emit(Opcode::kInside, f, mode, li);
                return;
            }
            if (pl.c == 0) {  // inside iff A x + B y + D <= 0 along the whole ray
                EmitQ(lit.complemented ? Opcode::kQeeKeepPositive : Opcode::kQeeKeepNonPositive, f,
                      {0, 0, 0, pl.a, pl.b, pl.d});
                return;
            }
            Coeffs r{0, 0, 0, -pl.a / pl.c, -pl.b / pl.c, -pl.d / pl.c};
            bool below = (pl.c > 0) != lit.complemented;  // inside is z <= r
            // The endpoint is excluded when the tested side lies beyond it (InsideMode).
            bool strict = below ? mode == kInsideAfter || mode == kInsideOpen
                                : mode == kInsideBefore || mode == kInsideOpen;
            Opcode op = below ? (strict ? Opcode::kZKeepLT : Opcode::kZKeepLE)
                              : (strict ? Opcode::kZKeepGT : Opcode::kZKeepGE);
            EmitQ(op, f, r);
            return;
        }
        RayForm r = RayFormOf(hs.quadric);
        if (r.c == 0 || !hs.quadric.AllFinite()) {
            ++stats_.extendedFallbacks;
            Emit(Opcode::kInside, f, mode, li);
            return;
        }
        // F3 = between the sheets (Δ > 0, z >= near envelope, z <= far envelope), then inside is
        // F3 when c > 0, ¬F3 when c < 0, flipped by a complement. One-sided: the set [n, f] holds
        // after z iff n <= z < f and before z iff n < z <= f, and the closure of its complement
        // holds after (before) z iff [n, f] does not, so the same strict end serves both; against
        // envelopes, z < min fᵢ is z < fᵢ for every strip (ZLT), z > max nᵢ is ZGT for every one.
        // The strips are those of the sheet's own ZLOAD/ZMAX when the patch is on the same
        // quadric (same coefficients, same rectangle), so `A − A` is exact here too.
        Coeffs disc = Discriminant(r);
        std::vector<Coeffs> nearS = Strips(r, disc, true, currentRect_);
        std::vector<Coeffs> farS = Strips(r, disc, false, currentRect_);
        const bool nearStrict = mode == kInsideBefore, farStrict = mode == kInsideAfter;
        Emit(Opcode::kFlagCopy, kF3, f);
        EmitQ(Opcode::kQeeKeepPositive, kF3, disc);
        for (const Coeffs& z : nearS)
            EmitQ(nearStrict ? Opcode::kZKeepGT : Opcode::kZKeepGE, kF3, z);
        for (const Coeffs& z : farS) EmitQ(farStrict ? Opcode::kZKeepLT : Opcode::kZKeepLE, kF3, z);
        bool insideIsBetween = (r.c > 0) != lit.complemented;
        Emit(insideIsBetween ? Opcode::kFlagAnd : Opcode::kFlagAndNot, f, kF3);
    }

    const FlatScene& scene_;
    const CompileOptions& options_;
    Program& program_;
    CompileStats& stats_;
    std::vector<Box3> boxes_;
    std::map<std::pair<int, bool>, std::int32_t> literalIndex_;
    PixelRect currentRect_;
    const std::vector<csg::Product>* products_ = nullptr;
    // The current solid's exit blocks, one group per product (CompileProduct).
    std::vector<std::vector<Block>> exitGroups_;
    // ZTEST's tie threshold for the blocks being emitted (−1: strict; CompileProduct).
    std::int32_t tieFrom_ = -1;
};

}  // namespace

void Compile(const FlatScene& scene, const CompileOptions& options, Program& program,
             CompileStats& stats) {
    Compiler(scene, options, program, stats).Run();
}

}  // namespace quadrix::pixelpowers
