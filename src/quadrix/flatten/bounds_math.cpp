// Inside functions, their evaluation and the analytic boxes (stage (a) of bounds.h).
#include <algorithm>
#include <cmath>

#include "quadrix/flatten/bounds_internal.h"
#include "quadrix/math/dense_solve.h"
#include "quadrix/math/symmetric_eigen.h"

namespace quadrix::bounds_detail {

namespace {

double FrobeniusOf(const InsideFn& f) {
    double frob = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) frob += f.a[i][j] * f.a[i][j];
    return std::sqrt(frob);
}

}  // namespace

bool NeedsEigen(const InsideFn& f) {
    const double frob = FrobeniusOf(f);
    return !f.isPlane && frob != 0 && std::isfinite(frob);
}

// Eigenvalue bounds widened by the Gershgorin remainder and a rounding allowance relative to
// ‖A‖ (Jacobi is backward stable: a few ulps of ‖A‖ per sweep).
void Bound(InsideFn& f, const SymmetricEigenResult* d, InsideEigen* eigen) {
    if (f.isPlane) return;
    const double frob = FrobeniusOf(f);
    if (frob == 0) {
        f.lamMin = f.lamMax = 0;
        return;
    }
    if (!std::isfinite(frob)) {
        f.lamMin = -kInf;
        f.lamMax = kInf;
        return;
    }
    SymmetricEigenResult own;
    if (d == nullptr) {
        SymmetricEigen(f.a, own.vals, own.vecs, own.offDiagonal);
        d = &own;
    }
    if (eigen) {
        eigen->ok = true;
        for (int i = 0; i < 3; ++i) {
            eigen->vals[i] = d->vals[i];
            for (int j = 0; j < 3; ++j) eigen->vecs[i][j] = d->vecs[i][j];
        }
    }
    double safety = 64 * kEps * frob + d->offDiagonal;
    f.lamMin = d->vals[0] - safety;
    f.lamMax = d->vals[2] + safety;
}

InsideFn MakeInsideFn(const FlatHalfSpace& hs, bool complemented, InsideEigen* eigen) {
    if (eigen) *eigen = InsideEigen{};
    InsideFn f = MakeInsideFnUnbounded(hs, complemented);
    Bound(f, nullptr, eigen);
    return f;
}

InsideFn MakeInsideFnUnbounded(const FlatHalfSpace& hs, bool complemented) {
    InsideFn f;
    double sign = complemented ? -1.0 : 1.0;
    if (hs.IsQuartic()) {
        // Not expected (IntersectionBounds substitutes quartics); conservative: all of space.
        f.isPlane = true;
        f.k = -1;
        return f;
    }
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
    return f;
}

double QuadricExtent(const InsideFn& f, const InsideEigen& e) {
    if (f.isPlane || !e.ok || !(e.vals[0] > 1e-14 * std::fabs(e.vals[2]))) return 0;
    // c = -Σ (v_i·b / λ_i) v_i, R = bᵀA⁻¹b - k = Σ (v_i·b)² / λ_i - k.
    double c[3] = {0, 0, 0}, r = -f.k;
    for (int i = 0; i < 3; ++i) {
        const double vb = e.vecs[0][i] * f.b[0] + e.vecs[1][i] * f.b[1] + e.vecs[2][i] * f.b[2];
        r += vb * vb / e.vals[i];
        for (int j = 0; j < 3; ++j) c[j] -= vb / e.vals[i] * e.vecs[j][i];
    }
    const double extent = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) +
                          std::sqrt(std::fmax(r, 0.0) / e.vals[0]);
    return std::isfinite(extent) ? extent : 0;
}

double EvaluateAt(const InsideFn& f, const double p[3]) {
    if (f.isPlane) return f.k + 2 * (f.b[0] * p[0] + f.b[1] * p[1] + f.b[2] * p[2]);
    double v = f.k;
    for (int i = 0; i < 3; ++i)
        v += p[i] * (f.a[i][0] * p[0] + f.a[i][1] * p[1] + f.a[i][2] * p[2] + 2 * f.b[i]);
    return v;
}

Local EvaluateLocal(const InsideFn& f, const double c[3]) {
    Local l;
    if (f.isPlane) {
        l.v = f.k + 2 * (f.b[0] * c[0] + f.b[1] * c[1] + f.b[2] * c[2]);
        l.mag = std::fabs(f.k) + 2 * (std::fabs(f.b[0] * c[0]) + std::fabs(f.b[1] * c[1]) +
                                      std::fabs(f.b[2] * c[2]));
        for (int i = 0; i < 3; ++i) l.g[i] = 2 * f.b[i];
        return l;
    }
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

// The centred form over |d_i| <= h_i (bounds.h): f(c+d) = f(c) + g·d + dᵀAd with the tighter of
// the entrywise and the Rayleigh bounds for dᵀAd. `slack` (optional) receives each axis' smear,
// max |∂f/∂x_i| over the box times h_i = (|g_i| + 2 Σ_j |a_ij| h_j) h_i, used to choose the split
// axis. (Only what lowers the lower bound is not enough: at a cell centred on a saddle's or an
// ellipse's axis, x² only raises the upper bound, yet halving x is what excludes the children.)
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
        if (t < 0)
            qloE += t;
        else
            qhiE += t;
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
        for (int i = 0; i < 3; ++i) {
            double dmax = std::fabs(l.g[i]);
            for (int j = 0; j < 3; ++j) dmax += 2 * std::fabs(a[i][j]) * h[j];
            slack[i] = dmax * h[i];
        }
    }
    double mag = l.mag + lin + std::fabs(qlo) + std::fabs(qhi);
    return {l.v - lin + qlo, l.v + lin + qhi, 32 * kEps * mag};
}

bool Cholesky(const InsideFn& f, const int* idx, int m, double l[3][3], double& condition,
              double maxCondition) {
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
        if (f.b[axis] > 0)
            box.hi[axis] = std::nextafter(bound, kInf);
        else
            box.lo[axis] = std::nextafter(bound, -kInf);
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

// Non-negative multipliers λ (at most 3 non-zero, by Carathéodory in R³) minimising
// |Σ λ_i g_i - t| over the given gradients (n <= kMaxSurrogate), by enumerating supports.
// Returns false when no support of at least minSupport members has positive multipliers.
bool NonNegativeCombination(int n, const double g[][3], const double t[3], double lambda[],
                            int minSupport) {
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
        if (!SolveDense(k, m, r, x, 1e-12)) continue;
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

Nappe DetectNappe(const InsideFn& f) {
    Nappe n;
    if (f.isPlane) return n;
    double vals[3], vecs[3][3], off;
    SymmetricEigen(f.a, vals, vecs, off);
    double big = std::fmax(std::fabs(vals[0]), std::fabs(vals[2]));
    // Exactly one clearly negative eigenvalue, the others clearly positive.
    if (!(big > 0) || !(vals[0] < -1e-9 * big) || !(vals[1] > 1e-9 * big)) return n;
    // The apex -A⁻¹b does not depend on the scale of f: solve with A / big (the pivot threshold
    // is absolute, and a quadric far from the origin has a tiny A).
    double m[3][3], r[3], apex[3];
    for (int i = 0; i < 3; ++i) {
        r[i] = -f.b[i] / big;
        for (int j = 0; j < 3; ++j) m[i][j] = f.a[i][j] / big;
    }
    if (!SolveDense(3, m, r, apex, 1e-12)) return n;
    Local at = EvaluateLocal(f, apex);
    // R = -f(apex) <= 0 up to rounding: a cone (0) or a hyperboloid of two sheets (< 0).
    double rValue = -at.v, tolerance = 64 * kEps * at.mag;
    if (rValue > tolerance) return n;  // one sheet: not convex
    n.ok = true;
    n.apex = Vec3{apex[0], apex[1], apex[2]};
    n.axis = Normalize(Vec3{vecs[0][0], vecs[1][0], vecs[2][0]});
    n.rPlus = std::fmax(rValue, 0.0) + tolerance;
    n.beta = -vals[0];
    for (int i = 0; i < 3; ++i) {
        n.vals[i] = vals[i];
        n.vecs[i] = Normalize(Vec3{vecs[0][i], vecs[1][i], vecs[2][i]});
    }
    return n;
}

}  // namespace quadrix::bounds_detail
