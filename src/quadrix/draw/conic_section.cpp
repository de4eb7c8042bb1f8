#include "quadrix/draw/conic_section.h"

#include <algorithm>
#include <cmath>

namespace quadrix::draw {

namespace {

constexpr double kRelZero = 1e-10;

Vec3 AnyPerpendicular(const Vec3& n) {
    const Vec3 a = std::fabs(n.x) <= std::fabs(n.y) && std::fabs(n.x) <= std::fabs(n.z)
                       ? Vec3{1, 0, 0}
                       : (std::fabs(n.y) <= std::fabs(n.z) ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    return Normalize(Cross(n, a));
}

double Bilinear(const Mat4& q, const Vec4& a, const Vec4& b) { return Dot(a, q * b); }

Curve3 MakeLine(const Vec3& o, const Vec3& u) {
    Curve3 c;
    c.kind = CurveKind::kLine;
    c.o = o;
    c.u = u;
    return c;
}

}  // namespace

bool ClipLineToBox(const Vec3& o, const Vec3& u, const Box3& box, double& t0, double& t1) {
    for (std::size_t i = 0; i < 3; ++i) {
        if (u[i] == 0) {
            if (o[i] < box.lo[i] || o[i] > box.hi[i]) return false;
            continue;
        }
        double a = (box.lo[i] - o[i]) / u[i], b = (box.hi[i] - o[i]) / u[i];
        if (a > b) std::swap(a, b);
        t0 = std::fmax(t0, a);
        t1 = std::fmin(t1, b);
    }
    return t0 < t1;
}

bool PlanePlaneLine(const Plane& p1, const Plane& p2, const Box3& box, Curve3& out) {
    const Vec3 n1 = p1.Normal(), n2 = p2.Normal();
    const Vec3 d = Cross(n1, n2);
    const double dd = Dot(d, d);
    if (!(dd > 1e-24 * Dot(n1, n1) * Dot(n2, n2))) return false;  // parallel (sin < 1e-12)
    // n·x = h on each plane (h = −D); the point of the line nearest the origin of the box centre.
    const Vec3 c = box.Center();
    const double h1 = -p1.Evaluate(c), h2 = -p2.Evaluate(c);
    const Vec3 p = c + (Cross(n2, d) * h1 + Cross(d, n1) * h2) / dd;
    const Vec3 u = d / std::sqrt(dd);
    double t0 = -HUGE_VAL, t1 = HUGE_VAL;
    if (!ClipLineToBox(p, u, box, t0, t1)) return false;
    out = MakeLine(p, u);
    out.t0 = t0;
    out.t1 = t1;
    return true;
}

std::vector<Curve3> PlaneQuadricCurves(const Plane& plane, const Quadric& quadric, const Box3& box,
                                       bool* tangent) {
    std::vector<Curve3> out;
    if (tangent) *tangent = false;
    const Vec3 n = plane.Normal();
    const double nn = Dot(n, n);
    if (!(nn > 0) || !std::isfinite(nn)) return out;
    const Vec3 c = box.Center();
    const Vec3 o = c - n * (plane.Evaluate(c) / nn);
    const Vec3 e1 = AnyPerpendicular(n);
    const Vec3 e2 = Normalize(Cross(n, e1));
    const Mat4 q = quadric.Matrix();
    const Vec4 h[3] = {Vec4(e1, 0), Vec4(e2, 0), Vec4(o, 1)};
    double m[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] = Bilinear(q, h[i], h[j]);
    // Eigen-decomposition of [[m00 m01] [m01 m11]] by one rotation.
    const double phi = 0.5 * std::atan2(2 * m[0][1], m[0][0] - m[1][1]);
    Vec3 w1 = e1 * std::cos(phi) + e2 * std::sin(phi);  // 3-D directions of the eigen-axes
    Vec3 w2 = e2 * std::cos(phi) - e1 * std::sin(phi);
    const double cs = std::cos(phi), sn = std::sin(phi);
    double l1 = m[0][0] * cs * cs + 2 * m[0][1] * sn * cs + m[1][1] * sn * sn;
    double l2 = m[0][0] * sn * sn - 2 * m[0][1] * sn * cs + m[1][1] * cs * cs;
    double b1 = m[0][2] * cs + m[1][2] * sn;
    double b2 = -m[0][2] * sn + m[1][2] * cs;
    const double k0 = m[2][2];
    if (std::fabs(l2) > std::fabs(l1)) {
        std::swap(l1, l2);
        std::swap(b1, b2);
        std::swap(w1, w2);
    }
    const double R = 0.5 * Length(box.Size());
    const double scale = std::fmax(std::fmax(std::fabs(l1) * R * R, std::fabs(b1) * R),
                                   std::fmax(std::fabs(b2) * R, std::fabs(k0)));
    if (!(scale > 0) || !std::isfinite(scale) || !(R > 0)) return out;
    const double tol = kRelZero * scale;
    auto addLine = [&](const Vec3& p, const Vec3& dir) {
        double t0 = -HUGE_VAL, t1 = HUGE_VAL;
        const Vec3 u = Normalize(dir);
        if (!ClipLineToBox(p, u, box, t0, t1)) return;
        Curve3 l = MakeLine(p, u);
        l.t0 = t0;
        l.t1 = t1;
        out.push_back(l);
    };
    if (std::fabs(l1) * R * R <= tol) {  // linear on the plane: 2 b1 σ + 2 b2 ρ + k = 0
        const double bb = b1 * b1 + b2 * b2;
        if (!(bb * R * R > tol * tol)) return out;
        const Vec3 p = o + (w1 * b1 + w2 * b2) * (-k0 / (2 * bb));
        addLine(p, w1 * (-b2) + w2 * b1);
        return out;
    }
    const double sc = -b1 / l1;  // centre along w1
    if (std::fabs(l2) * R * R <= tol) {
        const double k = k0 - b1 * b1 / l1;
        if (std::fabs(b2) * R <= tol) {  // parallel lines along w2: λ1 (σ − sc)² + k = 0
            const double r2 = -k / l1;
            if (std::fabs(k) <= tol) {
                if (tangent) *tangent = true;
                addLine(o + w1 * sc, w2);
            } else if (r2 > 0) {
                const double r = std::sqrt(r2);
                addLine(o + w1 * (sc - r), w2);
                addLine(o + w1 * (sc + r), w2);
            }
            return out;
        }
        // Parabola: ρ = −(λ1 σ'² + k)/(2 β2), σ' = σ − sc.
        Curve3 p;
        p.kind = CurveKind::kParabola;
        p.o = o + w1 * sc + w2 * (-k / (2 * b2));
        p.u = w1;
        p.v = w2 * (-l1 / (2 * b2));
        // |σ'| beyond 2R + |distance of the vertex from the box centre| leaves the box.
        const double span = 2 * R + Length(p.o - c);
        p.t0 = -span;
        p.t1 = span;
        out.push_back(p);
        return out;
    }
    const double rc = -b2 / l2;
    const double k = k0 - b1 * b1 / l1 - b2 * b2 / l2;
    const Vec3 centre = o + w1 * sc + w2 * rc;
    if (l1 * l2 > 0) {
        const double a2 = -k / l1, bq = -k / l2;
        if (std::fabs(k) <= tol || !(a2 > 0) || !(bq > 0)) return out;  // a point or nothing
        Curve3 e;
        e.kind = CurveKind::kEllipse;
        e.o = centre;
        e.u = w1 * std::sqrt(a2);
        e.v = w2 * std::sqrt(bq);
        e.t0 = 0;
        e.t1 = 2 * M_PI;
        out.push_back(e);
        return out;
    }
    if (std::fabs(k) <= tol) {  // λ1 σ² + λ2 ρ² = 0: ρ = ± m σ
        const double mm = std::sqrt(-l1 / l2);
        addLine(centre, w1 + w2 * mm);
        addLine(centre, w1 - w2 * mm);
        return out;
    }
    // Hyperbola. With −k/λ1 > 0: σ = ±a cosh τ, ρ = b sinh τ; otherwise the roles swap.
    Vec3 axisCosh = w1, axisSinh = w2;
    double a = std::sqrt(std::fabs(k / l1)), b = std::sqrt(std::fabs(k / l2));
    if (!(-k / l1 > 0)) {
        std::swap(axisCosh, axisSinh);
        std::swap(a, b);
    }
    const double reach = 2 * R + Length(centre - c);
    const double T = std::fmin(std::acosh(std::fmax(1.0, reach / a)), std::asinh(reach / b));
    for (int s = -1; s <= 1; s += 2) {
        Curve3 hcur;
        hcur.kind = CurveKind::kHyperbola;
        hcur.o = centre;
        hcur.u = axisCosh * (a * s);
        hcur.v = axisSinh * b;
        hcur.t0 = -T;
        hcur.t1 = T;
        out.push_back(hcur);
    }
    return out;
}

}  // namespace quadrix::draw
