#include "quadrix/engines/scanline/coefficients.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "quadrix/math/dense_solve.h"

namespace quadrix::scanline {

Line2 LineOfPlanes(const Plane& p1, const Plane& p2) {
    // C_p2·P1 − C_p1·P2 has no z term (4.7).
    return {p1.a * p2.c - p2.a * p1.c, p1.b * p2.c - p2.b * p1.c, p1.d * p2.c - p2.d * p1.c};
}

Conic2 ConicOfPlaneQuadric(const Plane& p, const Quadric& q) {
    // Derivation: with w = A_p x + B_p y + D_p and z = −w/C_p,
    //   C_p² Q = C_p²(A x² + B y² + 2D xy + 2G x + 2H y + K) + C w² − 2 C_p w (F x + E y + J);
    // (4.8) is half of that, term by term.
    const double ap = p.a, bp = p.b, cp = p.c, dp = p.d;
    const double cp2 = cp * cp;
    Conic2 c;
    c.a = 0.5 * (ap * ap * q.C() + cp2 * q.A()) - ap * cp * q.F();
    c.b = 0.5 * (bp * bp * q.C() + cp2 * q.B()) - bp * cp * q.E();
    c.c = ap * bp * q.C() - ap * cp * q.E() - bp * cp * q.F() + cp2 * q.D();
    c.d = ap * dp * q.C() - ap * cp * q.J() - dp * cp * q.F() + cp2 * q.G();
    c.e = bp * dp * q.C() - bp * cp * q.J() - dp * cp * q.E() + cp2 * q.H();
    c.f = 0.5 * (dp * dp * q.C() + cp2 * q.K()) - dp * cp * q.J();
    return c;
}

Plane LimbPlane(const Quadric& q) { return {q.F(), q.E(), q.C(), q.J()}; }

Conic2 LimbConic(const Quadric& q) {
    // (4.8) with the limb plane <F E C J>, every coefficient divided by C (4.12).
    Conic2 c;
    c.a = 0.5 * (q.A() * q.C() - q.F() * q.F());
    c.b = 0.5 * (q.B() * q.C() - q.E() * q.E());
    c.c = q.D() * q.C() - q.E() * q.F();
    c.d = q.G() * q.C() - q.F() * q.J();
    c.e = q.H() * q.C() - q.E() * q.J();
    c.f = 0.5 * (q.K() * q.C() - q.J() * q.J());
    return c;
}

bool LimbExists(const Quadric& q) { return q.C() > 0; }

std::optional<Vec3> IntersectThreePlanes(const Plane& p1, const Plane& p2, const Plane& p3) {
    double m[3][3] = {{p1.a, p1.b, p1.c}, {p2.a, p2.b, p2.c}, {p3.a, p3.b, p3.c}};
    double r[3] = {-p1.d, -p2.d, -p3.d}, x[3];
    // Zero test: a pivot within the elimination's rounding (a few ulps of the largest
    // coefficient) means the planes share a line or are parallel (all coefficients zero too).
    // x = (r0 − m02 z − m01 y) / m00: the decreasing order of back substitution.
    if (!SolveDense(3, m, r, x, 64 * kUnit * MaxAbsEntry(3, m), BackOrder::kDecreasing))
        return std::nullopt;
    return Vec3{x[0], x[1], x[2]};
}

Quadratic1 LineConicInX(const Line2& l, const Conic2& c) {
    // y = −(a_l x + c_l)/b_l into the conic, times b_l² (4.15).
    const double al = l.a, bl = l.b, cl = l.c;
    return {bl * (bl * c.a - al * c.c) + al * al * c.b,
            cl * (2 * al * c.b - bl * c.c) + bl * (bl * c.d - al * c.e),
            bl * (bl * c.f - cl * c.e) + cl * cl * c.b};
}

Quadratic1 LineConicInY(const Line2& l, const Conic2& c) {
    // x = −(b_l y + c_l)/a_l into the conic, times a_l² (4.16).
    const double al = l.a, bl = l.b, cl = l.c;
    return {bl * (bl * c.a - al * c.c) + al * al * c.b,
            cl * (2 * bl * c.a - al * c.c) - al * (bl * c.d - al * c.e),
            al * (al * c.f - cl * c.d) + cl * cl * c.a};
}

Quadratic1 ConicAtY(const Conic2& c, double y) {
    return {c.a, c.c * y + c.d, (c.b * y + c.e) * y + c.f};
}
Quadratic1 ConicAtX(const Conic2& c, double x) {
    return {c.b, c.c * x + c.e, (c.a * x + c.d) * x + c.f};
}

Quadratic1 VextrmQuadratic(const Conic2& c) {
    return {c.c * c.c - 4 * c.a * c.b, 2 * c.c * c.d - 4 * c.a * c.e, c.d * c.d - 4 * c.a * c.f};
}
Quadratic1 HextrmQuadratic(const Conic2& c) {
    return {c.c * c.c - 4 * c.a * c.b, 2 * c.c * c.e - 4 * c.b * c.d, c.e * c.e - 4 * c.b * c.f};
}

Line2 InsertLine(const Conic2& c) { return {2 * c.a, c.c, c.d}; }
Line2 HextrmLine(const Conic2& c) { return {c.c, 2 * c.b, c.e}; }

bool PlaneIsEdgeOn(const Plane& p) {
    return std::fabs(p.c) <= 64 * kUnit * (std::fabs(p.a) + std::fabs(p.b) + std::fabs(p.c));
}

bool QuadricIsViewCylinder(const Quadric& q, double length) {
    const double l = std::max(length, 1.0), l2 = l * l;
    double zTerms = (std::fabs(q.C()) + 2 * std::fabs(q.E()) + 2 * std::fabs(q.F())) * l2 +
                    2 * std::fabs(q.J()) * l;
    double others = (std::fabs(q.A()) + std::fabs(q.B()) + 2 * std::fabs(q.D())) * l2 +
                    2 * (std::fabs(q.G()) + std::fabs(q.H())) * l + std::fabs(q.K());
    return zTerms <= 64 * kUnit * others;
}

Roots1 SolveQuadratic1(const Quadratic1& q, double relError) {
    Roots1 r;
    if (!std::isfinite(q.a) || !std::isfinite(q.b) || !std::isfinite(q.c)) return r;
    const double scale = std::max({std::fabs(q.a), std::fabs(q.b), std::fabs(q.c)});
    if (scale == 0) return r;
    if (std::fabs(q.a) <= relError * scale) {  // linear within the coefficients' own error
        if (std::fabs(q.b) <= relError * scale) return r;
        r.kind = Roots1::kLinear;
        r.r0 = r.r1 = -q.c / q.b;
        return r;
    }
    double disc = q.b * q.b - 4 * q.a * q.c;
    double err = (2 * relError + 4 * kUnit) * (q.b * q.b + 4 * std::fabs(q.a * q.c));
    if (std::fabs(disc) <= err) {
        r.kind = Roots1::kDouble;
        r.r0 = r.r1 = -q.b / (2 * q.a);
        return r;
    }
    if (disc < 0) return r;
    double s = std::sqrt(disc);
    double h = -0.5 * (q.b + (q.b >= 0 ? s : -s));  // no cancellation
    double t0 = h / q.a, t1 = q.c / h;
    if (t0 > t1) std::swap(t0, t1);
    r.kind = Roots1::kTwo;
    r.r0 = t0;
    r.r1 = t1;
    return r;
}

double PlaneErrorEstimate(const Plane& p, const Vec3& x, double pointError) {
    double terms =
        std::fabs(p.a * x.x) + std::fabs(p.b * x.y) + std::fabs(p.c * x.z) + std::fabs(p.d);
    double grad = std::fabs(p.a) + std::fabs(p.b) + std::fabs(p.c);
    return 8 * kUnit * terms + grad * pointError;
}

bool SatisfiesPlane(const Plane& p, const Vec3& x, double pointError) {
    return p.Evaluate(x) <= PlaneErrorEstimate(p, x, pointError);
}

double QuadricErrorEstimate(const Quadric& q, const Vec3& x, double pointError) {
    const double ax = std::fabs(x.x), ay = std::fabs(x.y), az = std::fabs(x.z);
    double terms = std::fabs(q.A()) * ax * ax + std::fabs(q.B()) * ay * ay +
                   std::fabs(q.C()) * az * az + 2 * std::fabs(q.D()) * ax * ay +
                   2 * std::fabs(q.E()) * ay * az + 2 * std::fabs(q.F()) * ax * az +
                   2 * std::fabs(q.G()) * ax + 2 * std::fabs(q.H()) * ay +
                   2 * std::fabs(q.J()) * az + std::fabs(q.K());
    Vec3 g = q.Gradient(x);
    double grad = std::fabs(g.x) + std::fabs(g.y) + std::fabs(g.z);
    return 16 * kUnit * terms + grad * pointError;
}

bool SatisfiesQuadric(const Quadric& q, const Vec3& x, double pointError) {
    return q.Evaluate(x) <= QuadricErrorEstimate(q, x, pointError);
}

bool VerticesCoincide(double x1, double y1, double x2, double y2) {
    double tol =
        1e-9 * (1 + std::max({std::fabs(x1), std::fabs(y1), std::fabs(x2), std::fabs(y2)}));
    return std::fabs(x1 - x2) <= tol && std::fabs(y1 - y2) <= tol;
}

std::vector<Vec3> LineConicIntersections(const Line2& l, const Conic2& c) {
    std::vector<Vec3> out;
    // The coefficients of (4.15)/(4.16) are sums of triple products: relative error ~1e-13 is a
    // generous estimate for inputs that are themselves rounded results of (4.7)/(4.8).
    constexpr double kRel = 1e-12;
    if (std::fabs(l.b) > std::fabs(l.a)) {
        Roots1 r = SolveQuadratic1(LineConicInX(l, c), kRel);
        if (r.kind != Roots1::kTwo && r.kind != Roots1::kLinear) return out;
        for (double x : {r.r0, r.r1}) {
            out.push_back({x, -(l.a * x + l.c) / l.b, 0});
            if (r.kind == Roots1::kLinear) break;
        }
    } else if (l.a != 0) {
        Roots1 r = SolveQuadratic1(LineConicInY(l, c), kRel);
        if (r.kind != Roots1::kTwo && r.kind != Roots1::kLinear) return out;
        for (double y : {r.r0, r.r1}) {
            out.push_back({-(l.b * y + l.c) / l.a, y, 0});
            if (r.kind == Roots1::kLinear) break;
        }
    }
    return out;
}

}  // namespace quadrix::scanline
