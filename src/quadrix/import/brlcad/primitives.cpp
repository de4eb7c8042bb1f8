// BRL-CAD primitives as Quadrix half-spaces; the decompositions are those of FORMAT.md §6.1,
// written out per primitive below with the local frame each uses; the quartics (tor, eto, general
// tgc) are quartic_surface.h's, the pipe is pipe_solid.h's.
#include "quadrix/import/brlcad/primitives.h"

#include <fmt/format.h>

#include <cmath>

#include "quadrix/import/brlcad/pipe_solid.h"
#include "quadrix/import/shapes/mesh_solid.h"
#include "quadrix/math/quartic_surface.h"

namespace quadrix::import::brlcad {

namespace {

// librt's default distance tolerance (bn_tol.dist, 0.0005 mm): arb vertices closer than this are
// the same vertex (FORMAT.md §8 "Degenerate ARBs").
constexpr double kDistTol = 0.0005;
// Relative tolerance of librt's quadric-tgc test |A|·|D| = |B|·|C| (FORMAT.md §6.1 quotes
// NEAR_EQUAL(..., 0.0001)); we apply it relative to the products so that it is unit-free.
constexpr double kTgcRelTol = 1e-4;

// An affine frame P = O + u1 e1 + u2 e2 + u3 e3; local shapes are written in (u1, u2, u3).
class LocalFrame {
  public:
    LocalFrame(const Vec3& o, const Vec3& e1, const Vec3& e2, const Vec3& e3) {
        Mat4 w = Mat4::Identity();
        const Vec3 cols[4] = {e1, e2, e3, o};
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 3; ++r) w.m[r][c] = cols[c][r];
        if (auto inv = w.Inverse()) {
            local_ = *inv;
            ok_ = inv->AllFinite();
        }
    }
    bool ok() const { return ok_; }

    // Local quadric matrix (symmetric 4x4) → world quadric: Lᵀ Q L.
    ShapeHalfSpace Quad(const Mat4& q, bool transparent = false) const {
        ShapeHalfSpace h;
        h.isPlane = false;
        h.quadric = Quadric::FromMatrix(local_.Transposed() * q * local_);
        h.transparent = transparent;
        return h;
    }
    // Local plane a u1 + b u2 + c u3 + d <= 0 → world: Lᵀ p.
    ShapeHalfSpace Plane4(double a, double b, double c, double d, bool transparent = false) const {
        const double p[4] = {a, b, c, d};
        double w[4] = {0, 0, 0, 0};
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) w[j] += local_.m[i][j] * p[i];
        ShapeHalfSpace h;
        h.isPlane = true;
        h.plane = Plane{w[0], w[1], w[2], w[3]};
        h.transparent = transparent;
        return h;
    }

  private:
    Mat4 local_ = Mat4::Identity();
    bool ok_ = false;
};

Mat4 Diag(double a, double b, double c, double d) {
    Mat4 m = Mat4::Zero();
    m.m[0][0] = a;
    m.m[1][1] = b;
    m.m[2][2] = c;
    m.m[3][3] = d;
    return m;
}

ConvertResult Invalid(const Primitive& p, std::string why) {
    ConvertResult r;
    r.status = ConvertResult::Status::kInvalid;
    r.censusName = p.type;
    r.problem = std::move(why);
    return r;
}

// A unit vector perpendicular to h (for frames that only fix one axis).
Vec3 AnyPerpendicular(const Vec3& h) {
    Vec3 t = std::fabs(h.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    return Normalize(Cross(h, t));
}

ConvertResult Arb8(const Primitive& p) {
    ConvertResult r;
    Vec3 centre;
    for (const Vec3& v : p.pts) centre += v * 0.125;
    ShapeBody body;
    for (const auto& face : kArbFaces) {
        // The plane through the first three distinct, non-collinear vertices of the face
        // (rt_arb_add_pnt); faces with fewer are dropped (arb4..arb7 repeat vertices).
        std::vector<Vec3> pts;
        for (int k : face) {
            const Vec3& v = p.pts[k];
            bool dup = false;
            for (const Vec3& q : pts) dup = dup || Length(v - q) < kDistTol;
            if (dup) continue;
            if (pts.size() == 2) {
                Vec3 n = Cross(pts[1] - pts[0], v - pts[0]);
                if (Length(n) < kDistTol * (Length(pts[1] - pts[0]) + Length(v - pts[0]))) continue;
            }
            pts.push_back(v);
            if (pts.size() == 3) break;
        }
        if (pts.size() < 3) continue;
        Vec3 n = Normalize(Cross(pts[1] - pts[0], pts[2] - pts[0]));
        double d = -Dot(n, pts[0]);
        double side = Dot(n, centre) + d;
        if (std::fabs(side) < kDistTol) continue;  // the centre lies on it: a flat arb
        if (side > 0) {
            n = -n;
            d = -d;
        }
        ShapeHalfSpace h;
        h.plane = Plane{n.x, n.y, n.z, d};
        body.push_back(h);
    }
    if (body.size() < 4) return Invalid(p, "its vertices do not span a solid");
    // A concave or twisted arb (arb8_showcase has several) is, as in librt, the intersection of
    // its face planes, which can reach far beyond its vertices. rt only finds it along rays that
    // cross the solid's bounding box; we bound it by that box (the box of its vertices) with 6
    // more planes, which leave every convex arb untouched.
    bool convex = true;
    for (const Vec3& v : p.pts)
        for (const ShapeHalfSpace& h : body) convex = convex && h.plane.Evaluate(v) <= kDistTol;
    if (!convex) {
        Box3 box;
        for (const Vec3& v : p.pts) box.Extend(v);
        for (int axis = 0; axis < 3; ++axis) {
            ShapeHalfSpace lo, hi;
            Vec3 n;
            n[axis] = 1;
            hi.plane = Plane{n.x, n.y, n.z, -box.hi[axis]};
            lo.plane = Plane{-n.x, -n.y, -n.z, box.lo[axis]};
            body.push_back(hi);
            body.push_back(lo);
        }
    }
    r.shape.bodies.push_back(std::move(body));
    for (const Vec3& v : p.pts) r.shape.extent.push_back({v, {}, {}, {}});
    return r;
}

ConvertResult Arbn(const Primitive& p) {
    ConvertResult r;
    if (p.planes.size() < 4) return Invalid(p, "an arbn needs at least 4 planes");
    ShapeBody body;
    for (const Plane& pl : p.planes) {
        if (pl.IsZeroNormal()) return Invalid(p, "a plane has a zero normal");
        ShapeHalfSpace h;
        h.plane = pl;
        body.push_back(h);
    }
    r.shape.bodies.push_back(std::move(body));
    // The extent of an arbn (a bounded convex polyhedron, as librt requires) is the box of its
    // vertices: every point where three planes meet and no plane is violated (rt_arbn_prep does
    // the same enumeration). Tolerance relative to the planes' offsets.
    std::vector<Plane> u;
    double scale = 0;
    for (const Plane& pl : p.planes) {
        double n = Length(pl.Normal());
        u.push_back(Plane{pl.a / n, pl.b / n, pl.c / n, pl.d / n});
        scale = std::fmax(scale, std::fabs(pl.d / n));
    }
    const double tol = 1e-9 * std::fmax(scale, 1.0);
    const std::size_t n = u.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                const Vec3 a = u[i].Normal(), b = u[j].Normal(), c = u[k].Normal();
                const double det = Dot(a, Cross(b, c));
                if (std::fabs(det) < 1e-12) continue;
                // x = (-d_i (b×c) - d_j (c×a) - d_k (a×b)) / det
                const Vec3 x =
                    (Cross(b, c) * -u[i].d + Cross(c, a) * -u[j].d + Cross(a, b) * -u[k].d) / det;
                bool in = true;
                for (const Plane& q : u) in = in && q.Evaluate(x) <= tol;
                if (in) r.shape.extent.push_back({x, {}, {}, {}});
            }
    if (r.shape.extent.size() < 4) return Invalid(p, "its planes bound no solid");
    return r;
}

// bot (mesh_solid.h): solid mode (and surface mode when the mesh is closed) → the solid it
// bounds; plate mode with centred faces → prisms. Appended plates and plate_nocos put the
// thickness along each ray (FASTGEN), which is not a fixed solid: not drawn.
ConvertResult Bot(const Primitive& p) {
    ConvertResult r;
    r.censusName = "bot";
    auto refuse = [&](std::string why) {
        r.status = ConvertResult::Status::kNonQuadric;
        r.problem = std::move(why);
        return r;
    };
    MeshSolid m;
    if (p.botMode == 3 || p.botMode == 4) {
        bool appended = false;
        for (char a : p.faceAppended) appended = appended || a;
        if (p.botMode == 4 || appended)
            return refuse(
                "a plate-mode bot whose thickness follows each ray (plate_nocos or "
                "appended faces) is not a fixed solid");
        m = PlatesToSolid(p.vertices, p.faces, p.thickness);
    } else {
        std::vector<std::vector<int>> faces;
        for (const auto& f : p.faces) faces.push_back({f[0], f[1], f[2]});
        m = MeshToSolid(p.vertices, faces);
    }
    if (!m.ok) return refuse(m.problem);
    r.shape = std::move(m.shape);
    return r;
}

ConvertResult Half(const Primitive& p) {
    ConvertResult r;
    if (Length(p.N) == 0) return Invalid(p, "the normal N is zero");
    ShapeHalfSpace h;
    h.plane = Plane{p.N.x, p.N.y, p.N.z, -p.d};  // N·P <= d
    r.shape.bodies.push_back({h});
    r.shape.unbounded = true;
    return r;
}

ConvertResult Ell(const Primitive& p) {
    ConvertResult r;
    LocalFrame f(p.V, p.A, p.B, p.C);
    if (!f.ok()) return Invalid(p, "the semi-axes A, B, C are degenerate");
    r.shape.bodies.push_back({f.Quad(Diag(1, 1, 1, -1))});
    r.shape.extent.push_back({p.V, p.A, p.B, p.C});
    return r;
}

// A tgc whose end ellipses are not similar (|A|·|D| != |B|·|C|): the quartic general cone
// (quartic_surface.h) capped by the planes of its end ellipses. Extent: the two end ellipses.
ConvertResult GeneralTgc(const Primitive& p) {
    std::string why;
    auto q = QuarticSurface::GeneralCone(p.V, p.H, p.A, p.B, Length(p.C), Length(p.D), &why);
    if (!q) {
        ConvertResult bad = Invalid(p, why);
        bad.censusName = "tgc (quartic)";
        return bad;
    }
    ConvertResult r;
    r.censusName = "tgc (quartic)";
    ShapeHalfSpace cone;
    cone.SetQuartic(*q);
    ShapeBody body{cone};
    for (const Vec4& cap : q->GeneralConeCaps()) {
        ShapeHalfSpace h;
        h.plane = Plane::FromVec4(cap);
        body.push_back(h);
    }
    r.shape.bodies.push_back(std::move(body));
    auto unit = [](const Vec3& u) { return Length(u) > 0 ? Normalize(u) : Vec3{}; };
    r.shape.extent.push_back({p.V, p.A, p.B, {}});
    r.shape.extent.push_back({p.V + p.H, unit(p.A) * Length(p.C), unit(p.B) * Length(p.D), {}});
    return r;
}

// Torus: centre V, unit axis H, ring radius r1 (r_a), tube radius r2 (r_h). Its hull is the ring
// circle plus a ball of the tube radius (an exact Minkowski-sum extent).
ConvertResult Tor(const Primitive& p) {
    std::string why;
    auto q = QuarticSurface::Torus(p.V, p.H, p.r1, p.r2, &why);
    if (!q) return Invalid(p, why);
    ConvertResult r;
    ShapeHalfSpace h;
    h.SetQuartic(*q);
    r.shape.bodies.push_back({h});
    const Vec3 n = Normalize(p.H), e1 = AnyPerpendicular(n), e2 = Cross(n, e1);
    r.shape.extentSums.push_back(
        {{p.V, e1 * p.r1, e2 * p.r1, {}}, {{}, {p.r2, 0, 0}, {0, p.r2, 0}, {0, 0, p.r2}}});
    return r;
}

// Elliptical torus: centre V, axis N, radius of revolution r, meridian ellipse with semi-axis
// vector C and other semi-axis r_d. Extent: the circle of radius r plus the cylinder (disc ⊕
// segment) that holds the meridian ellipse's box, a containing sum.
ConvertResult Eto(const Primitive& p) {
    std::string why;
    auto q = QuarticSurface::EllipticalTorus(p.V, p.N, p.r, p.C, p.rd, &why);
    if (!q) return Invalid(p, why);
    ConvertResult r;
    ShapeHalfSpace h;
    h.SetQuartic(*q);
    r.shape.bodies.push_back({h});
    const Vec3 n = Normalize(p.N), e1 = AnyPerpendicular(n), e2 = Cross(n, e1);
    const double lc = Length(p.C);
    const double cz = Dot(p.C, n), crho = Length(p.C - n * cz);
    // The meridian ellipse's half extents along the radius and along the axis.
    const double er = std::sqrt(crho * crho + p.rd * p.rd * cz * cz / (lc * lc));
    const double ez = std::sqrt(cz * cz + p.rd * p.rd * crho * crho / (lc * lc));
    r.shape.extentSums.push_back(
        {{p.V, e1 * p.r, e2 * p.r, {}}, {{}, e1 * er, e2 * er, {}}, {{}, n * ez, {}, {}}});
    return r;
}

ConvertResult Pipe(const Primitive& p) {
    PipeShape s = PipeToShape(LayOutPipe(p.pipe));
    if (!s.ok) return Invalid(p, s.problem);
    ConvertResult r;
    r.shape = std::move(s.shape);
    return r;
}

// Truncated general cone, quadric case (FORMAT.md §6.1): P = V + s H + α A + β B,
// α² + β² <= (1 + s(k-1))², 0 <= s <= 1, k = |C|/|A| = |D|/|B|.
ConvertResult Tgc(const Primitive& p) {
    Vec3 v = p.V, h = p.H, a = p.A, b = p.B, c = p.C, d = p.D;
    double la = Length(a), lb = Length(b), lc = Length(c), ld = Length(d);
    if (Length(h) == 0) return Invalid(p, "the height vector H is zero");
    if ((la == 0 || lb == 0) && (lc == 0 || ld == 0))
        return Invalid(p, "both end ellipses are degenerate");
    // C must be parallel to A and D to B, in the same sense (librt's tgc); a zero C or D is a
    // degenerate end.
    auto parallel = [](const Vec3& u, const Vec3& w) {
        const double lu = Length(u), lw = Length(w);
        return lu == 0 || lw == 0 || Length(u / lu - w / lw) <= 1e-4;
    };
    if (!parallel(a, c) || !parallel(b, d)) return Invalid(p, "C must be parallel to A and D to B");
    double ad = la * ld, bc = lb * lc;
    if (std::fabs(ad - bc) > kTgcRelTol * std::fmax(ad, bc)) return GeneralTgc(p);
    if (la == 0 || lb == 0) {  // apex at the base: describe it from the top end
        v = v + h;
        h = -h;
        std::swap(a, c);
        std::swap(b, d);
        std::swap(la, lc);
        std::swap(lb, ld);
    }
    double k = lc / la;
    LocalFrame f(v, a, b, h);
    if (!f.ok()) return Invalid(p, "A, B and H are coplanar");
    ConvertResult r;
    r.censusName = "tgc";
    // α² + β² - (1 + (k-1)s)² <= 0 in (u1, u2, u3) = (α, β, s).
    double km = k - 1;
    Mat4 q = Diag(1, 1, -km * km, -1);
    q.m[2][3] = q.m[3][2] = -km;
    r.shape.bodies.push_back({f.Quad(q), f.Plane4(0, 0, -1, 0), f.Plane4(0, 0, 1, -1)});
    r.shape.extent.push_back({v, a, b, {}});
    r.shape.extent.push_back({v + h, a * k, b * k, {}});
    return r;
}

// The extent of rpc and rhc: their section (between V ± r R̂ and the vertex V + B) at both ends.
void AddCylinderSectionExtent(const Primitive& p, const Vec3& rhat, Shape& shape) {
    for (double sh : {0.0, 1.0}) {
        const Vec3 o = p.V + p.H * sh;
        shape.extent.push_back({o + rhat * p.r, {}, {}, {}});
        shape.extent.push_back({o - rhat * p.r, {}, {}, {}});
        shape.extent.push_back({o + p.B, {}, {}, {}});
    }
}

// Right parabolic cylinder: frame (B, r·R̂, H), R̂ = unit(H × B); u2² + u1 - 1 <= 0, u1 >= 0,
// 0 <= u3 <= 1. The parabola's vertex is V + B.
ConvertResult Rpc(const Primitive& p) {
    Vec3 rhat = Normalize(Cross(p.H, p.B));
    if (!(p.r > 0) || Length(rhat) == 0) return Invalid(p, "r must be positive and H not ∥ B");
    LocalFrame f(p.V, p.B, rhat * p.r, p.H);
    if (!f.ok()) return Invalid(p, "B or H is zero");
    Mat4 q = Diag(0, 1, 0, -1);
    q.m[0][3] = q.m[3][0] = 0.5;
    ConvertResult r;
    r.shape.bodies.push_back(
        {f.Quad(q), f.Plane4(-1, 0, 0, 0), f.Plane4(0, 0, -1, 0), f.Plane4(0, 0, 1, -1)});
    AddCylinderSectionExtent(p, rhat, r.shape);
    return r;
}

// Right hyperbolic cylinder. With z = distance from V along B̂ and w = (|B| + c - z)/c, the
// hyperbola is w² - (y/a)² = 1 with a = r c / sqrt(|B|(|B| + 2c)) (so y = ±r at z = 0); vertex
// at V + B, asymptotes meeting c beyond it. Frame (B, a R̂, H) with g = |B|/c:
// u2² - (1 + g - g u1)² + 1 <= 0, u1 >= 0, 0 <= u3 <= 1, and the transparent plane
// u1 <= 1 + 1/g (w >= 0) that removes the hyperbola's other branch.
ConvertResult Rhc(const Primitive& p) {
    double lb = Length(p.B);
    Vec3 rhat = Normalize(Cross(p.H, p.B));
    if (!(p.r > 0) || !(p.c > 0) || lb == 0 || Length(rhat) == 0)
        return Invalid(p, "r and c must be positive, B non-zero and not ∥ H");
    double a = p.r * p.c / std::sqrt(lb * (lb + 2 * p.c));
    double g = lb / p.c;
    LocalFrame f(p.V, p.B, rhat * a, p.H);
    if (!f.ok()) return Invalid(p, "H is zero");
    Mat4 q = Diag(-g * g, 1, 0, 1 - (1 + g) * (1 + g));
    q.m[0][3] = q.m[3][0] = g * (1 + g);
    ConvertResult r;
    r.shape.bodies.push_back({f.Quad(q), f.Plane4(-1, 0, 0, 0), f.Plane4(0, 0, -1, 0),
                              f.Plane4(0, 0, 1, -1), f.Plane4(1, 0, 0, -(1 + 1 / g), true)});
    AddCylinderSectionExtent(p, rhat, r.shape);
    return r;
}

// Elliptic paraboloid: frame (r1 Â, r2 (Ĥ×Â), H): u1² + u2² + u3 - 1 <= 0, u3 >= 0.
ConvertResult Epa(const Primitive& p) {
    Vec3 ahat = Normalize(p.A), bhat = Normalize(Cross(p.H, p.A));
    if (!(p.r1 > 0) || !(p.r2 > 0) || Length(bhat) == 0)
        return Invalid(p, "r_1 and r_2 must be positive and A not ∥ H");
    LocalFrame f(p.V, ahat * p.r1, bhat * p.r2, p.H);
    if (!f.ok()) return Invalid(p, "H is zero");
    Mat4 q = Diag(1, 1, 0, -1);
    q.m[2][3] = q.m[3][2] = 0.5;
    ConvertResult r;
    r.shape.bodies.push_back({f.Quad(q), f.Plane4(0, 0, -1, 0)});
    r.shape.extent.push_back({p.V, ahat * p.r1, bhat * p.r2, {}});
    r.shape.extent.push_back({p.V + p.H, {}, {}, {}});
    return r;
}

// Elliptic hyperboloid (one nappe of two sheets), as rhc with an elliptic section: frame
// (a1 Â, a2 (Ĥ×Â), H), g = |H|/c, a_i = r_i c / sqrt(|H|(|H| + 2c)):
// u1² + u2² - (1 + g - g u3)² + 1 <= 0, u3 >= 0, transparent u3 <= 1 + 1/g.
ConvertResult Ehy(const Primitive& p) {
    double lh = Length(p.H);
    Vec3 ahat = Normalize(p.A), bhat = Normalize(Cross(p.H, p.A));
    if (!(p.r1 > 0) || !(p.r2 > 0) || !(p.c > 0) || lh == 0 || Length(bhat) == 0)
        return Invalid(p, "r_1, r_2 and c must be positive, H non-zero and A not ∥ H");
    double s = p.c / std::sqrt(lh * (lh + 2 * p.c));
    double g = lh / p.c;
    LocalFrame f(p.V, ahat * (p.r1 * s), bhat * (p.r2 * s), p.H);
    if (!f.ok()) return Invalid(p, "degenerate frame");
    Mat4 q = Diag(1, 1, -g * g, 1 - (1 + g) * (1 + g));
    q.m[2][3] = q.m[3][2] = g * (1 + g);
    ConvertResult r;
    r.shape.bodies.push_back(
        {f.Quad(q), f.Plane4(0, 0, -1, 0), f.Plane4(0, 0, 1, -(1 + 1 / g), true)});
    r.shape.extent.push_back({p.V, ahat * p.r1, bhat * p.r2, {}});
    r.shape.extent.push_back({p.V + p.H, {}, {}, {}});
    return r;
}

// Hyperboloid of one sheet (FORMAT.md §6.1): end ellipses with semi-axes |A| (along Â) and b
// (along Ĥ×Â) at V and V + H, neck at V + H/2 with semi-axes bnr·|A|, bnr·b. With z measured
// from the neck in units of |H|/2, z = ±1 at the ends: (x/na)² + (y/nb)² - z² t = 1 with
// t = 1/bnr² - 1 so that the ends have the full size. Frame (na Â, nb B̂, H/2) at the neck.
ConvertResult Hyp(const Primitive& p) {
    double la = Length(p.A);
    Vec3 ahat = Normalize(p.A), bhat = Normalize(Cross(p.H, p.A));
    if (la == 0 || !(p.b > 0) || !(p.bnr > 0) || p.bnr > 1 || Length(bhat) == 0)
        return Invalid(p, "A and b must be non-zero, 0 < bnr <= 1 and A not ∥ H");
    LocalFrame f(p.V + p.H * 0.5, ahat * (la * p.bnr), bhat * (p.b * p.bnr), p.H * 0.5);
    if (!f.ok()) return Invalid(p, "H is zero");
    double t = 1 / (p.bnr * p.bnr) - 1;
    ConvertResult r;
    r.shape.bodies.push_back(
        {f.Quad(Diag(1, 1, -t, -1)), f.Plane4(0, 0, -1, -1), f.Plane4(0, 0, 1, -1)});
    r.shape.extent.push_back({p.V, p.A, bhat * p.b, {}});
    r.shape.extent.push_back({p.V + p.H, p.A, bhat * p.b, {}});
    return r;
}

// Particle: the union of a sphere r_v at V, a sphere r_h at V + H and the frustum of the cone
// tangent to both. With L = |H| and sin φ = (r_v - r_h)/L, each tangent circle lies r·sin φ
// from its sphere's centre along Ĥ, with radius r·cos φ.
ConvertResult Part(const Primitive& p) {
    double l = Length(p.H);
    if (!(p.rv > 0) || !(p.rh >= 0) || l == 0)
        return Invalid(p, "r_v must be positive, r_h non-negative and H non-zero");
    ConvertResult r;
    auto sphere = [&](const Vec3& c, double rad) {
        LocalFrame f(c, {rad, 0, 0}, {0, rad, 0}, {0, 0, rad});
        r.shape.bodies.push_back({f.Quad(Diag(1, 1, 1, -1))});
        r.shape.extent.push_back({c, {rad, 0, 0}, {0, rad, 0}, {0, 0, rad}});
    };
    if (p.rh > 0) sphere(p.V + p.H, p.rh);
    sphere(p.V, p.rv);
    double sinPhi = (p.rv - p.rh) / l;
    if (std::fabs(sinPhi) >= 1) {  // one sphere contains the other
        if (p.rh > p.rv)
            r.shape.bodies.erase(r.shape.bodies.begin() + 1);
        else if (p.rh > 0)
            r.shape.bodies.erase(r.shape.bodies.begin());
        return r;
    }
    double cosPhi = std::sqrt(1 - sinPhi * sinPhi);
    Vec3 hhat = p.H / l;
    double z1 = p.rv * sinPhi, z2 = l + p.rh * sinPhi;  // tangent circles, along Ĥ from V
    double c1 = p.rv * cosPhi, c2 = p.rh * cosPhi;
    if (!(z2 > z1)) return r;
    Vec3 e1 = AnyPerpendicular(hhat), e2 = Cross(hhat, e1);
    // Frame at the first circle: (c1 e1, c1 e2, (z2 - z1) Ĥ); radius ratio k = c2/c1.
    LocalFrame f(p.V + hhat * z1, e1 * c1, e2 * c1, hhat * (z2 - z1));
    double km = c2 / c1 - 1;
    Mat4 q = Diag(1, 1, -km * km, -1);
    q.m[2][3] = q.m[3][2] = -km;
    r.shape.bodies.push_back({f.Quad(q), f.Plane4(0, 0, -1, 0), f.Plane4(0, 0, 1, -1)});
    return r;
}

}  // namespace

ConvertResult ConvertPrimitive(const Primitive& p) {
    ConvertResult r;
    const std::string& t = p.type;
    if (t == "arb8")
        r = Arb8(p);
    else if (t == "arbn")
        r = Arbn(p);
    else if (t == "bot")
        r = Bot(p);
    else if (t == "half")
        r = Half(p);
    else if (t == "ell")
        r = Ell(p);
    else if (t == "tgc")
        r = Tgc(p);
    else if (t == "rpc")
        r = Rpc(p);
    else if (t == "rhc")
        r = Rhc(p);
    else if (t == "epa")
        r = Epa(p);
    else if (t == "ehy")
        r = Ehy(p);
    else if (t == "hyp")
        r = Hyp(p);
    else if (t == "part")
        r = Part(p);
    else if (t == "tor")
        r = Tor(p);
    else if (t == "eto")
        r = Eto(p);
    else if (t == "pipe")
        r = Pipe(p);
    else {
        r.status = ConvertResult::Status::kNonQuadric;
        r.problem = "this primitive type is not made of quadrics, quartics and planes";
    }
    if (r.censusName.empty()) r.censusName = t;
    return r;
}

}  // namespace quadrix::import::brlcad
