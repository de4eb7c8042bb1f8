#include "quadrix/freeform/bezier_curve.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "quadrix/freeform/bernstein.h"

namespace quadrix::freeform {

double Binomial(int n, int k) {
    if (k < 0 || k > n) return 0;
    // Pascal's triangle, exact in doubles up to n = 56 (C(56,28) < 2^53).
    static const auto kTable = [] {
        std::array<std::array<double, 57>, 57> t{};
        for (int a = 0; a <= 56; ++a) {
            t[a][0] = t[a][a] = 1;
            for (int b = 1; b < a; ++b) t[a][b] = t[a - 1][b - 1] + t[a - 1][b];
        }
        return t;
    }();
    if (n <= 56) return kTable[n][k];
    k = std::min(k, n - k);
    double r = 1;
    // r stays an integer at every step: r = C(n-k+i, i).
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return std::round(r);
}

BezierCurve::BezierCurve(int dim, int degree, std::vector<double> coefficients, double t0,
                         double t1)
    : dim_(dim), degree_(degree), t0_(t0), t1_(t1), c_(std::move(coefficients)) {
    assert(dim_ > 0 && degree_ >= 0);
    assert(c_.size() == static_cast<std::size_t>((degree_ + 1) * dim_));
}

BezierCurve BezierCurve::Scalar(std::vector<double> coefficients, double t0, double t1) {
    int degree = static_cast<int>(coefficients.size()) - 1;
    return BezierCurve(1, degree, std::move(coefficients), t0, t1);
}

BezierCurve BezierCurve::FromPoints(std::span<const Vec3> points, double t0, double t1) {
    std::vector<double> c;
    c.reserve(points.size() * 3);
    for (const Vec3& p : points) c.insert(c.end(), {p.x, p.y, p.z});
    return BezierCurve(3, static_cast<int>(points.size()) - 1, std::move(c), t0, t1);
}

BezierCurve BezierCurve::FromWeightedPoints(std::span<const Vec3> points,
                                            std::span<const double> weights, double t0, double t1) {
    assert(points.size() == weights.size());
    std::vector<double> c;
    c.reserve(points.size() * 4);
    for (std::size_t i = 0; i < points.size(); ++i) {
        double w = weights[i];
        c.insert(c.end(), {points[i].x * w, points[i].y * w, points[i].z * w, w});
    }
    return BezierCurve(4, static_cast<int>(points.size()) - 1, std::move(c), t0, t1);
}

void BezierCurve::Evaluate(double t, double* out) const {
    double s = (t - t0_) / (t1_ - t0_);
    DeCasteljau(c_.data(), degree_, dim_, s, out);
}

std::vector<double> BezierCurve::Evaluate(double t) const {
    std::vector<double> out(static_cast<std::size_t>(dim_));
    Evaluate(t, out.data());
    return out;
}

double BezierCurve::EvaluateScalar(double t) const {
    double out[kMaxStackDim];
    assert(dim_ <= kMaxStackDim);
    Evaluate(t, out);
    return out[0];
}

Vec3 BezierCurve::EvaluateVec3(double t) const {
    double out[kMaxStackDim];
    assert(dim_ >= 3 && dim_ <= kMaxStackDim);
    Evaluate(t, out);
    return {out[0], out[1], out[2]};
}

Vec4 BezierCurve::EvaluateVec4(double t) const {
    double out[kMaxStackDim];
    assert(dim_ >= 4 && dim_ <= kMaxStackDim);
    Evaluate(t, out);
    return {out[0], out[1], out[2], out[3]};
}

BezierCurve BezierCurve::Derivative() const {
    if (degree_ == 0)
        return BezierCurve(dim_, 0, std::vector<double>(static_cast<std::size_t>(dim_), 0.0), t0_,
                           t1_);
    // d/dt = n / (t1 - t0) · Σ (P_{i+1} - P_i) B_i^{n-1}(s)   (Farin §4.3, chain rule for s(t)).
    double f = degree_ / (t1_ - t0_);
    std::vector<double> d(static_cast<std::size_t>(degree_ * dim_));
    for (int i = 0; i < degree_; ++i)
        for (int k = 0; k < dim_; ++k)
            d[static_cast<std::size_t>(i * dim_ + k)] = f * (Point(i + 1)[k] - Point(i)[k]);
    return BezierCurve(dim_, degree_ - 1, std::move(d), t0_, t1_);
}

std::pair<BezierCurve, BezierCurve> BezierCurve::Split(double t) const {
    double s = (t - t0_) / (t1_ - t0_);
    std::vector<double> left(c_.size()), right(c_.size());
    SubdivideInto(c_.data(), degree_, dim_, s, left.data(), right.data());
    return {BezierCurve(dim_, degree_, std::move(left), t0_, t),
            BezierCurve(dim_, degree_, std::move(right), t, t1_)};
}

BezierCurve BezierCurve::Restricted(double a, double b) const {
    std::vector<double> out(c_.size());
    RestrictInto(c_.data(), degree_, dim_, (a - t0_) / (t1_ - t0_), (b - t0_) / (t1_ - t0_),
                 out.data());
    return BezierCurve(dim_, degree_, std::move(out), a, b);
}

BezierCurve BezierCurve::Elevated(int times) const {
    BezierCurve r = *this;
    for (int e = 0; e < times; ++e) {
        int n = r.degree_;
        // Q_i = i/(n+1) P_{i-1} + (1 - i/(n+1)) P_i, i = 0..n+1.
        std::vector<double> q(static_cast<std::size_t>((n + 2) * dim_));
        for (int i = 0; i <= n + 1; ++i) {
            double a = static_cast<double>(i) / (n + 1);
            for (int k = 0; k < dim_; ++k) {
                double prev = i > 0 ? r.Point(i - 1)[k] : 0.0;
                double cur = i <= n ? r.Point(i)[k] : 0.0;
                q[static_cast<std::size_t>(i * dim_ + k)] = a * prev + (1 - a) * cur;
            }
        }
        r = BezierCurve(dim_, n + 1, std::move(q), t0_, t1_);
    }
    return r;
}

BezierCurve BezierCurve::ElevatedTo(int degree) const {
    assert(degree >= degree_);
    return Elevated(degree - degree_);
}

BezierCurve BezierCurve::Reparametrized(double t0, double t1) const {
    return BezierCurve(dim_, degree_, c_, t0, t1);
}

BezierCurve BezierCurve::Component(int k) const {
    std::vector<double> c(static_cast<std::size_t>(degree_ + 1));
    for (int i = 0; i <= degree_; ++i) c[static_cast<std::size_t>(i)] = Point(i)[k];
    return BezierCurve(1, degree_, std::move(c), t0_, t1_);
}

BezierCurve BezierCurve::PlusConstant(double value) const {
    BezierCurve r = *this;
    for (double& c : r.c_) c += value;
    return r;
}

BezierCurve BezierCurve::Scaled(double factor) const {
    BezierCurve r = *this;
    for (double& c : r.c_) c *= factor;
    return r;
}

double BezierCurve::MinCoefficient(int k) const {
    double m = HUGE_VAL;
    for (int i = 0; i <= degree_; ++i) m = std::min(m, Point(i)[k]);
    return m;
}

double BezierCurve::MaxCoefficient(int k) const {
    double m = -HUGE_VAL;
    for (int i = 0; i <= degree_; ++i) m = std::max(m, Point(i)[k]);
    return m;
}

namespace {

BezierCurve Combine(const BezierCurve& a, const BezierCurve& b, double sign) {
    assert(a.Dim() == b.Dim());
    int n = std::max(a.Degree(), b.Degree());
    BezierCurve ea = a.ElevatedTo(n), eb = b.ElevatedTo(n);
    std::vector<double> c = ea.Coefficients();
    const std::vector<double>& d = eb.Coefficients();
    for (std::size_t i = 0; i < c.size(); ++i) c[i] += sign * d[i];
    return BezierCurve(a.Dim(), n, std::move(c), a.T0(), a.T1());
}

}  // namespace

BezierCurve Add(const BezierCurve& a, const BezierCurve& b) { return Combine(a, b, 1); }
BezierCurve Subtract(const BezierCurve& a, const BezierCurve& b) { return Combine(a, b, -1); }

BezierCurve Multiply(const BezierCurve& s, const BezierCurve& c) {
    assert(s.Dim() == 1);
    int m = s.Degree(), n = c.Degree(), dim = c.Dim();
    std::vector<double> out(static_cast<std::size_t>((m + n + 1) * dim), 0.0);
    for (int k = 0; k < dim; ++k)
        AccumulateProduct(s.Coefficients().data(), 1, m, c.Coefficients().data() + k, dim, n, 1.0,
                          out.data() + k, dim);
    return BezierCurve(dim, m + n, std::move(out), c.T0(), c.T1());
}

BezierCurve Dot(const BezierCurve& a, const BezierCurve& b) {
    assert(a.Dim() == b.Dim());
    int m = a.Degree(), n = b.Degree(), dim = a.Dim();
    std::vector<double> out(static_cast<std::size_t>(m + n + 1), 0.0);
    for (int k = 0; k < dim; ++k)
        AccumulateProduct(a.Coefficients().data() + k, dim, m, b.Coefficients().data() + k, dim, n,
                          1.0, out.data(), 1);
    return BezierCurve(1, m + n, std::move(out), a.T0(), a.T1());
}

BezierCurve Cross(const BezierCurve& a, const BezierCurve& b) {
    assert(a.Dim() == 3 && b.Dim() == 3);
    int m = a.Degree(), n = b.Degree();
    std::vector<double> out(static_cast<std::size_t>((m + n + 1) * 3), 0.0);
    const double* pa = a.Coefficients().data();
    const double* pb = b.Coefficients().data();
    // (a × b)_k = a_{k+1} b_{k+2} - a_{k+2} b_{k+1}
    for (int k = 0; k < 3; ++k) {
        int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        AccumulateProduct(pa + k1, 3, m, pb + k2, 3, n, 1.0, out.data() + k, 3);
        AccumulateProduct(pa + k2, 3, m, pb + k1, 3, n, -1.0, out.data() + k, 3);
    }
    return BezierCurve(3, m + n, std::move(out), a.T0(), a.T1());
}

}  // namespace quadrix::freeform
