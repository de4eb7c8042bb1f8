// Stage (b1) of bounds.h: the convex relaxation of a body, solved by a log-barrier
// interior-point method, polished by Newton on the KKT system and certified by Lagrangian duality.
#include <algorithm>
#include <cmath>

#include "quadrix/flatten/bounds_internal.h"
#include "quadrix/math/dense_solve.h"

namespace quadrix::bounds_detail {

namespace {

// The relaxation keeps the planes, positive semidefinite quadrics and nappes (bounds_internal.h)
// of the body (dropping a literal only enlarges the set: conservative) plus the six planes of
// the search region, so it is bounded. A nappe's log barrier -log(-f) is the standard barrier of
// a (Lorentz) second-order cone, convex inside the nappe, so the barrier method stays in the
// nappe of its starting point; the body is first proven to lie in that nappe (a separating plane
// constraint, else an LP over the other constraints), else the nappes are left out.
//
// Central path: for direction e, minimise -t e·x - Σ log(-f_i(x)) for growing t; its points give
// multipliers λ_i = 1 / (t · (-f_i(x̂))) >= 0 with e ≈ Σ λ_i ∇f_i(x̂) (KKT) and a duality gap of
// (number of constraints) / t. Newton on the KKT system of the active constraints then polishes
// x̂ and λ to rounding level.
//
// Certificate (weak duality, valid for any λ >= 0 and any x̂): for x in the set and the region,
//     e·x <= L(x) = e·x - Σ λ_i f_i(x) - μ f_ball(x),
// where f_ball <= 0 is a ball containing the region (μ >= 0 keeps M = Σ λ_i A_i + μ I/R²
// positive definite for cylinders and paraboloids). L is quadratic with Hessian -2M, so
//     L(x) <= L(x̂) + sup_d (r·d - dᵀMd),   r = ∇L(x̂),
// with sup = ¼ rᵀM⁻¹r <= |r|²/(4 λmin(M)), λmin(M) >= Σ λ_i λmin(A_i) + μ/R² (Weyl), or, for an
// indefinite M, <= |r| D + |λmin| D² over the region's diameter D; all evaluated with rounding
// allowances. The solver's accuracy only affects how tight the bound is. A nappe with λ > 0
// enters as its supporting plane through the apex, ∇f(x̂)·(x - apex) <= 0, valid for the whole
// nappe when x̂ is in it (reverse Cauchy–Schwarz for the Lorentzian form A: two vectors of the
// same closed cone have a non-positive product), so it adds nothing to M.
class ConvexRelaxation {
  public:
    // nappes[i].ok marks fns[i] as a nappe (may be empty: none).
    ConvexRelaxation(const std::vector<const InsideFn*>& fns, const std::vector<Nappe>& nappes,
                     const Box3& region)
        : region_(region) {
        for (std::size_t i = 0; i < fns.size(); ++i) {
            cons_.push_back(*fns[i]);
            nappes_.push_back(i < nappes.size() ? nappes[i] : Nappe{});
        }
        // The region's faces as planes x_i - hi <= 0 and lo - x_i <= 0 (scaled to unit normals).
        for (int i = 0; i < 3; ++i)
            for (int sign = -1; sign <= 1; sign += 2) {
                InsideFn p;
                p.isPlane = true;
                p.b[i] = 0.5 * sign;
                p.k = sign > 0 ? -region.hi[i] : region.lo[i];
                cons_.push_back(p);
                nappes_.push_back(Nappe{});
            }
        Vec3 size = region.Size();
        radius_ = 0.5 * Length(size) * (1 + 1e-9) + 1e-300;
        centre_ = region.Center();
        scale_ = std::fmax(size.x, std::fmax(size.y, size.z));
    }

    // Phase I: a point where every constraint is strictly negative (`out` is tried first); false
    // when none was found (an empty or flat set: the caller falls back to the branch-and-bound).
    bool FindInterior(Vec3& out) {
        if (!FindInteriorOfOthers(out)) return false;
        if (!HasNappes()) return true;
        // Seeds for the nappes: the point found, and the middle of each nappe axis' stretch
        // inside the planes (for a capped cone, a point on its axis between the caps).
        std::vector<Vec3> seeds{out};
        for (const Nappe& n : nappes_)
            if (n.ok) AxisSeed(n, seeds);
        for (const Vec3& s : seeds)
            if (StrictlyInside(s, true)) {
                out = s;
                return true;
            }
        return false;
    }

    // Points the nappes' axes toward the side of `interior` (the body's side).
    void OrientNappes(const Vec3& interior) {
        for (Nappe& n : nappes_)
            if (n.ok && Dot(interior - n.apex, n.axis) < 0) n.axis = -n.axis;
    }

    // Whether one of the plane constraints keeps the body in nappe i's nappe: a plane
    // n·x + d <= 0 through or beyond the apex (n·apex + d >= 0) whose normal is timelike for the
    // inverse form (nᵀA⁻¹n < 0: the parallel plane through the apex meets the double cone only at
    // the apex) and that faces the nappe (n·axis < 0). Perspective images of cylinders are cones
    // with their apex on the far clip plane, which separates their nappes this way. An apex
    // slightly inside the half-space (rounding) is allowed as a neck of that size.
    bool SeparatedByPlane(std::size_t i) {
        Nappe& n = nappes_[i];
        for (const InsideFn& f : cons_) {
            if (!f.isPlane) continue;
            Vec3 normal{2 * f.b[0], 2 * f.b[1], 2 * f.b[2]};
            double len = Length(normal);
            if (!(len > 0)) continue;
            double at = Dot(normal, n.apex) + f.k;
            double tolerance = 1e-9 * (len * Length(n.apex) + std::fabs(f.k));
            if (at < -tolerance || !(Dot(normal, n.axis) < 0)) continue;
            double form = 0;
            for (int j = 0; j < 3; ++j) {
                double c = Dot(n.vecs[j], normal) / len;
                form += c * c / n.vals[j];
            }
            if (!(form < -1e-9 / n.beta)) continue;
            double dist = std::fmax(0.0, -at) / len;
            n.rPlus = std::fmax(n.rPlus, n.beta * dist * dist * 4);
            return true;
        }
        return false;
    }

    bool HasNappes() const {
        for (const Nappe& n : nappes_)
            if (n.ok) return true;
        return false;
    }

    // Each nappe's side (the sign of axis·(x - apex) at the interior point), and the other
    // constraints as the sub-problem that must prove the body stays on that side.
    const std::vector<Nappe>& Nappes() const { return nappes_; }

    bool StrictlyInside(const Vec3& p, bool withNappes) const {
        if (!IsFinite(p)) return false;
        double q[3] = {p.x, p.y, p.z};
        for (std::size_t i = 0; i < cons_.size(); ++i)
            if ((withNappes || !nappes_[i].ok) && !(EvaluateAt(cons_[i], q) < 0)) return false;
        return true;
    }

  private:
    // The stretch of the nappe's axis line inside every plane constraint; its middle point.
    void AxisSeed(const Nappe& n, std::vector<Vec3>& seeds) const {
        double lo = -kInf, hi = kInf;
        for (const InsideFn& f : cons_) {
            if (!f.isPlane) continue;
            // f(apex + t axis) = f(apex) + 2 t b·axis
            double a0[3] = {n.apex.x, n.apex.y, n.apex.z};
            double v = EvaluateAt(f, a0);
            double slope = 2 * (f.b[0] * n.axis.x + f.b[1] * n.axis.y + f.b[2] * n.axis.z);
            if (slope > 0)
                hi = std::fmin(hi, -v / slope);
            else if (slope < 0)
                lo = std::fmax(lo, -v / slope);
            else if (v >= 0)
                return;
        }
        if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi)) return;
        seeds.push_back(n.apex + n.axis * (0.5 * (lo + hi)));
    }

  public:
    // Phase I over the constraints other than nappes.
    bool FindInteriorOfOthers(Vec3& out) {
        if (StrictlyInside(out, false)) return true;
        // Minimise s subject to f_i(x) <= s over (x, s), starting at the region's centre; stop as
        // soon as s < 0.
        double y[4] = {centre_.x, centre_.y, centre_.z, 0};
        double worst = -kInf;
        for (std::size_t i = 0; i < cons_.size(); ++i)
            if (!nappes_[i].ok) worst = std::fmax(worst, EvaluateAt(cons_[i], y));
        if (!std::isfinite(worst)) return false;
        y[3] = worst + std::fmax(1.0, std::fabs(worst));
        if (worst < 0) {
            out = centre_;
            return true;
        }
        const int n = static_cast<int>(cons_.size());
        double t = 1 / std::fmax(std::fabs(y[3]), 1e-300);
        for (int outer = 0; outer < 60; ++outer) {
            for (int inner = 0; inner < 50; ++inner) {
                double grad[4] = {0, 0, 0, t}, hess[4][4] = {};
                for (int i = 0; i < n; ++i) {
                    if (nappes_[i].ok) continue;
                    Local l = EvaluateLocal(cons_[i], y);
                    double u = y[3] - l.v;  // > 0
                    double gi[4] = {l.g[0], l.g[1], l.g[2], -1};
                    for (int a = 0; a < 4; ++a) {
                        grad[a] += gi[a] / u;
                        for (int b = 0; b < 4; ++b) hess[a][b] += gi[a] * gi[b] / (u * u);
                    }
                    for (int a = 0; a < 3; ++a)
                        for (int b = 0; b < 3; ++b) hess[a][b] += 2 * cons_[i].a[a][b] / u;
                }
                // Far constraints alone curve some directions (a slab between two parallel
                // planes): regularise relative to the largest curvature.
                double maxDiag = 0;
                for (int a = 0; a < 4; ++a) maxDiag = std::fmax(maxDiag, hess[a][a]);
                for (int a = 0; a < 4; ++a) hess[a][a] += 1e-13 * maxDiag;
                double step[4];
                if (!SolveNewton(4, hess, grad, step)) return false;
                double decrement = 0;
                for (int a = 0; a < 4; ++a) decrement -= grad[a] * step[a];
                if (!LineSearchPhase1(y, step, t)) break;
                if (y[3] < 0) {
                    out = Vec3{y[0], y[1], y[2]};
                    return true;
                }
                if (decrement < 1e-12) break;
            }
            if (n / t <= 1e-9 * std::fabs(y[3])) return false;  // converged with s >= 0
            t *= 10;
        }
        return false;
    }

    // A rigorous upper bound of e·x (e a unit vector) over the set ∩ region, from the interior
    // point `start`; +inf when the iterations failed. `xhat` receives the relaxation's extreme
    // point. `size` estimates the body's size along e (<= 0: unknown), which sets the initial
    // barrier weight; it is updated from what this direction found. `side` (0..5 or -1) is where
    // Recertify finds the solution again.
    double Maximize(const double e[3], int side, const Vec3& start, Vec3& xhat, double& size) {
        const int n = static_cast<int>(cons_.size());
        double x[3] = {start.x, start.y, start.z};
        // Initial duality gap n/t: about the distance to cover.
        double t = n / (size > 0 ? size : scale_);
        const double startValue = e[0] * start.x + e[1] * start.y + e[2] * start.z;
        for (int outer = 0; outer < 80; ++outer) {
            if (!Center(e, t, x)) return kInf;
            double reach = e[0] * x[0] + e[1] * x[1] + e[2] * x[2] - startValue;
            // The barrier only has to find the active set and a point near the extreme; the
            // polishing below does the rest.
            if (n / t <= 1e-4 * std::fmax(reach, 1e-12 * scale_)) break;
            t *= 30;
        }
        size = std::fmax(e[0] * x[0] + e[1] * x[1] + e[2] * x[2] - startValue, 0.0) * 2;
        std::vector<double> lambda(n, 0.0);
        for (int i = 0; i < n; ++i) {
            double v = EvaluateAt(cons_[i], x);
            lambda[i] = v < 0 ? 1 / (t * -v) : 0.0;
        }
        double bound = Certify(e, x, lambda, centre_, radius_);
        xhat = Vec3{x[0], x[1], x[2]};
        Solution scratch;
        Solution& best = side >= 0 ? solutions_[side] : scratch;
        best.x = xhat;
        best.lambda = lambda;
        double xp[3] = {x[0], x[1], x[2]};
        std::vector<double> polished(n, 0.0);
        if (Polish(e, lambda, xp, polished)) {
            double b2 = Certify(e, xp, polished, centre_, radius_);
            if (b2 < bound) {
                bound = b2;
                xhat = Vec3{xp[0], xp[1], xp[2]};
                best.x = xhat;
                best.lambda.swap(polished);
            }
        }
        return bound;
    }

    // The part of the certificate that depends on the point x̂ and the multipliers only, not on
    // the ball: the Lagrangian's value, gradient and Hessian sums with their rounding allowances.
    // CertifyExtremes certifies the same (x̂, λ) of a side with several balls (its passes), so it
    // makes these once per side. `ok` is false when a nappe's supporting plane has no point of
    // the nappe near x̂ (the certificate is then infinite).
    struct Sums {
        bool ok = false;
        double lhat = 0, errL = 0, m0 = 0, neckSlack = 0;
        double r[3] = {0, 0, 0}, errR[3] = {1, 1, 1};
        InsideFn mSum;  // Σ λ_i A_i, in an InsideFn to reuse Cholesky
        // The Cholesky solve of μ = 0 (M = mSum, r̃ = r: the same for every ball), made on first
        // use: 0 not yet, 1 made and `form0` holds rᵀM⁻¹r, -1 no factorisation or no finite form.
        mutable int form0State = 0;
        mutable double form0 = 0;
    };

    Sums MakeSums(const double e[3], const double x[3], const std::vector<double>& lambda) const {
        Sums s;
        s.lhat = e[0] * x[0] + e[1] * x[1] + e[2] * x[2];
        s.errL = std::fabs(s.lhat);
        for (int j = 0; j < 3; ++j) s.r[j] = e[j];
        for (std::size_t i = 0; i < cons_.size(); ++i) {
            double w = lambda[i];
            if (w == 0) continue;
            InsideFn f = cons_[i];
            if (nappes_[i].ok) {
                // The supporting plane through the apex, ∇f(p)·(x - apex) <= 0, from a point p
                // of the nappe near x̂.
                const Nappe& n = nappes_[i];
                Vec3 p;
                if (!PointInNappe(cons_[i], n, x, p)) return s;
                double pp[3] = {p.x, p.y, p.z};
                Local at = EvaluateLocal(cons_[i], pp);
                f = InsideFn{};
                f.isPlane = true;
                for (int j = 0; j < 3; ++j) f.b[j] = 0.5 * at.g[j];
                f.k = -(at.g[0] * n.apex.x + at.g[1] * n.apex.y + at.g[2] * n.apex.z);
                // A rounding-level one-sheet neck (R > 0) lets the nappe poke out of the cone by
                // its radius sqrt(R/β) near the apex.
                double gnorm = std::sqrt(at.g[0] * at.g[0] + at.g[1] * at.g[1] + at.g[2] * at.g[2]);
                s.neckSlack += 2 * w * gnorm * std::sqrt(n.rPlus / n.beta);
            }
            Local l = EvaluateLocal(f, x);
            s.lhat -= w * l.v;
            s.errL += w * (std::fabs(l.v) + l.mag);
            for (int j = 0; j < 3; ++j) {
                s.r[j] -= w * l.g[j];
                double gm = 2 * (std::fabs(f.a[j][0] * x[0]) + std::fabs(f.a[j][1] * x[1]) +
                                 std::fabs(f.a[j][2] * x[2]) + std::fabs(f.b[j]));
                s.errR[j] += w * (std::fabs(l.g[j]) + gm);
                for (int k = 0; k < 3; ++k) s.mSum.a[j][k] += w * f.a[j][k];
            }
            s.m0 += w * f.lamMin;
        }
        s.ok = true;
        return s;
    }

    // The certificate of a given point and multipliers (indexed like the constraints: the
    // literals, then the region's faces as listed in the constructor) with the ball around the
    // region, or around `ball` when given (which must be known to contain the set).
    double CertifyAt(const Sums& sums, const Vec3& x, const Box3* ball) const {
        if (!sums.ok) return kInf;
        const double p[3] = {x.x, x.y, x.z};
        if (!ball) return Certify(sums, p, centre_, radius_);
        const double radius = 0.5 * Length(ball->Size()) * (1 + 1e-9) + 1e-300;
        return Certify(sums, p, ball->Center(), radius);
    }

    // The certificate of the last Maximize for this side, with the ball around a smaller
    // region known to contain the set (the box found so far): no new iterations, and the
    // allowances that grow with the ball shrink.
    double Recertify(int side, const Box3& region) const {
        const Solution& best = solutions_[side];
        if (best.lambda.empty()) return kInf;
        double e[3] = {0, 0, 0};
        e[side / 2] = side % 2 ? 1 : -1;
        double x[3] = {best.x.x, best.x.y, best.x.z};
        double radius = 0.5 * Length(region.Size()) * (1 + 1e-9) + 1e-300;
        return Certify(e, x, best.lambda, region.Center(), radius);
    }

  private:
    // Newton iterations (Levenberg–Marquardt, for degenerate extremes such as a cylinder's
    // generator) on the KKT system of the active set A (at most 3 constraints carrying most of
    // the barrier multipliers' weight):  e = Σ_A λ_i ∇f_i(x),  f_i(x) = 0 (i in A).
    // False when the multipliers come out negative or the iterations fail.
    bool Polish(const double e[3], const std::vector<double>& lambda, double x[3],
                std::vector<double>& out) const {
        const int n = static_cast<int>(cons_.size());
        int act[3], k = 0;
        double weight[3] = {0, 0, 0};
        double maxWeight = 0;
        for (int i = 0; i < n; ++i) {
            Local l = EvaluateLocal(cons_[i], x);
            double w = lambda[i] * std::sqrt(l.g[0] * l.g[0] + l.g[1] * l.g[1] + l.g[2] * l.g[2]);
            maxWeight = std::fmax(maxWeight, w);
            int pos = k < 3 ? k++ : 3;
            while (pos > 0 && weight[pos - 1] < w) {
                if (pos < 3) {
                    act[pos] = act[pos - 1];
                    weight[pos] = weight[pos - 1];
                }
                --pos;
            }
            if (pos < 3) {
                act[pos] = i;
                weight[pos] = w;
            }
        }
        while (k > 0 && weight[k - 1] < 1e-3 * maxWeight) --k;
        if (k == 0) return false;
        double lam[3];
        for (int a = 0; a < k; ++a) lam[a] = lambda[act[a]];
        const int dim = 3 + k;
        for (int iter = 0; iter < 12; ++iter) {
            // Residual F and Jacobian J of (stationarity; activity).
            double f[6], jac[6][6] = {};
            Local loc[3];
            for (int j = 0; j < 3; ++j) f[j] = e[j];
            for (int a = 0; a < k; ++a) {
                const InsideFn& c = cons_[act[a]];
                loc[a] = EvaluateLocal(c, x);
                for (int j = 0; j < 3; ++j) {
                    f[j] -= lam[a] * loc[a].g[j];
                    for (int m = 0; m < 3; ++m) jac[j][m] -= lam[a] * 2 * c.a[j][m];
                    jac[j][3 + a] = -loc[a].g[j];
                    jac[3 + a][j] = loc[a].g[j];
                }
                f[3 + a] = loc[a].v;
            }
            double norm = 0;
            for (int j = 0; j < dim; ++j) norm += f[j] * f[j];
            if (norm <= 1e-30) break;
            // Newton: J Δ = -F directly (full accuracy); when J is singular (a degenerate
            // extreme), Levenberg–Marquardt (JᵀJ + εI) Δ = -JᵀF.
            double h[6][6] = {}, rhs[6] = {}, delta[6];
            for (int r = 0; r < dim; ++r) {
                for (int c = 0; c < dim; ++c) h[r][c] = jac[r][c];
                rhs[r] = -f[r];
            }
            // Refused when a pivot is below 1e-13 of the largest entry (numerically singular).
            if (SolveDense(dim, h, rhs, delta, 1e-13 * MaxAbsEntry(dim, h))) {
                for (int j = 0; j < 3; ++j) x[j] += delta[j];
                for (int a = 0; a < k; ++a) lam[a] += delta[3 + a];
                continue;
            }
            for (int r = 0; r < dim; ++r) {
                rhs[r] = 0;
                for (int c = 0; c < dim; ++c) h[r][c] = 0;
            }
            double maxDiag = 0;
            for (int r = 0; r < dim; ++r) {
                for (int c = 0; c < dim; ++c)
                    for (int m = 0; m < dim; ++m) h[r][c] += jac[m][r] * jac[m][c];
                for (int m = 0; m < dim; ++m) rhs[r] -= jac[m][r] * f[m];
                maxDiag = std::fmax(maxDiag, h[r][r]);
            }
            for (int r = 0; r < dim; ++r) h[r][r] += 1e-14 * maxDiag + 1e-300;
            if (!SolveDense(dim, h, rhs, delta)) return false;
            for (int j = 0; j < 3; ++j) x[j] += delta[j];
            for (int a = 0; a < k; ++a) lam[a] += delta[3 + a];
        }
        for (int a = 0; a < k; ++a) {
            if (!(lam[a] >= 0) || !std::isfinite(lam[a])) return false;
            out[act[a]] = lam[a];
        }
        return IsFinite(Vec3{x[0], x[1], x[2]});
    }

    // Newton iterations on -t e·x - Σ log(-f_i(x)) from a strictly feasible x.
    bool Center(const double e[3], double t, double x[3]) {
        const int n = static_cast<int>(cons_.size());
        for (int inner = 0; inner < 50; ++inner) {
            double grad[4] = {-t * e[0], -t * e[1], -t * e[2], 0}, hess[4][4] = {};
            for (int i = 0; i < n; ++i) {
                Local l = EvaluateLocal(cons_[i], x);
                double u = -l.v;  // > 0
                if (!(u > 0)) return false;
                for (int a = 0; a < 3; ++a) {
                    grad[a] += l.g[a] / u;
                    for (int b = 0; b < 3; ++b)
                        hess[a][b] += l.g[a] * l.g[b] / (u * u) + 2 * cons_[i].a[a][b] / u;
                }
            }
            // Directions along which only far constraints curve the barrier (a cylinder's axis)
            // are nearly singular: regularise relative to the largest curvature.
            double maxDiag = std::fmax(hess[0][0], std::fmax(hess[1][1], hess[2][2]));
            for (int a = 0; a < 3; ++a) hess[a][a] += 1e-13 * maxDiag;
            double step[4];
            if (!SolveNewton(3, hess, grad, step)) return true;  // keep the feasible point
            double decrement = -(grad[0] * step[0] + grad[1] * step[1] + grad[2] * step[2]);
            if (decrement < 1e-10) return true;
            if (!LineSearchCenter(e, t, x, step, grad)) return true;  // no progress possible
        }
        return true;
    }

    // The largest s in (0, 1] keeping every constraint negative along x + s·step (with a 1%
    // margin), from each constraint's quadratic f + s ∇f·step + s² stepᵀA step.
    double MaxStep(const double x[3], const double step[4]) const {
        double best = 1;
        for (const InsideFn& f : cons_) {
            Local l = EvaluateLocal(f, x);
            double b = l.g[0] * step[0] + l.g[1] * step[1] + l.g[2] * step[2];
            double a = 0;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) a += step[i] * f.a[i][j] * step[j];
            // Smallest positive root of a s² + b s + v = 0 with v < 0.
            double v = l.v, root = kInf;
            if (a == 0) {
                if (b > 0) root = -v / b;
            } else {
                double disc = b * b - 4 * a * v;
                if (disc >= 0) {
                    double q = -0.5 * (b + (b >= 0 ? 1 : -1) * std::sqrt(disc));
                    double r1 = q / a, r2 = q != 0 ? v / q : kInf;
                    if (r1 > 0) root = std::fmin(root, r1);
                    if (r2 > 0) root = std::fmin(root, r2);
                }
            }
            best = std::fmin(best, 0.99 * root);
        }
        return best;
    }

    double Barrier(const double e[3], double t, const double x[3]) const {
        double phi = -t * (e[0] * x[0] + e[1] * x[1] + e[2] * x[2]);
        for (const InsideFn& f : cons_) {
            double v = EvaluateAt(f, x);
            if (!(v < 0)) return kInf;
            phi -= std::log(-v);
        }
        return phi;
    }

    bool LineSearchCenter(const double e[3], double t, double x[3], const double step[4],
                          const double grad[4]) {
        double phi0 = Barrier(e, t, x);
        double slope = grad[0] * step[0] + grad[1] * step[1] + grad[2] * step[2];
        double s = MaxStep(x, step);
        for (int k = 0; k < 60; ++k, s *= 0.5) {
            double trial[3] = {x[0] + s * step[0], x[1] + s * step[1], x[2] + s * step[2]};
            double phi = Barrier(e, t, trial);
            if (phi <= phi0 + 0.25 * s * slope) {
                for (int a = 0; a < 3; ++a) x[a] = trial[a];
                return true;
            }
        }
        return false;
    }

    bool LineSearchPhase1(double y[4], const double step[4], double t) {
        auto phi = [&](const double* p) {
            double v = t * p[3];
            for (std::size_t i = 0; i < cons_.size(); ++i) {
                if (nappes_[i].ok) continue;
                double u = p[3] - EvaluateAt(cons_[i], p);
                if (!(u > 0)) return kInf;
                v -= std::log(u);
            }
            return v;
        };
        double phi0 = phi(y);
        double s = 1;
        for (int k = 0; k < 60; ++k, s *= 0.5) {
            double trial[4];
            for (int a = 0; a < 4; ++a) trial[a] = y[a] + s * step[a];
            if (phi(trial) < phi0) {
                for (int a = 0; a < 4; ++a) y[a] = trial[a];
                return true;
            }
        }
        return false;
    }

    // Solves H step = -grad (n = 3 or 4; math/dense_solve.h), refusing zero pivots only.
    static bool SolveNewton(int n, double (&h)[4][4], const double grad[4], double step[4]) {
        double r[4];
        for (int i = 0; i < n; ++i) r[i] = -grad[i];
        return SolveDense(n, h, r, step);
    }

    // A point of the closed nappe on the side fixed for it, near x: x itself, or x with its
    // distance from the axis shrunk a little (x̂ is on the surface up to rounding).
    bool PointInNappe(const InsideFn& f, const Nappe& n, const double x[3], Vec3& p) const {
        Vec3 u = Vec3{x[0], x[1], x[2]} - n.apex;
        double along = Dot(u, n.axis);
        if (!(along > 0)) return false;  // the side was oriented so that the body has along > 0
        Vec3 perp = u - n.axis * along;
        for (double shrink = 0; shrink < 1; shrink = shrink == 0 ? 1e-14 : shrink * 16) {
            p = n.apex + n.axis * along + perp * (1 - shrink);
            double q[3] = {p.x, p.y, p.z};
            if (EvaluateAt(f, q) <= 0) return true;
        }
        return false;
    }

    // The rigorous bound L(x̂) + sup_d (r·d - dᵀMd) (class comment), minimised over the ball
    // multiplier μ among a few candidates. sup_d = ¼ rᵀM⁻¹r, taken from a Cholesky solve when M
    // is well conditioned (its rounding then costs far less than the 1% added), else bounded by
    // |r|² / (4 λmin(M)) with Weyl's λmin.
    double Certify(const double e[3], const double x[3], const std::vector<double>& lambda,
                   const Vec3& centre, double radius, double* neckOut = nullptr) const {
        const Sums sums = MakeSums(e, x, lambda);
        if (!sums.ok) return kInf;
        if (neckOut) *neckOut = sums.neckSlack;
        return Certify(sums, x, centre, radius);
    }

    // The same from the sums of (x̂, λ), with the ball |x - centre| <= radius. A μ candidate is
    // skipped, with the same result, where its bound without the (non-negative) quadratic term
    // already reaches the best one, or where it repeats an earlier μ.
    double Certify(const Sums& sums, const double x[3], const Vec3& centre, double radius) const {
        constexpr double kGamma = 64 * kEps;
        const double* r = sums.r;
        const double* errR = sums.errR;
        const double m0 = sums.m0;
        double base = sums.lhat + kGamma * sums.errL + sums.neckSlack;
        // The ball |x - c|² <= R² around the region: f_ball = (|x - c|² - R²)/R², gradient
        // 2(x - c)/R², λmin = 1/R²; -f_ball <= 1 in the region.
        double r2 = radius * radius;
        double gb[3] = {2 * (x[0] - centre.x) / r2, 2 * (x[1] - centre.y) / r2,
                        2 * (x[2] - centre.z) / r2};
        double fb = ((x[0] - centre.x) * (x[0] - centre.x) + (x[1] - centre.y) * (x[1] - centre.y) +
                     (x[2] - centre.z) * (x[2] - centre.z) - r2) /
                    r2;
        double r0 = 0;
        for (int j = 0; j < 3; ++j) {
            double rj = std::fabs(r[j]) + kGamma * errR[j];
            r0 += rj * rj;
        }
        r0 = std::sqrt(r0);
        // Candidates for μ: none, one balancing the residual against the ball's cost, and ones
        // large enough to make M definite despite a rounding-level negative eigenvalue of a
        // cylinder's A. For an indefinite M the supremum is taken over the region only:
        // x, x̂ in the region, |x - x̂| <= D = 2R, so r·d - dᵀMd <= |r| D + max(0, -λmin) D².
        double best = kInf;
        const double diameter = 2 * radius;
        const double muR = 0.5 * r0 * radius, muM = 2 * std::fmax(0.0, -m0) * r2;
        const double muCandidates[5] = {0, muR, muM, muR + muM, 10 * (muR + muM)};
        const bool gbFinite = std::isfinite(gb[0]) && std::isfinite(gb[1]) && std::isfinite(gb[2]);
        for (int c = 0; c < 5; ++c) {
            const double mu = muCandidates[c];
            bool repeat = false;
            for (int c2 = 0; c2 < c; ++c2) repeat |= muCandidates[c2] == mu;
            if (repeat) continue;
            // quad >= 0 below (or NaN, which is not kept): this μ cannot lower the best.
            const double partial = base - mu * fb + kGamma * mu * 4;
            if (partial >= best) continue;
            double m = m0 + mu / r2;
            m = m > 0 ? m * (1 - 1e-12) : m * (1 + 1e-12);
            // r = r̃ + δ with |δ_j| <= γ errR_j: (r̃+δ)ᵀM⁻¹(r̃+δ) <= (√(r̃ᵀM⁻¹r̃) + |δ|/√λmin)².
            double rt[3], delta2 = 0, rNorm2 = 0;
            for (int j = 0; j < 3; ++j) {
                rt[j] = r[j] - mu * gb[j];
                double dj = kGamma * (errR[j] + mu * std::fabs(gb[j]));
                delta2 += dj * dj;
                double aj = std::fabs(rt[j]) + dj;
                rNorm2 += aj * aj;
            }
            double quad = std::sqrt(rNorm2) * diameter + std::fmax(0.0, -m) * diameter * diameter;
            if (m > 0) {
                quad = std::fmin(quad, rNorm2 / (4 * m));
                double form = 0;
                bool haveForm = false;
                if (mu == 0 && gbFinite && sums.form0State != 0) {
                    haveForm = sums.form0State > 0;
                    form = sums.form0;
                } else {
                    InsideFn mm = sums.mSum;
                    for (int j = 0; j < 3; ++j) mm.a[j][j] += mu / r2;
                    const int idx[3] = {0, 1, 2};
                    double l[3][3], condition;
                    if (Cholesky(mm, idx, 3, l, condition, 1e8)) {
                        double y[3];
                        CholeskySolve(l, 3, rt, y);
                        form = rt[0] * y[0] + rt[1] * y[1] + rt[2] * y[2];
                        haveForm = form >= 0 && std::isfinite(form);
                    }
                    if (mu == 0 && gbFinite) {
                        sums.form0State = haveForm ? 1 : -1;
                        sums.form0 = form;
                    }
                }
                if (haveForm) {
                    double root = std::sqrt(1.01 * form) + std::sqrt(delta2 / m);
                    quad = std::fmin(quad, 0.25 * root * root);
                }
            }
            double bound = partial + quad;
            if (std::isfinite(bound)) best = std::fmin(best, bound);
        }
        return best;
    }

    std::vector<InsideFn> cons_;
    Box3 region_;
    std::vector<Nappe> nappes_;  // per constraint; ok for nappes
    Vec3 centre_;
    double radius_ = 0, scale_ = 0;
    struct Solution {
        Vec3 x;
        std::vector<double> lambda;
    };
    Solution solutions_[6];  // the best (x̂, λ) of each side, for Recertify
};

}  // namespace

namespace {

// Proves that the body lies in the nappe its axis points to: by a separating plane constraint,
// else by the relaxation of the other constraints (the body strictly on the axis' side of the
// plane through the apex perpendicular to the axis).
bool VerifyNappeSides(const std::vector<const InsideFn*>& fns, ConvexRelaxation& relaxation,
                      const Box3& region, BoundsStats* stats) {
    const std::vector<Nappe>& oriented = relaxation.Nappes();
    std::vector<bool> separated(oriented.size(), false);
    bool all = true;
    for (std::size_t i = 0; i < oriented.size(); ++i)
        if (oriented[i].ok) {
            separated[i] = relaxation.SeparatedByPlane(i);
            all = all && separated[i];
        }
    if (all) return true;
    std::vector<const InsideFn*> others;
    for (std::size_t i = 0; i < fns.size(); ++i)
        if (!oriented[i].ok) others.push_back(fns[i]);
    ConvexRelaxation sub(others, {}, region);
    Vec3 interior{kInf, kInf, kInf};
    if (!sub.FindInteriorOfOthers(interior)) return false;
    for (std::size_t i = 0; i < oriented.size(); ++i) {
        const Nappe& n = oriented[i];
        if (!n.ok || separated[i]) continue;
        double e[3] = {-n.axis.x, -n.axis.y, -n.axis.z};
        Vec3 xhat;
        double size = -1;
        double bound = sub.Maximize(e, -1, interior, xhat, size);
        if (stats) ++stats->convexSolves;
        // max of -axis·x over the others < -axis·apex: every point has axis·(x - apex) > 0.
        if (!(bound < -Dot(n.axis, n.apex))) return false;
    }
    return true;
}

}  // namespace

RelaxationOutcome BoundByConvexRelaxation(const std::vector<const InsideFn*>& fns,
                                          const std::vector<Nappe>& nappes, const Box3& region,
                                          Box3& work, BoundsStats* stats) {
    RelaxationOutcome out;
    bool anyNappe = false;
    for (const Nappe& n : nappes) anyNappe |= n.ok;
    for (int attempt = anyNappe ? 0 : 1; attempt < 2 && !out.solved; ++attempt) {
        // Attempt 0 with the nappes, attempt 1 without them.
        std::vector<const InsideFn*> used;
        std::vector<Nappe> usedNappes;
        for (std::size_t i = 0; i < fns.size(); ++i) {
            bool nappe = i < nappes.size() && nappes[i].ok;
            if (nappe && attempt == 1) continue;
            used.push_back(fns[i]);
            usedNappes.push_back(nappe ? nappes[i] : Nappe{});
        }
        if (used.empty()) break;
        ConvexRelaxation relaxation(used, usedNappes, region);
        Vec3 interior{kInf, kInf, kInf};
        if (!relaxation.FindInterior(interior)) continue;
        if (attempt == 0) {
            relaxation.OrientNappes(interior);
            if (!VerifyNappeSides(used, relaxation, region, stats)) continue;
        }
        out.solved = true;
        out.usedNappes = attempt == 0;
        const Box3 before = work;
        // One solve per side over the region, then re-certification with balls around the box
        // found so far while it keeps shrinking (the certificate's allowances grow with the
        // ball: a cylinder's rounding-level negative eigenvalue costs ~ eps·R²).
        for (int axis = 0; axis < 3; ++axis) {
            double size = -1;  // learnt from the first direction of each axis
            for (int sign = -1; sign <= 1; sign += 2) {
                double e[3] = {0, 0, 0};
                e[axis] = sign;
                int side = 2 * axis + (sign > 0);
                Vec3 xhat;
                double bound = relaxation.Maximize(e, side, interior, xhat, size);
                if (stats) ++stats->convexSolves;
                if (!std::isfinite(bound)) continue;
                out.extremes[side] = xhat;
                out.haveExtreme[side] = true;
                if (sign > 0)
                    work.hi[axis] = std::fmin(work.hi[axis], bound);
                else
                    work.lo[axis] = std::fmax(work.lo[axis], -bound);
            }
        }
        // The interior point lies in the relaxed set, so every certified side must keep it;
        // one that does not (the certificate's rounding allowances fell short, as for a cone
        // whose apex is 10⁹ sizes away and whose A is PSD only to within 1e-13) is not trusted:
        // the branch-and-bound decides instead.
        bool keepsInterior = true;
        for (int i = 0; i < 3; ++i) {
            double tol = 1e-9 * (std::fabs(interior[i]) + region.hi[i] - region.lo[i]);
            keepsInterior &= work.lo[i] <= interior[i] + tol && interior[i] - tol <= work.hi[i];
        }
        if (!keepsInterior) {
            work = before;
            return RelaxationOutcome{};
        }
        if (work.Empty()) {
            out.empty = true;
            return out;
        }
        double previous = Length(region.Size());
        for (int pass = 0; pass < 4; ++pass) {
            Box3 smaller = work.Intersected(region);
            double size = Length(smaller.Size());
            if (!(size < 0.5 * previous)) break;
            previous = size;
            for (int side = 0; side < 6; ++side) {
                if (!out.haveExtreme[side]) continue;
                int axis = side / 2;
                double bound = relaxation.Recertify(side, smaller);
                if (side % 2)
                    work.hi[axis] = std::fmin(work.hi[axis], bound);
                else
                    work.lo[axis] = std::fmax(work.lo[axis], -bound);
            }
        }
    }
    return out;
}

bool CertifyExtremes(const std::vector<const InsideFn*>& fns, const std::vector<Nappe>& nappes,
                     const Box3& region, const Vec3& interior, const CandidateExtreme extremes[6],
                     Box3& work, double neck[6]) {
    ConvexRelaxation relaxation(fns, nappes, region);
    // A nappe's certificate is its supporting plane, valid only when the body lies in the nappe
    // its axis points to: orient by the interior point, and require a separating plane (the
    // cheap proof; the LP of VerifyNappeSides is the relaxation's business).
    relaxation.OrientNappes(interior);
    for (std::size_t i = 0; i < nappes.size(); ++i)
        if (nappes[i].ok && !relaxation.SeparatedByPlane(i)) return false;
    // Pass 0 with the ball around the region, then (as BoundByConvexRelaxation does) with balls
    // around the box certified so far while it keeps shrinking: the allowances grow with the ball
    // (a cylinder's rounding-level negative eigenvalue costs ~ eps·R²), so from a search region
    // 1e12 wide the box shrinks 1e11 → 1e9 → 1e4 → exact in about five passes of six
    // certificates each.
    constexpr int kMaxPasses = 12;
    Box3 box = work;
    double previous = kInf;
    // Each side certifies the same (x̂, λ) in every pass, with a smaller ball: its sums once.
    ConvexRelaxation::Sums sums[6];
    for (int side = 0; side < 6; ++side) {
        double e[3] = {0, 0, 0};
        e[side / 2] = side % 2 ? 1 : -1;
        const CandidateExtreme& c = extremes[side];
        const double p[3] = {c.x.x, c.x.y, c.x.z};
        sums[side] = relaxation.MakeSums(e, p, c.lambda);
    }
    for (int pass = 0; pass < kMaxPasses; ++pass) {
        const Box3 ball = box.Intersected(region);
        const double size = Length(ball.Size());
        if (pass > 0 && !(size < 0.99 * previous)) break;
        previous = pass > 0 ? size : Length(region.Size());
        for (int side = 0; side < 6; ++side) {
            const int axis = side / 2;
            const CandidateExtreme& c = extremes[side];
            const double neckSlack = sums[side].ok ? sums[side].neckSlack : 0.0;
            const double bound = relaxation.CertifyAt(sums[side], c.x, pass ? &ball : nullptr);
            if (!std::isfinite(bound)) {
                if (pass == 0) return false;
                continue;
            }
            const double before = side % 2 ? box.hi[axis] : -box.lo[axis];
            if (side % 2)
                box.hi[axis] = std::fmin(box.hi[axis], bound);
            else
                box.lo[axis] = std::fmax(box.lo[axis], -bound);
            if (neck && (pass == 0 || bound < before)) neck[side] = neckSlack;
        }
        if (box.Empty()) return false;
    }
    work = box;
    return true;
}

}  // namespace quadrix::bounds_detail
