// Stage (b1) for bodies of many literals: the convex relaxation over a working set (bounds.h,
// "Many literals"). The interior-point method costs O(n) per Newton step but needs more steps,
// and longer line searches, as n grows: one body of 10⁴ planes took 1 s, 10⁵ over a minute.
// The relaxation of a subset W of the literals contains the body, so its certified bounds are
// valid for the whole body; its extreme point x̂ of a side is a point of the whole relaxation
// when no literal outside W is violated there, and then the bound of that side is as tight as
// the whole relaxation's. So: start from W = the literals that cut nearest to the centre along
// each axis direction, solve, add the literals most violated at the extreme points, repeat
// until none is violated (cutting planes; a handful of rounds in practice). Each round is O(n)
// outside the solve, the solve O(|W|) per step: near-linear in n. After kMaxRounds the last
// bounds are returned (conservative, possibly looser than the whole relaxation's).
#include <algorithm>
#include <cmath>

#include "quadrix/flatten/bounds_internal.h"

namespace quadrix::bounds_detail {

namespace {

constexpr std::size_t kPerDirection = 24;  // literals per axis direction in the first set
constexpr std::size_t kAddPerSide = 16;    // most violated literals added per side and round
constexpr int kMaxRounds = 12;

// The ray parameter s > 0 at which c + s e leaves the plane f <= 0 (inf: never).
double ExitAlong(const InsideFn& f, const double c[3], int axis, int sign) {
    const double slope = 2 * f.b[axis] * sign;
    if (!(slope > 0)) return kInf;
    const double v = EvaluateAt(f, c);
    return std::fmax(0.0, -v) / slope;
}

}  // namespace

RelaxationOutcome BoundByWorkingSetRelaxation(const std::vector<const InsideFn*>& fns,
                                              const std::vector<Nappe>& nappes, const Box3& region,
                                              Box3& work, BoundsStats* stats) {
    const std::size_t n = fns.size();
    std::vector<char> inSet(n, 0);
    std::vector<std::size_t> set;
    auto add = [&](std::size_t i) {
        if (!inSet[i]) {
            inSet[i] = 1;
            set.push_back(i);
        }
    };
    // Every quadric and nappe (bodies of many literals are mostly planes), and per axis
    // direction the planes met first along it from the region's centre.
    const Vec3 centre = region.Center();
    const double c[3] = {centre.x, centre.y, centre.z};
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t i = 0; i < n; ++i)
        if (!fns[i]->isPlane || (i < nappes.size() && nappes[i].ok)) add(i);
    for (int side = 0; side < 6; ++side) {
        order.clear();
        for (std::size_t i = 0; i < n; ++i)
            if (fns[i]->isPlane) {
                double s = ExitAlong(*fns[i], c, side / 2, side % 2 ? 1 : -1);
                if (s < kInf) order.push_back({s, i});
            }
        const std::size_t k = std::min(kPerDirection, order.size());
        std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k),
                         order.end());
        for (std::size_t j = 0; j < k; ++j) add(order[j].second);
    }
    RelaxationOutcome out;
    const Box3 start = work;
    std::vector<const InsideFn*> subset;
    std::vector<Nappe> subsetNappes;
    for (int round = 0; round < kMaxRounds; ++round) {
        subset.clear();
        subsetNappes.clear();
        for (std::size_t i : set) {
            subset.push_back(fns[i]);
            subsetNappes.push_back(i < nappes.size() ? nappes[i] : Nappe{});
        }
        Box3 box = start;
        out = BoundByConvexRelaxation(subset, subsetNappes, region, box, stats);
        if (!out.solved || out.empty) {
            work = box;
            return out;
        }
        work = box;
        // The literals outside the set violated at each extreme point, most violated first.
        std::size_t added = 0;
        for (int side = 0; side < 6; ++side) {
            if (!out.haveExtreme[side]) continue;
            const Vec3& e = out.extremes[side];
            const double p[3] = {e.x, e.y, e.z};
            order.clear();
            for (std::size_t i = 0; i < n; ++i) {
                if (inSet[i]) continue;
                Local l = EvaluateLocal(*fns[i], p);
                const double scale =
                    std::sqrt(l.g[0] * l.g[0] + l.g[1] * l.g[1] + l.g[2] * l.g[2]) + 1e-300;
                if (l.v > 1e-9 * (l.mag + 1e-300)) order.push_back({-l.v / scale, i});
            }
            const std::size_t k = std::min(kAddPerSide, order.size());
            std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k),
                              order.end());
            for (std::size_t j = 0; j < k; ++j) {
                if (!inSet[order[j].second]) ++added;
                add(order[j].second);
            }
        }
        if (added == 0) return out;
    }
    return out;
}

}  // namespace quadrix::bounds_detail
