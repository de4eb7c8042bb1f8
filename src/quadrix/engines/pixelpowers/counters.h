// The counters of engine `pixelpowers`, declared once (engines/counters.h): the Goldfeather
// normal form and the compiled program (seed 004, Table 1), the simulated machine's work, and,
// with compare=on, the comparison with raycast. Some are reported only in some modes (strips in
// depth=approx, shading in shading=paper, depth words in fixed point, cmp_ with compare=on).
#pragma once

#include "quadrix/engines/counters.h"

namespace quadrix::pixelpowers {

#define QUADRIX_PIXELPOWERS_COUNTERS(X)                                                          \
    X(kExactMode, "exact_mode", "1 when depths are exact (depth=exact)")                         \
    X(kPaperShading, "paper_shading", "1 when the paper's approximate normals shade")            \
    X(kPrimitives, "primitives", "distinct bodies used by the drawn solids")                     \
    X(kHalfSpaces, "half_spaces", "distinct half-spaces used by them")                           \
    X(kTreePrimitives, "tree_primitives", "primitives of the CSG trees")                         \
    X(kTreeOperators, "tree_operators", "operators of the CSG trees")                            \
    X(kProducts, "products", "products of the normal form")                                      \
    X(kProductFactors, "product_factors", "factors of those products")                           \
    X(kPrunedProducts, "pruned_products", "products dropped (disjoint boxes)")                   \
    X(kPrunedFactors, "pruned_factors", "factors and subtrahends dropped")                       \
    X(kTerms, "terms", "display-theorem terms compiled")                                         \
    X(kPrunedTerms, "pruned_terms", "terms whose boxes miss each other or the screen")           \
    X(kPrunedParings, "pruned_parings", "subtracted factors not sent for a term")                \
    X(kPatches, "patches", "patches (blocks) broadcast")                                         \
    X(kPrunedPatches, "pruned_patches", "plane patches whose face polygon is empty")             \
    X(kOpcodes, "opcodes", "instructions of the program")                                        \
    X(kEquations, "equations", "quadratic expressions broadcast")                                \
    X(kEstimatedMs10mhz, "estimated_ms_10mhz", "the program's time on the paper's 10 MHz")       \
    X(kStrips, "strips", "depth=approx: parabolic strips broadcast")                             \
    X(kStripSheetsCapped, "strip_sheets_capped", "depth=approx: sheets that hit max_strips")     \
    X(kExtendedFallbacks, "extended_fallbacks", "depth=approx: C = 0 sheets done by roots")      \
    X(kShadedPatches, "shaded_patches", "shading=paper: patches broadcasting normals")           \
    X(kShadingFallbacks, "shading_fallbacks", "shading=paper: C = 0 patches, exact normal")      \
    X(kShadingSqrtBound, "shading_sqrt_bound", "shading=paper: n.l error bound of the sqrt")     \
    X(kShadingDenominatorSpread, "shading_denominator_spread",                                   \
      "shading=paper: relative error of the constant denominator")                               \
    X(kDepthBits, "depth_bits", "bits of the fixed-point depth words")                           \
    X(kDepthStep, "depth_step", "device z of one depth step")                                    \
    X(kDepthOrigin, "depth_origin", "device z of depth word 0")                                  \
    X(kTiles, "tiles", "tiles of the frame buffer run")                                          \
    X(kBlockRuns, "block_runs", "blocks run on a tile")                                          \
    X(kBlocksAbandoned, "blocks_abandoned", "blocks stopped early (no pixel enabled)")           \
    X(kInstructionsExecuted, "instructions_executed", "instructions executed")                   \
    X(kPixelOperations, "pixel_operations", "pixel-processor operations")                        \
    X(kRootSolves, "root_solves", "square roots taken by the root unit")                         \
    X(kZWrites, "z_writes", "depth-buffer writes")                                               \
    X(kCoveredPixels, "covered_pixels", "pixels where a surface was drawn")                      \
    X(kBitsPerPixelPaper, "bits_per_pixel_paper", "per-pixel memory of the paper's machine")     \
    X(kBitsPerPixelSimulated, "bits_per_pixel_simulated", "per-pixel memory simulated")          \
    X(kCompileSeconds, "compile_seconds", "time compiling the program")                          \
    X(kMachineSeconds, "machine_seconds", "time running the simulated machine")                  \
    X(kSolidsNotDrawn, "solids_not_drawn", "solids left to raycast (normal form too large)")     \
    X(kCmpCoveredBoth, "cmp_covered_both", "compare=on: pixels covered by both engines")         \
    X(kCmpCoveredOnlyHere, "cmp_covered_only_here", "compare=on: covered here only")             \
    X(kCmpCoveredOnlyRaycast, "cmp_covered_only_raycast", "compare=on: covered by raycast only") \
    X(kCmpSameSolidShare, "cmp_same_solid_share", "compare=on: share with the same solid")       \
    X(kCmpDepthErrorMax, "cmp_depth_error_max", "compare=on: largest depth error")               \
    X(kCmpDepthErrorMean, "cmp_depth_error_mean", "compare=on: mean depth error")                \
    X(kCmpDepthErrorP999, "cmp_depth_error_p999", "compare=on: 99.9th percentile depth error")   \
    X(kCmpDepthErrorOverTolerance, "cmp_depth_error_over_tolerance",                             \
      "compare=on: pixels whose depth error exceeds the tolerance")                              \
    X(kCmpIntensityErrorMax, "cmp_intensity_error_max", "compare=on: largest Lambert error")     \
    X(kCmpIntensityErrorMean, "cmp_intensity_error_mean", "compare=on: mean Lambert error")      \
    X(kCmpIntensityErrorP99, "cmp_intensity_error_p99", "compare=on: 99th percentile error")

enum PixelPowersCounter : std::size_t { QUADRIX_PIXELPOWERS_COUNTERS(QUADRIX_COUNTER_ID) };
inline constexpr CounterDecl kPixelPowersCounters[] = {
    QUADRIX_PIXELPOWERS_COUNTERS(QUADRIX_COUNTER_DECL)};

}  // namespace quadrix::pixelpowers
