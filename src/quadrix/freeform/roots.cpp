#include "quadrix/freeform/roots.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "quadrix/freeform/bernstein.h"

namespace quadrix::freeform {

namespace {

int Sign(double x) { return (x > 0) - (x < 0); }

// Sign changes among the non-zero coefficients, and the signs of the first and last non-zero ones
// (the signs of f just inside the two ends).
struct Variation {
    int changes = 0;
    int first = 0, last = 0;
};

Variation CountVariation(const std::vector<double>& c) {
    Variation v;
    for (double x : c) {
        int s = Sign(x);
        if (s == 0) continue;
        if (v.first == 0) v.first = s;
        if (v.last != 0 && s != v.last) ++v.changes;
        v.last = s;
    }
    return v;
}

class RootFinder {
  public:
    RootFinder(const RootOptions& options) : options_(options) {}

    // Roots of the polynomial with local coefficients c on the global interval [a, b].
    bool Search(const std::vector<double>& c, double a, double b) {
        Variation var = CountVariation(c);
        if (var.changes == 0) return true;
        if (var.changes == 1) return Add(Bisect(c, a, b, var.first));
        if (b - a <= options_.tolerance) {
            if (var.first != var.last) return Add(0.5 * (a + b));
            return true;
        }
        int n = static_cast<int>(c.size()) - 1;
        std::vector<double> left(c.size()), right(c.size());
        SubdivideInto(c.data(), n, 1, 0.5, left.data(), right.data());
        double m = 0.5 * (a + b);
        if (!Search(left, a, m)) return false;
        // A root exactly at the split point belongs to neither open half.
        if (left.back() == 0) {
            Variation l = CountVariation(left), r = CountVariation(right);
            if (l.last != 0 && r.first != 0 && l.last != r.first && !Add(m)) return false;
        }
        return Search(right, m, b);
    }

    std::vector<double> Roots() {
        std::sort(roots_.begin(), roots_.end());
        return roots_;
    }

  private:
    bool Add(double t) {
        roots_.push_back(t);
        return static_cast<int>(roots_.size()) <= options_.maxRoots;
    }

    // One simple root in (a, b); f has sign `sa` just right of a.
    double Bisect(const std::vector<double>& c, double a, double b, int sa) const {
        int n = static_cast<int>(c.size()) - 1;
        double lo = 0, hi = 1;  // local parameters
        for (int it = 0; it < 200 && (hi - lo) * (b - a) > options_.tolerance; ++it) {
            double mid = 0.5 * (lo + hi);
            double f;
            DeCasteljau(c.data(), n, 1, mid, &f);
            if (f == 0) return a + mid * (b - a);
            if (Sign(f) == sa)
                lo = mid;
            else
                hi = mid;
        }
        return a + 0.5 * (lo + hi) * (b - a);
    }

    RootOptions options_;
    std::vector<double> roots_;
};

}  // namespace

std::optional<std::vector<double>> SignChanges(const BezierCurve& f, const RootOptions& options) {
    RootFinder finder(options);
    if (!finder.Search(f.Coefficients(), f.T0(), f.T1())) return std::nullopt;
    return finder.Roots();
}

namespace {

// Depth-first with a budget of pieces: a polynomial that touches the bound along a stretch would
// otherwise split into exponentially many undecided pieces.
bool AtMost(const std::vector<double>& c0, double bound, double width0, double tolerance) {
    struct Piece {
        std::vector<double> c;
        double width;
    };
    std::vector<Piece> stack = {{c0, width0}};
    int n = static_cast<int>(c0.size()) - 1;
    for (int budget = 20000; !stack.empty(); --budget) {
        if (budget == 0) return false;  // undecided: conservative
        Piece p = std::move(stack.back());
        stack.pop_back();
        double hi = -HUGE_VAL;
        for (double x : p.c) {
            if (!std::isfinite(x)) return false;
            hi = std::max(hi, x);
        }
        if (hi <= bound) continue;
        // The end coefficients are values of f: one of them above the bound settles it.
        if (p.c.front() > bound || p.c.back() > bound) return false;
        if (p.width <= tolerance) return false;  // undecided at the resolution: conservative
        std::vector<double> left(p.c.size()), right(p.c.size());
        SubdivideInto(p.c.data(), n, 1, 0.5, left.data(), right.data());
        stack.push_back({std::move(right), 0.5 * p.width});
        stack.push_back({std::move(left), 0.5 * p.width});
    }
    return true;
}

}  // namespace

bool AtMostEverywhere(const BezierCurve& f, double bound, double tolerance) {
    return AtMost(f.Coefficients(), bound, f.T1() - f.T0(), tolerance);
}

double MaximumBound(const BezierCurve& f, double tolerance) {
    struct Piece {
        double upper;
        std::vector<double> c;
        bool operator<(const Piece& o) const { return upper < o.upper; }
    };
    const std::vector<double>& c0 = f.Coefficients();
    double lower = std::max(c0.front(), c0.back());  // f attains its end values
    std::priority_queue<Piece> queue;
    queue.push({*std::max_element(c0.begin(), c0.end()), c0});
    int n = f.Degree();
    // Best-first: the piece with the largest hull maximum is split until that maximum is within
    // tolerance of a value f attains; the budget bounds the work for flat maxima.
    for (int it = 0; it < 4000 && !queue.empty(); ++it) {
        Piece top = queue.top();
        if (top.upper - lower <= tolerance) return top.upper;
        queue.pop();
        std::vector<double> left(top.c.size()), right(top.c.size());
        SubdivideInto(top.c.data(), n, 1, 0.5, left.data(), right.data());
        lower = std::max(lower, left.back());
        for (auto* half : {&left, &right})
            queue.push({*std::max_element(half->begin(), half->end()), std::move(*half)});
    }
    return queue.empty() ? lower : queue.top().upper;
}

}  // namespace quadrix::freeform
