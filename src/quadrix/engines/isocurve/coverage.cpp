#include "quadrix/engines/isocurve/coverage.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace quadrix::isocurve {

namespace {

// Point of the original surface at oriented parameters (t running, f fixed).
Vec3 At(const freeform::Surface& s, Constant c, double t, double f) {
    return c == Constant::kV ? s.Point(t, f) : s.Point(f, t);
}

// A uniform grid over the oriented parameter domain listing the strips that overlap each cell.
class StripIndex {
  public:
    StripIndex(const Extraction& e, double t0, double t1, double f0, double f1)
        : e_(e), t0_(t0), t1_(t1), f0_(f0), f1_(f1), cells_(kN * kN) {
        for (std::size_t i = 0; i < e.strips.size(); ++i) {
            const CoveredStrip& s = e.strips[i];
            int a0 = CellT(s.t0), a1 = CellT(s.t1), b0 = CellF(s.fixedLo), b1 = CellF(s.fixedHi);
            for (int b = b0; b <= b1; ++b)
                for (int a = a0; a <= a1; ++a)
                    cells_[static_cast<std::size_t>(b * kN + a)].push_back(i);
        }
    }

    // Strips containing (t, f); `strict` counts only interior points.
    void Find(double t, double f, std::vector<std::size_t>& out,
              std::vector<std::size_t>& strict) const {
        out.clear();
        strict.clear();
        for (std::size_t i : cells_[static_cast<std::size_t>(CellF(f) * kN + CellT(t))]) {
            const CoveredStrip& s = e_.strips[i];
            if (t >= s.t0 && t <= s.t1 && f >= s.fixedLo && f <= s.fixedHi) {
                out.push_back(i);
                if (t > s.t0 && t < s.t1 && f > s.fixedLo && f < s.fixedHi) strict.push_back(i);
            }
        }
    }

  private:
    static constexpr int kN = 64;
    int CellT(double t) const {
        return std::clamp(static_cast<int>((t - t0_) / (t1_ - t0_) * kN), 0, kN - 1);
    }
    int CellF(double f) const {
        return std::clamp(static_cast<int>((f - f0_) / (f1_ - f0_) * kN), 0, kN - 1);
    }
    const Extraction& e_;
    double t0_, t1_, f0_, f1_;
    std::vector<std::vector<std::size_t>> cells_;
};

// Distance from p to the curve f = const, t ∈ [a, b]: sampled, then refined by golden sections
// around the best sample.
double DistanceToCurve(const freeform::Surface& s, Constant c, double f, double a, double b,
                       const Vec3& p) {
    const int kSamples = 64;
    double bestT = a, best = HUGE_VAL;
    for (int i = 0; i <= kSamples; ++i) {
        double t = a + (b - a) * i / kSamples;
        double d = Length(At(s, c, t, f) - p);
        if (d < best) {
            best = d;
            bestT = t;
        }
    }
    double lo = std::max(a, bestT - (b - a) / kSamples),
           hi = std::min(b, bestT + (b - a) / kSamples);
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    for (int it = 0; it < 60; ++it) {
        double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        double d1 = Length(At(s, c, x1, f) - p), d2 = Length(At(s, c, x2, f) - p);
        best = std::min({best, d1, d2});
        if (d1 < d2)
            hi = x2;
        else
            lo = x1;
    }
    return best;
}

struct Domain {
    double t0, t1, f0, f1;
};

Domain Oriented(const freeform::Surface& s, Constant c) {
    if (c == Constant::kV) return {s.U0(), s.U1(), s.V0(), s.V1()};
    return {s.V0(), s.V1(), s.U0(), s.U1()};
}

}  // namespace

CoverageReport CheckCoverage(const freeform::Surface& surface, const Extraction& e, int samples,
                             std::uint64_t seed) {
    CoverageReport r;
    Domain d = Oriented(surface, e.constant);
    StripIndex index(e, d.t0, d.t1, d.f0, d.f1);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> ut(d.t0, d.t1), uf(d.f0, d.f1);
    std::vector<std::size_t> found, strict;
    double sum = 0;
    for (int i = 0; i < samples; ++i) {
        double t = ut(rng), f = uf(rng);
        ++r.samples;
        index.Find(t, f, found, strict);
        if (found.empty()) {
            ++r.outsideStrips;
            ++r.uncovered;
            continue;
        }
        if (strict.size() > 1) ++r.inSeveralStrips;
        const CoveredStrip& s = e.strips[found.front()];
        Vec3 p = At(surface, e.constant, t, f);
        double dist = std::min(Length(p - At(surface, e.constant, t, s.fixedLo)),
                               Length(p - At(surface, e.constant, t, s.fixedHi)));
        if (dist >= e.delta)
            dist = std::min(DistanceToCurve(surface, e.constant, s.fixedLo, s.t0, s.t1, p),
                            DistanceToCurve(surface, e.constant, s.fixedHi, s.t0, s.t1, p));
        if (dist >= e.delta) ++r.uncovered;
        r.maxDistance = std::max(r.maxDistance, dist);
        sum += dist;
    }
    r.meanDistance = r.samples ? sum / r.samples : 0;
    return r;
}

double MaxAdjacentRatio(const freeform::Surface& surface, const Extraction& e, int perStrip) {
    double worst = 0;
    for (const CoveredStrip& s : e.strips) {
        if (!s.resolved) continue;
        for (int i = 0; i <= perStrip; ++i) {
            double t = s.t0 + (s.t1 - s.t0) * i / perStrip;
            double dist = Length(At(surface, e.constant, t, s.fixedLo) -
                                 At(surface, e.constant, t, s.fixedHi));
            worst = std::max(worst, dist / e.delta);
        }
    }
    return worst;
}

double StripAreaRatio(const freeform::Surface& surface, const Extraction& e) {
    Domain d = Oriented(surface, e.constant);
    double area = 0;
    for (const CoveredStrip& s : e.strips) area += (s.t1 - s.t0) * (s.fixedHi - s.fixedLo);
    return area / ((d.t1 - d.t0) * (d.f1 - d.f0));
}

}  // namespace quadrix::isocurve
