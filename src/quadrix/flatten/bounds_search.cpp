// Stage (b2) of bounds.h: a best-first branch-and-bound per direction over boxes, for the sides
// the convex relaxation could not settle (non-convex literals: hyperboloids of one sheet,
// complemented quadrics, nappes whose side could not be proven).
#include <algorithm>
#include <cmath>
#include <queue>

#include "quadrix/flatten/bounds_internal.h"

namespace quadrix::bounds_detail {

namespace {

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

class Refiner {
  public:
    Refiner(std::vector<InsideFn> fns, const BoundsOptions& options, BoundsStats* stats)
        : fns_(std::move(fns)), options_(options), stats_(stats) {
        allMask_ = fns_.size() >= 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << fns_.size()) - 1);
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
    bool Active(std::uint64_t mask, std::size_t i) const { return i >= 64 || (mask >> i & 1u); }

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
                if (c.mask != 0)
                    maxHalf = std::fmax(maxHalf, std::fmax(c.h[0], std::fmax(c.h[1], c.h[2])));
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
        if (sign > 0)
            work.hi[axis] = std::fmin(work.hi[axis], face);
        else
            work.lo[axis] = std::fmax(work.lo[axis], face);
    }

    std::vector<InsideFn> fns_;
    BoundsOptions options_;
    BoundsStats* stats_;
    std::uint64_t allMask_ = 0;
    std::vector<Local> locals_;   // per literal, valid for the cell being assessed
    std::vector<int> undecided_;  // literals undecided on the cell being assessed
    Box3 inner_;                  // box of points found in the set
};

}  // namespace

bool RefineByBranchAndBound(std::vector<InsideFn> fns, const std::vector<Vec3>& seeds,
                            const bool sides[6], const BoundsOptions& options, BoundsStats* stats,
                            Box3& work) {
    Refiner refiner(std::move(fns), options, stats);
    for (const Vec3& s : seeds) refiner.Seed(s);
    return refiner.Refine(work, sides);
}

}  // namespace quadrix::bounds_detail
