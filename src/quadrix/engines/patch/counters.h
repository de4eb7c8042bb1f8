// The counters of engine `patch`, declared once (engines/counters.h): the patches made from the
// bodies, the bodies the processor cannot draw (by Rejection, patch.h), and the timing and cost
// models of seed 000 (§1.3 and Tables 1.1-1.7). The names keep the spaces of the seed's wording.
#pragma once

#include "quadrix/engines/counters.h"

namespace quadrix::patch {

// X(id, name, meaning). The "bodies skipped:" rows follow Rejection from kEmpty to kMalformed and
// are named by RejectionName (a test checks both).
#define QUADRIX_PATCH_COUNTERS(X)                                                             \
    X(kPatches, "patches", "quadric patches drawn")                                           \
    X(kBodiesDrawnOpen, "bodies drawn open", "patches whose opaque plane faces are missing")  \
    X(kRedundantPlanesDropped, "redundant planes dropped", "cutting planes found redundant")  \
    X(kCsgSolidsSkipped, "csg solids skipped", "CSG solids (left to raycast)")                \
    X(kSkippedEmpty, "bodies skipped: empty", "bodies provably empty")                        \
    X(kSkippedInvisible, "bodies skipped: invisible (transparent quadric)",                   \
      "transparent quadrics without a plane face")                                            \
    X(kSkippedNoQuadric, "bodies skipped: no quadric", "bodies of planes only")               \
    X(kSkippedSeveralQuadrics, "bodies skipped: more than one quadric",                       \
      "bodies of several quadrics (one square-root datapath)")                                \
    X(kSkippedTooManyPlanes, "bodies skipped: more than four cutting planes",                 \
      "bodies cut by more than four planes")                                                  \
    X(kSkippedOpaquePlaneFace, "bodies skipped: opaque plane face (caps=skip)",               \
      "bodies with a visible opaque plane face, caps=skip")                                   \
    X(kSkippedViewAlongSurface, "bodies skipped: C = 0 (view direction along the quadric)",   \
      "quadrics the rays meet at most once")                                                  \
    X(kSkippedNotFinite, "bodies skipped: non-finite coefficients", "NaN or infinite bodies") \
    X(kSkippedMalformed, "bodies skipped: literal naming no half-space", "malformed bodies")  \
    X(kWindowPixels, "window pixels", "pixels of the patches' windows")                       \
    X(kSurfacePixels, "surface pixels", "pixels where a patch's surface was drawn")           \
    X(kCycles, "cycles", "processor clock cycles, one patch after another")                   \
    X(kStreamedCycles, "streamed cycles", "clock cycles with patches streamed back to back")  \
    X(kEstimatedSeconds, "estimated seconds", "the cycles at the processor's clock")          \
    X(kTransistors, "transistors", "transistors of the datapath (cost model)")                \
    X(kReferenceMismatches, "reference mismatches", "mode=fixed verify: pixels differing")    \
    X(kMaxDepthErrorLsb, "max depth error lsb", "mode=fixed compare: largest depth error")    \
    X(kDepthUlp, "depth ulp", "mode=fixed: device z of one depth unit")

enum PatchCounter : std::size_t { QUADRIX_PATCH_COUNTERS(QUADRIX_COUNTER_ID) };
inline constexpr CounterDecl kPatchCounters[] = {QUADRIX_PATCH_COUNTERS(QUADRIX_COUNTER_DECL)};

}  // namespace quadrix::patch
