// Stage (a''), bounds.h: the box of a body of ONE quadric and planes from its critical points.
//
// Why: a BRL-CAD tgc/rcc (and every capped cylinder or cone of a CAD model) is one quadric cut by
// two planes; seen obliquely it has no analytic box (stage a) and the convex relaxation (b1) costs
// about a millisecond each, which made a 2,200-primitive helicopter flatten in 3 s (issue 20).
//
// The set S = {f <= 0} ∩ {p_i <= 0} is intersected with the region box (B0's faces where they are
// finite, else the search limit), so it is compact, and the maximum of a coordinate e·x over S is
// attained at a point where e is a combination of the gradients of the active constraints (the
// Fritz John conditions, which also cover singular points). With one quadric and planes the
// active sets give finitely many candidates, each by a linear solve and at most one quadratic:
//   {p_i, p_j, p_k}  a vertex (three planes);
//   {f, p_i, p_j}    the edge of two planes cut by the quadric (a line ∩ f: ≤ 2 points);
//   {f, p_i}         on the conic f ∩ p_i, where ∇f's projection on the plane is ∥ e's: in plane
//                    coordinates t, (M t + m) ∥ g is the line g⊥·(M t + m) = 0, cut by the conic;
//   {f}              where ∇f = 2(A x + b) ∥ e: two linear equations (a line), cut by f;
//   the apex         of a cone (A x + b = 0 on f = 0), where ∇f vanishes.
// Critical points that are not isolated (a ruling of a cylinder ⊥ e, a face ⊥ e) form sets on
// which e·x is constant, whose feasible ends are candidates of a larger active set. So the box of
// the feasible candidates is S's box. It is used only when that is safe:
//   - a feasible candidate on a face of the search region means S is unbounded there: nullopt;
//   - a candidate that is neither clearly feasible (residuals within 1e-8 of the terms' size)
//     nor clearly infeasible (beyond 1e-5), or an ill-conditioned solve that is nearly feasible,
//     means rounding could decide: nullopt;
//   - no feasible candidate (empty or degenerate): nullopt;
//   - A must be positive semidefinite or well conditioned (a pair of planes as a quadric has
//     singular lines that are not candidates): otherwise nullopt.
// On nullopt the later stages decide as before. The box is widened by 1e-7 of its coordinates
// and size (the candidates' rounding). About 20-40 µs a body.
#include <cmath>
#include <optional>

#include "quadrix/flatten/bounds_internal.h"

namespace quadrix::bounds_detail {

namespace {

struct Plane3 {
    Vec3 n;
    double k;
    bool artificial;
};

double Norm1(const Vec3& x) { return std::fabs(x.x) + std::fabs(x.y) + std::fabs(x.z); }

Vec3 Times(const double a[3][3], const Vec3& x) {
    return {a[0][0] * x.x + a[0][1] * x.y + a[0][2] * x.z,
            a[1][0] * x.x + a[1][1] * x.y + a[1][2] * x.z,
            a[2][0] * x.x + a[2][1] * x.y + a[2][2] * x.z};
}

// Solves [r0; r1; r2] x = (c0, c1, c2) by Cramer's rule; false when the determinant is zero or
// not finite. `conditioned` is false when |det| < 1e-6 |r0||r1||r2|.
bool Solve3(const Vec3& r0, const Vec3& r1, const Vec3& r2, double c0, double c1, double c2,
            Vec3& x, bool& conditioned) {
    const Vec3 a = Cross(r1, r2), b = Cross(r2, r0), c = Cross(r0, r1);
    const double det = Dot(r0, a);
    if (det == 0 || !std::isfinite(det)) return false;
    conditioned = std::fabs(det) >= 1e-6 * Length(r0) * Length(r1) * Length(r2);
    x = (a * c0 + b * c1 + c * c2) / det;
    return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
}

class CriticalPoints {
  public:
    CriticalPoints(const InsideFn& q, std::vector<Plane3> planes)
        : q_(q), planes_(std::move(planes)) {}

    std::optional<Box3> Run() {
        if (!QuadricSupported()) return std::nullopt;
        const std::size_t m = planes_.size();
        for (std::size_t i = 0; i < m && ok_; ++i)
            for (std::size_t j = i + 1; j < m && ok_; ++j) {
                for (std::size_t k = j + 1; k < m && ok_; ++k) Vertex(i, j, k);
                Edge(i, j);
            }
        for (std::size_t i = 0; i < m && ok_; ++i)
            for (int axis = 0; axis < 3 && ok_; ++axis) OnConic(i, axis);
        for (int axis = 0; axis < 3 && ok_; ++axis) OnQuadric(axis);
        Apex();
        if (!ok_ || box_.Empty()) return std::nullopt;
        for (int i = 0; i < 3; ++i) {
            const double size = box_.hi[i] - box_.lo[i];
            box_.lo[i] -= 1e-7 * (std::fabs(box_.lo[i]) + size) + 1e-300;
            box_.hi[i] += 1e-7 * (std::fabs(box_.hi[i]) + size) + 1e-300;
        }
        return box_;
    }

  private:
    bool QuadricSupported() {
        // Positive semidefinite (ellipsoids, elliptic cylinders and paraboloids, any rank), or
        // invertible with a pivot ratio below 1e8 (cones, hyperboloids).
        double norm = 0;
        for (auto& row : q_.a)
            for (double v : row) norm = std::fmax(norm, std::fabs(v));
        if (!(norm > 0)) return false;
        if (q_.lamMin >= -1e-12 * norm) return true;
        const Vec3 r0{q_.a[0][0], q_.a[0][1], q_.a[0][2]}, r1{q_.a[1][0], q_.a[1][1], q_.a[1][2]},
            r2{q_.a[2][0], q_.a[2][1], q_.a[2][2]};
        const double det = Dot(r0, Cross(r1, r2));
        return std::fabs(det) >= 1e-8 * Length(r0) * Length(r1) * Length(r2);
    }

    // The largest residual of x over the constraints, relative to the size of their terms, and
    // whether x lies on a face of the search region.
    double Residual(const Vec3& x, bool* onArtificial) const {
        double worst = -kInf;
        for (const Plane3& p : planes_) {
            const double v = Dot(p.n, x) + p.k;
            const double mag = std::fabs(p.k) + Length(p.n) * Norm1(x) + 1e-300;
            worst = std::fmax(worst, v / mag);
            if (p.artificial && std::fabs(v) <= 1e-6 * mag) *onArtificial = true;
        }
        const double px[3] = {x.x, x.y, x.z};
        const Local l = EvaluateLocal(q_, px);
        return std::fmax(worst, l.v / (l.mag + 1e-300));
    }

    void Consider(const Vec3& x, bool conditioned) {
        if (!ok_) return;
        if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z))) {
            if (conditioned) ok_ = false;
            return;
        }
        bool onArtificial = false;
        const double r = Residual(x, &onArtificial);
        if (!conditioned) {
            if (r <= 1e-5) ok_ = false;  // ill-conditioned and nearly feasible: not trusted
            return;
        }
        if (r > 1e-5) return;  // clearly infeasible
        if (r > 1e-8 || onArtificial) {
            ok_ = false;  // rounding could decide, or S reaches the search region's face
            return;
        }
        box_.Extend(x);
    }

    // The points x0 + t d (d ≠ 0) where the quadric vanishes: a t² + 2 β t + γ = 0, by the
    // stable formula (a root from a ≈ 0, d nearly a null direction of A, is far away and
    // rejected as infeasible; the other is accurate).
    void LineCut(const Vec3& x0, const Vec3& d, bool conditioned) {
        const double a = Dot(d, Times(q_.a, d));
        const double beta = Dot(d, Times(q_.a, x0)) + q_.b[0] * d.x + q_.b[1] * d.y + q_.b[2] * d.z;
        const double px[3] = {x0.x, x0.y, x0.z};
        const double gamma = EvaluateAt(q_, px);
        if (a == 0) {
            if (beta != 0) Consider(x0 + d * (-gamma / (2 * beta)), conditioned);
            return;
        }
        const double disc = beta * beta - a * gamma;
        if (disc < 0) {
            // Tangent up to rounding: the double root.
            if (disc >= -1e-12 * (beta * beta + std::fabs(a * gamma)))
                Consider(x0 + d * (-beta / a), conditioned);
            return;
        }
        const double qv = -(beta + std::copysign(std::sqrt(disc), beta));
        Consider(x0 + d * (qv / a), conditioned);
        Consider(qv != 0 ? x0 + d * (gamma / qv) : x0, conditioned);
    }

    void Vertex(std::size_t i, std::size_t j, std::size_t k) {
        const Plane3 &a = planes_[i], &b = planes_[j], &c = planes_[k];
        Vec3 x;
        bool conditioned = true;
        if (!Solve3(a.n, b.n, c.n, -a.k, -b.k, -c.k, x, conditioned)) return;
        const bool artificial = a.artificial || b.artificial || c.artificial;
        if (!conditioned && artificial) return;
        Consider(x, conditioned);
    }

    void Edge(std::size_t i, std::size_t j) {
        const Plane3 &a = planes_[i], &b = planes_[j];
        const Vec3 d = Cross(a.n, b.n);
        Vec3 x0;
        bool conditioned = true;
        if (!Solve3(a.n, b.n, d, -a.k, -b.k, 0, x0, conditioned)) return;
        if (!conditioned && (a.artificial || b.artificial)) return;
        LineCut(x0, d, conditioned);
    }

    // {f, p_i}: in plane coordinates x = p0 + U t (U orthonormal), q(t) = tᵀMt + 2mᵀt + c.
    void OnConic(std::size_t i, int axis) {
        const Plane3& p = planes_[i];
        const double nn = Dot(p.n, p.n);
        if (!(nn > 0)) return;
        const Vec3 n = p.n / std::sqrt(nn);
        const Vec3 helper = std::fabs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        const Vec3 uc = Cross(n, helper);
        const Vec3 u = uc / Length(uc);
        const Vec3 v = Cross(n, u);
        const Vec3 p0 = p.n * (-p.k / nn);
        Vec3 e;
        e[axis] = 1;
        const double g[2] = {Dot(u, e), Dot(v, e)};
        if (std::hypot(g[0], g[1]) <= 1e-9) return;  // the face is ⊥ e: covered by its edges
        const Vec3 au = Times(q_.a, u), av = Times(q_.a, v);
        const double mm[2][2] = {{Dot(u, au), Dot(u, av)}, {Dot(v, au), Dot(v, av)}};
        const Vec3 grad0 = Times(q_.a, p0) + Vec3{q_.b[0], q_.b[1], q_.b[2]};
        const double mv[2] = {Dot(u, grad0), Dot(v, grad0)};
        const double gp[2] = {-g[1], g[0]};
        // w·t + s = 0 with w = M g⊥, s = g⊥·m.
        const double w[2] = {mm[0][0] * gp[0] + mm[0][1] * gp[1],
                             mm[1][0] * gp[0] + mm[1][1] * gp[1]};
        const double s = gp[0] * mv[0] + gp[1] * mv[1];
        const double wn = std::hypot(w[0], w[1]);
        double mNorm = 0;
        for (auto& row : mm)
            for (double x : row) mNorm = std::fmax(mNorm, std::fabs(x));
        if (!(wn > 1e-9 * mNorm) || !(mNorm > 0)) return;  // not isolated, or none
        const double t0[2] = {-s * w[0] / (wn * wn), -s * w[1] / (wn * wn)};
        const double dir[2] = {-w[1] / wn, w[0] / wn};
        LineCut(p0 + u * t0[0] + v * t0[1], u * dir[0] + v * dir[1], true);
    }

    // {f}: rows j, l ≠ axis of A x + b = 0.
    void OnQuadric(int axis) {
        const int j = (axis + 1) % 3, l = (axis + 2) % 3;
        const Vec3 rj{q_.a[j][0], q_.a[j][1], q_.a[j][2]}, rl{q_.a[l][0], q_.a[l][1], q_.a[l][2]};
        const Vec3 d = Cross(rj, rl);
        if (!(Length(d) > 1e-9 * Length(rj) * Length(rl))) return;  // not isolated
        Vec3 x0;
        bool conditioned = true;
        if (!Solve3(rj, rl, d, -q_.b[j], -q_.b[l], 0, x0, conditioned)) return;
        LineCut(x0, d, conditioned);
    }

    void Apex() {
        if (!ok_ || q_.lamMin >= 0) return;  // a semidefinite quadric has no isolated apex
        const Vec3 r0{q_.a[0][0], q_.a[0][1], q_.a[0][2]}, r1{q_.a[1][0], q_.a[1][1], q_.a[1][2]},
            r2{q_.a[2][0], q_.a[2][1], q_.a[2][2]};
        Vec3 c;
        bool conditioned = true;
        if (!Solve3(r0, r1, r2, -q_.b[0], -q_.b[1], -q_.b[2], c, conditioned)) return;
        const double pc[3] = {c.x, c.y, c.z};
        const Local l = EvaluateLocal(q_, pc);
        if (std::fabs(l.v) <= 1e-8 * (l.mag + 1e-300)) Consider(c, conditioned);
    }

    const InsideFn& q_;
    std::vector<Plane3> planes_;
    Box3 box_;
    bool ok_ = true;
};

}  // namespace

std::optional<Box3> CriticalPointBox(const std::vector<InsideFn>& shaping, const Box3& b0,
                                     const BoundsOptions& options) {
    constexpr std::size_t kMaxPlanes = 16;
    const InsideFn* quadric = nullptr;
    std::vector<Plane3> planes;
    for (const InsideFn& f : shaping) {
        if (!f.isPlane) {
            if (quadric) return std::nullopt;  // two quadrics: the relaxation
            quadric = &f;
            continue;
        }
        planes.push_back({{2 * f.b[0], 2 * f.b[1], 2 * f.b[2]}, f.k, false});
    }
    if (!quadric || planes.size() > kMaxPlanes) return std::nullopt;
    const double limit = options.searchLimit;
    for (int i = 0; i < 3; ++i) {
        Vec3 e;
        e[i] = 1;
        const bool hiReal = b0.hi[i]<limit, loReal = b0.lo[i]> - limit;
        planes.push_back({e, -(hiReal ? b0.hi[i] : limit), !hiReal});
        planes.push_back({-e, loReal ? b0.lo[i] : -limit, !loReal});
    }
    return CriticalPoints(*quadric, std::move(planes)).Run();
}

}  // namespace quadrix::bounds_detail
