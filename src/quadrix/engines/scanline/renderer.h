// The Renderer and Shader of engine `scanline` (seed 001 chapters 5 and 6): RenderScanlines draws
// the units of a scene from the Resolver's show-edges and show-faces (resolver.h) into the Frame.
// The phases, one file each:
//   edge_list.h          ESL and AEL (§5.1, §5.3), pass two's sort, conic edges by differences
//                        (§5.5.2);
//   vertex_table.h       §5.4's vertices of the stack bodies' show-edges, built once per frame;
//   vertex_processing.h  pass one (§5.4): deletion after swaps next to CE, recursion through
//                        edges within the scan line, insertion with stacks from the neighbour;
//   face_stack.h         the FACE STACKS (§5.2–5.4) carried by the active edges from row to row
//                        (the swap rule, derivations) and pass three's walk over the crossings,
//                        with the §5.5.1 depth order at a crossing (FaceOrder, depth_order.h);
//   stack_verifier.h     the verifier of every crossing (structure, the face test at Q, order);
//   row_bodies.h         the bodies of each row and span, following the AEL (nothing per row or
//                        span loops over all bodies or all operands);
//   csg_spans.h          CSG solids by per-span body templates and trees pruned per span;
//   span_shader.h        the Shader (chapter 6): depth along a span by differences, normals at
//                        the shading interval (6.9), the span's faces;
//   ray_evaluator.h      exact per-ray evaluation (as raycast) where no incremental answer is
//                        at hand: sample pixels of bodies drawn exactly (render=exact, CSG
//                        operands), pixels within kOnEdge of a crossing, refused bodies, S0;
//   scan_context.h       what the phases share; renderer.cpp composes them per band of rows.
// The face stacks are the default for bodies drawn on their own; the EXACT path (render=exact;
// always for CSG operands and refused bodies): between two crossings the set of faces of every
// body is constant (the crossings of a body's show-edges are a superset of its face boundaries),
// so each span's stack is built once: every body whose x range on this row meets the span is
// evaluated exactly at ONE pixel of the span (the ray/half-space intervals of the body), which
// names its visible show-face (surface and sheet); faces are inserted in depth order with the
// same tie-breaks. When several bodies share a span the nearest of them is taken per pixel, since
// bodies of different solids may interpenetrate without a show-edge (the paper's scenes had
// none; interpenetrationPixels counts where the stack head was not the nearest). Bodies the
// Resolver refused (QUARTIC i-lines) are evaluated exactly at every pixel of their unit's screen
// bounds (documented refusal). Bands of 32 rows run in parallel; each band starts its AEL from the
// ESL at its first row and derives every stack there, so the image does not depend on the number
// of threads.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "quadrix/engines/scanline/depth_order.h"
#include "quadrix/engines/scanline/resolver.h"
#include "quadrix/eval/ray_evaluator.h"
#include "quadrix/frame/frame.h"
#include "quadrix/math/interval_list.h"

namespace quadrix::scanline {

// Something the renderer draws: a body on its own (a solid of one body, or one operand of a
// union of bodies), or a CSG solid whose tree is combined per pixel.
// Units are numbered by solid and, within a union of bodies, in operand order
// (scanline_engine.cpp), so raycast's rule for exact depth ties (ScanContext::UnitWinsTie) is:
// the lower solid; within a union, the lower unit where the tied points are entries and the
// higher one where both are exits (a union of interval lists is opened by the first start, the
// left operand's on a tie, and closed by the last end, the right operand's on a tie:
// math/interval_list.h). Coplanar faces of a union's bodies then name raycast's surface.
struct Unit {
    enum class Kind : std::uint8_t { kBody, kCsg } kind = Kind::kBody;
    int solid = -1;
    int body = -1;                         // kBody
    int node = -1;                         // kCsg: the root of the solid's tree
    std::vector<int> bodies;               // kCsg: every body (leaf) of the tree
    int x0 = 0, x1 = -1, y0 = 0, y1 = -1;  // inclusive pixel ranges from the Flattener's bounds
};

struct RenderSettings {
    int shadeInterval = 1;  // Δmax of (6.9); 1 = exact normals
    bool fastShading = false;
    // CSG solids: true = per-span body templates combined by interval CSG per pixel; false =
    // exact evaluation of the whole tree at every pixel (for comparison).
    bool csgTemplates = true;
    // Bodies marked in `stackBody` (RenderScanlines) get their visible face from the FACE STACK
    // of §5.2–5.4 (default); false = every body evaluated exactly once per span (render=exact).
    bool faceStacks = true;
    // Also evaluate the stack bodies exactly at every span's sample pixel and count the spans
    // whose stack head differs (verifyMismatchSpans). Costs one exact evaluation per body/span.
    bool verify = false;
    // The carried stacks' verifier (pass three, every crossing: structure, the face test at Q,
    // order of entering faces; corrections keep the frame exact). false = trust the carried
    // stacks as they are (check=off: to measure them alone; degenerate rows may then differ).
    bool checkStacks = true;
};

struct RendererCounters {
    std::uint64_t edgesStarted = 0, edgeSwaps = 0, spans = 0, emptySpans = 0, faceInserts = 0;
    std::uint64_t depthCalcs = 0, sampleEvaluations = 0, sideEvaluations = 0;
    std::uint64_t exactPixels = 0, perPixelUnitPixels = 0, normals = 0, covered = 0;
    std::uint64_t tieBreaks = 0;
    std::uint64_t csgPixels = 0, csgTemplateBodies = 0, csgFallbackPixels = 0;
    std::uint64_t csgTemplateReuses = 0;   // templates kept from an earlier span of the row
    std::uint64_t rootFallbackPixels = 0;  // a stack face had no root: pixel evaluated exactly
    // Face stacks (§5.2–5.4): faces inserted into / deleted from the stack at edge crossings,
    // the deepest stack, the sum of stack depths over stack spans (mean = sum / stackSpans),
    // exact evaluations that seed a row's stack left of every crossing, the pixels where a face
    // of another body below the head was nearer (interpenetrating bodies have no show-edge),
    // and the verification (verify=on): spans checked, spans whose stack head differs.
    std::uint64_t stackInserts = 0, stackDeletes = 0, stackMaxDepth = 0, stackDepthSum = 0;
    std::uint64_t stackSpans = 0, stackSeedEvaluations = 0, stackTieBreaks = 0;
    std::uint64_t interpenetrationPixels = 0, verifySpans = 0, verifyMismatchSpans = 0;
    // The verifier (pass three, every event): toggled faces whose face test at Q overruled the
    // carried stack (spurious or degenerate show-edges), events whose carried stack was not its
    // left neighbour's ⊕ the event's faces (a change at a vertex not carried on), and entering
    // faces found out of depth order with their own body's faces. All are corrected.
    std::uint64_t stackCorrections = 0, stackRepairs = 0, stackOrderCorrections = 0;
    // Faces of edges ending exactly on a row centre that the face test keeps (or drops) on that
    // row only, as raycast's closed half-spaces do (FaceStacks::UpdateClosedRowFaces).
    std::uint64_t closedRowFaces = 0;
    // Carrying the stacks (§5.3, §5.4): pass-two swaps that updated a stack (the swap rule),
    // stacks made from the left neighbour's (starting edges, ends of moves, rebuilds), rebuilds
    // whose set changed, and the faces inserted into / deleted from stacks while carrying.
    std::uint64_t stackSwapUpdates = 0, stackDerivations = 0, stackDerivationsChanged = 0;
    std::uint64_t stackDeriveInserts = 0, stackDeriveDeletes = 0;
    // Pass one's vertex processing (§5.4): vertices processed, those reached recursively through
    // an edge lying within the scan line, swaps that moved a finishing edge next to CE (each
    // updates the intervening edge's stack), and vertex components whose finishing and starting
    // edges did not toggle the same faces (an end not in the vertex table, a lost conic leg):
    // there the next stack edge is derived again in pass three (the fallback).
    std::uint64_t stackVertices = 0, stackVertexRecursions = 0, stackDeletionSwaps = 0;
    std::uint64_t stackVertexFallbacks = 0;
    // Pass three's derivations from the left neighbour on rows other than a band's first (the
    // rebuild: after vertex fallbacks, S0 changes and lost conic legs; 0 when every change was
    // carried by pass one and pass two).
    std::uint64_t stackRebuilds = 0;
    // verify=on, per span and stack body present there: the body's first face on the stack
    // against its exact visible face (the stack machinery proper, free of interpenetration).
    std::uint64_t verifyBodies = 0, verifyBodyMismatches = 0;
    void Add(const RendererCounters& o);
};

// Draws everything: ESL/AEL over the rows, spans, face stacks and the span shader. The rows are
// cut into fixed bands of 32 run in parallel (oneTBB); each band starts its AEL from the ESL at
// its first row, so the image does not depend on the number of threads.
// `pixelBody[b]` marks bodies the Resolver refused (no show-edges): evaluated exactly per pixel
// over their unit's bounds. `stackBody[b]` marks bodies drawn from face stacks (bodies of kBody
// units that were not refused); the others (CSG operands, refused bodies) use the exact
// per-span evaluation. `faces` are the Resolver's show-faces the edges point at.
//
// Face stacks (settings.faceStacks): each active edge of a stack body carries its face stack
// (the faces right of it, nearest first) from row to row through pass one (vertex_processing.h)
// and pass two (the swap rule, edge_list.h); pass three orders the toggled faces, rebuilds only
// where those cannot carry a stack, and verifies every crossing with the face test at Q
// (face_stack.h, stack_verifier.h).
void RenderScanlines(const FlatScene& scene, std::vector<ShowEdge>& edges,
                     const std::vector<ShowFace>& faces, const std::vector<Unit>& units,
                     const std::vector<bool>& pixelBody, const std::vector<bool>& stackBody,
                     const RenderSettings& settings, Frame& frame, RendererCounters& counters);

}  // namespace quadrix::scanline
