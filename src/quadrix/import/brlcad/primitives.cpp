// BRL-CAD primitives as Quadrix half-spaces; the decompositions are those of FORMAT.md §6.1.
// The primitives OpenSCAD shares (ell, arb8, tgc, tor, eto, bot) are adapters to the builders of
// import/shapes/; the others are written out below with the local frame each uses
// (shapes/local_frame.h); the pipe is pipe_solid.h's.
#include "quadrix/import/brlcad/primitives.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>

#include "quadrix/import/brlcad/pipe_solid.h"
#include "quadrix/import/shapes/ellipsoid.h"
#include "quadrix/import/shapes/hexahedron.h"
#include "quadrix/import/shapes/local_frame.h"
#include "quadrix/import/shapes/mesh_solid.h"
#include "quadrix/import/shapes/torus.h"
#include "quadrix/import/shapes/truncated_cone.h"

namespace quadrix::import::brlcad {

namespace {

ConvertResult Invalid(const Primitive& p, std::string why) {
    ConvertResult r;
    r.status = ConvertResult::Status::kInvalid;
    r.censusName = p.type;
    r.problem = std::move(why);
    return r;
}

// A builder's shape, or the primitive refused as degenerate with the builder's reason.
ConvertResult FromBuilder(const Primitive& p, ShapeResult s) {
    if (!s.ok) return Invalid(p, std::move(s.problem));
    ConvertResult r;
    r.shape = std::move(s.shape);
    return r;
}

// arb8 (arb4..arb7 repeat vertices): hexahedron.h.
ConvertResult Arb8(const Primitive& p) { return FromBuilder(p, HexahedronShape(p.pts)); }

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

// ars (librt's rt_ars_tess): consecutive curves joined by quadrilaterals, (i, j) (i+1, j)
// (i+1, j+1) (i, j+1) with j wrapping round each closed curve, split into two triangles; equal
// points are one vertex (the first and last curves of a closed ars shrink to a point), triangles
// with a repeated vertex are dropped. The mesh is then drawn as the solid it bounds
// (mesh_solid.h), which refuses one with an open edge: such an ars bounds no solid.
ConvertResult Ars(const Primitive& p) {
    ConvertResult r;
    r.censusName = "ars";
    auto refuse = [&](std::string why) {
        r.status = ConvertResult::Status::kNonQuadric;
        r.problem = std::move(why);
        return r;
    };
    const auto& curves = p.arsCurves;
    if (curves.size() < 2 || curves[0].size() < 3)
        return refuse(fmt::format("an ars of {} curves of {} points bounds no solid", curves.size(),
                                  curves.empty() ? 0 : curves[0].size()));
    std::vector<Vec3> vertices;
    std::map<std::array<double, 3>, int> index;
    auto vertex = [&](const Vec3& v) {
        auto [it, added] = index.try_emplace({v.x, v.y, v.z}, static_cast<int>(vertices.size()));
        if (added) vertices.push_back(v);
        return it->second;
    };
    std::vector<std::vector<int>> faces;
    auto triangle = [&](int a, int b, int c) {
        if (a != b && b != c && a != c) faces.push_back({a, b, c});
    };
    const std::size_t n = curves[0].size();
    for (std::size_t i = 0; i + 1 < curves.size(); ++i) {
        if (curves[i + 1].size() != n) return Invalid(p, "its curves have different lengths");
        for (std::size_t j = 0; j < n; ++j) {
            const std::size_t k = (j + 1) % n;
            const int a = vertex(curves[i][j]), b = vertex(curves[i + 1][j]),
                      c = vertex(curves[i + 1][k]), d = vertex(curves[i][k]);
            triangle(a, b, c);
            triangle(a, c, d);
        }
    }
    MeshSolid m = MeshToSolid(vertices, faces);
    if (!m.ok)
        return refuse(
            fmt::format("its curves do not bound a closed solid ({}); an ars is drawn "
                        "when its first and last curves close it",
                        m.problem));
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

ConvertResult Ell(const Primitive& p) { return FromBuilder(p, EllipsoidShape(p.V, p.A, p.B, p.C)); }

// Torus: centre V, axis H, ring radius r1 (r_a), tube radius r2 (r_h); torus.h.
ConvertResult Tor(const Primitive& p) { return FromBuilder(p, TorusShape(p.V, p.H, p.r1, p.r2)); }

// Elliptical torus: centre V, axis N, radius of revolution r, meridian ellipse with semi-axis
// vector C and other semi-axis r_d; torus.h.
ConvertResult Eto(const Primitive& p) {
    return FromBuilder(p, EllipticalTorusShape(p.V, p.N, p.r, p.C, p.rd));
}

ConvertResult Pipe(const Primitive& p) {
    PipeShape s = PipeToShape(LayOutPipe(p.pipe));
    if (!s.ok) return Invalid(p, s.problem);
    ConvertResult r;
    r.shape = std::move(s.shape);
    return r;
}

// Truncated general cone (truncated_cone.h); its census name tells the quartic case apart.
ConvertResult Tgc(const Primitive& p) {
    ConeShape cone = TruncatedConeShape(p.V, p.H, p.A, p.B, p.C, p.D);
    const bool quartic = cone.quartic;
    ConvertResult r = FromBuilder(p, std::move(cone));
    r.censusName = quartic ? "tgc (quartic)" : "tgc";
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
    Mat4 q = DiagonalQuadric(0, 1, 0, -1);
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
    Mat4 q = DiagonalQuadric(-g * g, 1, 0, 1 - (1 + g) * (1 + g));
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
    Mat4 q = DiagonalQuadric(1, 1, 0, -1);
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
    Mat4 q = DiagonalQuadric(1, 1, -g * g, 1 - (1 + g) * (1 + g));
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
        {f.Quad(DiagonalQuadric(1, 1, -t, -1)), f.Plane4(0, 0, -1, -1), f.Plane4(0, 0, 1, -1)});
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
        ShapeResult s = SphereShape(c, rad);
        if (!s.ok) return false;
        r.shape.bodies.push_back(std::move(s.shape.bodies[0]));
        r.shape.extent.push_back(s.shape.extent[0]);
        return true;
    };
    if ((p.rh > 0 && !sphere(p.V + p.H, p.rh)) || !sphere(p.V, p.rv))
        return Invalid(p, "a sphere's radius is too small to be represented");
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
    // The cone of truncated_cone.h from the first circle: base (c1 e1, c1 e2), height
    // (z2 - z1) Ĥ, radius ratio k = c2/c1.
    if (auto body = SimilarConeBody(p.V + hhat * z1, e1 * c1, e2 * c1, hhat * (z2 - z1), c2 / c1))
        r.shape.bodies.push_back(std::move(*body));
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
    else if (t == "ars")
        r = Ars(p);
    else {
        r.status = ConvertResult::Status::kNonQuadric;
        r.problem = fmt::format(
            "Quadrix does not convert BRL-CAD's {} (it draws arb4-8, arbn, ars, bot, ehy, ell, "
            "epa, eto, half, hyp, part, pipe, rhc, rpc, tgc and tor; docs/import.md)",
            t);
    }
    if (r.censusName.empty()) r.censusName = t;
    return r;
}

}  // namespace quadrix::import::brlcad
