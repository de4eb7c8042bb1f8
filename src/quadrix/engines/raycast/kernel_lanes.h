// Lanes of engine `raycast`'s sub-tile kernels (kernel.h): a kernel's sets over the pixels of a
// sub-tile, one array per field, combined by branch-free loops the compiler vectorises (built for
// AVX2 and for the baseline, chosen at load time). Per pixel a lane holds ∅ or one interval
// (n = 0 or 1) and a cut T: the lane equals the kernel's exact set on t < T, ids included
// (T = +inf: exactly). Where an operation would give a second interval, the lane keeps the first
// and sets T to the second one's start; everything below T is then as in the full list (set
// operations are pointwise in t, and a sweep emits the same endpoints below T from the same
// events below T: the argument of Trace's depth cuts, trace.h). The first visible endpoint of a
// solid is therefore exact when it lies below T; a pixel where it does not, or where a body's set
// is not in its batch, is marked in `over` and evaluated by Kernel::Run. The operations are the
// one-interval cases of math/interval_list.h written as selects, with the same comparisons and
// tie rules (checked bit for bit against Kernel::Run and Trace by
// RaycastOptions.SpeedOptionsChangeNoBit): no arithmetic, so nothing to round.
#pragma once

#include <cstdint>

#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/engines/raycast/tiling.h"

namespace quadrix::raycast {

struct Lane {
    double lo[kLanePixels], hi[kLanePixels], cut[kLanePixels];
    std::int64_t loId[kLanePixels], hiId[kLanePixels], n[kLanePixels];
};

// A body's set from its batch (body_batch.h; `state` is BodyBatch::state): ∅ where the pixel
// centre is outside the body's bounds `r` or the batch is kEmpty, its interval where kOne, its
// first interval and cut where kCut, `over` where kScalar.
void LanePush(int np, const double* xs, const double* ys, const Rect& r, const std::uint8_t* state,
              const double* lo, const double* hi, const double* cut, const std::int64_t* loId,
              const std::int64_t* hiId, Lane& out, std::int64_t* __restrict over);

// a = a ∪ b (UnionOfOne; ∅ ∪ B = B, A ∪ ∅ = A); two disjoint pieces keep the first.
void LaneUnion(int np, Lane& a, const Lane& b);

// a = a ∩ b (IntersectionOfOne; ∅ when either is ∅ or they meet in a point or not at all).
void LaneIntersection(int np, Lane& a, const Lane& b);

// a = a − b (AppendDifferenceOfOne; ∅ − B = ∅, A − ∅ = A): b covering a's start leaves
// [b.hi, a.hi] when b ends first; b before or after a leaves a; b starting inside a leaves
// [a.lo, b.lo] and [b.hi, a.hi], each when not a point (both: the first, cut at b.hi).
void LaneDifference(int np, Lane& a, const Lane& b);

}  // namespace quadrix::raycast
