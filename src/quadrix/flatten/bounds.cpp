// Conservative bounds of bodies and CSG trees; the method is described in bounds.h.
#include "quadrix/flatten/bounds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>

namespace quadrix {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The inside function of one literal (f <= 0 inside) as f(p) = pᵀAp + 2b·p + k; a plane has
// A = 0 and b = n/2. Normalised so that the largest coefficient has magnitude 1 (the scale does
// not change the set and keeps magnitudes in range).
struct InsideFn {
    bool isPlane = true;
    double a[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    double b[3] = {0, 0, 0}, k = 0;
    // Bounds on the eigenvalues of A (lamMin <= λ <= lamMax), widened by a rounding allowance.
    double lamMin = 0, lamMax = 0;
};

// Eigenvalue bounds of the symmetric 3×3 A by cyclic Jacobi rotations, then Gershgorin discs
// around the (almost) diagonal result plus a rounding allowance relative to ‖A‖.
void ComputeEigenBounds(InsideFn& f) {
    double m[3][3];
    double frob = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            m[i][j] = f.a[i][j];
            frob += m[i][j] * m[i][j];
        }
    frob = std::sqrt(frob);
    if (frob == 0) {
        f.lamMin = f.lamMax = 0;
        return;
    }
    if (!std::isfinite(frob)) {
        f.lamMin = -kInf;
        f.lamMax = kInf;
        return;
    }
    for (int sweep = 0; sweep < 12; ++sweep) {
        double off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
        if (off <= 1e-34 * frob * frob) break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (m[p][q] == 0) continue;
                // Jacobi rotation annihilating m[p][q] (Golub & Van Loan, §8.5).
                double theta = (m[q][q] - m[p][p]) / (2 * m[p][q]);
                double t = (theta >= 0 ? 1.0 : -1.0) /
                           (std::fabs(theta) + std::sqrt(theta * theta + 1));
                double c = 1 / std::sqrt(t * t + 1), s = t * c;
                for (int r = 0; r < 3; ++r) {
                    double mrp = m[r][p], mrq = m[r][q];
                    m[r][p] = c * mrp - s * mrq;
                    m[r][q] = s * mrp + c * mrq;
                }
                for (int r = 0; r < 3; ++r) {
                    double mpr = m[p][r], mqr = m[q][r];
                    m[p][r] = c * mpr - s * mqr;
                    m[q][r] = s * mpr + c * mqr;
                }
            }
    }
    double lo = kInf, hi = -kInf;
    for (int i = 0; i < 3; ++i) {
        double radius = 0;
        for (int j = 0; j < 3; ++j)
            if (j != i) radius += std::fabs(m[i][j]);
        lo = std::fmin(lo, m[i][i] - radius);
        hi = std::fmax(hi, m[i][i] + radius);
    }
    double safety = 64 * kEps * frob;
    f.lamMin = lo - safety;
    f.lamMax = hi + safety;
}

InsideFn MakeInsideFn(const FlatHalfSpace& hs, bool complemented) {
    InsideFn f;
    double sign = complemented ? -1.0 : 1.0;
    if (hs.isPlane) {
        const Plane& p = hs.plane;
        double s = std::fmax(std::fmax(std::fabs(p.a), std::fabs(p.b)),
                             std::fmax(std::fabs(p.c), std::fabs(p.d)));
        if (!(s > 0) || !std::isfinite(s)) s = 1;
        s = sign / s;
        f.isPlane = true;
        f.b[0] = 0.5 * (p.a * s);
        f.b[1] = 0.5 * (p.b * s);
        f.b[2] = 0.5 * (p.c * s);
        f.k = p.d * s;
        return f;
    }
    const Quadric& q = hs.quadric;
    double s = q.MaxAbs();
    if (!(s > 0) || !std::isfinite(s)) s = 1;
    s = sign / s;
    f.isPlane = false;
    f.a[0][0] = q.A() * s;
    f.a[1][1] = q.B() * s;
    f.a[2][2] = q.C() * s;
    f.a[0][1] = f.a[1][0] = q.D() * s;
    f.a[1][2] = f.a[2][1] = q.E() * s;
    f.a[0][2] = f.a[2][0] = q.F() * s;
    f.b[0] = q.G() * s;
    f.b[1] = q.H() * s;
    f.b[2] = q.J() * s;
    f.k = q.K() * s;
    ComputeEigenBounds(f);
    return f;
}

double EvaluateAt(const InsideFn& f, const double p[3]) {
    double v = f.k;
    for (int i = 0; i < 3; ++i)
        v += p[i] * (f.a[i][0] * p[0] + f.a[i][1] * p[1] + f.a[i][2] * p[2] + 2 * f.b[i]);
    return v;
}

// Value, gradient and the magnitude of the summed terms (for rounding allowances) at a point.
struct Local {
    double v;
    double g[3];
    double mag;
};

Local EvaluateLocal(const InsideFn& f, const double c[3]) {
    Local l;
    l.v = f.k;
    l.mag = std::fabs(f.k);
    for (int i = 0; i < 3; ++i) {
        double ac = f.a[i][0] * c[0] + f.a[i][1] * c[1] + f.a[i][2] * c[2];
        l.v += c[i] * (ac + 2 * f.b[i]);
        l.g[i] = 2 * (ac + f.b[i]);
        for (int j = 0; j < 3; ++j) l.mag += std::fabs(f.a[i][j] * c[i] * c[j]);
        l.mag += 2 * std::fabs(f.b[i] * c[i]);
    }
    return l;
}

struct Range {
    double lo, hi, margin;
};

// The centred form over |d_i| <= h_i (bounds.h): f(c+d) = f(c) + g·d + dᵀAd with the tighter of
// the entrywise and the Rayleigh bounds for dᵀAd. `slack` (optional) receives each axis' share
// of what lowers the lower bound, used to choose the split axis.
Range RangeFromLocal(const Local& l, const double a[3][3], double lamMin, double lamMax,
                     const double h[3], double* slack) {
    double lini[3], lin = 0;
    for (int i = 0; i < 3; ++i) {
        lini[i] = std::fabs(l.g[i]) * h[i];
        lin += lini[i];
    }
    double qloE = 0, qhiE = 0;
    for (int i = 0; i < 3; ++i) {
        double t = a[i][i] * h[i] * h[i];
        if (t < 0) qloE += t;
        else qhiE += t;
        for (int j = i + 1; j < 3; ++j) {
            double cross = 2 * std::fabs(a[i][j]) * h[i] * h[j];
            qloE -= cross;
            qhiE += cross;
        }
    }
    double hh = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    double qlo = std::fmax(qloE, std::fmin(0.0, lamMin) * hh);
    double qhi = std::fmin(qhiE, std::fmax(0.0, lamMax) * hh);
    if (slack) {
        for (int i = 0; i < 3; ++i)
            slack[i] = lini[i] + (hh > 0 && qlo < 0 ? -qlo * (h[i] * h[i] / hh) : 0.0);
    }
    double mag = l.mag + lin + std::fabs(qlo) + std::fabs(qhi);
    return {l.v - lin + qlo, l.v + lin + qhi, 32 * kEps * mag};
}

// Cholesky factorisation of the m×m submatrix A[idx][idx]; false unless positive definite with
// a pivot ratio (a rough condition number) below kMaxCondition.
constexpr double kMaxCondition = 1e10;

bool Cholesky(const InsideFn& f, const int* idx, int m, double l[3][3], double& condition,
              double maxCondition = kMaxCondition) {
    double minPivot = kInf, maxDiag = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) l[i][j] = 0;
    for (int j = 0; j < m; ++j) {
        maxDiag = std::fmax(maxDiag, std::fabs(f.a[idx[j]][idx[j]]));
        double s = f.a[idx[j]][idx[j]];
        for (int k = 0; k < j; ++k) s -= l[j][k] * l[j][k];
        if (!(s > 0) || !std::isfinite(s)) return false;
        minPivot = std::fmin(minPivot, s);
        l[j][j] = std::sqrt(s);
        for (int i = j + 1; i < m; ++i) {
            double t = f.a[idx[i]][idx[j]];
            for (int k = 0; k < j; ++k) t -= l[i][k] * l[j][k];
            l[i][j] = t / l[j][j];
        }
    }
    condition = maxDiag / minPivot;
    return condition < maxCondition;
}

void CholeskySolve(const double l[3][3], int m, const double* rhs, double* x) {
    double y[3];
    for (int i = 0; i < m; ++i) {
        double s = rhs[i];
        for (int k = 0; k < i; ++k) s -= l[i][k] * y[k];
        y[i] = s / l[i][i];
    }
    for (int i = m - 1; i >= 0; --i) {
        double s = y[i];
        for (int k = i + 1; k < m; ++k) s -= l[k][i] * x[k];
        x[i] = s / l[i][i];
    }
}

Box3 AnalyticPlaneBox(const InsideFn& f) {
    int nonZero = 0, axis = -1;
    for (int i = 0; i < 3; ++i)
        if (f.b[i] != 0) {
            ++nonZero;
            axis = i;
        }
    if (nonZero == 0) return f.k <= 0 ? Box3::Everything() : Box3{};
    Box3 box = Box3::Everything();
    if (nonZero == 1) {
        double bound = -f.k / (2 * f.b[axis]);
        if (!std::isfinite(bound)) return box;
        // One rounded division: step one ulp outward to stay conservative.
        if (f.b[axis] > 0) box.hi[axis] = std::nextafter(bound, kInf);
        else box.lo[axis] = std::nextafter(bound, -kInf);
    }
    return box;
}

// Stage (a) for one inside function. `centre` receives the ellipsoid's centre (0 on free axes)
// when there is one: a good seed for the inner box.
Box3 AnalyticBox(const InsideFn& f, Vec3* centre, bool* hasCentre) {
    *hasCentre = false;
    if (f.isPlane) return AnalyticPlaneBox(f);
    // Axes the quadric does not depend on are free (an elliptic cylinder along them).
    int idx[3], m = 0;
    for (int i = 0; i < 3; ++i) {
        bool freeAxis = f.b[i] == 0 && f.a[i][0] == 0 && f.a[i][1] == 0 && f.a[i][2] == 0;
        if (!freeAxis) idx[m++] = i;
    }
    if (m == 0) return f.k <= 0 ? Box3::Everything() : Box3{};
    double l[3][3], condition = 0;
    if (!Cholesky(f, idx, m, l, condition)) return Box3::Everything();
    double rhs[3], cs[3];
    for (int i = 0; i < m; ++i) rhs[i] = -f.b[idx[i]];
    CholeskySolve(l, m, rhs, cs);
    double p[3] = {0, 0, 0};
    for (int i = 0; i < m; ++i) p[idx[i]] = cs[i];
    // R = bᵀA⁻¹b - k computed as -f(c̃) at the computed centre c̃: f is stationary at the true
    // centre, so the centre's error (relative cond·eps) enters R only to second order, and the
    // cancellation between bᵀA⁻¹b and k (a small ellipsoid far from the origin) costs only the
    // rounding of one evaluation. The centre's own error is covered by the padding below.
    Local at = EvaluateLocal(f, p);
    double rErr = 32 * kEps * at.mag;
    double r = -at.v;
    if (r < -rErr) return Box3{};  // provably empty
    r = std::fmax(r, 0.0) + rErr;
    double rel = 64 * kEps * condition;
    Box3 box = Box3::Everything();
    for (int i = 0; i < m; ++i) {
        double e[3] = {0, 0, 0}, col[3];
        e[i] = 1;
        CholeskySolve(l, m, e, col);  // column i of A⁻¹ (restricted to the bounded axes)
        double half = std::sqrt(r * std::fmax(col[i], 0.0)) * (1 + rel);
        double pad = rel * (std::fabs(cs[i]) + half) + 1e-300;
        box.lo[idx[i]] = cs[i] - half - pad;
        box.hi[idx[i]] = cs[i] + half + pad;
    }
    *centre = Vec3{p[0], p[1], p[2]};
    *hasCentre = true;
    return box;
}

// Solves the k×k system m x = r (k <= 3) by Gaussian elimination with partial pivoting; false
// when (nearly) singular.
bool SolveSmall(int k, double m[3][3], double r[3], double x[3]) {
    for (int col = 0; col < k; ++col) {
        int piv = col;
        for (int i = col + 1; i < k; ++i)
            if (std::fabs(m[i][col]) > std::fabs(m[piv][col])) piv = i;
        if (!(std::fabs(m[piv][col]) > 1e-12)) return false;
        for (int j = 0; j < k; ++j) std::swap(m[piv][j], m[col][j]);
        std::swap(r[piv], r[col]);
        for (int i = col + 1; i < k; ++i) {
            double f = m[i][col] / m[col][col];
            for (int j = col; j < k; ++j) m[i][j] -= f * m[col][j];
            r[i] -= f * r[col];
        }
    }
    for (int i = k - 1; i >= 0; --i) {
        double s = r[i];
        for (int j = i + 1; j < k; ++j) s -= m[i][j] * x[j];
        x[i] = s / m[i][i];
    }
    return true;
}

// Non-negative multipliers λ (at most 3 non-zero, by Carathéodory in R³) minimising
// |Σ λ_i g_i - t| over the given gradients (n <= kMaxSurrogate), by enumerating supports.
// Returns false when no support of at least minSupport members has positive multipliers.
constexpr int kMaxSurrogate = 4;

bool NonNegativeCombination(int n, const double g[][3], const double t[3], double lambda[],
                            int minSupport = 2) {
    double bestResidual = kInf;
    bool found = false;
    for (int subset = 1; subset < (1 << n); ++subset) {
        int members[3], k = 0;
        bool tooMany = false;
        for (int i = 0; i < n; ++i)
            if (subset >> i & 1) {
                if (k == 3) {
                    tooMany = true;
                    break;
                }
                members[k++] = i;
            }
        if (tooMany || k < minSupport) continue;
        // Normal equations GᵀG x = Gᵀt over the support.
        double m[3][3], r[3], x[3];
        for (int i = 0; i < k; ++i) {
            const double* gi = g[members[i]];
            r[i] = gi[0] * t[0] + gi[1] * t[1] + gi[2] * t[2];
            for (int j = 0; j < k; ++j) {
                const double* gj = g[members[j]];
                m[i][j] = gi[0] * gj[0] + gi[1] * gj[1] + gi[2] * gj[2];
            }
        }
        if (!SolveSmall(k, m, r, x)) continue;
        bool positive = true;
        for (int i = 0; i < k; ++i) positive &= x[i] > 0;
        if (!positive) continue;
        double res[3] = {-t[0], -t[1], -t[2]};
        for (int i = 0; i < k; ++i)
            for (int j = 0; j < 3; ++j) res[j] += x[i] * g[members[i]][j];
        double residual = res[0] * res[0] + res[1] * res[1] + res[2] * res[2];
        if (residual < bestResidual) {
            bestResidual = residual;
            for (int i = 0; i < n; ++i) lambda[i] = 0;
            for (int i = 0; i < k; ++i) lambda[members[i]] = x[i];
            found = true;
        }
    }
    return found;
}

// One branch-and-bound cell.
struct Cell {
    double key;  // sign × the coordinate of the cell's face in the searched direction
    double c[3], h[3];
    double share[3];     // each axis' share of the undecided slack (where to split)
    std::uint64_t mask;  // literals still undecided on this cell (bit i = fns[i], i < 64)
};

struct CellLess {
    bool operator()(const Cell& x, const Cell& y) const { return x.key < y.key; }
};


// Stage (b1): the convex relaxation, solved by a log-barrier interior-point method and certified
// by Lagrangian duality (bounds.h).
//
// The relaxation keeps the planes and positive semidefinite quadrics of the body (dropping a
// literal only enlarges the set: conservative) plus the six planes of the search region, so it is
// bounded. For direction e the central path minimises  -t e·x - Σ log(-f_i(x))  for growing t; its
// points give multipliers λ_i = 1 / (t · (-f_i(x̂))) >= 0 with e ≈ Σ λ_i ∇f_i(x̂) (KKT) and a
// duality gap of (number of constraints) / t.
//
// Certificate (weak duality, valid for any λ >= 0 and any x̂): for x in the set and the region,
//     e·x <= L(x) = e·x - Σ λ_i f_i(x) - μ f_ball(x),
// where f_ball <= 0 is a ball containing the region (μ >= 0 keeps M = Σ λ_i A_i + μ I/R² positive
// definite for cylinders and paraboloids). L is quadratic with Hessian -2M, so
//     L(x) <= L(x̂) + |r|² / (4 λmin(M)),   r = ∇L(x̂),   λmin(M) >= Σ λ_i λmin(A_i) + μ/R²,
// evaluated with rounding allowances. The solver's accuracy only affects how tight it is.
class ConvexRelaxation {
public:
    ConvexRelaxation(std::vector<const InsideFn*> fns, const Box3& region) : region_(region) {
        for (const InsideFn* f : fns) cons_.push_back(*f);
        // The region's faces as planes x_i - hi <= 0 and lo - x_i <= 0 (scaled to unit normals).
        for (int i = 0; i < 3; ++i)
            for (int sign = -1; sign <= 1; sign += 2) {
                InsideFn p;
                p.isPlane = true;
                p.b[i] = 0.5 * sign;
                p.k = sign > 0 ? -region.hi[i] : region.lo[i];
                cons_.push_back(p);
            }
        Vec3 size = region.Size();
        radius_ = 0.5 * Length(size) * (1 + 1e-9) + 1e-300;
        centre_ = region.Center();
        scale_ = std::fmax(size.x, std::fmax(size.y, size.z));
    }

    // Phase I: a point where every constraint is strictly negative; false when none was found
    // (an empty or flat set: the caller falls back to the branch-and-bound).
    bool FindInterior(Vec3& out) {
        // Minimise s subject to f_i(x) <= s over (x, s), starting at the region's centre; stop as
        // soon as s < 0.
        double y[4] = {centre_.x, centre_.y, centre_.z, 0};
        double worst = -kInf;
        for (const InsideFn& f : cons_) worst = std::fmax(worst, EvaluateAt(f, y));
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
            if (n / t < 1e-12 * scale_ * scale_) return false;  // converged with s >= 0
            t *= 10;
        }
        return false;
    }

    // A rigorous upper bound of sign·x_axis over the set ∩ region, from the interior point
    // `start`; +inf when the iterations failed. `xhat` receives the relaxation's extreme point.
    double Maximize(int axis, int sign, const Vec3& start, Vec3& xhat) {
        const int n = static_cast<int>(cons_.size());
        double e[3] = {0, 0, 0};
        e[axis] = sign;
        double x[3] = {start.x, start.y, start.z};
        double t = n / scale_;  // initial duality gap: about the region's size
        const double startValue = sign * start[axis];
        for (int outer = 0; outer < 80; ++outer) {
            if (!Center(e, t, x)) return kInf;
            double reach = sign * x[axis] - startValue;
            // Stop when the duality gap is a small fraction of the distance covered (about the
            // body's half-size in this direction).
            if (n / t <= 1e-7 * std::fmax(reach, 1e-12 * scale_)) break;
            t *= 20;
        }
        xhat = Vec3{x[0], x[1], x[2]};
        // Multipliers of the central path, then polished: the KKT multipliers of the (at most
        // three) constraints that carry most of the weight, by non-negative least squares at x̂.
        // The polished ones make the residual r vanish to rounding at a vertex or rim.
        std::vector<double> lambda(n, 0.0), polished(n, 0.0);
        int top[kMaxSurrogate];
        double topWeight[kMaxSurrogate];
        int count = 0;
        for (int i = 0; i < n; ++i) {
            double v = EvaluateAt(cons_[i], x);
            lambda[i] = v < 0 ? 1 / (t * -v) : 0.0;
            Local l = EvaluateLocal(cons_[i], x);
            double w = lambda[i] * std::sqrt(l.g[0] * l.g[0] + l.g[1] * l.g[1] + l.g[2] * l.g[2]);
            // Keep the kMaxSurrogate heaviest (insertion into a tiny sorted list).
            int pos = count < kMaxSurrogate ? count++ : kMaxSurrogate;
            while (pos > 0 && topWeight[pos - 1] < w) {
                if (pos < kMaxSurrogate) {
                    top[pos] = top[pos - 1];
                    topWeight[pos] = topWeight[pos - 1];
                }
                --pos;
            }
            if (pos < kMaxSurrogate) {
                top[pos] = i;
                topWeight[pos] = w;
            }
        }
        double bound = Certify(e, x, lambda);
        double g[kMaxSurrogate][3], mult[kMaxSurrogate];
        for (int k = 0; k < count; ++k) {
            Local l = EvaluateLocal(cons_[top[k]], x);
            for (int j = 0; j < 3; ++j) g[k][j] = l.g[j];
        }
        if (NonNegativeCombination(count, g, e, mult, 1)) {
            for (int k = 0; k < count; ++k) polished[top[k]] = mult[k];
            bound = std::fmin(bound, Certify(e, x, polished));
        }
        return bound;
    }

private:
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
            double step[4];
            if (!SolveNewton(3, hess, grad, step)) return false;
            double decrement = -(grad[0] * step[0] + grad[1] * step[1] + grad[2] * step[2]);
            if (decrement < 1e-14) return true;
            if (!LineSearchCenter(e, t, x, step, grad)) return true;  // no progress possible
            if (decrement < 1e-10) return true;
        }
        return true;
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
        double s = 1;
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
            for (const InsideFn& f : cons_) {
                double u = p[3] - EvaluateAt(f, p);
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

    // Solves H step = -grad (n = 3 or 4) by Gaussian elimination with partial pivoting.
    static bool SolveNewton(int n, double h[4][4], const double grad[4], double step[4]) {
        double r[4];
        for (int i = 0; i < n; ++i) r[i] = -grad[i];
        for (int col = 0; col < n; ++col) {
            int piv = col;
            for (int i = col + 1; i < n; ++i)
                if (std::fabs(h[i][col]) > std::fabs(h[piv][col])) piv = i;
            if (!(std::fabs(h[piv][col]) > 0) || !std::isfinite(h[piv][col])) return false;
            if (piv != col) {
                for (int j = 0; j < n; ++j) std::swap(h[piv][j], h[col][j]);
                std::swap(r[piv], r[col]);
            }
            for (int i = col + 1; i < n; ++i) {
                double f = h[i][col] / h[col][col];
                for (int j = col; j < n; ++j) h[i][j] -= f * h[col][j];
                r[i] -= f * r[col];
            }
        }
        for (int i = n - 1; i >= 0; --i) {
            double s = r[i];
            for (int j = i + 1; j < n; ++j) s -= h[i][j] * step[j];
            step[i] = s / h[i][i];
            if (!std::isfinite(step[i])) return false;
        }
        return true;
    }

    // The rigorous bound L(x̂) + sup_d (r·d - dᵀMd) (class comment), minimised over the ball
    // multiplier μ among a few candidates. sup_d = ¼ rᵀM⁻¹r, taken from a Cholesky solve when M
    // is well conditioned (its rounding then costs far less than the 1% added), else bounded by
    // |r|² / (4 λmin(M)) with Weyl's λmin.
    double Certify(const double e[3], const double x[3], const std::vector<double>& lambda) const {
        constexpr double kGamma = 64 * kEps;
        double lhat = e[0] * x[0] + e[1] * x[1] + e[2] * x[2];
        double errL = std::fabs(lhat);
        double r[3] = {e[0], e[1], e[2]}, errR[3] = {1, 1, 1};
        double m0 = 0;
        InsideFn mSum;  // Σ λ_i A_i, in an InsideFn to reuse Cholesky
        for (std::size_t i = 0; i < cons_.size(); ++i) {
            double w = lambda[i];
            if (w == 0) continue;
            const InsideFn& f = cons_[i];
            Local l = EvaluateLocal(f, x);
            lhat -= w * l.v;
            errL += w * (std::fabs(l.v) + l.mag);
            for (int j = 0; j < 3; ++j) {
                r[j] -= w * l.g[j];
                double gm = 2 * (std::fabs(f.a[j][0] * x[0]) + std::fabs(f.a[j][1] * x[1]) +
                                 std::fabs(f.a[j][2] * x[2]) + std::fabs(f.b[j]));
                errR[j] += w * (std::fabs(l.g[j]) + gm);
                for (int k = 0; k < 3; ++k) mSum.a[j][k] += w * f.a[j][k];
            }
            m0 += w * f.lamMin;
        }
        double base = lhat + kGamma * errL;
        // The ball |x - c|² <= R² around the region: f_ball = (|x - c|² - R²)/R², gradient
        // 2(x - c)/R², λmin = 1/R²; -f_ball <= 1 in the region.
        double r2 = radius_ * radius_;
        double gb[3] = {2 * (x[0] - centre_.x) / r2, 2 * (x[1] - centre_.y) / r2,
                        2 * (x[2] - centre_.z) / r2};
        double fb = ((x[0] - centre_.x) * (x[0] - centre_.x) +
                     (x[1] - centre_.y) * (x[1] - centre_.y) +
                     (x[2] - centre_.z) * (x[2] - centre_.z) - r2) / r2;
        double r0 = 0;
        for (int j = 0; j < 3; ++j) {
            double rj = std::fabs(r[j]) + kGamma * errR[j];
            r0 += rj * rj;
        }
        r0 = std::sqrt(r0);
        double best = kInf;
        const double muCandidates[5] = {0, 0.05 * r0 * radius_, 0.5 * r0 * radius_,
                                        5 * r0 * radius_, 1e-300};
        for (double mu : muCandidates) {
            double m = (m0 + mu / r2) * (1 - 1e-12);
            if (!(m > 0)) continue;
            // r = r̃ + δ with |δ_j| <= γ errR_j: (r̃+δ)ᵀM⁻¹(r̃+δ) <= (√(r̃ᵀM⁻¹r̃) + |δ|/√λmin)².
            double rt[3], delta2 = 0, rNorm2 = 0;
            for (int j = 0; j < 3; ++j) {
                rt[j] = r[j] - mu * gb[j];
                double dj = kGamma * (errR[j] + mu * std::fabs(gb[j]));
                delta2 += dj * dj;
                double aj = std::fabs(rt[j]) + dj;
                rNorm2 += aj * aj;
            }
            double quad = rNorm2 / (4 * m);
            InsideFn mm = mSum;
            for (int j = 0; j < 3; ++j) mm.a[j][j] += mu / r2;
            const int idx[3] = {0, 1, 2};
            double l[3][3], condition;
            if (Cholesky(mm, idx, 3, l, condition, 1e8)) {
                double y[3];
                CholeskySolve(l, 3, rt, y);
                double form = rt[0] * y[0] + rt[1] * y[1] + rt[2] * y[2];
                if (form >= 0 && std::isfinite(form)) {
                    double root = std::sqrt(1.01 * form) + std::sqrt(delta2 / m);
                    quad = std::fmin(quad, 0.25 * root * root);
                }
            }
            double bound = base - mu * fb + kGamma * mu * 4 + quad;
            if (std::isfinite(bound)) best = std::fmin(best, bound);
        }
        return best;
    }

    std::vector<InsideFn> cons_;
    Box3 region_;
    Vec3 centre_;
    double radius_ = 0, scale_ = 0;
};

// Stage (b2): refines a box side by side. See bounds.h for the method.
class Refiner {
public:
    Refiner(std::vector<InsideFn> fns, const BoundsOptions& options, BoundsStats* stats)
        : fns_(std::move(fns)), options_(options), stats_(stats) {
        allMask_ = fns_.size() >= 64 ? ~std::uint64_t{0}
                                     : ((std::uint64_t{1} << fns_.size()) - 1);
        locals_.resize(fns_.size());
        undecided_.reserve(fns_.size());
    }

    void Seed(const Vec3& p) {
        double q[3] = {p.x, p.y, p.z};
        if (IsInside(q, allMask_)) inner_.Extend(p);
    }

    // Refines the sides selected by sides[2*axis + (sign > 0)]; returns false when the set is
    // proven empty.
    bool Refine(Box3& work, const bool sides[6]) {
        bool huge = false;
        for (int i = 0; i < 3; ++i)
            huge |= !(work.lo[i] >= -UnboundedThreshold() && work.hi[i] <= UnboundedThreshold());
        if (huge && !Localize(work)) return false;
        // Screen axes first: they matter most to the Flattener.
        for (int axis = 0; axis < 3; ++axis)
            for (int sign = -1; sign <= 1; sign += 2) {
                if (!sides[2 * axis + (sign > 0)]) continue;
                if (!RefineSide(work, axis, sign)) return false;
            }
        return true;
    }

    double UnboundedThreshold() const { return 1e-3 * options_.searchLimit; }

private:
    bool Active(std::uint64_t mask, std::size_t i) const {
        return i >= 64 || (mask >> i & 1u);
    }

    bool IsInside(const double p[3], std::uint64_t mask) const {
        for (std::size_t i = 0; i < fns_.size(); ++i)
            if (Active(mask, i) && !(EvaluateAt(fns_[i], p) <= 0)) return false;
        return true;
    }

    // Classifies a cell for the search along (axis, sign) (axis < 0: no direction, while
    // localising): false when it is certainly outside the set; otherwise narrows its mask and
    // fills its split shares.
    bool Assess(Cell& cell, int axis, int sign) {
        if (stats_) ++stats_->boxesTested;
        std::uint64_t mask = cell.mask;
        undecided_.clear();
        double shareSingle[3] = {0, 0, 0};
        for (std::size_t i = 0; i < fns_.size(); ++i) {
            if (!Active(mask, i)) continue;
            const InsideFn& f = fns_[i];
            locals_[i] = EvaluateLocal(f, cell.c);
            double slack[3];
            Range r = RangeFromLocal(locals_[i], f.a, f.lamMin, f.lamMax, cell.h, slack);
            if (r.lo > r.margin) return false;  // NaN compares false: never "outside"
            if (r.hi <= -r.margin && i < 64) {
                mask &= ~(std::uint64_t{1} << i);
                continue;
            }
            undecided_.push_back(static_cast<int>(i));
            double total = slack[0] + slack[1] + slack[2];
            if (total > 0 && std::isfinite(total))
                for (int j = 0; j < 3; ++j) shareSingle[j] += slack[j] / total;
        }
        cell.mask = mask;
        for (int j = 0; j < 3; ++j) cell.share[j] = shareSingle[j];
        if (axis >= 0 && undecided_.size() >= 2) {
            double surrogateShare[3];
            if (SurrogateExcludes(cell, axis, sign, surrogateShare)) return false;
            if (std::isfinite(surrogateShare[0]))
                for (int j = 0; j < 3; ++j) cell.share[j] += surrogateShare[j];
        }
        return true;
    }

    // Near an extreme point where several literals are active (a rim, a vertex) no single
    // literal excludes the cells just beyond it unless they are tiny. A non-negative
    // combination Σλ_i f_i is <= 0 wherever all f_i are, so it may exclude a cell too; with λ
    // chosen so that its gradient at the cell's centre points along the searched direction (as
    // the KKT multipliers do at the extreme), cells beyond the extreme are excluded as thin slabs,
    // as at a smooth extreme. `share` receives the combination's slack shares (NaN when none).
    bool SurrogateExcludes(const Cell& cell, int axis, int sign, double share[3]) {
        share[0] = share[1] = share[2] = std::numeric_limits<double>::quiet_NaN();
        int n = std::min<int>(static_cast<int>(undecided_.size()), kMaxSurrogate);
        double g[kMaxSurrogate][3], lambda[kMaxSurrogate];
        for (int i = 0; i < n; ++i) {
            const Local& l = locals_[undecided_[i]];
            // Normalise each gradient so the multipliers are comparable.
            double len = std::sqrt(l.g[0] * l.g[0] + l.g[1] * l.g[1] + l.g[2] * l.g[2]);
            if (!(len > 0) || !std::isfinite(len)) return false;
            for (int j = 0; j < 3; ++j) g[i][j] = l.g[j] / len;
        }
        double target[3] = {0, 0, 0};
        target[axis] = sign;
        if (!NonNegativeCombination(n, g, target, lambda)) return false;
        Local sum{0, {0, 0, 0}, 0};
        double a[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        double lamMin = 0, lamMax = 0;
        for (int i = 0; i < n; ++i) {
            if (lambda[i] == 0) continue;
            const InsideFn& f = fns_[undecided_[i]];
            const Local& l = locals_[undecided_[i]];
            double len = std::sqrt(l.g[0] * l.g[0] + l.g[1] * l.g[1] + l.g[2] * l.g[2]);
            double w = lambda[i] / len;
            sum.v += w * l.v;
            sum.mag += w * l.mag;
            for (int j = 0; j < 3; ++j) {
                sum.g[j] += w * l.g[j];
                for (int k = 0; k < 3; ++k) a[j][k] += w * f.a[j][k];
            }
            // Weyl: the eigenvalues of a sum lie within the sums of the bounds.
            lamMin += w * f.lamMin;
            lamMax += w * f.lamMax;
        }
        // The combination's own rounding (a few ulps of each weighted term) joins the margin.
        sum.mag *= 2;
        Range r = RangeFromLocal(sum, a, lamMin, lamMax, cell.h, share);
        double total = share[0] + share[1] + share[2];
        if (total > 0 && std::isfinite(total))
            for (int j = 0; j < 3; ++j) share[j] /= total;
        else
            share[0] = share[1] = share[2] = std::numeric_limits<double>::quiet_NaN();
        return r.lo > r.margin;
    }

    // The axis to split: the largest share of the undecided literals' slack, plus half a
    // literal's worth for the searched axis (which is what narrows the bound itself) unless the
    // cell is already much thinner than the tolerance along it.
    int SplitAxis(const Cell& cell, int axis, double tol) const {
        double share[3] = {cell.share[0], cell.share[1], cell.share[2]};
        bool thin = cell.h[axis] < 0.125 * tol;
        if (!thin) share[axis] += 0.5;
        int best = -1;
        for (int j = 0; j < 3; ++j) {
            if (!(cell.h[j] > 0) || (thin && j == axis)) continue;
            if (best < 0 || share[j] > share[best]) best = j;
        }
        return best < 0 ? axis : best;
    }

    // Phase 0: isotropic subdivision of the (possibly huge) starting box down to cells a quarter
    // of the size of what is left, so the directional searches start from a box of about the
    // set's size instead of the search limit (bisection from 10^6 × the scene scale with huge
    // lateral extents would otherwise spend its budget on cells tied in the searched coordinate).
    bool Localize(Box3& work) {
        const double limit = options_.searchLimit;
        std::vector<Cell> cells(1), next;
        Cell& root = cells[0];
        for (int i = 0; i < 3; ++i) {
            double lo = std::fmax(work.lo[i], -limit), hi = std::fmin(work.hi[i], limit);
            if (!(lo <= hi)) return true;  // beyond the search limit: leave as is
            root.c[i] = 0.5 * lo + 0.5 * hi;
            root.h[i] = 0.5 * hi - 0.5 * lo;
        }
        root.mask = allMask_;
        if (!Assess(root, -1, 0)) return false;
        constexpr std::size_t kMaxCells = 256;
        for (int round = 0; round < 400; ++round) {
            Box3 hull;
            double maxHalf = 0;
            for (const Cell& c : cells) {
                hull.Extend(Vec3{c.c[0] - c.h[0], c.c[1] - c.h[1], c.c[2] - c.h[2]});
                hull.Extend(Vec3{c.c[0] + c.h[0], c.c[1] + c.h[1], c.c[2] + c.h[2]});
                if (c.mask != 0) maxHalf = std::fmax(maxHalf, std::fmax(c.h[0], std::fmax(c.h[1], c.h[2])));
            }
            Vec3 size = hull.Size();
            double extent = std::fmax(size.x, std::fmax(size.y, size.z));
            if (2 * maxHalf <= 0.25 * extent || cells.size() > kMaxCells) break;
            next.clear();
            for (const Cell& c : cells) {
                if (c.mask == 0) {  // entirely inside: nothing to refine
                    next.push_back(c);
                    continue;
                }
                int s = 0;
                for (int j = 1; j < 3; ++j)
                    if (c.h[j] > c.h[s]) s = j;
                double half = 0.5 * c.h[s];
                if (!(half > 8 * kEps * std::fabs(c.c[s])) || !(half > 1e-290)) {
                    next.push_back(c);
                    continue;
                }
                for (int side = -1; side <= 1; side += 2) {
                    Cell child = c;
                    child.h[s] = half;
                    child.c[s] = c.c[s] + side * half;
                    if (!Assess(child, -1, 0)) continue;
                    if (IsInside(child.c, child.mask))
                        inner_.Extend(Vec3{child.c[0], child.c[1], child.c[2]});
                    next.push_back(child);
                }
            }
            if (next.empty()) return false;
            cells.swap(next);
        }
        Box3 hull;
        for (const Cell& c : cells) {
            hull.Extend(Vec3{c.c[0] - c.h[0], c.c[1] - c.h[1], c.c[2] - c.h[2]});
            hull.Extend(Vec3{c.c[0] + c.h[0], c.c[1] + c.h[1], c.c[2] + c.h[2]});
        }
        // Sides still at the search limit stay as they were (possibly infinite).
        for (int i = 0; i < 3; ++i) {
            if (hull.lo[i] > -limit) work.lo[i] = std::fmax(work.lo[i], hull.lo[i]);
            if (hull.hi[i] < limit) work.hi[i] = std::fmin(work.hi[i], hull.hi[i]);
        }
        return true;
    }

    double Tolerance() const {
        if (inner_.Empty()) return 0;
        double size = 0;
        for (int i = 0; i < 3; ++i) size = std::fmax(size, inner_.hi[i] - inner_.lo[i]);
        return std::fmax(options_.relTolerance * size, 1e-15 * options_.searchLimit);
    }

    // Probes a point of the cell on its extreme face, then its centre, for the inner box.
    void Probe(const Cell& cell, int axis, int sign) {
        double p[3] = {cell.c[0], cell.c[1], cell.c[2]};
        p[axis] = cell.c[axis] + sign * cell.h[axis];
        if (IsInside(p, cell.mask)) {
            inner_.Extend(Vec3{p[0], p[1], p[2]});
            return;
        }
        if (IsInside(cell.c, cell.mask)) inner_.Extend(Vec3{cell.c[0], cell.c[1], cell.c[2]});
    }

    bool RefineSide(Box3& work, int axis, int sign) {
        const double limit = options_.searchLimit;
        Cell root;
        for (int i = 0; i < 3; ++i) {
            double lo = std::fmax(work.lo[i], -limit), hi = std::fmin(work.hi[i], limit);
            if (!(lo <= hi)) return true;  // entirely beyond the search limit: leave as is
            root.c[i] = 0.5 * lo + 0.5 * hi;
            root.h[i] = 0.5 * hi - 0.5 * lo;
        }
        root.mask = allMask_;
        root.key = sign * (root.c[axis] + sign * root.h[axis]);
        if (!Assess(root, axis, sign)) return false;
        Probe(root, axis, sign);

        std::priority_queue<Cell, std::vector<Cell>, CellLess> queue;
        queue.push(root);
        int popped = 0;
        while (!queue.empty()) {
            Cell cell = queue.top();
            queue.pop();
            ++popped;
            if (stats_) ++stats_->boxesPopped;
            double face = cell.c[axis] + sign * cell.h[axis];
            int s = SplitAxis(cell, axis, Tolerance());
            double half = 0.5 * cell.h[s];
            bool splittable = half > 8 * kEps * std::fabs(cell.c[s]) && half > 1e-290;
            if (Done(cell, axis, sign, popped) || !splittable) {
                SetSide(work, axis, sign, face);
                return true;
            }
            for (int side = -1; side <= 1; side += 2) {
                Cell child = cell;
                child.h[s] = half;
                child.c[s] = cell.c[s] + side * half;
                if (!Assess(child, axis, sign)) continue;
                child.key = sign * (child.c[axis] + sign * child.h[axis]);
                Probe(child, axis, sign);
                queue.push(child);
            }
        }
        return false;  // every cell was excluded: the set is empty
    }

    bool Done(const Cell& cell, int axis, int sign, int popped) {
        if (cell.mask == 0) return true;  // the whole cell is in the set: the face is attained
        if (popped > options_.maxBoxesPerDirection) {
            if (stats_) ++stats_->budgetExhausted;
            return true;
        }
        if (inner_.Empty()) return false;
        double tol = Tolerance();
        double reached = sign > 0 ? inner_.hi[axis] : -inner_.lo[axis];
        if (reached > UnboundedThreshold()) return true;  // will be reported unbounded anyway
        return cell.key - reached <= tol;
    }

    void SetSide(Box3& work, int axis, int sign, double face) const {
        if (sign > 0) work.hi[axis] = std::fmin(work.hi[axis], face);
        else work.lo[axis] = std::fmax(work.lo[axis], face);
    }

    std::vector<InsideFn> fns_;
    BoundsOptions options_;
    BoundsStats* stats_;
    std::uint64_t allMask_ = 0;
    std::vector<Local> locals_;     // per literal, valid for the cell being assessed
    std::vector<int> undecided_;    // literals undecided on the cell being assessed
    Box3 inner_;                    // box of points found in the set
};

}  // namespace

Box3 LiteralBox(const FlatHalfSpace& halfSpace, bool complemented) {
    Vec3 centre;
    bool hasCentre;
    return AnalyticBox(MakeInsideFn(halfSpace, complemented), &centre, &hasCentre);
}

double HalfSpaceScale(const FlatHalfSpace& hs) {
    if (hs.isPlane) {
        double n = Length(hs.plane.Normal());
        double s = n > 0 ? std::fabs(hs.plane.d) / n : 0.0;
        return std::isfinite(s) ? s : 0.0;
    }
    // Largest of |b|/|A| (about the distance of the centre), sqrt(|k|/|A|) (about a radius) and
    // the coordinates of the analytic box.
    const Quadric& q = hs.quadric;
    double aMax = 0;
    for (int i = 0; i < 6; ++i) aMax = std::fmax(aMax, std::fabs(q.k[i]));
    double bMax = std::fmax(std::fabs(q.G()), std::fmax(std::fabs(q.H()), std::fabs(q.J())));
    double s = 0;
    if (aMax > 0) s = std::fmax(bMax / aMax, std::sqrt(std::fabs(q.K()) / aMax));
    else if (bMax > 0) s = std::fabs(q.K()) / bMax;
    Box3 box = LiteralBox(hs, false);
    for (int i = 0; i < 3; ++i) {
        if (std::isfinite(box.lo[i])) s = std::fmax(s, std::fabs(box.lo[i]));
        if (std::isfinite(box.hi[i])) s = std::fmax(s, std::fabs(box.hi[i]));
    }
    return std::isfinite(s) ? s : 0.0;
}

Box3 IntersectionBounds(std::span<const BoundLiteral> literals, const BoundsOptions& options,
                        BoundsStats* stats) {
    if (stats) ++stats->bodies;
    std::vector<InsideFn> fns;
    std::vector<Box3> boxes;
    std::vector<Vec3> seeds;
    fns.reserve(literals.size());
    boxes.reserve(literals.size());
    Box3 b0 = Box3::Everything();
    for (const BoundLiteral& lit : literals) {
        fns.push_back(MakeInsideFn(*lit.halfSpace, lit.complemented));
        Vec3 centre;
        bool hasCentre = false;
        boxes.push_back(AnalyticBox(fns.back(), &centre, &hasCentre));
        if (hasCentre) seeds.push_back(centre);
        b0 = b0.Intersected(boxes.back());
    }
    if (b0.Empty()) return Box3{};

    // Drop literals that contain all of B0: they cannot shape the set inside B0.
    std::vector<InsideFn> shaping;
    int shapingIndex = -1;
    bool b0Finite = b0.Finite();
    double c[3], h[3];
    for (int j = 0; j < 3; ++j) {
        c[j] = 0.5 * b0.lo[j] + 0.5 * b0.hi[j];
        h[j] = 0.5 * b0.hi[j] - 0.5 * b0.lo[j];
    }
    for (std::size_t i = 0; i < fns.size(); ++i) {
        if (b0Finite) {
            const InsideFn& f = fns[i];
            Range r = RangeFromLocal(EvaluateLocal(f, c), f.a, f.lamMin, f.lamMax, h, nullptr);
            if (r.hi <= r.margin) continue;
        }
        shaping.push_back(fns[i]);
        shapingIndex = static_cast<int>(i);
    }
    if (shaping.empty()) {
        if (stats) ++stats->analyticOnly;
        return b0;
    }
    // One shaping quadric whose analytic bounds are B0's on every axis it bounds: within B0 the
    // set is its ellipse/ellipsoid section times B0's range on its free axes (AnalyticBox bounds a
    // quadric only when it is positive definite on the axes it depends on and free along the
    // others), so B0 is exact.
    if (shaping.size() == 1 && !shaping[0].isPlane) {
        const Box3& own = boxes[shapingIndex];
        bool exact = false;
        for (int i = 0; i < 3; ++i) {
            if (!(std::isfinite(own.lo[i]) && std::isfinite(own.hi[i]))) continue;
            exact = own.lo[i] == b0.lo[i] && own.hi[i] == b0.hi[i];
            if (!exact) break;
        }
        if (exact) {
            if (stats) ++stats->analyticOnly;
            return b0;
        }
    }
    double previousSize = kInf;
    Box3 work = b0;
    std::vector<const InsideFn*> convex;
    bool hasNonConvex = false;
    for (const InsideFn& f : shaping) {
        // Positive semidefinite up to rounding (normalised coefficients, ‖A‖ <= 3).
        if (f.isPlane || f.lamMin >= -1e-12) convex.push_back(&f);
        else hasNonConvex = true;
    }
    const double limit = options.searchLimit;
    const double threshold = 1e-3 * limit;  // beyond this a side counts as unbounded
    Vec3 extremes[6];
    bool haveExtreme[6] = {false, false, false, false, false, false};
    if (!convex.empty()) {
        // Two passes: the first over the search region, the second (when the first found a
        // much smaller box) over that box, which tightens the rounding allowances.
        for (int pass = 0; pass < 2; ++pass) {
            Box3 region = work.Intersected(
                Box3{{-limit, -limit, -limit}, {limit, limit, limit}});
            if (region.Empty()) break;
            double size = Length(region.Size());
            if (pass == 1 && !(size < 0.1 * previousSize)) break;
            previousSize = size;
            ConvexRelaxation relaxation(convex, region);
            Vec3 interior;
            if (!relaxation.FindInterior(interior)) break;
            for (int axis = 0; axis < 3; ++axis)
                for (int sign = -1; sign <= 1; sign += 2) {
                    Vec3 xhat;
                    double bound = relaxation.Maximize(axis, sign, interior, xhat);
                    if (stats) ++stats->convexSolves;
                    int side = 2 * axis + (sign > 0);
                    if (std::isfinite(bound)) {
                        extremes[side] = xhat;
                        haveExtreme[side] = true;
                        if (sign > 0) work.hi[axis] = std::fmin(work.hi[axis], bound);
                        else work.lo[axis] = std::fmax(work.lo[axis], -bound);
                    }
                }
            if (work.Empty()) return Box3{};
        }
    }
    // Sides the relaxation may not have settled: a non-convex literal could cut off the
    // relaxation's extreme, or bound a side the relaxation leaves unbounded.
    bool sides[6];
    bool anySide = false;
    for (int side = 0; side < 6; ++side) {
        int axis = side / 2;
        bool high = side % 2 == 1;
        double v = high ? work.hi[axis] : -work.lo[axis];
        bool settled = !hasNonConvex && (haveExtreme[side] || v > threshold);
        if (hasNonConvex && haveExtreme[side] && v <= threshold) {
            double p[3] = {extremes[side].x, extremes[side].y, extremes[side].z};
            settled = true;
            for (const InsideFn& f : shaping) {
                Local l = EvaluateLocal(f, p);
                if (l.v > 1e-9 * (l.mag + 1e-300)) settled = false;
            }
        }
        sides[side] = !settled;
        anySide |= sides[side];
    }
    if (anySide) {
        Refiner refiner(std::move(shaping), options, stats);
        if (b0Finite) refiner.Seed(b0.Center());
        for (const Vec3& s : seeds) refiner.Seed(s);
        for (int side = 0; side < 6; ++side)
            if (haveExtreme[side]) refiner.Seed(extremes[side]);
        if (!refiner.Refine(work, sides)) return Box3{};
    }
    for (int i = 0; i < 3; ++i) {
        if (work.lo[i] < -threshold) work.lo[i] = -kInf;
        if (work.hi[i] > threshold) work.hi[i] = kInf;
    }
    return work.Empty() ? Box3{} : work;
}

Box3 BodyBounds(const FlatScene& scene, const FlatBody& body, const BoundsOptions& options,
                BoundsStats* stats) {
    std::vector<BoundLiteral> lits;
    lits.reserve(body.literals.size());
    for (const FlatLiteral& l : body.literals)
        lits.push_back({&scene.halfSpaces[l.halfSpace], l.complemented});
    return IntersectionBounds(lits, options, stats);
}

std::vector<Box3> TreeBounds(const FlatScene& scene, const std::vector<Box3>& bodyBoxes) {
    std::vector<Box3> out(scene.nodes.size());
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const FlatCsgNode& node = scene.nodes[i];
        if (node.isLeaf) {
            out[i] = bodyBoxes[node.body];
            continue;
        }
        Box3 box;
        switch (node.op) {
            case scene::CsgOp::kUnion:
                for (int c : node.children) box.Extend(out[c]);
                break;
            case scene::CsgOp::kIntersection:
                box = Box3::Everything();
                for (int c : node.children) box = box.Intersected(out[c]);
                if (node.children.empty()) box = Box3{};
                break;
            case scene::CsgOp::kDifference:
                if (!node.children.empty()) box = out[node.children[0]];
                break;
        }
        out[i] = box.Empty() ? Box3{} : box;  // one canonical empty box
    }
    return out;
}

void ComputeSceneBounds(FlatScene& scene, const BoundsOptions& options, BoundsStats* stats) {
    std::vector<Box3> bodyBoxes(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        bodyBoxes[i] = BodyBounds(scene, scene.bodies[i], options, stats);
        scene.bodies[i].bounds = bodyBoxes[i];
    }
    std::vector<Box3> nodeBoxes = TreeBounds(scene, bodyBoxes);
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) scene.nodes[i].bounds = nodeBoxes[i];
    Box3 image{{0, 0, -kInf},
               {static_cast<double>(scene.width), static_cast<double>(scene.height), kInf}};
    for (FlatSolid& s : scene.solids) {
        Box3 b = s.root >= 0 ? nodeBoxes[s.root] : Box3{};
        b = b.Intersected(image);
        s.bounds = b.Empty() ? Box3{} : b;
    }
}

}  // namespace quadrix
