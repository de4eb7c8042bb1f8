// The counters of engine `scanline`, declared once (engines/counters.h): its enum of ids and the
// table the registry row lists (docs/engines.md). The names follow the report of seed 001 §6-7:
// the Resolver's intersection lines (ilines) and vertices (ivertices) by type, the Renderer's
// edges, spans and face stacks (§5.3-5.4), the CSG span templates and the verifier.
#pragma once

#include "quadrix/engines/counters.h"

namespace quadrix::scanline {

// X(id, name, meaning). The ilines_ and ivertices_ rows are in the order of ILineType and
// IVertexType (resolver.h): the engine indexes them by type.
#define QUADRIX_SCANLINE_COUNTERS(X)                                                               \
    X(kBodies, "bodies", "bodies given to the Resolver")                                           \
    X(kHsbsPlanar, "hsbs_planar", "plane half-space boundaries resolved")                          \
    X(kHsbsQuadric, "hsbs_quadric", "quadric half-space boundaries resolved")                      \
    X(kShowFaces, "show_faces", "show-faces (visible pieces of surfaces) made")                    \
    X(kIlinesNoexist, "ilines_NOEXIST", "intersection lines found not to exist")                   \
    X(kIlinesPoint, "ilines_POINT", "intersection lines that are a point")                         \
    X(kIlinesLinear, "ilines_LINEAR", "straight intersection lines")                               \
    X(kIlinesConic, "ilines_CONIC", "conic intersection lines (plane-quadric)")                    \
    X(kIlinesEdge, "ilines_EDGE", "i-lines on an edge-on plane (image lines)")                     \
    X(kIlinesQuartic, "ilines_QUARTIC", "quadric-quadric (quartic) intersection lines")            \
    X(kIverticesCalculated, "ivertices_calculated", "intersection vertices computed")              \
    X(kIverticesKept, "ivertices_kept", "intersection vertices on the body's boundary")            \
    X(kIverticesHextrm, "ivertices_HEXTRM", "vertices at horizontal extrema of a curve")           \
    X(kIverticesVextrm, "ivertices_VEXTRM", "vertices at vertical extrema of a curve")             \
    X(kIverticesLimb, "ivertices_LIMB", "vertices on a limb (plane and limb plane)")               \
    X(kIverticesIsect, "ivertices_ISECT", "vertices of three planes or plane-plane-quadric")       \
    X(kShowEdgesLinear, "show_edges_linear", "straight show-edges")                                \
    X(kShowEdgesHorizontal, "show_edges_horizontal", "horizontal show-edges")                      \
    X(kShowEdgesConic, "show_edges_conic", "conic show-edges")                                     \
    X(kPerPixelBodies, "per_pixel_bodies", "bodies evaluated exactly per pixel")                   \
    X(kCsgSolids, "csg_solids", "CSG solids drawn by span templates")                              \
    X(kCsgPixels, "csg_pixels", "pixels of CSG spans")                                             \
    X(kCsgTemplateBodies, "csg_template_bodies", "bodies entered into CSG span templates")         \
    X(kCsgTemplateReuses, "csg_template_reuses", "templates kept from an earlier span of the row") \
    X(kCsgExactFallbackPixels, "csg_exact_fallback_pixels", "CSG pixels settled by exact rays")    \
    X(kEdgesStarted, "edges_started", "edges entered into the active edge list")                   \
    X(kEdgeSwaps, "edge_swaps", "neighbouring active edges swapped (crossings)")                   \
    X(kSpans, "spans", "spans between consecutive active edges")                                   \
    X(kEmptySpans, "empty_spans", "spans with no face")                                            \
    X(kFaceInserts, "face_inserts", "faces inserted into span face lists")                         \
    X(kDepthCalculations, "depth_calculations", "depth evaluations of a face")                     \
    X(kTieBreaks, "tie_breaks", "equal-depth faces ordered by a second test")                      \
    X(kSpanSampleEvaluations, "span_sample_evaluations", "sample points evaluated in spans")       \
    X(kRowSideEvaluations, "row_side_evaluations", "row-side tests of faces")                      \
    X(kExactPixels, "exact_pixels", "pixels whose depth was computed exactly")                     \
    X(kRootFallbackPixels, "root_fallback_pixels",                                                 \
      "pixels of a rootless stack face, evaluated exactly")                                        \
    X(kPerPixelUnitEvaluations, "per_pixel_unit_evaluations", "pixels of per-pixel bodies")        \
    X(kIntensityCalculations, "intensity_calculations", "normals computed for shading")            \
    X(kPixels, "pixels", "pixels of the image")                                                    \
    X(kCoveredPixels, "covered_pixels", "pixels where a surface was drawn")                        \
    X(kFaceStackBodies, "face_stack_bodies", "bodies drawn through carried face stacks")           \
    X(kFaceStackInserts, "face_stack_inserts", "faces inserted into carried stacks")               \
    X(kFaceStackDeletes, "face_stack_deletes", "faces deleted from carried stacks")                \
    X(kFaceStackMaxDepth, "face_stack_max_depth", "deepest carried face stack")                    \
    X(kFaceStackMeanDepth, "face_stack_mean_depth", "mean carried stack depth per span")           \
    X(kFaceStackSpans, "face_stack_spans", "spans drawn from carried stacks")                      \
    X(kFaceStackSeedEvaluations, "face_stack_seed_evaluations",                                    \
      "exact evaluations seeding a row's stack")                                                   \
    X(kFaceStackTieBreaks, "face_stack_tie_breaks", "ties broken in carried stacks")               \
    X(kFaceStackCorrections, "face_stack_corrections",                                             \
      "toggled faces whose face test overruled the stack")                                         \
    X(kFaceStackRepairs, "face_stack_repairs", "events whose stack was not carried on (repaired)") \
    X(kFaceStackClosedRowFaces, "face_stack_closed_row_faces",                                     \
      "faces of edges ending on a row centre, that row only")                                      \
    X(kFaceStackOrderCorrections, "face_stack_order_corrections",                                  \
      "entering faces out of depth order (corrected)")                                             \
    X(kFaceStackSwapUpdates, "face_stack_swap_updates", "pass-two swaps that updated a stack")     \
    X(kFaceStackDerivations, "face_stack_derivations", "stacks made from the left neighbour's")    \
    X(kFaceStackDerivationsChanged, "face_stack_derivations_changed",                              \
      "rebuilds whose set of faces changed")                                                       \
    X(kFaceStackDeriveInserts, "face_stack_derive_inserts", "inserts while deriving stacks")       \
    X(kFaceStackDeriveDeletes, "face_stack_derive_deletes", "deletes while deriving stacks")       \
    X(kFaceStackVertices, "face_stack_vertices", "vertices processed on carried stacks")           \
    X(kFaceStackVertexRecursions, "face_stack_vertex_recursions",                                  \
      "vertices reached through an edge within the row")                                           \
    X(kFaceStackDeletionSwaps, "face_stack_deletion_swaps",                                        \
      "swaps moving a finishing edge next to CE")                                                  \
    X(kFaceStackVertexFallbacks, "face_stack_vertex_fallbacks",                                    \
      "vertex components derived again in pass three")                                             \
    X(kFaceStackRebuilds, "face_stack_rebuilds",                                                   \
      "pass-three derivations after a band's first row")                                           \
    X(kInterpenetrationPixels, "interpenetration_pixels",                                          \
      "pixels where another body's face was nearer")                                               \
    X(kOverlapMaxDepth, "overlap_max_depth", "most surfaces overlapping at one place (guard)")     \
    X(kOverlapSolidsToRaycast, "overlap_solids_to_raycast", "solids left to raycast by the guard") \
    X(kSolidsToRaycast, "solids_to_raycast", "solids left to raycast in all")                      \
    X(kVerifySpans, "verify_spans", "spans checked by the verifier (verify=on)")                   \
    X(kVerifyMismatchSpans, "verify_mismatch_spans", "verified spans that differed")               \
    X(kVerifyBodyFaces, "verify_body_faces", "span and body pairs checked against exact faces")    \
    X(kVerifyBodyFaceMismatches, "verify_body_face_mismatches", "verified body faces differing")   \
    X(kResolverSeconds, "resolver_seconds", "time in the Resolver")                                \
    X(kRendererShaderSeconds, "renderer_shader_seconds", "time in the Renderer and Shader")

enum ScanlineCounter : std::size_t { QUADRIX_SCANLINE_COUNTERS(QUADRIX_COUNTER_ID) };
inline constexpr CounterDecl kScanlineCounters[] = {
    QUADRIX_SCANLINE_COUNTERS(QUADRIX_COUNTER_DECL)};

}  // namespace quadrix::scanline
