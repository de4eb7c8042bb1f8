#include "quadrix/freeform/bspline.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

namespace quadrix::freeform {

std::string CheckKnots(const std::vector<double>& knots, int degree, int count) {
    if (degree < 0) return "negative degree";
    if (count < degree + 1)
        return "need at least " + std::to_string(degree + 1) + " control points for degree " +
               std::to_string(degree) + ", got " + std::to_string(count);
    std::size_t expected = static_cast<std::size_t>(count + degree + 1);
    if (knots.size() != expected)
        return "expected " + std::to_string(expected) +
               " knots (control points + degree + 1), got " + std::to_string(knots.size());
    for (std::size_t i = 0; i < knots.size(); ++i) {
        if (!std::isfinite(knots[i])) return "knot " + std::to_string(i + 1) + " is not finite";
        if (i > 0 && knots[i] < knots[i - 1]) return "knots must not decrease";
    }
    for (std::size_t i = 1; i + 1 < knots.size(); ++i) {
        // Multiplicity above p + 1 inside the vector leaves a basis function identically zero.
        std::size_t j = i;
        while (j < knots.size() && knots[j] == knots[i]) ++j;
        if (j - i > static_cast<std::size_t>(degree + 1) && i > 0 && j < knots.size())
            return "an interior knot has multiplicity above degree + 1";
    }
    if (!(knots[static_cast<std::size_t>(degree)] < knots[static_cast<std::size_t>(count)]))
        return "empty parameter domain";
    return {};
}

namespace {

bool NearlyEqualPoints(const double* a, const double* b, int dim, double scale) {
    // Roundoff-level agreement: pieces cut from one continuous curve meet up to a few ulps.
    double tol = 1e-12 * scale;
    for (int k = 0; k < dim; ++k)
        if (std::fabs(a[k] - b[k]) > tol) return false;
    return true;
}

double MaxAbs(const std::vector<double>& c) {
    double m = 0;
    for (double x : c) m = std::max(m, std::fabs(x));
    return m;
}

// Joins segments of one degree; joinContinuous[k] tells whether segments k and k+1 share their
// end point (one control point and multiplicity p) or not (two and multiplicity p + 1).
BSplineCurve JoinSegments(const std::vector<BezierCurve>& segments,
                          const std::vector<bool>& joinContinuous) {
    assert(!segments.empty());
    int p = segments.front().Degree(), dim = segments.front().Dim();
    std::vector<double> knots(static_cast<std::size_t>(p + 1), segments.front().T0());
    std::vector<double> c = segments.front().Coefficients();
    for (std::size_t s = 1; s < segments.size(); ++s) {
        const BezierCurve& seg = segments[s];
        assert(seg.Degree() == p && seg.Dim() == dim);
        bool cont = joinContinuous[s - 1];
        knots.insert(knots.end(), static_cast<std::size_t>(cont ? p : p + 1), seg.T0());
        const std::vector<double>& sc = seg.Coefficients();
        c.insert(c.end(), sc.begin() + (cont ? dim : 0), sc.end());
    }
    knots.insert(knots.end(), static_cast<std::size_t>(p + 1), segments.back().T1());
    return BSplineCurve(dim, p, std::move(knots), std::move(c));
}

std::vector<BezierCurve> ElevatedToCommonDegree(const std::vector<BezierCurve>& segments) {
    int p = 0;
    for (const BezierCurve& s : segments) p = std::max(p, s.Degree());
    std::vector<BezierCurve> out;
    out.reserve(segments.size());
    for (const BezierCurve& s : segments) out.push_back(s.ElevatedTo(p));
    return out;
}

std::vector<double> ClampedKnots(int degree, double a, double b) {
    std::vector<double> k(static_cast<std::size_t>(degree + 1), a);
    k.insert(k.end(), static_cast<std::size_t>(degree + 1), b);
    return k;
}

std::vector<bool> ContinuousJoins(const std::vector<BezierCurve>& segments) {
    std::vector<bool> joins;
    for (std::size_t s = 0; s + 1 < segments.size(); ++s) {
        const BezierCurve& a = segments[s];
        const BezierCurve& b = segments[s + 1];
        double scale = std::max(MaxAbs(a.Coefficients()), MaxAbs(b.Coefficients()));
        joins.push_back(NearlyEqualPoints(a.Point(a.Degree()), b.Point(0), a.Dim(), scale));
    }
    return joins;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// BSplineCurve

BSplineCurve::BSplineCurve(int dim, int degree, std::vector<double> knots,
                           std::vector<double> coefficients)
    : dim_(dim), degree_(degree), knots_(std::move(knots)), c_(std::move(coefficients)) {
    assert(dim_ > 0 && degree_ >= 0);
    assert(c_.size() % static_cast<std::size_t>(dim_) == 0);
    assert(knots_.size() ==
           c_.size() / static_cast<std::size_t>(dim_) + static_cast<std::size_t>(degree_) + 1);
}

BSplineCurve BSplineCurve::FromBezier(const BezierCurve& c) { return JoinSegments({c}, {}); }

BSplineCurve BSplineCurve::FromBezierSegments(const std::vector<BezierCurve>& segments) {
    std::vector<BezierCurve> e = ElevatedToCommonDegree(segments);
    return JoinSegments(e, ContinuousJoins(e));
}

int BSplineCurve::FindSpan(double t) const {
    int p = degree_, n = Count();
    if (t >= knots_[static_cast<std::size_t>(n)]) {
        int k = n - 1;
        while (k > p &&
               knots_[static_cast<std::size_t>(k)] == knots_[static_cast<std::size_t>(k + 1)])
            --k;
        return k;
    }
    if (t <= knots_[static_cast<std::size_t>(p)]) {
        int k = p;
        while (k < n - 1 &&
               knots_[static_cast<std::size_t>(k)] == knots_[static_cast<std::size_t>(k + 1)])
            ++k;
        return k;
    }
    auto first = knots_.begin() + p;
    auto last = knots_.begin() + n + 1;
    int k = static_cast<int>(std::upper_bound(first, last, t) - knots_.begin()) - 1;
    return std::clamp(k, p, n - 1);
}

void BSplineCurve::Blossom(int span, const double* args, double* out) const {
    int p = degree_, k = span;
    std::vector<double> d(static_cast<std::size_t>((p + 1) * dim_));
    std::copy(c_.begin() + static_cast<std::ptrdiff_t>((k - p) * dim_),
              c_.begin() + static_cast<std::ptrdiff_t>((k + 1) * dim_), d.begin());
    for (int r = 1; r <= p; ++r) {
        double x = args[r - 1];
        for (int j = p; j >= r; --j) {
            int i = k - p + j;
            double ti = knots_[static_cast<std::size_t>(i)];
            double tr = knots_[static_cast<std::size_t>(i + p + 1 - r)];
            double a = (x - ti) / (tr - ti);
            for (int q = 0; q < dim_; ++q) {
                std::size_t at = static_cast<std::size_t>(j * dim_ + q);
                d[at] = (1 - a) * d[at - static_cast<std::size_t>(dim_)] + a * d[at];
            }
        }
    }
    std::copy(d.begin() + p * dim_, d.begin() + (p + 1) * dim_, out);
}

void BSplineCurve::Evaluate(double t, double* out) const {
    std::vector<double> args(static_cast<std::size_t>(std::max(degree_, 1)), t);
    Blossom(FindSpan(t), args.data(), out);
}

std::vector<double> BSplineCurve::Evaluate(double t) const {
    std::vector<double> out(static_cast<std::size_t>(dim_));
    Evaluate(t, out.data());
    return out;
}

BSplineCurve BSplineCurve::Derivative() const {
    int p = degree_, n = Count();
    if (p == 0) {
        std::vector<double> knots(knots_.begin() + 1, knots_.end() - 1);
        // Degree 0 has no derivative inside spans; keep a zero curve of degree 0 on the domain.
        std::vector<double> k0 = {T0(), T1()};
        return BSplineCurve(dim_, 0, k0, std::vector<double>(static_cast<std::size_t>(dim_), 0.0));
    }
    std::vector<double> q(static_cast<std::size_t>((n - 1) * dim_));
    for (int i = 0; i + 1 < n; ++i) {
        double den =
            knots_[static_cast<std::size_t>(i + p + 1)] - knots_[static_cast<std::size_t>(i + 1)];
        for (int k = 0; k < dim_; ++k)
            q[static_cast<std::size_t>(i * dim_ + k)] =
                den > 0 ? p * (Point(i + 1)[k] - Point(i)[k]) / den : 0.0;
    }
    std::vector<double> knots(knots_.begin() + 1, knots_.end() - 1);
    return BSplineCurve(dim_, p - 1, std::move(knots), std::move(q));
}

BSplineCurve BSplineCurve::WithKnotInserted(double t, int times) const {
    BSplineCurve r = *this;
    for (int e = 0; e < times; ++e) {
        int p = r.degree_, n = r.Count();
        if (!(t >= r.T0() && t < r.T1())) return r;
        int mult = static_cast<int>(std::count(r.knots_.begin(), r.knots_.end(), t));
        if (mult >= p + 1) return r;
        // k: the last index with t_k <= t (a multiple knot t is passed over).
        int k = static_cast<int>(std::upper_bound(r.knots_.begin(), r.knots_.end(), t) -
                                 r.knots_.begin()) -
                1;
        std::vector<double> q(static_cast<std::size_t>((n + 1) * dim_));
        for (int i = 0; i <= n; ++i) {
            for (int c = 0; c < dim_; ++c) {
                double v;
                if (i <= k - p) {
                    v = r.Point(i)[c];
                } else if (i >= k + 1) {
                    v = r.Point(i - 1)[c];
                } else {
                    double ti = r.knots_[static_cast<std::size_t>(i)];
                    double a = (t - ti) / (r.knots_[static_cast<std::size_t>(i + p)] - ti);
                    v = (1 - a) * r.Point(i - 1)[c] + a * r.Point(i)[c];
                }
                q[static_cast<std::size_t>(i * dim_ + c)] = v;
            }
        }
        std::vector<double> knots = r.knots_;
        knots.insert(knots.begin() + k + 1, t);
        r = BSplineCurve(dim_, p, std::move(knots), std::move(q));
    }
    return r;
}

std::vector<double> BSplineCurve::Breakpoints() const {
    std::vector<double> b;
    for (int i = degree_; i <= Count(); ++i) {
        double t = knots_[static_cast<std::size_t>(i)];
        if (b.empty() || t > b.back()) b.push_back(t);
    }
    return b;
}

std::vector<BezierCurve> BSplineCurve::ToBezier() const {
    std::vector<BezierCurve> out;
    int p = degree_;
    std::vector<double> args(static_cast<std::size_t>(std::max(p, 1)));
    for (int k = p; k < Count(); ++k) {
        double a = knots_[static_cast<std::size_t>(k)], b = knots_[static_cast<std::size_t>(k + 1)];
        if (!(a < b)) continue;
        std::vector<double> c(static_cast<std::size_t>((p + 1) * dim_));
        for (int i = 0; i <= p; ++i) {
            for (int r = 0; r < p; ++r) args[static_cast<std::size_t>(r)] = r < p - i ? a : b;
            Blossom(k, args.data(), c.data() + i * dim_);
        }
        out.emplace_back(dim_, p, std::move(c), a, b);
    }
    return out;
}

BSplineCurve BSplineCurve::Elevated(int times) const {
    std::vector<BezierCurve> segs = ToBezier();
    for (BezierCurve& s : segs) s = s.Elevated(times);
    return FromBezierSegments(segs);
}

BSplineCurve BSplineCurve::Restricted(double a, double b) const {
    std::vector<double> breaks = {a};
    for (double t : Breakpoints())
        if (t > a && t < b) breaks.push_back(t);
    breaks.push_back(b);
    return FromBezierSegments(BezierPiecesOn(*this, breaks));
}

std::vector<BezierCurve> BezierPiecesOn(const BSplineCurve& c, const std::vector<double>& breaks) {
    std::vector<BezierCurve> spans = c.ToBezier();
    std::vector<BezierCurve> out;
    std::size_t s = 0;
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
        double a = breaks[k], b = breaks[k + 1];
        double mid = 0.5 * (a + b);
        while (s + 1 < spans.size() && spans[s].T1() <= mid) ++s;
        out.push_back(spans[s].Restricted(a, b));
    }
    return out;
}

namespace {

std::vector<double> MergedBreaks(const BSplineCurve& a, const BSplineCurve& b) {
    double lo = std::max(a.T0(), b.T0()), hi = std::min(a.T1(), b.T1());
    std::vector<double> all = a.Breakpoints();
    std::vector<double> bb = b.Breakpoints();
    all.insert(all.end(), bb.begin(), bb.end());
    all.push_back(lo);
    all.push_back(hi);
    std::sort(all.begin(), all.end());
    std::vector<double> out;
    for (double t : all)
        if (t >= lo && t <= hi && (out.empty() || t > out.back())) out.push_back(t);
    return out;
}

template <typename Op>
BSplineCurve PiecewiseOp(const BSplineCurve& a, const BSplineCurve& b, Op op) {
    std::vector<double> breaks = MergedBreaks(a, b);
    std::vector<BezierCurve> pa = BezierPiecesOn(a, breaks), pb = BezierPiecesOn(b, breaks);
    std::vector<BezierCurve> out;
    for (std::size_t k = 0; k < pa.size(); ++k) out.push_back(op(pa[k], pb[k]));
    return BSplineCurve::FromBezierSegments(out);
}

}  // namespace

BSplineCurve Add(const BSplineCurve& a, const BSplineCurve& b) {
    return PiecewiseOp(a, b, [](const BezierCurve& x, const BezierCurve& y) { return Add(x, y); });
}
BSplineCurve Subtract(const BSplineCurve& a, const BSplineCurve& b) {
    return PiecewiseOp(a, b,
                       [](const BezierCurve& x, const BezierCurve& y) { return Subtract(x, y); });
}
BSplineCurve Multiply(const BSplineCurve& s, const BSplineCurve& c) {
    return PiecewiseOp(s, c,
                       [](const BezierCurve& x, const BezierCurve& y) { return Multiply(x, y); });
}
BSplineCurve Dot(const BSplineCurve& a, const BSplineCurve& b) {
    return PiecewiseOp(a, b, [](const BezierCurve& x, const BezierCurve& y) { return Dot(x, y); });
}
BSplineCurve Cross(const BSplineCurve& a, const BSplineCurve& b) {
    return PiecewiseOp(a, b,
                       [](const BezierCurve& x, const BezierCurve& y) { return Cross(x, y); });
}

// ---------------------------------------------------------------------------------------------
// BSplineSurface

BSplineSurface::BSplineSurface(int dim, int degreeU, int degreeV, std::vector<double> knotsU,
                               std::vector<double> knotsV, std::vector<double> coefficients)
    : dim_(dim),
      degreeU_(degreeU),
      degreeV_(degreeV),
      knotsU_(std::move(knotsU)),
      knotsV_(std::move(knotsV)),
      c_(std::move(coefficients)) {
    assert(dim_ > 0);
    assert(c_.size() == static_cast<std::size_t>(CountU() * CountV() * dim_));
}

BSplineSurface BSplineSurface::FromBezier(const BezierSurface& s) {
    return BSplineSurface(s.Dim(), s.DegreeU(), s.DegreeV(),
                          ClampedKnots(s.DegreeU(), s.U0(), s.U1()),
                          ClampedKnots(s.DegreeV(), s.V0(), s.V1()), s.Coefficients());
}

BSplineCurve BSplineSurface::RowsAsCurveInV() const {
    return BSplineCurve(CountU() * dim_, degreeV_, knotsV_, c_);
}

BSplineSurface BSplineSurface::FromRowsCurve(const BSplineCurve& rows, int dim, int degreeU,
                                             std::vector<double> knotsU) {
    return BSplineSurface(dim, degreeU, rows.Degree(), std::move(knotsU), rows.Knots(),
                          rows.Coefficients());
}

void BSplineSurface::Evaluate(double u, double v, double* out) const {
    IsoCurveAtV(v).Evaluate(u, out);
}

std::vector<double> BSplineSurface::Evaluate(double u, double v) const {
    std::vector<double> out(static_cast<std::size_t>(dim_));
    Evaluate(u, v, out.data());
    return out;
}

BSplineCurve BSplineSurface::IsoCurveAtV(double v) const {
    return BSplineCurve(dim_, degreeU_, knotsU_, RowsAsCurveInV().Evaluate(v));
}

BSplineCurve BSplineSurface::IsoCurveAtU(double u) const { return Transposed().IsoCurveAtV(u); }

BSplineSurface BSplineSurface::DerivativeV() const {
    return FromRowsCurve(RowsAsCurveInV().Derivative(), dim_, degreeU_, knotsU_);
}

BSplineSurface BSplineSurface::DerivativeU() const {
    return Transposed().DerivativeV().Transposed();
}

BSplineSurface BSplineSurface::WithKnotInsertedV(double v, int times) const {
    return FromRowsCurve(RowsAsCurveInV().WithKnotInserted(v, times), dim_, degreeU_, knotsU_);
}

BSplineSurface BSplineSurface::WithKnotInsertedU(double u, int times) const {
    return Transposed().WithKnotInsertedV(u, times).Transposed();
}

BSplineSurface BSplineSurface::ElevatedV(int times) const {
    return FromRowsCurve(RowsAsCurveInV().Elevated(times), dim_, degreeU_, knotsU_);
}

BSplineSurface BSplineSurface::ElevatedU(int times) const {
    return Transposed().ElevatedV(times).Transposed();
}

BSplineSurface BSplineSurface::Restricted(double ua, double ub, double va, double vb) const {
    BSplineSurface r = FromRowsCurve(RowsAsCurveInV().Restricted(va, vb), dim_, degreeU_, knotsU_);
    BSplineSurface t = r.Transposed();
    return FromRowsCurve(t.RowsAsCurveInV().Restricted(ua, ub), dim_, t.degreeU_, t.knotsU_)
        .Transposed();
}

BSplineSurface BSplineSurface::Transposed() const {
    int nu = CountU(), nv = CountV();
    std::vector<double> t(c_.size());
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            for (int k = 0; k < dim_; ++k)
                t[static_cast<std::size_t>((i * nv + j) * dim_ + k)] = Point(i, j)[k];
    return BSplineSurface(dim_, degreeV_, degreeU_, knotsV_, knotsU_, std::move(t));
}

PatchGrid BSplineSurface::ToPatches() const {
    // v first: each v span gives a strip, Bézier in v and still B-spline in u.
    std::vector<BezierCurve> vSegs = RowsAsCurveInV().ToBezier();
    std::vector<double> breaksV, breaksU;
    for (const BezierCurve& s : vSegs) breaksV.push_back(s.T0());
    breaksV.push_back(vSegs.back().T1());
    std::vector<std::vector<BezierSurface>> rows;  // rows[b][a]
    for (const BezierCurve& vs : vSegs) {
        BSplineSurface strip = FromRowsCurve(BSplineCurve::FromBezier(vs), dim_, degreeU_, knotsU_);
        // In the transpose, u is the "v" of the rows curve: extract Bézier segments along u.
        BSplineSurface t = strip.Transposed();
        std::vector<BezierCurve> uSegs = t.RowsAsCurveInV().ToBezier();
        std::vector<BezierSurface> row;
        for (const BezierCurve& us : uSegs)
            row.push_back(
                BezierSurface::FromRowsCurve(us, dim_, degreeV_, vs.T0(), vs.T1()).Transposed());
        if (breaksU.empty()) {
            for (const BezierCurve& us : uSegs) breaksU.push_back(us.T0());
            breaksU.push_back(uSegs.back().T1());
        }
        rows.push_back(std::move(row));
    }
    std::vector<BezierSurface> patches;
    for (auto& row : rows)
        for (auto& p : row) patches.push_back(std::move(p));
    return PatchGrid(std::move(breaksU), std::move(breaksV), std::move(patches));
}

std::vector<BSplineSurface> BSplineSurface::SplitIntoUSpans() const {
    std::vector<BSplineSurface> out;
    for (const BezierCurve& seg : Transposed().RowsAsCurveInV().ToBezier())
        out.push_back(
            FromRowsCurve(BSplineCurve::FromBezier(seg), dim_, degreeV_, knotsV_).Transposed());
    return out;
}

// ---------------------------------------------------------------------------------------------
// PatchGrid

PatchGrid::PatchGrid(std::vector<double> breaksU, std::vector<double> breaksV,
                     std::vector<BezierSurface> patches)
    : breaksU_(std::move(breaksU)), breaksV_(std::move(breaksV)), patches_(std::move(patches)) {
    assert(patches_.size() == static_cast<std::size_t>(SpansU() * SpansV()));
}

namespace {

int SpanOf(const std::vector<double>& breaks, double t) {
    int n = static_cast<int>(breaks.size()) - 1;
    int k =
        static_cast<int>(std::upper_bound(breaks.begin(), breaks.end(), t) - breaks.begin()) - 1;
    return std::clamp(k, 0, n - 1);
}

}  // namespace

int PatchGrid::SpanU(double u) const { return SpanOf(breaksU_, u); }
int PatchGrid::SpanV(double v) const { return SpanOf(breaksV_, v); }

void PatchGrid::Evaluate(double u, double v, double* out) const {
    Patch(SpanU(u), SpanV(v)).Evaluate(u, v, out);
}

std::vector<double> PatchGrid::Evaluate(double u, double v) const {
    std::vector<double> out(static_cast<std::size_t>(Dim()));
    Evaluate(u, v, out.data());
    return out;
}

std::vector<BezierCurve> PatchGrid::IsoCurveAtV(double v) const {
    int b = SpanV(v);
    std::vector<BezierCurve> out;
    for (int a = 0; a < SpansU(); ++a) out.push_back(Patch(a, b).IsoCurveAtV(v));
    return out;
}

PatchGrid PatchGrid::Transposed() const {
    std::vector<BezierSurface> t;
    for (int a = 0; a < SpansU(); ++a)
        for (int b = 0; b < SpansV(); ++b) t.push_back(Patch(a, b).Transposed());
    return PatchGrid(breaksV_, breaksU_, std::move(t));
}

BSplineSurface PatchGrid::ToBSpline() const {
    int m = 0, n = 0;
    for (const BezierSurface& p : patches_) {
        m = std::max(m, p.DegreeU());
        n = std::max(n, p.DegreeV());
    }
    int dim = Dim();
    // Step 1: per patch row, join along u. In the transpose of a patch, rows run along u.
    std::vector<std::vector<BezierCurve>> uSegs(static_cast<std::size_t>(SpansV()));
    std::vector<bool> uJoins(static_cast<std::size_t>(std::max(SpansU() - 1, 0)), true);
    for (int b = 0; b < SpansV(); ++b) {
        for (int a = 0; a < SpansU(); ++a)
            uSegs[static_cast<std::size_t>(b)].push_back(
                Patch(a, b).ElevatedTo(m, n).Transposed().RowsAsCurveInV());
        std::vector<bool> j = ContinuousJoins(uSegs[static_cast<std::size_t>(b)]);
        for (std::size_t k = 0; k < j.size(); ++k) uJoins[k] = uJoins[k] && j[k];
    }
    // Step 2: each joined row strip (B-spline in u, Bézier in v) as a Bézier curve in v of rows.
    std::vector<BezierCurve> vSegs;
    std::vector<double> knotsU;
    for (int b = 0; b < SpansV(); ++b) {
        BSplineCurve inU = JoinSegments(uSegs[static_cast<std::size_t>(b)], uJoins);
        // inU is the rows curve of the transposed strip (its "u" is v, one Bézier span).
        BSplineSurface strip =
            BSplineSurface::FromRowsCurve(inU, dim, n,
                                          ClampedKnots(n, breaksV_[static_cast<std::size_t>(b)],
                                                       breaksV_[static_cast<std::size_t>(b + 1)]))
                .Transposed();
        knotsU = strip.KnotsU();
        BSplineCurve rows = strip.RowsAsCurveInV();
        vSegs.push_back(rows.ToBezier().front());
    }
    BSplineCurve inV = JoinSegments(vSegs, ContinuousJoins(vSegs));
    return BSplineSurface::FromRowsCurve(inV, dim, m, knotsU);
}

PatchGrid NormalField(const BSplineSurface& s) {
    PatchGrid g = s.ToPatches();
    std::vector<BezierSurface> n;
    for (const BezierSurface& p : g.Patches()) n.push_back(NormalField(p));
    return PatchGrid(g.BreaksU(), g.BreaksV(), std::move(n));
}

}  // namespace quadrix::freeform
