// The window fit of the Flattener (seed 001 §2.1.6, docs/language.md §3.8): the uniform scale k
// (pixels per unit of the view plane) and the translation (ox, oy) that map PROVISIONAL device
// space (view_setup.h: x right, y down, vrp's projection at the origin) to device space,
//     x_dev = k x + ox,   y_dev = k y + oy,   z_dev = k z.
//
// The window. whw and whh are the window's half-width and half-height on the view plane, centred
// on vrp. Pixels are square, so:
//   - both given:  k = min(W / (2 whw), H / (2 whh)): the whole window fits in the image;
//   - one given:   k = W / (2 whw) or H / (2 whh): the other half-size follows from the image's
//                  aspect (whh = whw H / W);
//   - in both cases the window is centred on vrp: ox = W/2, oy = H/2.
// No window: auto-fit. The scene's extent E on each axis (the hull of the solids' boxes there)
// fills the image less `margin` per side: k = min over the axes of W (1 - 2m) / E_x and
// H (1 - 2m) / E_y, and each axis is centred on its extent's middle.
//
// What the auto-fit sees (FitTreeBounds). Unbounded solids (a ground plane, a union with one) must
// not make the fit impossible or the picture a dot: the fit uses the BOUNDED parts of the scene
// and the unbounded ones are drawn clipped to that window. Per node and per axis the fit interval
// is the node's conservative box on that axis when it is finite there, else:
//   union        → the hull of the children's finite fit intervals (the bounded members),
//   intersection → the intersection of the children's finite fit intervals,
//   difference   → the minuend's fit interval,
//   body         → unknown (±∞);
// an axis no solid bounds is centred on vrp. In perspective the image of the points at infinity
// is the plane z = d (view_setup.h); a body whose box reaches it goes to infinity in the world,
// and its screen box is only bounded by the near plane (at 1e-4 d, so it would be 10⁴ times too
// large): such a body counts as unbounded on every axis. So does a body whose box reaches the
// fit's near plane (depth `nearDepth`, the image of n_e = 1e-4 d): it passes beside or behind the
// eye, or holds it (issue 23: the eye inside a solid), and its screen box is again only the
// near plane's. Only a scene in which no axis is bounded by anything, and no window is given,
// cannot be fitted (the Flattener's message then says which solid holds or passes the eye).
//
// fbp has no effect on auto-scaling (§2.1.6): the boxes given here are computed with the fit
// clip planes, not the final ones.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/vec.h"

namespace quadrix {

// Per-node fit boxes (see above) from the per-body conservative boxes (indexed like
// scene.bodies) and the per-node ones (TreeBounds of the same bodies). An axis with no finite
// fit interval is [-∞, +∞]; an empty box means the node is empty. `farDepth` > 0 (perspective:
// the depth d of the image of infinity) marks bodies reaching z >= farDepth (1 - 1e-9) as
// unbounded on every axis; `nearDepth` < 0 (perspective: the depth of the fit's near plane) marks
// those reaching z <= nearDepth (1 - 1e-9) likewise.
std::vector<Box3> FitTreeBounds(const FlatScene& scene, const std::vector<Box3>& bodyBoxes,
                                const std::vector<Box3>& nodeBoxes, double farDepth = 0,
                                double nearDepth = -HUGE_VAL);
// One node of FitTreeBounds: `real` is its TreeBounds box, `leafBody` (for a leaf) its body's
// conservative box, `fit` the fit boxes of its children. A node's fit box is thus a function of
// its subtree alone.
Box3 FitNodeBounds(const FlatCsgNode& node, const Box3& real, const Box3& leafBody,
                   const std::vector<Box3>& fit, double farDepth = 0, double nearDepth = -HUGE_VAL);
// True when `box` reaches the near plane at depth `nearDepth` (< 0) as FitTreeBounds counts it.
inline bool ReachesNearPlane(const Box3& box, double nearDepth) {
    return std::isfinite(nearDepth) && nearDepth < 0 && !box.Empty() &&
           !(box.lo.z > nearDepth * (1 - 1e-9));
}

struct WindowRequest {
    int width = 0, height = 0;
    double margin = 0.02;  // auto-fit: fraction of the image left free per side
    std::optional<double> whh, whw;
};

struct WindowFit {
    double k = 1, ox = 0, oy = 0;
};

enum class WindowFitStatus {
    kOk,
    kNothingBounded,  // auto-fit: no solid is bounded on either screen axis
    kNoExtent,        // auto-fit: the bounded extent is a point (or flat seen edge-on)
};

// `fitBoxes`: one box per solid (FitTreeBounds of its root) or freeform surface, in provisional
// space; empty boxes are ignored. With a window (whh or whw) the boxes are not looked at.
WindowFitStatus FitWindow(const WindowRequest& request, const std::vector<Box3>& fitBoxes,
                          WindowFit& fit);

}  // namespace quadrix
