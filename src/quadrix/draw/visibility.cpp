#include "quadrix/draw/visibility.h"

#include <algorithm>
#include <cmath>

namespace quadrix::draw {

bool PointVisible(SceneProbe& probe, const Vec3& p) {
    const FlatScene& s = probe.scene();
    const double tau =
        1e-7 * std::max({static_cast<double>(std::max(s.width, s.height)), std::fabs(p.z), 1.0});
    return probe.FirstOpaqueHit(p.x, p.y) >= p.z - tau;
}

std::vector<CurvePiece> SplitByVisibility(const std::vector<Curve3>& curves,
                                          const std::vector<CurvePiece>& pieces, SceneProbe& probe,
                                          double step, VisibilityCounters& counters) {
    std::vector<CurvePiece> out;
    for (const CurvePiece& piece : pieces) {
        const Curve3& c = curves[static_cast<std::size_t>(piece.curve)];
        const double len = ProjectedLength(c, piece.t0, piece.t1);
        if (!(len > 1e-6)) continue;  // seen end-on: a point in the drawing
        const int n = static_cast<int>(std::clamp(std::ceil(len / step), 1.0, 100000.0));
        const double span = piece.t1 - piece.t0;
        const double inset = 1e-9 * span;
        auto paramAt = [&](int i) {
            if (i == 0) return piece.t0 + inset;
            if (i == n) return piece.t1 - inset;
            return piece.t0 + span * i / n;
        };
        auto test = [&](double t) {
            ++counters.rayTests;
            return PointVisible(probe, c.At(t));
        };
        double start = piece.t0;
        double tPrev = paramAt(0);
        bool vPrev = test(tPrev);
        for (int i = 1; i <= n; ++i) {
            const double t = paramAt(i);
            const bool v = test(t);
            if (v != vPrev) {
                double lo = tPrev, hi = t;
                for (int k = 0; k < 60; ++k) {
                    const double mid = 0.5 * (lo + hi);
                    if (mid <= lo || mid >= hi) break;
                    if (test(mid) == vPrev) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                const double cut = 0.5 * (lo + hi);
                out.push_back({piece.curve, start, cut, vPrev, piece.tangent});
                ++counters.changes;
                start = cut;
                vPrev = v;
            }
            tPrev = t;
        }
        out.push_back({piece.curve, start, piece.t1, vPrev, piece.tangent});
    }
    return out;
}

}  // namespace quadrix::draw
