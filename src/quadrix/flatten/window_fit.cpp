// The window fit; the rules are written out in window_fit.h.
#include "quadrix/flatten/window_fit.h"

#include <cmath>

#include "quadrix/flatten/bottom_up.h"

namespace quadrix {

namespace {

constexpr double kUnbounded = HUGE_VAL;

bool FiniteOn(const Box3& b, int axis) {
    return !b.Empty() && std::isfinite(b.lo[axis]) && std::isfinite(b.hi[axis]);
}

void SetUnknown(Box3& b, int axis) {
    b.lo[axis] = -kUnbounded;
    b.hi[axis] = kUnbounded;
}

// The fit box of one non-leaf node from its children's fit boxes (window_fit.h).
Box3 CombineFit(const FlatCsgNode& node, const std::vector<Box3>& fit) {
    Box3 out = Box3::Everything();
    for (int axis = 0; axis < 3; ++axis) {
        double lo = kUnbounded, hi = -kUnbounded;
        bool known = false;
        switch (node.op) {
            case scene::CsgOp::kUnion:
                for (int c : node.children)
                    if (FiniteOn(fit[c], axis)) {
                        lo = std::fmin(lo, fit[c].lo[axis]);
                        hi = std::fmax(hi, fit[c].hi[axis]);
                        known = true;
                    }
                break;
            case scene::CsgOp::kIntersection:
                lo = -kUnbounded, hi = kUnbounded;
                for (int c : node.children)
                    if (FiniteOn(fit[c], axis)) {
                        lo = std::fmax(lo, fit[c].lo[axis]);
                        hi = std::fmin(hi, fit[c].hi[axis]);
                        known = true;
                    }
                // Disjoint fit intervals: the set may still be non-empty through its unbounded
                // members, so the axis is left to the rest of the scene.
                known = known && lo <= hi;
                break;
            case scene::CsgOp::kDifference:
                if (!node.children.empty() && FiniteOn(fit[node.children[0]], axis)) {
                    lo = fit[node.children[0]].lo[axis];
                    hi = fit[node.children[0]].hi[axis];
                    known = true;
                }
                break;
        }
        if (known) {
            out.lo[axis] = lo;
            out.hi[axis] = hi;
        }
    }
    return out;
}

}  // namespace

Box3 FitNodeBounds(const FlatCsgNode& node, const Box3& real, const Box3& leafBody,
                   const std::vector<Box3>& fit, double farDepth, double nearDepth) {
    if (real.Empty()) return Box3{};  // the empty box
    if (node.isLeaf) {
        Box3 b = leafBody;
        bool reachesInfinity =
            (farDepth > 0 && !(b.hi.z < farDepth * (1 - 1e-9))) || ReachesNearPlane(b, nearDepth);
        for (int axis = 0; axis < 3; ++axis)
            if (reachesInfinity || !FiniteOn(b, axis)) SetUnknown(b, axis);
        return b;
    }
    Box3 b = CombineFit(node, fit);
    // Where both are known the node's own box can only tighten the fit interval.
    for (int axis = 0; axis < 3; ++axis) {
        if (!FiniteOn(b, axis) || !FiniteOn(real, axis)) continue;
        double lo = std::fmax(b.lo[axis], real.lo[axis]);
        double hi = std::fmin(b.hi[axis], real.hi[axis]);
        if (lo <= hi) {
            b.lo[axis] = lo;
            b.hi[axis] = hi;
        }
    }
    return b;
}

std::vector<Box3> FitTreeBounds(const FlatScene& scene, const std::vector<Box3>& bodyBoxes,
                                const std::vector<Box3>& nodeBoxes, double farDepth,
                                double nearDepth) {
    std::vector<Box3> fit(scene.nodes.size());
    BottomUp(scene, [&](std::size_t i) {
        const FlatCsgNode& node = scene.nodes[i];
        fit[i] = FitNodeBounds(node, nodeBoxes[i], node.isLeaf ? bodyBoxes[node.body] : Box3{}, fit,
                               farDepth, nearDepth);
    });
    return fit;
}

WindowFitStatus FitWindow(const WindowRequest& request, const std::vector<Box3>& fitBoxes,
                          WindowFit& fit) {
    const double w = request.width, h = request.height, m = request.margin;
    fit = WindowFit{};
    if (request.whw || request.whh) {
        double k = kUnbounded;
        if (request.whw) k = std::fmin(k, 0.5 * w / *request.whw);
        if (request.whh) k = std::fmin(k, 0.5 * h / *request.whh);
        fit.k = k;
        fit.ox = 0.5 * w;
        fit.oy = 0.5 * h;
        return WindowFitStatus::kOk;
    }
    Box3 extent;
    bool known[2] = {false, false};
    for (const Box3& b : fitBoxes)
        for (int axis = 0; axis < 2; ++axis)
            if (FiniteOn(b, axis)) {
                extent.lo[axis] = std::fmin(extent.lo[axis], b.lo[axis]);
                extent.hi[axis] = std::fmax(extent.hi[axis], b.hi[axis]);
                known[axis] = true;
            }
    if (!known[0] && !known[1]) return WindowFitStatus::kNothingBounded;
    const double size[2] = {w, h};
    double k = kUnbounded, centre[2] = {0, 0};
    for (int axis = 0; axis < 2; ++axis) {
        if (!known[axis]) continue;  // centred on vrp
        double span = extent.hi[axis] - extent.lo[axis];
        centre[axis] = 0.5 * (extent.lo[axis] + extent.hi[axis]);
        if (span > 0) k = std::fmin(k, size[axis] * (1 - 2 * m) / span);
    }
    if (!(k < kUnbounded) || !(k > 0)) return WindowFitStatus::kNoExtent;
    fit.k = k;
    fit.ox = 0.5 * w - k * centre[0];
    fit.oy = 0.5 * h - k * centre[1];
    return WindowFitStatus::kOk;
}

}  // namespace quadrix
