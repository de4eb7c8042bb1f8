#include "quadrix/engines/isocurve/extraction.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "quadrix/freeform/roots.h"
#include "quadrix/util/seconds_since.h"

namespace quadrix::isocurve {

using freeform::BezierCurve;

namespace {

// The xyz part and the weight of a homogeneous curve.
std::pair<BezierCurve, BezierCurve> SplitHomogeneous(const BezierCurve& c) {
    std::vector<double> xyz, w;
    for (int i = 0; i <= c.Degree(); ++i) {
        const double* p = c.Point(i);
        xyz.insert(xyz.end(), {p[0], p[1], p[2]});
        w.push_back(p[3]);
    }
    return {BezierCurve(3, c.Degree(), std::move(xyz), c.T0(), c.T1()),
            BezierCurve(1, c.Degree(), std::move(w), c.T0(), c.T1())};
}

}  // namespace

BezierCurve IsoDistanceExcess(const BezierCurve& c1, const BezierCurve& c2, double delta2) {
    if (c1.Dim() == 3) {
        BezierCurve d = Subtract(c1, c2);
        return Dot(d, d).PlusConstant(-delta2);
    }
    auto [p1, w1] = SplitHomogeneous(c1);
    auto [p2, w2] = SplitHomogeneous(c2);
    BezierCurve d = Subtract(Multiply(w2, p1), Multiply(w1, p2));
    BezierCurve w = Multiply(w1, w2);
    return Subtract(Dot(d, d), Multiply(w, w).Scaled(delta2));
}

double CurveLength(IsoFamily& family, const Isocurve& curve) {
    double sum = 0;
    for (const BezierCurve& s : family.Pieces(curve.fixed, curve.t0, curve.t1)) sum += ArcLength(s);
    return sum;
}

namespace {

class Adaptive {
  public:
    Adaptive(IsoFamily& family, double delta, const ExtractOptions& options, Extraction& out)
        : family_(family),
          delta2_(delta * delta),
          options_(options),
          out_(out),
          minWidth_(options.parameterTolerance * (family.Run1() - family.Run0())),
          forcedWidth_(std::ldexp(family.Fixed1() - family.Fixed0(), -options.minLevel)) {
        roots_.tolerance = 1e-12 * (family.Run1() - family.Run0());
    }

    // The paper starts from the two boundary curves (base = 1); base N > 1 starts from N + 1
    // uniformly spaced curves and refines each interval dyadically.
    void Run(int base) {
        double v0 = family_.Fixed0(), v1 = family_.Fixed1();
        double a = family_.Run0(), b = family_.Run1();
        std::vector<double> fixed;
        for (int k = 0; k <= base; ++k) fixed.push_back(k == base ? v1 : v0 + (v1 - v0) * k / base);
        for (double f : fixed) Emit(f, a, b, 0);
        for (int k = 0; k < base; ++k)
            Aux(fixed[static_cast<std::size_t>(k)], fixed[static_cast<std::size_t>(k + 1)], a, b,
                0);
    }

  private:
    void Emit(double fixed, double a, double b, int level) {
        out_.curves.push_back({family_.Which(), fixed, a, b, level});
        out_.stats.deepestLevel = std::max(out_.stats.deepestLevel, level);
    }

    void Covered(double v1, double v2, double a, double b, bool resolved = true) {
        if (options_.keepStrips) out_.strips.push_back({v1, v2, a, b, resolved});
    }

    void Aux(double v1, double v2, double a, double b, int level) {
        ++out_.stats.pairs;
        // End condition 4: pairs wider than 2^-minLevel of the domain are always refined.
        if (v2 - v1 > forcedWidth_ * (1 + 1e-12)) return Middle(v1, v2, a, b, level);
        std::vector<BezierCurve> c1 = family_.Pieces(v1, a, b), c2 = family_.Pieces(v2, a, b);
        std::vector<BezierCurve> f;
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for (std::size_t k = 0; k < c1.size(); ++k) {
            f.push_back(IsoDistanceExcess(c1[k], c2[k], delta2_));
            lo = std::min(lo, f.back().MinCoefficient());
            hi = std::max(hi, f.back().MaxCoefficient());
        }
        if (!std::isfinite(lo) || !std::isfinite(hi)) {
            // End condition 7: a weight function that vanishes or overflowing coordinates make
            // Δ² meaningless here; do not refine on garbage.
            ++out_.stats.unresolved;
            return Covered(v1, v2, a, b, false);
        }
        if (hi <= 0) return Covered(v1, v2, a, b);       // Δ² <= δ² for all t (hull bound)
        if (lo > 0) return Middle(v1, v2, a, b, level);  // Δ² > δ² for all t

        ++out_.stats.rootSearches;
        std::vector<double> cuts = {a};
        for (const BezierCurve& piece : f) {
            std::optional<std::vector<double>> r = freeform::SignChanges(piece, roots_);
            if (!r) return Middle(v1, v2, a, b, level);  // end condition 3
            for (double t : *r)
                if (t > cuts.back() + minWidth_ && t < b - minWidth_) cuts.push_back(t);  // 2
        }
        cuts.push_back(b);
        out_.stats.crossings += static_cast<int>(cuts.size()) - 2;
        std::size_t k = 0;
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
            double ca = cuts[i], cb = cuts[i + 1];
            if (cb - ca <= minWidth_) {
                ++out_.stats.slivers;
                Covered(v1, v2, ca, cb);
                continue;
            }
            double mid = 0.5 * (ca + cb);
            while (k + 1 < f.size() && f[k].T1() <= mid) ++k;
            if (f[k].EvaluateScalar(mid) <= 0)
                Covered(v1, v2, ca, cb);  // end condition 1: decided once
            else
                Middle(v1, v2, ca, cb, level);
        }
    }

    void Middle(double v1, double v2, double a, double b, int level) {
        if (level >= options_.maxLevel ||
            static_cast<int>(out_.curves.size()) >= options_.maxCurves) {
            ++out_.stats.unresolved;
            Covered(v1, v2, a, b, false);
            return;
        }
        double vm = 0.5 * (v1 + v2);
        Emit(vm, a, b, level + 1);
        Aux(v1, vm, a, b, level + 1);
        Aux(vm, v2, a, b, level + 1);
    }

    IsoFamily& family_;
    double delta2_;
    const ExtractOptions& options_;
    Extraction& out_;
    double minWidth_;
    double forcedWidth_;
    freeform::RootOptions roots_;
};

// End condition 6: joins pieces of one fixed value that meet end to end.
void MergeCurves(std::vector<Isocurve>& curves) {
    std::sort(curves.begin(), curves.end(), [](const Isocurve& x, const Isocurve& y) {
        return x.fixed != y.fixed ? x.fixed < y.fixed : x.t0 < y.t0;
    });
    std::vector<Isocurve> out;
    for (const Isocurve& c : curves) {
        if (!out.empty() && out.back().fixed == c.fixed && out.back().t1 >= c.t0)
            out.back().t1 = std::max(out.back().t1, c.t1);
        else
            out.push_back(c);
    }
    curves = std::move(out);
}

Extraction Finish(IsoFamily& family, Extraction e, std::chrono::steady_clock::time_point start) {
    MergeCurves(e.curves);
    e.stats.curves = static_cast<int>(e.curves.size());
    e.stats.length = 0;
    for (const Isocurve& c : e.curves) e.stats.length += CurveLength(family, c);
    e.stats.seconds = SecondsSince(start);
    return e;
}

// True when every pair of the uniform family with n intervals has Δ ≤ δ everywhere.
bool UniformCovers(IsoFamily& family, int n, double delta2) {
    double v0 = family.Fixed0(), v1 = family.Fixed1();
    double a = family.Run0(), b = family.Run1();
    for (int k = 0; k < n; ++k) {
        double fa = v0 + (v1 - v0) * k / n, fb = k + 1 == n ? v1 : v0 + (v1 - v0) * (k + 1) / n;
        std::vector<BezierCurve> c1 = family.Pieces(fa, a, b), c2 = family.Pieces(fb, a, b);
        for (std::size_t i = 0; i < c1.size(); ++i)
            if (!freeform::AtMostEverywhere(IsoDistanceExcess(c1[i], c2[i], delta2), 0.0))
                return false;
    }
    return true;
}

// The smallest n >= minCount (doubling, then bisection) for which UniformCovers holds; the
// predicate is not monotone in n in general, but the n returned always satisfies it (or is the
// cap).
int UniformCount(IsoFamily& family, double delta2, int minCount) {
    const int kMaxCurves = 1 << 16;
    int hi = std::max(minCount, 1);
    while (hi < kMaxCurves && !UniformCovers(family, hi, delta2)) {
        family.ClearCache();
        hi *= 2;
    }
    int lo = std::max(hi / 2, minCount - 1);  // fails, or is below the minimum
    while (hi - lo > 1) {
        int mid = lo + (hi - lo) / 2;
        family.ClearCache();
        if (UniformCovers(family, mid, delta2))
            hi = mid;
        else
            lo = mid;
    }
    family.ClearCache();
    return hi;
}

Extraction AdaptiveIn(const freeform::Surface& surface, Constant constant, double delta,
                      const ExtractOptions& options) {
    auto start = std::chrono::steady_clock::now();
    IsoFamily family(surface, constant);
    Extraction e;
    e.constant = constant;
    e.delta = delta;
    if (!surface.WeightPositive()) {
        // End condition 7 for a whole surface: it reaches infinity (a weight function that
        // vanishes in the domain); nothing sensible can be drawn.
        e.stats.unresolved = 1;
        return Finish(family, std::move(e), start);
    }
    int base = std::max(options.baseCount, 0);
    if (base == 0) {
        // Auto: N + 1 uniform curves such that N 2^L is the uniform count rounded up, N in [4, 8).
        int n = UniformCount(family, delta * delta, 1);
        int shift = std::max(0, static_cast<int>(std::floor(std::log2(n))) - 2);
        base = (n + (1 << shift) - 1) >> shift;
    }
    e.baseCount = base;
    Adaptive(family, delta, options, e).Run(base);
    return Finish(family, std::move(e), start);
}

Extraction UniformIn(const freeform::Surface& surface, Constant constant, double delta,
                     const ExtractOptions& options) {
    auto start = std::chrono::steady_clock::now();
    IsoFamily family(surface, constant);
    Extraction e;
    e.constant = constant;
    e.delta = delta;
    if (!surface.WeightPositive()) {  // as in AdaptiveIn
        e.stats.unresolved = 1;
        return Finish(family, std::move(e), start);
    }
    int n = UniformCount(family, delta * delta, 1 << std::max(options.minLevel, 0));
    double v0 = family.Fixed0(), v1 = family.Fixed1();
    for (int k = 0; k <= n; ++k) {
        double f = k == n ? v1 : v0 + (v1 - v0) * k / n;
        e.curves.push_back({constant, f, family.Run0(), family.Run1(), k == 0 || k == n ? 0 : 1});
        if (options.keepStrips && k > 0)
            e.strips.push_back({e.curves[static_cast<std::size_t>(k - 1)].fixed, f, family.Run0(),
                                family.Run1(), true});
    }
    e.stats.pairs = n;
    return Finish(family, std::move(e), start);
}

template <typename Fn>
Extraction BestDirection(const freeform::Surface& surface, double delta,
                         const ExtractOptions& options, Fn extract) {
    if (options.direction == Direction::kConstV)
        return extract(surface, Constant::kV, delta, options);
    if (options.direction == Direction::kConstU)
        return extract(surface, Constant::kU, delta, options);
    // kAuto: the direction whose curves are shorter in total (the cheaper coverage to draw).
    Extraction v = extract(surface, Constant::kV, delta, options);
    Extraction u = extract(surface, Constant::kU, delta, options);
    double seconds = v.stats.seconds + u.stats.seconds;
    Extraction& best = u.stats.length < v.stats.length ? u : v;
    best.stats.seconds = seconds;
    return std::move(best);
}

}  // namespace

Extraction ExtractAdaptive(const freeform::Surface& surface, double delta,
                           const ExtractOptions& options) {
    return BestDirection(surface, delta, options, AdaptiveIn);
}

Extraction ExtractUniform(const freeform::Surface& surface, double delta,
                          const ExtractOptions& options) {
    return BestDirection(surface, delta, options, UniformIn);
}

}  // namespace quadrix::isocurve
