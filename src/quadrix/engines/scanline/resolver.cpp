#include "quadrix/engines/scanline/resolver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "quadrix/math/symmetric_eigen.h"

namespace quadrix::scanline {

const char* ToString(ILineType t) {
    switch (t) {
        case ILineType::kNoExist:
            return "NOEXIST";
        case ILineType::kPoint:
            return "POINT";
        case ILineType::kLinear:
            return "LINEAR";
        case ILineType::kConic:
            return "CONIC";
        case ILineType::kEdge:
            return "EDGE";
        case ILineType::kQuartic:
            return "QUARTIC";
    }
    return "?";
}

const char* ToString(IVertexType t) {
    switch (t) {
        case IVertexType::kHextrm:
            return "HEXTRM";
        case IVertexType::kVextrm:
            return "VEXTRM";
        case IVertexType::kLimb:
            return "LIMB";
        case IVertexType::kIsect:
            return "ISECT";
    }
    return "?";
}

double ShowEdge::XAt(double y) const {
    if (!conic) return -(line.b * y + line.c) / line.a;
    const double a = shape.a, b = shape.c * y + shape.d, c = (shape.b * y + shape.e) * y + shape.f;
    double disc = b * b - 4 * a * c;
    if (disc < 0) {
        // Zero test (3) on the row's quadratic: within rounding, the leg touches its VEXTRM.
        if (disc < -(8 * kUnit) * (b * b + 4 * std::fabs(a * c)))
            return std::numeric_limits<double>::quiet_NaN();
        disc = 0;
    }
    const double s = std::sqrt(disc);
    const double q = -0.5 * (b + (b >= 0 ? s : -s));
    // q/a is the root (−b ∓ s)/(2a) with the sign of b; c/q the other (Vieta), no cancellation.
    const double minus = b >= 0 ? q / a : c / q;  // (−b − s)/(2a)
    const double plus = b >= 0 ? c / q : q / a;   // (−b + s)/(2a)
    return leg < 0 ? minus : plus;
}

namespace {

constexpr double kPointError = 1e-7;  // device units: error budget of computed i-vertices

Plane Negated(const Plane& p) { return {-p.a, -p.b, -p.c, -p.d}; }
Quadric Negated(const Quadric& q) {
    Quadric r = q;
    for (double& v : r.k) v = -v;
    return r;
}

// z of the plane at (x, y); the plane must not be edge-on.
double PlaneZ(const Plane& p, double x, double y) { return -(p.a * x + p.b * y + p.d) / p.c; }

// The sheets' z of a quadric at (x, y): count 0, 1 (C = 0) or 2 (front < back).
int QuadricZ(const Quadric& q, double x, double y, double z[2]) {
    const double c = q.C(), h = q.F() * x + q.E() * y + q.J();
    const double a =
        q.A() * x * x + q.B() * y * y + 2 * q.D() * x * y + 2 * q.G() * x + 2 * q.H() * y + q.K();
    if (c == 0) {
        if (h == 0) return 0;
        z[0] = -a / (2 * h);
        return 1;
    }
    double disc = h * h - a * c;
    if (disc < 0) {
        if (disc < -(8 * kUnit) * (h * h + std::fabs(a * c))) return 0;
        disc = 0;
    }
    const double s = std::sqrt(disc);
    const double qq = -(h + (h >= 0 ? s : -s));
    double z0 = qq / c, z1 = qq != 0 ? a / qq : z0;
    if (z0 > z1) std::swap(z0, z1);
    z[0] = z0;
    z[1] = z1;
    return 2;
}

// True when f(x) = xᵀAx + 2bᵀx + k has one strict sign for every finite x (with a margin).
bool AffineDefinite(const std::array<double, 10>& m) {
    double a[3][3] = {{m[0], m[3], m[5]}, {m[3], m[1], m[4]}, {m[5], m[4], m[2]}};
    const double b[3] = {m[6], m[7], m[8]};
    double scale = 0;
    for (double v : m) scale = std::max(scale, std::fabs(v));
    if (scale == 0 || !std::isfinite(scale)) return false;
    double e[3], v[3][3];
    double offDiagonal = 0;
    SymmetricEigen(a, e, v, offDiagonal);
    const double tol = 1e-9 * scale;
    for (int sign : {-1, 1}) {  // −1: f < 0 everywhere, +1: f > 0 everywhere
        bool ok = true;
        double extreme = m[9];  // sup f (sign −1) or inf f (sign +1)
        for (int i = 0; i < 3 && ok; ++i) {
            double bi = v[0][i] * b[0] + v[1][i] * b[1] + v[2][i] * b[2];
            double ei = e[i] * sign;  // must be >= 0 (PSD after the sign flip)
            if (ei < -tol) {
                ok = false;
            } else if (ei <= tol) {
                if (std::fabs(bi) > tol) ok = false;  // linear growth along a null direction
            } else {
                extreme -= bi * bi / e[i];  // min/max of e y² + 2 b y is −b²/e
            }
        }
        if (ok && extreme * sign > 1e-7 * scale) return true;
    }
    return false;
}

}  // namespace

bool QuadricSurfacesDisjoint(const Quadric& q1, const Quadric& q2) {
    // The natural λ is the ratio of the quadratic parts (equal for coaxial cylinders and
    // concentric spheres: then q2 − λ q1 is a constant).
    auto quadScale = [](const Quadric& q) {
        double m = 0;
        for (std::size_t i = 0; i < 6; ++i) m = std::max(m, std::fabs(q.k[i]));
        return m;
    };
    double s1 = quadScale(q1), s2 = quadScale(q2);
    if (!(s1 > 0) || !(s2 > 0)) {
        s1 = q1.MaxAbs();
        s2 = q2.MaxAbs();
    }
    if (!(s1 > 0) || !(s2 > 0)) return false;
    const double s = s2 / s1;
    std::array<double, 10> m{};
    auto tryLambda = [&](double lambda) {
        for (std::size_t i = 0; i < 10; ++i) m[i] = q2.k[i] - lambda * q1.k[i];
        return AffineDefinite(m);
    };
    // λ on a logarithmic grid around the ratio of the scales, nearest first (coaxial or
    // concentric surfaces succeed at the first try).
    if (tryLambda(s) || tryLambda(0)) return true;
    for (int i = 1; i <= 64; ++i) {
        for (double l : {s * std::exp(i / 8.0), s * std::exp(-i / 8.0)})
            if (tryLambda(l) || tryLambda(-l)) return true;
    }
    return tryLambda(-s);
}

namespace {

class BodyResolver {
  public:
    BodyResolver(const FlatScene& scene, int body, double yLo, double yHi, bool allBoundaries,
                 ResolvedBody& out, std::vector<ShowFace>& faces, std::vector<ShowEdge>& edges,
                 ResolverCounters& c)
        : scene_(scene),
          body_(body),
          yLo_(yLo),
          yHi_(yHi),
          all_(allBoundaries),
          out_(out),
          faces_(faces),
          edges_(edges),
          c_(c) {}

    void Run() {
        out_.body = body_;
        if (!BuildHsbs()) {
            out_.perPixel = true;
            ++c_.perPixelBodies;
            return;
        }
        BuildFaces();
        BuildTable();
        if (out_.perPixel) {
            ++c_.perPixelBodies;
            return;
        }
        BuildVertices();
        BuildEdges();
    }

  private:
    int N() const { return static_cast<int>(out_.hsbs.size()); }
    ILine& At(int i, int j) {
        return out_
            .table[static_cast<std::size_t>(i) * out_.hsbs.size() + static_cast<std::size_t>(j)];
    }
    const Hsb& H(int i) const { return out_.hsbs[static_cast<std::size_t>(i)]; }
    bool HasFaces(int i) const { return H(i).face[0] >= 0 || H(i).face[1] >= 0; }
    // Whether HSB i's surface can bound something the renderer needs: a show-face, or (CSG
    // operands) any interval endpoint, i.e. any surface not containing the view direction.
    bool Bounds(int i) const {
        if (HasFaces(i)) return true;
        if (!all_) return false;
        return H(i).isPlane ? !H(i).edgeOn : !H(i).viewCylinder;
    }

    bool BuildHsbs() {
        const FlatBody& b = scene_.bodies[static_cast<std::size_t>(body_)];
        const double length = std::max(scene_.width, scene_.height);
        for (const FlatLiteral& lit : b.literals) {
            if (lit.halfSpace < 0 ||
                static_cast<std::size_t>(lit.halfSpace) >= scene_.halfSpaces.size()) {
                out_.reason = "literal names a missing half-space";
                return false;
            }
            const FlatHalfSpace& fh = scene_.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
            Hsb h;
            h.halfSpace = lit.halfSpace;
            h.isPlane = fh.isPlane;
            h.opaque = !fh.transparent && !fh.isClip;
            if (fh.isPlane) {
                if (!fh.plane.AllFinite() || fh.plane.IsZeroNormal()) {
                    out_.reason = "degenerate or non-finite plane";
                    return false;
                }
                h.plane = lit.complemented ? Negated(fh.plane) : fh.plane;
                h.edgeOn = PlaneIsEdgeOn(h.plane);
                ++c_.planarHsbs;
            } else {
                if (!fh.quadric.AllFinite() || fh.quadric.IsDegenerateToLinear()) {
                    out_.reason = "degenerate or non-finite quadric";
                    return false;
                }
                h.quadric = lit.complemented ? Negated(fh.quadric) : fh.quadric;
                h.viewCylinder = QuadricIsViewCylinder(h.quadric, length);
                if (h.viewCylinder) {  // snap the z terms the zero test found to be rounding
                    h.quadric.k[2] = h.quadric.k[4] = h.quadric.k[5] = h.quadric.k[8] = 0;
                }
                ++c_.quadricHsbs;
            }
            out_.hsbs.push_back(h);
        }
        return !out_.hsbs.empty();
    }

    void AddFace(Hsb& h, int slot, Sheet sheet, int index) {
        h.face[slot] = static_cast<int>(faces_.size());
        faces_.push_back({body_, index, h.halfSpace, sheet});
        ++c_.faces;
    }

    void BuildFaces() {
        for (int i = 0; i < N(); ++i) {
            Hsb& h = out_.hsbs[static_cast<std::size_t>(i)];
            if (!h.opaque) continue;
            if (h.isPlane) {
                if (!h.edgeOn) AddFace(h, 0, Sheet::kPlane, i);
            } else if (!h.viewCylinder) {
                AddFace(h, 0, Sheet::kFront, i);
                AddFace(h, 1, Sheet::kBack, i);
            }
        }
    }

    void BuildTable() {
        out_.table.assign(out_.hsbs.size() * out_.hsbs.size(), ILine{});
        for (int i = 0; i < N(); ++i) {
            for (int j = 0; j <= i; ++j) {
                ILine& l = At(i, j);
                l.i = i;
                l.j = j;
                if (i == j) {
                    BuildLimb(l);
                } else if (Bounds(i) || Bounds(j)) {
                    BuildPair(l);
                }
                ++c_.ilines[static_cast<int>(l.type)];
            }
        }
    }

    // A surface containing the view direction (edge-on plane, view cylinder) projects to a curve,
    // its OUTLINE, where an operand's ray set switches between everything and nothing. Only CSG
    // operands need it (elsewhere such a surface matters only where it cuts a face: its i-lines).
    bool Outline(int i) const { return all_ && (H(i).isPlane ? H(i).edgeOn : H(i).viewCylinder); }

    void BuildLimb(ILine& l) {
        const Hsb& h = H(l.i);
        if (Outline(l.i)) {
            l.limb = true;
            if (h.isPlane) {
                l.type = ILineType::kLinear;
                l.line = {h.plane.a, h.plane.b, h.plane.d};
            } else {
                const Quadric& q = h.quadric;
                l.type = ILineType::kConic;
                l.conicShape = true;
                l.conic = {q.A(), q.B(), 2 * q.D(), 2 * q.G(), 2 * q.H(), q.K()};
                l.insert = InsertLine(l.conic);
            }
            return;
        }
        if (h.isPlane || !Bounds(l.i)) return;
        l.limb = true;
        const Quadric& q = h.quadric;
        if (q.C() != 0) {
            l.type = ILineType::kConic;
            l.conicShape = true;
            l.conic = LimbConic(q);
            l.insert = InsertLine(l.conic);
        } else if (q.F() != 0 || q.E() != 0) {
            // C = 0: the single root −a/(2 b) runs to infinity where b = F x + E y + J = 0.
            l.type = ILineType::kLinear;
            l.line = {q.F(), q.E(), q.J()};
        }
    }

    void BuildPair(ILine& l) {
        const Hsb &hi = H(l.i), &hj = H(l.j);
        if (hi.isPlane && hj.isPlane) {
            if (hi.edgeOn && hj.edgeOn) {
                l.type = ILineType::kPoint;
                return;
            }
            Line2 line = LineOfPlanes(hi.plane, hj.plane);
            double n = std::fabs(hi.plane.a) + std::fabs(hi.plane.b) + std::fabs(hi.plane.c);
            double m = std::fabs(hj.plane.a) + std::fabs(hj.plane.b) + std::fabs(hj.plane.c);
            if (std::fabs(line.a) + std::fabs(line.b) <= 64 * kUnit * n * m) return;  // parallel
            l.type = ILineType::kLinear;
            l.line = line;
            return;
        }
        if (!hi.isPlane && !hj.isPlane) {
            if (QuadricSurfacesDisjoint(hi.quadric, hj.quadric)) return;
            l.type = ILineType::kQuartic;
            out_.perPixel = true;
            out_.reason = "two quadrics whose surfaces may meet (quartic i-line)";
            return;
        }
        const Hsb& p = hi.isPlane ? hi : hj;
        const Hsb& q = hi.isPlane ? hj : hi;
        if (p.edgeOn) {
            l.type = ILineType::kEdge;
            l.line = {p.plane.a, p.plane.b, p.plane.d};
        } else {
            l.type = ILineType::kConic;
            l.conicShape = true;
            l.conic = ConicOfPlaneQuadric(p.plane, q.quadric);
            l.insert = InsertLine(l.conic);
        }
    }

    // ---- i-vertices ----

    // A plane of i-line (i, j) that is not edge-on (nullptr when none).
    const Plane* CarrierPlane(const ILine& l) const {
        if (l.limb) return nullptr;
        if (H(l.i).isPlane && !H(l.i).edgeOn) return &H(l.i).plane;
        if (H(l.j).isPlane && !H(l.j).edgeOn) return &H(l.j).plane;
        return nullptr;
    }
    const Hsb* QuadricOf(const ILine& l) const {
        if (!H(l.i).isPlane) return &H(l.i);
        if (!H(l.j).isPlane) return &H(l.j);
        return nullptr;
    }

    // 3-D points of the i-line above (x, y): one for LINEAR/CONIC (on the carrier plane or the
    // limb plane), up to two for EDGE (the quadric's sheets), none when unknown (limb line).
    int CurvePoints(const ILine& l, double x, double y, Vec3 pts[2]) const {
        if (l.limb) {
            if (Outline(l.i)) return 0;  // every z: unknown, the piece is kept
            const Quadric& q = H(l.i).quadric;
            if (q.C() == 0) return 0;
            pts[0] = {x, y, PlaneZ(LimbPlane(q), x, y)};
            return 1;
        }
        if (l.type == ILineType::kEdge) {
            double z[2];
            int n = QuadricZ(QuadricOf(l)->quadric, x, y, z);
            for (int k = 0; k < n; ++k) pts[k] = {x, y, z[k]};
            return n;
        }
        const Plane* p = CarrierPlane(l);
        if (!p) return 0;
        pts[0] = {x, y, PlaneZ(*p, x, y)};
        return 1;
    }

    // Whether a point of i-line l satisfies every HSI other than l's own; quadrics are skipped
    // where `quadricsChecked` is false (their crossings with l were not computed).
    bool InsideOthers(const ILine& l, const Vec3& p, bool quadricsChecked) const {
        for (int k = 0; k < N(); ++k) {
            if (k == l.i || k == l.j) continue;
            if (!H(k).isPlane && !quadricsChecked) continue;
            if (!H(k).Satisfied(p, kPointError * (1 + std::fabs(p.z)))) return false;
        }
        return true;
    }

    // With `piece` (a candidate show-edge, tested at its midpoint) a point must also pass the
    // wedge test below; i-vertices are kept on the zero test alone (extra vertices only cut
    // edges into more pieces).
    bool AnyInsideOthers(const ILine& l, double x, double y, bool quadricsChecked,
                         bool piece = false) const {
        Vec3 pts[2];
        int n = CurvePoints(l, x, y, pts);
        if (n == 0) return true;  // unknown z (limb line at infinity): keep, conservatively
        for (int k = 0; k < n; ++k)
            if (InsideOthers(l, pts[k], quadricsChecked) &&
                (!piece || !WedgeCutByOther(l, pts[k], quadricsChecked)))
                return true;
        return false;
    }

    // Outward normal (gradient) of HSB k at p: HSBs are "value <= 0 inside".
    Vec3 OutwardNormal(int k, const Vec3& p) const {
        const Hsb& h = H(k);
        if (h.isPlane) return h.plane.Normal();
        const Quadric& q = h.quadric;
        return {q.A() * p.x + q.D() * p.y + q.F() * p.z + q.G(),
                q.D() * p.x + q.B() * p.y + q.E() * p.z + q.H(),
                q.F() * p.x + q.E() * p.y + q.C() * p.z + q.J()};
    }

    // The wedge test for a candidate show-edge on i-line (i, j) at its point p. The zero test (4)
    // accepts p when it lies ON the surface of a third HSB k (|value| <= E), which happens along
    // whole pieces when three or more HSBs share a line: at a mitred joint of several tubes every
    // bisecting plane of a tube contains the joint's normal line. Near such a line the body is
    // the intersection of the half-spaces through it, a wedge bounded by only TWO of them; the
    // pair (i, j) bounds the body there only if it is that pair. In the plane normal to the
    // i-line at p the wedge of (i, j) is the cone of the rays r_i (in surface i, inside j) and
    // r_j (in surface j, inside i); it is the body's wedge iff every HSB k through p keeps both
    // rays inside (n_k · r <= 0, linearised at p). True when some k cuts the wedge: the piece is
    // then not a boundary between faces i and j (one of them is not on the body's surface
    // there, or the body has no interior), and making it a show-edge would toggle faces that do
    // not change sides — the spurious edges that forced face-test corrections in the renderer.
    bool WedgeCutByOther(const ILine& l, const Vec3& p, bool quadricsChecked) const {
        if (l.limb || l.i == l.j) return false;  // one surface: no wedge
        const Vec3 ni = Normalize(OutwardNormal(l.i, p)), nj = Normalize(OutwardNormal(l.j, p));
        const Vec3 u = Cross(ni, nj);
        // Tangent surfaces (a plane touching a quadric): no wedge to test; keep the piece.
        if (!(Length(u) > 1e-6)) return false;
        Vec3 ri = Normalize(Cross(u, ni)), rj = Normalize(Cross(u, nj));
        if (Dot(nj, ri) > 0) ri = ri * -1.0;
        if (Dot(ni, rj) > 0) rj = rj * -1.0;
        constexpr double kCos = 1e-7;  // |cos| of the angle between a ray and a surface
        const double pointError = kPointError * (1 + std::fabs(p.z));
        for (int k = 0; k < N(); ++k) {
            if (k == l.i || k == l.j) continue;
            const Hsb& hk = H(k);
            if (!hk.isPlane && !quadricsChecked) continue;
            const double v = hk.Evaluate(p);
            const double e = hk.isPlane ? PlaneErrorEstimate(hk.plane, p, pointError)
                                        : QuadricErrorEstimate(hk.quadric, p, pointError);
            if (std::fabs(v) > e) continue;  // strictly inside (outside was rejected before)
            const Vec3 nk = OutwardNormal(k, p);
            const double len = Length(nk);
            if (!(len > 0)) continue;
            if (Dot(nk, ri) > kCos * len || Dot(nk, rj) > kCos * len) return true;
        }
        return false;
    }

    bool Exists(const ILine& l) const {
        return l.type == ILineType::kLinear || l.type == ILineType::kConic ||
               l.type == ILineType::kEdge;
    }

    // Crossings with HSB k of i-line l in closed form; false when they need a quartic.
    bool Crossings(const ILine& l, int k, std::vector<Vec3>& pts) const {
        const Hsb& hk = H(k);
        if (l.limb && Outline(l.i)) return true;  // outlines are kept whole (no filtering)
        if (!l.conicShape) {
            if (hk.isPlane) {
                if (l.limb) {     // C = 0 limb line ∩ plane trace
                    return true;  // no useful z; the line is kept whole
                }
                if (l.type == ILineType::kEdge) {
                    if (hk.edgeOn) {  // two traces: a point
                        Line2 t{hk.plane.a, hk.plane.b, hk.plane.d};
                        double det = l.line.a * t.b - l.line.b * t.a;
                        if (std::fabs(det) <=
                            64 * kUnit * (std::fabs(l.line.a * t.b) + std::fabs(l.line.b * t.a)))
                            return true;
                        pts.push_back({(l.line.b * t.c - l.line.c * t.b) / det,
                                       (l.line.c * t.a - l.line.a * t.c) / det, 0});
                        return true;
                    }
                    // quadric ∩ plane k, projected, meets the trace (§4.5.10).
                    auto v = LineConicIntersections(
                        l.line, ConicOfPlaneQuadric(hk.plane, QuadricOf(l)->quadric));
                    pts.insert(pts.end(), v.begin(), v.end());
                    return true;
                }
                // LINEAR: three planes (§4.5.8).
                auto v = IntersectThreePlanes(H(l.i).plane, H(l.j).plane, hk.plane);
                if (v) pts.push_back(*v);
                return true;
            }
            if (l.type == ILineType::kLinear && !l.limb) {  // plane–plane–quadric (§4.5.10)
                const Plane* p = CarrierPlane(l);
                if (!p) return true;
                auto v = LineConicIntersections(l.line, ConicOfPlaneQuadric(*p, hk.quadric));
                pts.insert(pts.end(), v.begin(), v.end());
                return true;
            }
            return false;  // EDGE or limb line with another quadric
        }
        if (!hk.isPlane) return false;  // conic ∩ second quadric: quartic
        // CONIC (plane p ∩ quadric, or a limb conic on its limb plane) ∩ plane k: the line where
        // the conic's plane meets plane k (4.7), intersected with the conic (§4.5.9).
        Plane carrier = l.limb ? LimbPlane(H(l.i).quadric) : *CarrierPlane(l);
        auto v = LineConicIntersections(LineOfPlanes(carrier, hk.plane), l.conic);
        pts.insert(pts.end(), v.begin(), v.end());
        return true;
    }

    void Insert(ILine& l, const IVertex& v) {
        ++c_.verticesKept;
        ++c_.verticesByType[static_cast<int>(v.type)];
        if (!l.conicShape) {
            l.lists[0].push_back(v);
            return;
        }
        if (v.type == IVertexType::kVextrm) {  // rule (1): both lists
            l.lists[0].push_back(v);
            l.lists[1].push_back(v);
            return;
        }
        // Rule (3), with zero test (4) on the insert line: near it, both lists.
        double s = l.insert.Evaluate(v.x, v.y);
        double e = 1e-9 * (1 + l.insert.TermScale(v.x, v.y));
        if (s <= e) l.lists[0].push_back(v);
        if (s >= -e) l.lists[1].push_back(v);
    }

    void TryVertex(ILine& l, IVertexType type, const Vec3& xy, bool quadricsChecked) {
        ++c_.verticesCalculated;
        if (!std::isfinite(xy.x) || !std::isfinite(xy.y)) return;
        if (!AnyInsideOthers(l, xy.x, xy.y, quadricsChecked)) return;
        Vec3 pts[2];
        double z = CurvePoints(l, xy.x, xy.y, pts) > 0 ? pts[0].z : 0;
        Insert(l, {type, xy.x, xy.y, z});
    }

    void BuildVertices() {
        for (int i = 0; i < N(); ++i) {
            for (int j = 0; j <= i; ++j) {
                ILine& l = At(i, j);
                if (!Exists(l)) continue;
                bool quadricsChecked = true;
                for (int k = 0; k < N(); ++k) {
                    if (k == i || k == j) continue;
                    std::vector<Vec3> pts;
                    if (!Crossings(l, k, pts)) {
                        quadricsChecked = false;
                        continue;
                    }
                    IVertexType type = l.limb ? IVertexType::kLimb : IVertexType::kIsect;
                    for (const Vec3& p : pts) TryVertex(l, type, p, true);
                }
                l.filteredByAllHsbs = quadricsChecked;
                // LIMB i-vertices of plane–quadric i-lines (§4.5.11).
                if (!l.limb && (l.type == ILineType::kConic || l.type == ILineType::kEdge)) {
                    const Quadric& q = QuadricOf(l)->quadric;
                    if (q.C() != 0) {
                        std::vector<Vec3> pts;
                        if (l.type == ILineType::kConic)
                            pts = LineConicIntersections(
                                LineOfPlanes(*CarrierPlane(l), LimbPlane(q)), l.conic);
                        else
                            pts = LineConicIntersections(l.line, LimbConic(q));
                        for (const Vec3& p : pts)
                            TryVertex(l, IVertexType::kLimb, p, quadricsChecked);
                    }
                }
                if (l.conicShape) {  // extrema (§4.5.12)
                    constexpr double kRel = 1e-12;
                    Roots1 rv = SolveQuadratic1(VextrmQuadratic(l.conic), kRel);
                    if (rv.kind != Roots1::kNone) {
                        for (double y : {rv.r0, rv.r1}) {
                            double x = -(l.conic.c * y + l.conic.d) / (2 * l.conic.a);
                            TryVertex(l, IVertexType::kVextrm, {x, y, 0}, quadricsChecked);
                            if (rv.r0 == rv.r1) break;
                        }
                    }
                    Roots1 rh = SolveQuadratic1(HextrmQuadratic(l.conic), kRel);
                    if (rh.kind != Roots1::kNone && l.conic.b != 0) {
                        for (double x : {rh.r0, rh.r1}) {
                            double y = -(l.conic.c * x + l.conic.e) / (2 * l.conic.b);
                            TryVertex(l, IVertexType::kHextrm, {x, y, 0}, quadricsChecked);
                            if (rh.r0 == rh.r1) break;
                        }
                    }
                }
                for (auto& list : l.lists) {
                    std::sort(list.begin(), list.end(),
                              [](const IVertex& a, const IVertex& b) { return a.y < b.y; });
                    // Zero test (5): coincident i-vertices merge; the older keeps its type.
                    std::vector<IVertex> merged;
                    for (const IVertex& v : list)
                        if (merged.empty() ||
                            !VerticesCoincide(merged.back().x, merged.back().y, v.x, v.y))
                            merged.push_back(v);
                    list.swap(merged);
                }
            }
        }
    }

    // ---- show-edges ----

    int QuadricSheetFace(const ILine& l, const Hsb& q, double x, double y, double z) const {
        const Quadric& Q = q.quadric;
        double nz = Q.F() * x + Q.E() * y + Q.C() * z + Q.J();  // (4.11)
        bool front;
        if (nz != 0) {
            // §4.4 table: limb (C > 0): n_z < 0 → front; no limb: n_z < 0 → back.
            front = LimbExists(Q) ? nz < 0 : nz > 0;
        } else {
            const Plane* p = CarrierPlane(l);
            front = !(p && p->c > 0);  // the plane cut away the front sheet when C_p > 0
        }
        return q.face[front ? 0 : 1];
    }

    void BuildEdges() {
        for (int i = 0; i < N(); ++i) {
            for (int j = 0; j <= i; ++j) {
                const ILine& l = At(i, j);
                if (!Exists(l)) continue;
                const int lists = l.conicShape ? 2 : 1;
                for (int s = 0; s < lists; ++s) BuildLegEdges(l, i * N() + j, s);
            }
        }
    }

    void BuildLegEdges(const ILine& l, int index, int list) {
        ShowEdge proto;
        proto.body = body_;
        proto.iline = index;
        proto.conic = l.conicShape;
        if (l.conicShape) {
            proto.shape = l.conic;
            proto.leg = list == 0 ? -1 : 1;
        } else {
            proto.line = l.line;
            // A horizontal line is crossed by no row centre (except exactly: then its neighbours
            // bound the same pixels), and x = −(b y + c)/a is undefined: its pieces are
            // horizontal show-edges, which only link their end vertices for the renderer.
            if (std::fabs(l.line.a) <= 64 * kUnit * std::fabs(l.line.b)) {
                BuildHorizontalEdges(l, proto);
                return;
            }
        }
        std::vector<double> ys{yLo_, yHi_};
        for (const IVertex& v : l.lists[list])
            if (v.y > yLo_ && v.y < yHi_) ys.push_back(v.y);
        if (l.conicShape) {  // the leg's domain ends at the VEXTRMs, kept or not
            Roots1 rv = SolveQuadratic1(VextrmQuadratic(l.conic), 1e-12);
            for (double y : {rv.r0, rv.r1})
                if (rv.kind != Roots1::kNone && y > yLo_ && y < yHi_) ys.push_back(y);
        }
        std::sort(ys.begin(), ys.end());
        for (std::size_t k = 0; k + 1 < ys.size(); ++k) {
            double y0 = ys[k], y1 = ys[k + 1];
            if (!(y1 > y0)) continue;
            ++c_.piecesTested;
            double ym = 0.5 * (y0 + y1);
            ShowEdge e = proto;
            double xm = e.XAt(ym);
            if (!std::isfinite(xm)) continue;
            if (!AnyInsideOthers(l, xm, ym, l.filteredByAllHsbs, true)) continue;
            e.yBottom = y0;
            e.yTop = y1;
            AssignFaces(l, e, xm, ym);
            (e.conic ? c_.edgesConic : c_.edgesLinear) += 1;
            edges_.push_back(e);
        }
    }

    // The pieces of a horizontal LINEAR i-line between consecutive i-vertices (in x) whose
    // midpoint passes the same tests as any other piece. Unbounded pieces (no vertex at one end)
    // link nothing and are not made.
    void BuildHorizontalEdges(const ILine& l, const ShowEdge& proto) {
        if (l.line.b == 0) return;
        std::vector<IVertex> vs = l.lists[0];
        std::sort(vs.begin(), vs.end(),
                  [](const IVertex& p, const IVertex& q) { return p.x < q.x; });
        for (std::size_t k = 0; k + 1 < vs.size(); ++k) {
            const IVertex &v0 = vs[k], &v1 = vs[k + 1];
            if (!(v1.x > v0.x) || v0.y < yLo_ || v0.y > yHi_) continue;
            ++c_.piecesTested;
            const double xm = 0.5 * (v0.x + v1.x);
            const double ym = -(l.line.a * xm + l.line.c) / l.line.b;
            if (!AnyInsideOthers(l, xm, ym, l.filteredByAllHsbs, true)) continue;
            ShowEdge e = proto;
            e.horizontal = true;
            const bool firstLow = v0.y <= v1.y;
            const IVertex& lo = firstLow ? v0 : v1;
            const IVertex& hi = firstLow ? v1 : v0;
            e.yBottom = lo.y;
            e.xBottom = lo.x;
            e.yTop = hi.y;
            e.xTop = hi.x;
            AssignFaces(l, e, xm, ym);
            ++c_.edgesHorizontal;
            edges_.push_back(e);
        }
    }

    void AssignFaces(const ILine& l, ShowEdge& e, double x, double y) const {
        const Hsb &hi = H(l.i), &hj = H(l.j);
        if (l.limb) {
            e.faces[0] = hi.face[0];
            e.faces[1] = hi.face[1];
            return;
        }
        if (hi.isPlane && hj.isPlane) {
            e.faces[0] = hi.face[0];
            e.faces[1] = hj.face[0];
            return;
        }
        const Hsb& p = hi.isPlane ? hi : hj;
        const Hsb& q = hi.isPlane ? hj : hi;
        if (l.type == ILineType::kEdge) {  // one face: the sheet the list stands for
            Vec3 pts[2];
            int n = CurvePoints(l, x, y, pts);
            e.faces[0] = n > 0 ? q.face[0] : -1;
            e.faces[1] = n > 1 ? q.face[1] : -1;
            return;
        }
        e.faces[0] = p.face[0];
        e.faces[1] = QuadricSheetFace(l, q, x, y, PlaneZ(p.plane, x, y));
    }

    const FlatScene& scene_;
    int body_;
    double yLo_, yHi_;
    bool all_;
    ResolvedBody& out_;
    std::vector<ShowFace>& faces_;
    std::vector<ShowEdge>& edges_;
    ResolverCounters& c_;
};

}  // namespace

void ResolveBody(const FlatScene& scene, int body, double yLo, double yHi, bool allBoundaries,
                 ResolvedBody& out, std::vector<ShowFace>& faces, std::vector<ShowEdge>& edges,
                 ResolverCounters& counters) {
    BodyResolver(scene, body, yLo, yHi, allBoundaries, out, faces, edges, counters).Run();
}

}  // namespace quadrix::scanline
