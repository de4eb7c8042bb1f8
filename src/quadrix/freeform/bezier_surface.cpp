#include "quadrix/freeform/bezier_surface.h"

#include <algorithm>
#include <cassert>

#include "quadrix/freeform/bernstein.h"

namespace quadrix::freeform {

BezierSurface::BezierSurface(int dim, int degreeU, int degreeV, std::vector<double> coefficients,
                             double u0, double u1, double v0, double v1)
    : dim_(dim),
      degreeU_(degreeU),
      degreeV_(degreeV),
      u0_(u0),
      u1_(u1),
      v0_(v0),
      v1_(v1),
      c_(std::move(coefficients)) {
    assert(dim_ > 0 && degreeU_ >= 0 && degreeV_ >= 0);
    assert(c_.size() == static_cast<std::size_t>((degreeU_ + 1) * (degreeV_ + 1) * dim_));
}

BezierSurface BezierSurface::FromPoints(int degreeU, int degreeV, const std::vector<Vec3>& points) {
    assert(points.size() == static_cast<std::size_t>((degreeU + 1) * (degreeV + 1)));
    std::vector<double> c;
    c.reserve(points.size() * 3);
    for (const Vec3& p : points) c.insert(c.end(), {p.x, p.y, p.z});
    return BezierSurface(3, degreeU, degreeV, std::move(c));
}

BezierSurface BezierSurface::FromWeightedPoints(int degreeU, int degreeV,
                                                const std::vector<Vec3>& points,
                                                const std::vector<double>& weights) {
    assert(points.size() == weights.size());
    assert(points.size() == static_cast<std::size_t>((degreeU + 1) * (degreeV + 1)));
    std::vector<double> c;
    c.reserve(points.size() * 4);
    for (std::size_t i = 0; i < points.size(); ++i) {
        double w = weights[i];
        c.insert(c.end(), {points[i].x * w, points[i].y * w, points[i].z * w, w});
    }
    return BezierSurface(4, degreeU, degreeV, std::move(c));
}

BezierCurve BezierSurface::RowsAsCurveInV() const {
    return BezierCurve((degreeU_ + 1) * dim_, degreeV_, c_, v0_, v1_);
}

BezierSurface BezierSurface::FromRowsCurve(const BezierCurve& rows, int dim, int degreeU, double u0,
                                           double u1) {
    assert(rows.Dim() == (degreeU + 1) * dim);
    return BezierSurface(dim, degreeU, rows.Degree(), rows.Coefficients(), u0, u1, rows.T0(),
                         rows.T1());
}

void BezierSurface::Evaluate(double u, double v, double* out) const {
    int rowSize = (degreeU_ + 1) * dim_;
    double stackRow[64];
    std::vector<double> heapRow;
    double* row = stackRow;
    if (rowSize > 64) {
        heapRow.resize(static_cast<std::size_t>(rowSize));
        row = heapRow.data();
    }
    DeCasteljau(c_.data(), degreeV_, rowSize, (v - v0_) / (v1_ - v0_), row);
    DeCasteljau(row, degreeU_, dim_, (u - u0_) / (u1_ - u0_), out);
}

std::vector<double> BezierSurface::Evaluate(double u, double v) const {
    std::vector<double> out(static_cast<std::size_t>(dim_));
    Evaluate(u, v, out.data());
    return out;
}

Vec3 BezierSurface::EvaluateVec3(double u, double v) const {
    assert(dim_ >= 3 && dim_ <= kMaxStackDim);
    double out[kMaxStackDim];
    Evaluate(u, v, out);
    return {out[0], out[1], out[2]};
}

Vec4 BezierSurface::EvaluateVec4(double u, double v) const {
    assert(dim_ >= 4 && dim_ <= kMaxStackDim);
    double out[kMaxStackDim];
    Evaluate(u, v, out);
    return {out[0], out[1], out[2], out[3]};
}

BezierCurve BezierSurface::IsoCurveAtV(double v) const {
    std::vector<double> row(static_cast<std::size_t>((degreeU_ + 1) * dim_));
    DeCasteljau(c_.data(), degreeV_, (degreeU_ + 1) * dim_, (v - v0_) / (v1_ - v0_), row.data());
    return BezierCurve(dim_, degreeU_, std::move(row), u0_, u1_);
}

BezierCurve BezierSurface::IsoCurveAtU(double u) const { return Transposed().IsoCurveAtV(u); }

BezierSurface BezierSurface::DerivativeV() const {
    return FromRowsCurve(RowsAsCurveInV().Derivative(), dim_, degreeU_, u0_, u1_);
}

BezierSurface BezierSurface::DerivativeU() const { return Transposed().DerivativeV().Transposed(); }

std::pair<BezierSurface, BezierSurface> BezierSurface::SplitV(double v) const {
    auto [lo, hi] = RowsAsCurveInV().Split(v);
    return {FromRowsCurve(lo, dim_, degreeU_, u0_, u1_),
            FromRowsCurve(hi, dim_, degreeU_, u0_, u1_)};
}

std::pair<BezierSurface, BezierSurface> BezierSurface::SplitU(double u) const {
    auto [lo, hi] = Transposed().SplitV(u);
    return {lo.Transposed(), hi.Transposed()};
}

BezierSurface BezierSurface::Restricted(double ua, double ub, double va, double vb) const {
    BezierSurface r = FromRowsCurve(RowsAsCurveInV().Restricted(va, vb), dim_, degreeU_, u0_, u1_);
    BezierSurface t = r.Transposed();
    return FromRowsCurve(t.RowsAsCurveInV().Restricted(ua, ub), dim_, t.degreeU_, t.u0_, t.u1_)
        .Transposed();
}

BezierSurface BezierSurface::ElevatedV(int times) const {
    return FromRowsCurve(RowsAsCurveInV().Elevated(times), dim_, degreeU_, u0_, u1_);
}

BezierSurface BezierSurface::ElevatedU(int times) const {
    return Transposed().ElevatedV(times).Transposed();
}

BezierSurface BezierSurface::ElevatedTo(int degreeU, int degreeV) const {
    assert(degreeU >= degreeU_ && degreeV >= degreeV_);
    BezierSurface r = *this;
    if (degreeV > degreeV_) r = r.ElevatedV(degreeV - degreeV_);
    if (degreeU > degreeU_) r = r.ElevatedU(degreeU - degreeU_);
    return r;
}

BezierSurface BezierSurface::Reparametrized(double u0, double u1, double v0, double v1) const {
    return BezierSurface(dim_, degreeU_, degreeV_, c_, u0, u1, v0, v1);
}

BezierSurface BezierSurface::Transposed() const {
    std::vector<double> t(c_.size());
    int nu = degreeU_ + 1, nv = degreeV_ + 1;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            for (int k = 0; k < dim_; ++k)
                t[static_cast<std::size_t>((i * nv + j) * dim_ + k)] = Point(i, j)[k];
    return BezierSurface(dim_, degreeV_, degreeU_, std::move(t), v0_, v1_, u0_, u1_);
}

BezierSurface BezierSurface::Components(int first, int count) const {
    assert(first >= 0 && first + count <= dim_);
    std::size_t n = static_cast<std::size_t>((degreeU_ + 1) * (degreeV_ + 1));
    std::vector<double> c(n * static_cast<std::size_t>(count));
    for (std::size_t p = 0; p < n; ++p)
        for (int k = 0; k < count; ++k)
            c[p * static_cast<std::size_t>(count) + static_cast<std::size_t>(k)] =
                c_[p * static_cast<std::size_t>(dim_) + static_cast<std::size_t>(first + k)];
    return BezierSurface(count, degreeU_, degreeV_, std::move(c), u0_, u1_, v0_, v1_);
}

namespace {

BezierSurface Combine(const BezierSurface& a, const BezierSurface& b, double sign) {
    assert(a.Dim() == b.Dim());
    int m = std::max(a.DegreeU(), b.DegreeU()), n = std::max(a.DegreeV(), b.DegreeV());
    BezierSurface ea = a.ElevatedTo(m, n), eb = b.ElevatedTo(m, n);
    std::vector<double> c = ea.Coefficients();
    const std::vector<double>& d = eb.Coefficients();
    for (std::size_t i = 0; i < c.size(); ++i) c[i] += sign * d[i];
    return BezierSurface(a.Dim(), m, n, std::move(c), a.U0(), a.U1(), a.V0(), a.V1());
}

// out(k) += factor · a(ka) · b(kb) as tensor-product Bernstein polynomials: the coefficient of
// B_{i1+i2}^{m1+m2}(s) B_{j1+j2}^{n1+n2}(r) receives the product of the univariate factors
// (bezier_curve.h) in u and in v.
void AccumulateProduct2D(const BezierSurface& a, int ka, const BezierSurface& b, int kb,
                         double factor, std::vector<double>& out, int outDim, int kOut) {
    int m1 = a.DegreeU(), n1 = a.DegreeV(), m2 = b.DegreeU(), n2 = b.DegreeV();
    int mu = m1 + m2;
    for (int j1 = 0; j1 <= n1; ++j1)
        for (int j2 = 0; j2 <= n2; ++j2) {
            double fv = Binomial(n1, j1) * Binomial(n2, j2) / Binomial(n1 + n2, j1 + j2);
            for (int i1 = 0; i1 <= m1; ++i1) {
                double av = a.Point(i1, j1)[ka];
                if (av == 0) continue;
                double fa = fv * Binomial(m1, i1) * av * factor;
                for (int i2 = 0; i2 <= m2; ++i2) {
                    double fu = Binomial(m2, i2) / Binomial(mu, i1 + i2);
                    std::size_t idx = static_cast<std::size_t>(
                        ((j1 + j2) * (mu + 1) + (i1 + i2)) * outDim + kOut);
                    out[idx] += fa * fu * b.Point(i2, j2)[kb];
                }
            }
        }
}

BezierSurface ProductShape(const BezierSurface& a, const BezierSurface& b, int dim) {
    int m = a.DegreeU() + b.DegreeU(), n = a.DegreeV() + b.DegreeV();
    return BezierSurface(
        dim, m, n, std::vector<double>(static_cast<std::size_t>((m + 1) * (n + 1) * dim), 0.0),
        a.U0(), a.U1(), a.V0(), a.V1());
}

}  // namespace

BezierSurface Add(const BezierSurface& a, const BezierSurface& b) { return Combine(a, b, 1); }
BezierSurface Subtract(const BezierSurface& a, const BezierSurface& b) { return Combine(a, b, -1); }

BezierSurface Multiply(const BezierSurface& scalar, const BezierSurface& s) {
    assert(scalar.Dim() == 1);
    BezierSurface r = ProductShape(scalar, s, s.Dim());
    for (int k = 0; k < s.Dim(); ++k)
        AccumulateProduct2D(scalar, 0, s, k, 1.0, r.Coefficients(), s.Dim(), k);
    return r;
}

BezierSurface Dot(const BezierSurface& a, const BezierSurface& b) {
    assert(a.Dim() == b.Dim());
    BezierSurface r = ProductShape(a, b, 1);
    for (int k = 0; k < a.Dim(); ++k) AccumulateProduct2D(a, k, b, k, 1.0, r.Coefficients(), 1, 0);
    return r;
}

BezierSurface Cross(const BezierSurface& a, const BezierSurface& b) {
    assert(a.Dim() == 3 && b.Dim() == 3);
    BezierSurface r = ProductShape(a, b, 3);
    for (int k = 0; k < 3; ++k) {
        int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        AccumulateProduct2D(a, k1, b, k2, 1.0, r.Coefficients(), 3, k);
        AccumulateProduct2D(a, k2, b, k1, -1.0, r.Coefficients(), 3, k);
    }
    return r;
}

BezierSurface NormalField(const BezierSurface& s) {
    if (s.Dim() == 3) return Cross(s.DerivativeU(), s.DerivativeV());
    assert(s.Dim() == 4);
    BezierSurface p = s.Components(0, 3), w = s.Components(3, 1);
    BezierSurface pu = p.DerivativeU(), pv = p.DerivativeV();
    BezierSurface wu = w.DerivativeU(), wv = w.DerivativeV();
    // N = w Pu×Pv − wv Pu×P − wu P×Pv  (derivation in the header).
    BezierSurface n = Multiply(w, Cross(pu, pv));
    n = Subtract(n, Multiply(wv, Cross(pu, p)));
    n = Subtract(n, Multiply(wu, Cross(p, pv)));
    return n;
}

}  // namespace quadrix::freeform
