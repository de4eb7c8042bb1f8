// Stage (a'') of bounds.h: the box of a body of ONE convex quadric and planes from the critical
// points of the coordinates, certified by the relaxation's weak-duality bound.
//
// Why: a BRL-CAD rcc/tgc (every capped cylinder or cone of a CAD model) is one quadric cut by two
// planes. Seen obliquely it has no analytic box (stage a), and the interior-point method of the
// relaxation (b1) costs about a millisecond per body: 90 % of the flatten time of a 2,200-body
// model (issue 20). Its extremes are known in closed form.
//
// The set. S = {f <= 0} ∩ {p_j <= 0} ∩ R, where f is a positive semidefinite quadric (ellipsoid,
// elliptic cylinder, paraboloid) or a nappe (one nappe of a cone or of a two-sheet hyperboloid,
// bounds_internal.h), the p_j are planes and R is the search region (B0's faces where they are
// finite, else the faces at ±searchLimit, cut for a capped cylinder to the box of a ball proven
// to hold it: CylinderBootstrap below). S is convex and compact, so the maximum of e·x
// (e = ±e_i) is attained, at a point where e = Σ λ_j ∇g_j over the active constraints g_j with
// λ >= 0 (KKT; the planes and a convex quadric satisfy Slater's condition when S has an interior).
// With one quadric f and planes the active sets give finitely many isolated candidates, each from
// a linear solve and at most one quadratic:
//   {p_i, p_j, p_k}  a vertex: three planes;
//   {f, p_i, p_j}    the edge line of two planes cut by f (<= 2 points);
//   {f, p_i}         on the conic f ∩ p_i: ∇f ∈ span(e, n_i), i.e. (A x + b)·w = 0 with
//                    w = e × n_i, a second plane: a line, cut by f;
//   {f}              ∇f = 2(A x + b) ∥ e: rows j, k ≠ i of A x + b = 0, a line, cut by f;
//   the apex         of a cone (∇f = 0 on f = 0; its certificate fails, so the stage declines
//                    when the apex is an extreme).
// Critical points that are not isolated (a generator of a cylinder ⊥ e, a face ⊥ e) form sets on
// which e·x is constant; their ends are candidates of a larger active set, so they are skipped.
// The candidates satisfying every constraint (to rounding, or to 1e-9 of the region in distance:
// kFeasible) are kept; per side the best one is the candidate extreme x̂.
//
// The certificate. Rounding in the solves, a tolerance in the feasibility test or a missed
// candidate must not make the box too small, so the box is not the candidates' box: x̂ with
// multipliers λ >= 0 fitted to e over the constraints active there (NonNegativeCombination) goes
// through the relaxation's Lagrangian bound (CertifyExtremes, bounds_relaxation.cpp), which holds
// for ANY x̂ and λ >= 0, with rounding allowances. The enumeration only has to be right for the
// bound to be tight; to keep boxes as tight as the relaxation's, the stage declines (nullopt: the
// later stages decide) when a certified side lies more than 1e-7 × (size + |coordinate|) from its
// candidate, 1e-5 for a nappe (kTight: a candidate was missed, or the KKT multipliers do not
// exist, as at an apex), beyond the certificate's own allowance for a nappe's rounding-level
// neck (which it adds by construction: a long slim cone far from the origin, the helicopter's
// tail boom, has a neck allowance of ~2e-5 of its box, and the relaxation it was sent to, at
// ~1 ms, adds the same). It also declines when
//   - the body has no quadric, two or more, a non-convex one, or more than 16 planes;
//   - a feasible candidate lies on a face of R that is not B0's (S is unbounded, or it leaves
//     the bootstrap box, which would be a bug: then the later stages decide safely);
//   - no candidate is feasible (empty or flat sets: the relaxation proves emptiness);
//   - a nappe is not separated from its twin by one of the planes (the certificate's supporting
//     plane needs it; capped cones are separated by their small-end cap).
// Cost: ~10-20 µs for a capped cylinder or cone (56 vertex solves, 28 edges, 24 conics, the
// certificate), where the interior-point method took ~1 ms. A capped cylinder whose region is its
// bootstrap box enumerates only its own planes and B0's faces (the bootstrap box's faces lie apart
// from the body: CriticalPoints), no vertex, one edge and six conics: about a third fewer
// instructions for the 1,024 bodies the 10,131-body helicopter bounds itself.
#include <algorithm>
#include <cmath>
#include <optional>

#include "quadrix/flatten/bounds_internal.h"
#include "quadrix/math/symmetric_eigen.h"

namespace quadrix::bounds_detail {

namespace {

constexpr std::size_t kMaxPlanes = 16;
// A candidate is kept when every constraint holds at it to within its rounding (1024 eps of the
// terms' magnitude, room for the conditioning of the solves) or, where the region is bounded by
// B0 or the cylinder bootstrap (not by the search limit), to within 1e-9 of its diameter in
// distance (value / |gradient|). Not a relative residual: a thin cylinder far from the origin
// has terms ~M² and a value ~r² on its axis, so a residual of 1e-9 M² accepts points many radii
// away (and a candidate beyond the body on the region's face declares it unbounded).
constexpr double kRounding = 1024 * kEps, kFeasible = 1e-9;
// Certified side vs candidate, relative to size + |coordinate|: a missed candidate or a wrong
// multiplier leaves gaps of percents; what is left is the certificate's rounding allowance. That
// allowance is the precision of the literal itself: a quadric far from the origin (device space)
// has normalised coefficients whose terms, of magnitude `mag`, cancel to its value, so its
// surface is known to ~eps·mag/|∇f|, ~1e-8 of the coordinates for a cylinder 10⁴ px deep. A
// nappe's certificate also allows for a rounding-level one-sheet neck of radius ~sqrt(eps) ×
// size near the apex (bounds_relaxation.cpp Certify): up to ~2e-6, as in the relaxation.
constexpr double kTight = 1e-7, kTightNappe = 1e-5;

double Frobenius(const double a[3][3]) {
    double s = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s += a[i][j] * a[i][j];
    return std::sqrt(s);
}

Vec3 Times(const double a[3][3], const Vec3& x) {
    return {a[0][0] * x.x + a[0][1] * x.y + a[0][2] * x.z,
            a[1][0] * x.x + a[1][1] * x.y + a[1][2] * x.z,
            a[2][0] * x.x + a[2][1] * x.y + a[2][2] * x.z};
}

Vec3 Row(const double a[3][3], int i) { return {a[i][0], a[i][1], a[i][2]}; }

bool Finite(const Vec3& x) {
    return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
}

// Solves the rows r_i · x = c_i by Cramer's rule; false when the determinant vanishes (up to
// 1e-12 of the rows' lengths' product: the point would be meaningless) or x is not finite.
bool Solve3(const Vec3& r0, const Vec3& r1, const Vec3& r2, double c0, double c1, double c2,
            Vec3& x) {
    const Vec3 a = Cross(r1, r2), b = Cross(r2, r0), c = Cross(r0, r1);
    const double det = Dot(r0, a);
    if (!(std::fabs(det) > 1e-12 * Length(r0) * Length(r1) * Length(r2))) return false;
    x = (a * c0 + b * c1 + c * c2) / det;
    return Finite(x);
}

class CriticalPoints {
  public:
    // cons: the literals then the region's six faces (CandidateExtreme's order); `quadric` the
    // index of the quadric; artificial[j]: constraint j is a face at the search limit or of the
    // bootstrap box; apart[j]: a face of the bootstrap box, which lies apart from the body (the
    // box holds a ball that holds the body, grown by 1e-6 of its radius, a thousand times the
    // feasibility tolerance of 1e-9 of the region's diameter), so active sets including it yield
    // no feasible candidate and it takes no part in the enumeration; it stays a constraint for
    // the feasibility test and the multipliers. (Only a body with a wedge sharp enough to pass a
    // point that far away within the tolerance of each constraint could tell: there the full
    // enumeration would decline and the later stages decide, while this one still certifies its
    // box, which holds the body either way.)
    CriticalPoints(std::vector<InsideFn> cons, int quadric, std::vector<char> artificial,
                   const std::vector<char>& apart, double diameter)
        : cons_(std::move(cons)),
          artificial_(std::move(artificial)),
          quadric_(quadric),
          diameter_(diameter) {
        for (std::size_t j = 0; j < cons_.size(); ++j)
            if (cons_[j].isPlane && !apart[j]) planes_.push_back(static_cast<int>(j));
    }

    // The candidate extremes of the six sides; false when the stage must decline.
    bool Run(CandidateExtreme extremes[6], Vec3& interior) {
        const std::size_t m = planes_.size();
        for (std::size_t i = 0; i < m; ++i)
            for (std::size_t j = i + 1; j < m; ++j) {
                for (std::size_t k = j + 1; k < m; ++k) Vertex(planes_[i], planes_[j], planes_[k]);
                Edge(planes_[i], planes_[j]);
            }
        for (int p : planes_)
            for (int axis = 0; axis < 3; ++axis) OnConic(p, axis);
        for (int axis = 0; axis < 3; ++axis) OnQuadric(axis);
        Apex();
        if (unbounded_ || count_ == 0) return false;
        interior = sum_ / static_cast<double>(count_);
        for (int side = 0; side < 6; ++side) {
            extremes[side].x = best_[side];
            extremes[side].lambda = Multipliers(side, best_[side]);
        }
        return true;
    }

    double Value(int side) const { return bestValue_[side]; }

  private:
    Vec3 Normal(int j) const { return {2 * cons_[j].b[0], 2 * cons_[j].b[1], 2 * cons_[j].b[2]}; }

    // A point x; kept when every constraint holds at it (kRounding, kFeasible).
    void Consider(const Vec3& x) {
        if (!Finite(x)) return;
        const double p[3] = {x.x, x.y, x.z};
        bool onArtificial = false;
        for (std::size_t j = 0; j < cons_.size(); ++j) {
            const Local l = EvaluateLocal(cons_[j], p);
            const double grad = std::sqrt(l.g[0] * l.g[0] + l.g[1] * l.g[1] + l.g[2] * l.g[2]);
            const double tol = std::fmax(kRounding * l.mag, kFeasible * grad * diameter_);
            if (!(l.v <= tol)) return;
            onArtificial |= artificial_[j] && l.v >= -tol;
        }
        unbounded_ |= onArtificial;
        ++count_;
        sum_ = sum_ + x;
        for (int side = 0; side < 6; ++side) {
            const double v = side % 2 ? x[side / 2] : -x[side / 2];
            if (v > bestValue_[side]) {
                bestValue_[side] = v;
                best_[side] = x;
            }
        }
    }

    // The points x0 + t d where the quadric vanishes: α t² + 2 β t + γ = 0 by the stable
    // formula (with α ≈ 0, d nearly a null direction of A, one root is far away: infeasible).
    void LineCut(const Vec3& x0, const Vec3& d) {
        const InsideFn& q = cons_[quadric_];
        const double alpha = Dot(d, Times(q.a, d));
        const double beta = Dot(d, Times(q.a, x0)) + q.b[0] * d.x + q.b[1] * d.y + q.b[2] * d.z;
        const double p[3] = {x0.x, x0.y, x0.z};
        const double gamma = EvaluateAt(q, p);
        if (alpha == 0) {
            if (beta != 0) Consider(x0 + d * (-gamma / (2 * beta)));
            return;
        }
        double disc = beta * beta - alpha * gamma;
        if (disc < 0) {
            // Tangent up to rounding: the double root (the feasibility test judges it).
            if (!(disc >= -1e-12 * (beta * beta + std::fabs(alpha * gamma)))) return;
            disc = 0;
        }
        const double root = -(beta + std::copysign(std::sqrt(disc), beta));
        Consider(x0 + d * (root / alpha));
        if (root != 0) Consider(x0 + d * (gamma / root));
    }

    void Vertex(int i, int j, int k) {
        Vec3 x;
        if (Solve3(Normal(i), Normal(j), Normal(k), -cons_[i].k, -cons_[j].k, -cons_[k].k, x))
            Consider(x);
    }

    // The line through two planes, x0 + t d with d = n_i × n_j.
    void Edge(int i, int j) {
        const Vec3 ni = Normal(i), nj = Normal(j), d = Cross(ni, nj);
        Vec3 x0;
        if (Solve3(ni, nj, d, -cons_[i].k, -cons_[j].k, 0, x0)) LineCut(x0, d);
    }

    // Critical points of x_axis on the conic f ∩ p_i: (A x + b)·w = 0, w = e × n_i.
    void OnConic(int i, int axis) {
        const Vec3 n = Normal(i);
        Vec3 e;
        e[axis] = 1;
        const Vec3 w = Cross(e, n);
        if (!(Length(w) > 1e-9 * Length(n))) return;  // the face is ⊥ e: its edges decide
        const InsideFn& q = cons_[quadric_];
        const Vec3 aw = Times(q.a, w);  // (A x + b)·w = aw·x + b·w (A symmetric)
        const Vec3 d = Cross(n, aw);
        if (!(Length(d) > 1e-9 * Length(n) * Length(aw))) return;  // not isolated, or none
        const double bw = q.b[0] * w.x + q.b[1] * w.y + q.b[2] * w.z;
        Vec3 x0;
        if (Solve3(n, aw, d, -cons_[i].k, -bw, 0, x0)) LineCut(x0, d);
    }

    // Critical points of x_axis on the quadric: rows j, k ≠ axis of A x + b = 0.
    void OnQuadric(int axis) {
        const InsideFn& q = cons_[quadric_];
        const int j = (axis + 1) % 3, k = (axis + 2) % 3;
        const Vec3 rj = Row(q.a, j), rk = Row(q.a, k), d = Cross(rj, rk);
        if (!(Length(d) > 1e-9 * Length(rj) * Length(rk))) return;  // not isolated
        Vec3 x0;
        if (Solve3(rj, rk, d, -q.b[j], -q.b[k], 0, x0)) LineCut(x0, d);
    }

    // The centre -A⁻¹b of an invertible A, a candidate when it lies on f (a cone's apex).
    void Apex() {
        const InsideFn& q = cons_[quadric_];
        Vec3 c;
        if (!Solve3(Row(q.a, 0), Row(q.a, 1), Row(q.a, 2), -q.b[0], -q.b[1], -q.b[2], c)) return;
        const double p[3] = {c.x, c.y, c.z};
        const Local l = EvaluateLocal(q, p);
        if (std::fabs(l.v) <= kRounding * l.mag + 1e-300) Consider(c);
    }

    // λ >= 0 over the (at most kMaxSurrogate) constraints most nearly active at x, fitted to e
    // (zero where no fit exists: the certificate is then loose and the stage declines).
    std::vector<double> Multipliers(int side, const Vec3& x) const {
        std::vector<double> lambda(cons_.size(), 0.0);
        const double p[3] = {x.x, x.y, x.z};
        std::vector<std::pair<double, int>> active;
        for (std::size_t j = 0; j < cons_.size(); ++j) {
            const Local l = EvaluateLocal(cons_[j], p);
            const double rel = std::fabs(l.v) / (l.mag + 1e-300);
            if (rel <= 1e-7) active.push_back({rel, static_cast<int>(j)});
        }
        std::sort(active.begin(), active.end());
        if (active.size() > static_cast<std::size_t>(kMaxSurrogate)) active.resize(kMaxSurrogate);
        double g[kMaxSurrogate][3], l[kMaxSurrogate] = {0, 0, 0, 0};
        double t[3] = {0, 0, 0};
        t[side / 2] = side % 2 ? 1 : -1;
        const int n = static_cast<int>(active.size());
        // Unit gradients: NonNegativeCombination's pivot threshold is absolute, and a quadric's
        // normalised coefficients can be tiny (a cylinder far from the origin).
        double norm[kMaxSurrogate];
        for (int a = 0; a < n; ++a) {
            const Local at = EvaluateLocal(cons_[active[a].second], p);
            norm[a] = std::sqrt(at.g[0] * at.g[0] + at.g[1] * at.g[1] + at.g[2] * at.g[2]);
            if (!(norm[a] > 0) || !std::isfinite(norm[a])) norm[a] = 1;
            for (int c = 0; c < 3; ++c) g[a][c] = at.g[c] / norm[a];
        }
        if (n > 0 && NonNegativeCombination(n, g, t, l, 1))
            for (int a = 0; a < n; ++a) lambda[active[a].second] = l[a] / norm[a];
        return lambda;
    }

    std::vector<InsideFn> cons_;
    std::vector<char> artificial_;
    std::vector<int> planes_;
    int quadric_;
    double diameter_;  // of the region
    bool unbounded_ = false;
    std::size_t count_ = 0;
    Vec3 sum_;
    Vec3 best_[6];
    double bestValue_[6] = {-kInf, -kInf, -kInf, -kInf, -kInf, -kInf};
};

// A box certainly containing a capped cylinder (bootstrap of the certificate). An elliptic
// cylinder's A has a rounding-level smallest eigenvalue, which costs the certificate
// ~ eps R²/r for a ball of radius R around a search region 10⁶ scene sizes wide: far too much
// to get started. So the region is first cut to a box around a ball |x - c| <= R that contains
// the body, from the eigen-decomposition A = Σ λ_i u_i u_iᵀ + E (|λ_0| <= η: the axis u_0;
// λ_1, λ_2 >= μ > 0; ‖E‖ <= the Jacobi residual and rounding, folded into η). With c on the axis
// (c = -Σ_{i=1,2} (u_i·b/λ_i) u_i), d = x - c = s u_0 + w (s axial, w ⊥ u_0):
//     f(x) = dᵀAd + g·d + f(c),   g = 2(A c + b) ≈ 0,
//     dᵀAd >= μ|w|² - η(s² + |w|²),
// and two caps n·x + k <= 0 with n·u_0 of either sign bound |s| <= S0 + S1|w|. Inside the body
// f <= 0, so a2 |w|² - a1 |w| - a0 <= 0 with a2 = μ - η(1 + S1²), a1 = 2ηS0S1 + |g|(1 + S1),
// a0 = ηS0² + |g|S0 - f(c): |w| <= W (the positive root), |s| <= S0 + S1 W, and
// R = sqrt(W² + (S0 + S1 W)²), enlarged by 1e-6 for the rounding of these few operations (a
// larger ball only costs the certificate a little). nullopt when the quadric is not a
// cylinder or the planes do not cap it on both sides.
std::optional<Box3> CylinderBootstrap(const InsideFn& q, const std::vector<InsideFn>& planes) {
    double vals[3], vecs[3][3], off;
    SymmetricEigen(q.a, vals, vecs, off);
    const double frob = Frobenius(q.a);
    const double eta = std::fabs(vals[0]) + 2 * (off + 64 * kEps * frob);
    const double mu = vals[1];
    if (!(mu > 1e-6 * vals[2]) || !(std::fabs(vals[0]) <= 1e-9 * vals[2])) return std::nullopt;
    Vec3 u[3];
    for (int i = 0; i < 3; ++i) u[i] = Vec3{vecs[0][i], vecs[1][i], vecs[2][i]};
    const Vec3 b{q.b[0], q.b[1], q.b[2]};
    // On the axis, midway between the steepest cap of each side (where they cross the axis).
    Vec3 c = u[1] * (-Dot(u[1], b) / vals[1]) + u[2] * (-Dot(u[2], b) / vals[2]);
    {
        double steepest[2] = {0, 0}, cross[2] = {0, 0};
        for (const InsideFn& f : planes) {
            const Vec3 n{2 * f.b[0], 2 * f.b[1], 2 * f.b[2]};
            const double len = Length(n), alpha = Dot(n, u[0]);
            if (!(len > 0)) continue;
            const int side = alpha > 0 ? 0 : 1;
            if (!(std::fabs(alpha) / len > steepest[side])) continue;
            steepest[side] = std::fabs(alpha) / len;
            cross[side] = -(Dot(n, c) + f.k) / alpha;
        }
        if (!(steepest[0] > 1e-3 && steepest[1] > 1e-3)) return std::nullopt;
        c = c + u[0] * (0.5 * cross[0] + 0.5 * cross[1]);
    }
    const double pc[3] = {c.x, c.y, c.z};
    const Local at = EvaluateLocal(q, pc);
    const double gNorm = std::sqrt(at.g[0] * at.g[0] + at.g[1] * at.g[1] + at.g[2] * at.g[2]) +
                         64 * kEps * (frob * Length(c) + Length(b));
    const double minusFc = -at.v + 32 * kEps * at.mag;
    // The caps: s <= (κ + |n||w|)/α for α = n·u_0 > 0, -s <= (κ + |n||w|)/|α| for α < 0,
    // κ = -k - n·c; the steepest plane of each sign (largest |α|/|n|).
    double best[2] = {0, 0}, s0[2] = {0, 0}, s1[2] = {0, 0};
    for (const InsideFn& f : planes) {
        const Vec3 n{2 * f.b[0], 2 * f.b[1], 2 * f.b[2]};
        const double len = Length(n), alpha = Dot(n, u[0]);
        if (!(len > 0)) continue;
        const int side = alpha > 0 ? 0 : 1;
        const double steep = std::fabs(alpha) / len;
        if (!(steep > 1e-3) || !(steep > best[side])) continue;
        const double kappa = -f.k - Dot(n, c);
        best[side] = steep;
        s0[side] = std::fabs(kappa) * (1 + 1e-12) / std::fabs(alpha) +
                   64 * kEps * (std::fabs(f.k) + len * Length(c)) / std::fabs(alpha);
        s1[side] = 1 / steep;
    }
    if (!(best[0] > 0 && best[1] > 0)) return std::nullopt;
    const double S0 = std::fmax(s0[0], s0[1]), S1 = std::fmax(s1[0], s1[1]);
    const double a2 = mu - eta * (1 + S1 * S1);
    if (!(a2 > 0.5 * mu)) return std::nullopt;
    const double a1 = 2 * eta * S0 * S1 + gNorm * (1 + S1);
    const double a0 = eta * S0 * S0 + gNorm * S0 + std::fmax(minusFc, 0.0);
    const double w = (a1 + std::sqrt(a1 * a1 + 4 * a2 * a0)) / (2 * a2);
    const double sMax = S0 + S1 * w;
    const double radius = std::sqrt(w * w + sMax * sMax) * (1 + 1e-6) + 1e-300;
    if (!std::isfinite(radius)) return std::nullopt;
    Box3 box;
    for (int i = 0; i < 3; ++i) {
        const double pad = radius + 1e-12 * std::fabs(c[i]);
        box.lo[i] = c[i] - pad;
        box.hi[i] = c[i] + pad;
    }
    return box;
}

}  // namespace

std::optional<Box3> CriticalPointBox(const std::vector<InsideFn>& shaping, const Box3& b0,
                                     const BoundsOptions& options, bool* neckWide) {
    int quadric = -1;
    std::size_t planes = 0;
    for (std::size_t j = 0; j < shaping.size(); ++j) {
        if (shaping[j].isPlane) {
            ++planes;
            continue;
        }
        if (quadric >= 0) return std::nullopt;  // two quadrics: the relaxation
        quadric = static_cast<int>(j);
    }
    if (quadric < 0 || planes > kMaxPlanes) return std::nullopt;
    const InsideFn& q = shaping[quadric];
    std::vector<Nappe> nappes(shaping.size());
    if (!(q.lamMin >= -1e-12 * Frobenius(q.a))) {
        nappes[quadric] = DetectNappe(q);
        if (!nappes[quadric].ok) return std::nullopt;  // not convex
    }
    // The region: B0 within the search limit (and within the bootstrap box of a cylinder), its
    // faces in the relaxation's order; faces that are not B0's are artificial.
    const double limit = options.searchLimit;
    Box3 outer{{-limit, -limit, -limit}, {limit, limit, limit}};
    if (!nappes[quadric].ok) {
        // The caps: the body's planes and B0's finite faces (axis-aligned planes folded into B0).
        std::vector<InsideFn> caps;
        for (const InsideFn& f : shaping)
            if (f.isPlane) caps.push_back(f);
        for (int i = 0; i < 3; ++i)
            for (int sign = -1; sign <= 1; sign += 2) {
                const double bound = sign > 0 ? b0.hi[i] : b0.lo[i];
                if (!std::isfinite(bound)) continue;
                InsideFn p;
                p.b[i] = 0.5 * sign;
                p.k = -sign * bound;
                caps.push_back(p);
            }
        if (auto boot = CylinderBootstrap(q, caps)) outer = outer.Intersected(*boot);
    }
    const Box3 region = b0.Intersected(outer);
    if (region.Empty()) return std::nullopt;
    std::vector<InsideFn> cons = shaping;
    std::vector<char> artificial(shaping.size(), 0), apart(shaping.size(), 0);
    for (int i = 0; i < 3; ++i)
        for (int sign = -1; sign <= 1; sign += 2) {
            InsideFn p;
            p.isPlane = true;
            p.b[i] = 0.5 * sign;
            p.k = sign > 0 ? -region.hi[i] : region.lo[i];
            cons.push_back(p);
            const bool ofB0 = sign > 0 ? b0.hi[i] < outer.hi[i] : b0.lo[i] > outer.lo[i];
            const bool atLimit = sign > 0 ? !(outer.hi[i] < limit) : !(outer.lo[i] > -limit);
            artificial.push_back(!ofB0);
            apart.push_back(!ofB0 && !atLimit && !options.criticalPointsOnApartFaces);
        }
    // The distance tolerance only where the region is not the search limit's (for a cone: B0).
    bool bounded = true;
    for (int i = 0; i < 3; ++i) bounded &= outer.hi[i] < limit || b0.hi[i] < limit;
    CriticalPoints points(std::move(cons), quadric, std::move(artificial), apart,
                          bounded ? Length(region.Size()) : 0.0);
    CandidateExtreme extremes[6];
    Vec3 interior;
    if (!points.Run(extremes, interior)) return std::nullopt;
    std::vector<const InsideFn*> fns;
    for (const InsideFn& f : shaping) fns.push_back(&f);
    Box3 box = b0;
    double neck[6] = {0, 0, 0, 0, 0, 0};
    if (!CertifyExtremes(fns, nappes, region, interior, extremes, box, neck)) return std::nullopt;
    // Tight: every certified side within kTight of its candidate (beyond the neck allowance).
    bool wide = false;
    for (int side = 0; side < 6; ++side) {
        const int axis = side / 2;
        const double certified = side % 2 ? box.hi[axis] : -box.lo[axis];
        const double size = box.hi[axis] - box.lo[axis];
        const double value = points.Value(side);
        const double tight = nappes[quadric].ok ? kTightNappe : kTight;
        const double gap = std::fabs(certified - value),
                     allowed = tight * (size + std::fabs(value));
        if (!(gap <= allowed + neck[side])) return std::nullopt;
        wide |= !(gap <= allowed);
    }
    if (neckWide) *neckWide = wide;
    return box;
}

}  // namespace quadrix::bounds_detail
