#include "quadrix/engines/raycast/kernel_lanes.h"

#include <cmath>

#include "quadrix/util/cpu_features.h"

namespace quadrix::raycast {

namespace {

// The loops' bodies, each built for AVX2 and for the baseline below (util/cpu_features.h).

// A body's set from its batch: ∅ where the pixel centre is outside the body's bounds `r` or the
// batch is kEmpty, its interval where kOne, its first interval and cut where kCut, `over` where
// kScalar.
[[gnu::always_inline]] inline void LanePushBody(int np, const double* xs, const double* ys,
                                                const Rect& r, const std::uint8_t* state,
                                                const double* lo, const double* hi,
                                                const double* cut, const std::int64_t* loId,
                                                const std::int64_t* hiId, Lane& out,
                                                std::int64_t* __restrict over) {
    for (int p = 0; p < np; ++p) {
        // Bitwise, not short-circuit, so that every comparison is made and the loop has no
        // branches (a skipped comparison could not be if-converted under -ftrapping-math).
        const bool in = !((xs[p] < r.x0) | (xs[p] > r.x1) | (ys[p] < r.y0) | (ys[p] > r.y1));
        out.lo[p] = lo[p];
        out.hi[p] = hi[p];
        out.loId[p] = loId[p];
        out.hiId[p] = hiId[p];
        // BodyBatch::kOne: the interval; kCut: its first interval below its cut; kScalar: over.
        const bool isCut = in & (state[p] == 3);
        out.cut[p] = isCut ? cut[p] : HUGE_VAL;
        out.n[p] = (in & (state[p] == 1)) | (isCut & (lo[p] < hi[p]));
        over[p] |= in & (state[p] == 2);
    }
}

// a = a ∪ b (UnionOfOne; ∅ ∪ B = B, A ∪ ∅ = A); two disjoint pieces keep the first.
[[gnu::always_inline]] inline void LaneUnionBody(int np, Lane& a, const Lane& b) {
    for (int p = 0; p < np; ++p) {
        const double alo = a.lo[p], ahi = a.hi[p], blo = b.lo[p], bhi = b.hi[p];
        const std::int64_t aloId = a.loId[p], ahiId = a.hiId[p], bloId = b.loId[p],
                           bhiId = b.hiId[p];
        const bool na = a.n[p] != 0, nb = b.n[p] != 0;
        const bool aFirst = alo <= blo;
        const double flo = aFirst ? alo : blo, fhi = aFirst ? ahi : bhi;
        const std::int64_t floId = aFirst ? aloId : bloId, fhiId = aFirst ? ahiId : bhiId;
        const double glo = aFirst ? blo : alo;
        const bool joined = glo <= fhi;
        const bool bLast = bhi >= ahi;
        const double lastHi = bLast ? bhi : ahi;
        const std::int64_t lastHiId = bLast ? bhiId : ahiId;
        const double uhi = joined ? lastHi : fhi;
        const std::int64_t uhiId = joined ? lastHiId : fhiId;
        const bool both = na & nb, onlyB = !na & nb;
        const double ac = a.cut[p], bc = b.cut[p];
        const double cut0 = ac < bc ? ac : bc;
        const bool cutHere = both & !joined & (glo < cut0);
        // Both: the joined (or first) piece; only b: b; else a as it is.
        const double keepLo = onlyB ? blo : alo, keepHi = onlyB ? bhi : ahi;
        const std::int64_t keepLoId = onlyB ? bloId : aloId, keepHiId = onlyB ? bhiId : ahiId;
        a.lo[p] = both ? flo : keepLo;
        a.loId[p] = both ? floId : keepLoId;
        a.hi[p] = both ? uhi : keepHi;
        a.hiId[p] = both ? uhiId : keepHiId;
        a.n[p] = na | nb;
        a.cut[p] = cutHere ? glo : cut0;
    }
}

// a = a ∩ b (IntersectionOfOne; ∅ when either is ∅ or they meet in a point or not at all).
[[gnu::always_inline]] inline void LaneIntersectionBody(int np, Lane& a, const Lane& b) {
    for (int p = 0; p < np; ++p) {
        const bool openB = b.lo[p] >= a.lo[p], closeA = a.hi[p] <= b.hi[p];
        const double lo = openB ? b.lo[p] : a.lo[p], hi = closeA ? a.hi[p] : b.hi[p];
        const std::int64_t loId = openB ? b.loId[p] : a.loId[p];
        const std::int64_t hiId = closeA ? a.hiId[p] : b.hiId[p];
        const bool keep = (a.n[p] != 0) & (b.n[p] != 0) & (lo < hi);
        a.lo[p] = lo;
        a.hi[p] = hi;
        a.loId[p] = loId;
        a.hiId[p] = hiId;
        a.n[p] = keep;
        a.cut[p] = a.cut[p] < b.cut[p] ? a.cut[p] : b.cut[p];
    }
}

// a = a − b (AppendDifferenceOfOne; ∅ − B = ∅, A − ∅ = A): b covering a's start leaves
// [b.hi, a.hi] when b ends first; b before or after a leaves a; b starting inside a leaves
// [a.lo, b.lo] and [b.hi, a.hi], each when not a point (both: the first, cut at b.hi).
[[gnu::always_inline]] inline void LaneDifferenceBody(int np, Lane& a, const Lane& b) {
    for (int p = 0; p < np; ++p) {
        const bool na = a.n[p] != 0, nb = b.n[p] != 0;
        const double alo = a.lo[p], ahi = a.hi[p], blo = b.lo[p], bhi = b.hi[p];
        const std::int64_t aloId = a.loId[p], ahiId = a.hiId[p], bloId = b.loId[p],
                           bhiId = b.hiId[p];
        const bool covers = (blo < alo) & (bhi >= alo);
        const bool apart = (bhi < alo) | (blo > ahi);
        const bool tail = bhi < ahi;  // [b.hi, a.hi] is a piece
        const bool head = alo < blo;  // [a.lo, b.lo] is a piece (when b starts inside a)
        const bool inside = !covers & !apart;
        // The result when both are non-empty: covers → tail or ∅; apart → a; inside → head
        // (cut at the tail when there is one), or else tail, or else ∅.
        const bool useTail = covers | (inside & !head);
        const bool useHead = inside & head;
        const bool nonEmpty = apart | (useTail & tail) | useHead;
        const bool change = na & nb;
        const double ac = a.cut[p], bc = b.cut[p];
        const double cut0 = ac < bc ? ac : bc;
        const bool cutHere = change & useHead & tail & (bhi < cut0);
        const bool newLo = change & useTail, newHi = change & useHead;
        a.lo[p] = newLo ? bhi : alo;
        a.loId[p] = newLo ? bhiId : aloId;
        a.hi[p] = newHi ? blo : ahi;
        a.hiId[p] = newHi ? bloId : ahiId;
        a.n[p] = na & (!nb | nonEmpty);
        a.cut[p] = cutHere ? bhi : cut0;
    }
}

#define QUADRIX_LANE_OP(Name)                                                              \
    QUADRIX_AVX2 void Name##Avx2(int np, Lane& a, const Lane& b) { Name##Body(np, a, b); } \
    void Name##Baseline(int np, Lane& a, const Lane& b) { Name##Body(np, a, b); }
QUADRIX_LANE_OP(LaneUnion)
QUADRIX_LANE_OP(LaneIntersection)
QUADRIX_LANE_OP(LaneDifference)
#undef QUADRIX_LANE_OP

QUADRIX_AVX2 void LanePushAvx2(int np, const double* xs, const double* ys, const Rect& r,
                               const std::uint8_t* state, const double* lo, const double* hi,
                               const double* cut, const std::int64_t* loId,
                               const std::int64_t* hiId, Lane& out, std::int64_t* __restrict over) {
    LanePushBody(np, xs, ys, r, state, lo, hi, cut, loId, hiId, out, over);
}
void LanePushBaseline(int np, const double* xs, const double* ys, const Rect& r,
                      const std::uint8_t* state, const double* lo, const double* hi,
                      const double* cut, const std::int64_t* loId, const std::int64_t* hiId,
                      Lane& out, std::int64_t* __restrict over) {
    LanePushBody(np, xs, ys, r, state, lo, hi, cut, loId, hiId, out, over);
}

}  // namespace

void LanePush(int np, const double* xs, const double* ys, const Rect& r, const std::uint8_t* state,
              const double* lo, const double* hi, const double* cut, const std::int64_t* loId,
              const std::int64_t* hiId, Lane& out, std::int64_t* __restrict over) {
    if (gCpuHasAvx2)
        LanePushAvx2(np, xs, ys, r, state, lo, hi, cut, loId, hiId, out, over);
    else
        LanePushBaseline(np, xs, ys, r, state, lo, hi, cut, loId, hiId, out, over);
}

void LaneUnion(int np, Lane& a, const Lane& b) {
    gCpuHasAvx2 ? LaneUnionAvx2(np, a, b) : LaneUnionBaseline(np, a, b);
}

void LaneIntersection(int np, Lane& a, const Lane& b) {
    gCpuHasAvx2 ? LaneIntersectionAvx2(np, a, b) : LaneIntersectionBaseline(np, a, b);
}

void LaneDifference(int np, Lane& a, const Lane& b) {
    gCpuHasAvx2 ? LaneDifferenceAvx2(np, a, b) : LaneDifferenceBaseline(np, a, b);
}

}  // namespace quadrix::raycast
