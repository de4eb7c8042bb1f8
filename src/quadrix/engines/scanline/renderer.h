// The Renderer and Shader of engine `scanline` (seed 001 chapters 5 and 6).
//
// Renderer (chapter 5):
//  - Edge Start List (ESL): one bucket per scan line; a show-edge goes to the bucket of the first
//    row whose centre y = j + ½ lies in [yBottom, yTop] (closed, see renderer.cpp BuildEsl).
//  - Active Edge List (AEL): edges crossing the current scan line (CSL), kept in ascending x by
//    pass two's bubble (insertion) sort; swaps are counted as in Table 7.2. Pass one removes
//    finishing edges and inserts starting ones (§5.4, below). Horizontal show-edges and edges
//    whose [yBottom, yTop] holds no row centre never enter the AEL: they lie within one scan
//    line, and pass one recurses through them from vertex to vertex.
//  - Conic edges are traced with first and second differences (§5.5.2): the quadratic (5.3) of
//    the CSL, B_r += C_c, C_r += ΔC, ΔC += 2 B_c per row, then the root on the edge's leg.
//  - FACE STACKS (default for bodies drawn on their own; §5.2–5.4). Every active edge of such a
//    body carries its face stack from row to row: the show-faces immediately to its right on
//    the CSL, nearest first. Each show-edge bounds two faces that change sides at it, so an
//    edge's stack is its left neighbour's with the edge's faces toggled (a face on it leaves,
//    one off it is inserted in depth order by the §5.5.1 comparisons: depth at the crossing P;
//    equal: depth at Q, half-way into the edge's region; equal: slope dz/dx; equal: rate
//    d²z/dx²). Passes one and two keep "stack = left neighbour's ⊕ own faces" for every stack
//    edge, so the stacks change only where the AEL changes:
//      pass one  — §5.4 literally: a walk over the AEL with the current-edge pointer CE that
//                  processes the vertices of the CSL (edge ends with y in (j − ½, j + ½], from
//                  a vertex table built once per frame): (1) each incident finishing edge is
//                  moved next to CE by successive swaps (the swap rule below, applied to every
//                  edge passed) and deleted; (2) the opposite vertex of each incident edge
//                  lying within the scan line (horizontal, or holding no row centre) is
//                  processed recursively; (3) the starting edges are inserted at CE with their
//                  stacks from the left neighbour's ⊕ their faces. The toggles of a vertex
//                  group's finishing and starting edges cancel, so nothing right of it changes;
//                  where they do not (an end missing from the table), the next stack edge is
//                  rebuilt in pass three (vertex fallback);
//      pass two  — the swap rule: when edge E moves left past edge X in the insertion sort, X
//                  takes E's stack as it is (the region right of X is the one that was right of
//                  E); if E moves on past X', X' takes E's new stack, its own ⊕ E's faces; when
//                  E's move ends, its stack is its new left neighbour's ⊕ its faces;
//      pass three walks the AEL left to right and puts the faces that passes one and two
//                  toggled into depth order at each crossing (they keep the stacks as sets).
//                  It derives a stack from its left neighbour's only at a band's first row and
//                  where the above cannot carry it (REBUILD: after a vertex fallback, a change
//                  of S0, a conic leg lost to rounding and found again); a rebuilt set that
//                  differs from the carried one rebuilds the next stack edge too. Rebuilds and
//                  fallbacks are 0 on every example and gallery scene.
//    An edge toggles on the rows whose centre lies in the HALF-OPEN [yBottom, yTop) (ends
//    snapped to a row centre within 1e-9): on its last row, when that row's centre is its top,
//    it is a breakpoint only ("ending"). Raycast's closed half-spaces may still draw such a
//    face on that row (a box whose side y = j + ½ is an edge-on plane): the face test at Q
//    decides it for that row only, outside the carried stacks (closedRowFaces).
//    Crossings closer than 1e-4 px form one event. The VERIFIER checks every event: the stack
//    after it must be the stack before it ⊕ the event's faces (else stackRepairs), and every
//    toggled face must be on it exactly when the face test at Q finds the face's point inside
//    its body's other HSIs (else stackCorrections); both are corrected, so the frame stays
//    exact. Faces entering at the event are checked against the nearest faces of their own
//    body above and below (stackOrderCorrections). All three are 0 on every example and
//    gallery scene since the Resolver's wedge test removed the spurious show-edges at mitred
//    joints (resolver.h). The span's faces are each body's first face on the stack; when
//    several bodies share a span the nearest of them is taken per pixel, since bodies of
//    different solids may interpenetrate without a show-edge (the paper's scenes had none;
//    interpenetrationPixels counts where the head was not the nearest). The left of every
//    crossing (S0) holds faces of bodies reaching the image's left side, found per row by one
//    exact evaluation (stackSeedEvaluations). Bands of 32 rows run in parallel; each band
//    derives every stack at its first row.
//    EXACT path (render=exact; always for CSG operands and refused bodies): between two
//    crossings the set of faces of every body is constant (the crossings of a body's show-edges
//    are a superset of its face boundaries), so each span's stack is built once: every body
//    whose x range on this row meets the span is evaluated exactly at ONE pixel of the span (the
//    ray/half-space intervals of the body), which names its visible show-face (surface and
//    sheet); faces are inserted in depth order with the same tie-breaks.
//  - Per-row and per-span work follows the AEL: each row's bodies (rowBodies_) are those with a
//    crossing on it (plus the few whose bounds reach an image side, tested there, and refused
//    bodies), sorted on their x range; spans take the bodies whose range meets them from a
//    sweep over that list. Nothing per row or span loops over all bodies or all operands.
//  - A pixel whose centre lies within kOnEdge of a crossing is evaluated exactly on its own.
//  - Bodies the Resolver refused (QUARTIC i-lines) are evaluated exactly at every pixel of their
//    unit's screen bounds (documented refusal).
//  - CSG solids (anything but a union of bodies) by per-span BODY TEMPLATES: in a span, each
//    operand body's interval list along the ray has a constant structure (which show-faces bound
//    which intervals, in which order), because all of its own face boundaries are breakpoints. The
//    structure is read once per span at the sample pixel; at every pixel the endpoints' depths come
//    from the span shader's incremental conics, and the lists are combined by the interval CSG of
//    the tree (union/intersection/difference of sorted lists, as raycast). Operand surfaces of
//    DIFFERENT bodies may cross inside a span (their intersection curves are quartic in general and
//    are not show-edges), which is exactly why the CSG combination is redone per pixel. A template
//    endpoint without a root at some pixel falls back to exact evaluation of the tree there.
//    The tree is PRUNED per span to the operands whose x range meets the span (an absent operand
//    is ∅: dropped from unions and subtrahends, emptying intersections and differences whose
//    minuend it is), so a union of 10,000 spheres costs per span the few spheres there. An
//    operand's template holds between two of its own crossings, so it is read once there and
//    reused (re-seeked) by the spans in between, which other bodies' crossings cut.
//    CSG bodies get i-lines and limbs for transparent HSBs too (their endpoints matter for CSG).
//
// Shader (chapter 6), writing the Frame (depth, normal, surface, body, solid):
//  - quadric depth along a span from the span's conic in (x, z): h(x) and k(x) of
//    c z² + 2 h z + k = 0 updated by differences (h += F, k += Δk, Δk += 2A), root by sheet;
//  - normals (the Frame's "intensity" input) exactly per pixel when Δmax = 1, else at the span
//    ends and every Δ = min((x_r − x_l)/16 + 1, Δmax) pixels (6.9) with linear interpolation of the
//    unit normal between; "fast" shading uses one normal per face and span.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "quadrix/engines/raycast/ray_literal.h"
#include "quadrix/engines/scanline/resolver.h"
#include "quadrix/frame/frame.h"
#include "quadrix/math/interval_list.h"

namespace quadrix::scanline {

// Something the renderer draws: a body on its own (a solid of one body, or one operand of a
// union of bodies), or a CSG solid whose tree is combined per pixel.
// Units are numbered by solid and, within a union of bodies, in operand order
// (scanline_engine.cpp), so raycast's rule for exact depth ties (UnitWinsTie in renderer.cpp) is:
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
    int threads = 0;  // 0 = all hardware threads; rows are cut in bands of 32 run in parallel
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
    // row only, as raycast's closed half-spaces do (ApplyEvent in renderer.cpp).
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

// Exact per-ray evaluation of bodies and CSG trees (the same interval semantics as `raycast`).
class RayEvaluator {
  public:
    explicit RayEvaluator(const FlatScene& scene);
    struct Hit {
        double t = HUGE_VAL;
        int halfSpace = -1, body = -1;
    };
    // The first opaque finite endpoint of the body's / tree's set on the ray through (x, y).
    bool Body(int body, double x, double y, Hit& hit);
    bool Node(int node, double x, double y, Hit& hit);
    // The set of a body on the ray (ids are tags: see TagHalfSpace).
    void BodySet(int body, double x, double y, IntervalList& out);
    // The set of a tree whose leaves' sets are given by `leaf(body, out)`.
    template <class LeafFn>
    void TreeSet(int node, LeafFn&& leaf, IntervalList& out);
    // The first opaque finite endpoint of a list built from tags.
    bool First(const IntervalList& l, Hit& hit) const;
    int TagHalfSpace(int tag) const { return tags_[static_cast<std::size_t>(tag)].halfSpace; }
    const raycast::RayHalfSpace& Ray(int halfSpace) const {
        return halfSpaces_[static_cast<std::size_t>(halfSpace)];
    }

  private:
    struct Tag {
        int halfSpace, body;
        bool complemented, opaque;
    };

    const FlatScene& scene_;
    std::vector<raycast::RayHalfSpace> halfSpaces_;
    std::vector<Tag> tags_;
    std::vector<int> bodyFirstTag_;
    raycast::LiteralCounters literalCounters_;
};

// Depth ordering of two show-faces at (x, y) with the tie-breaks of §5.5.1: depth at (x, y);
// equal within `tolerance` → depth at (x + 1, y) ("Q on the next scan line" turned to the span
// direction); equal again → slope dz/dx; equal → rate d²z/dx² (smaller is in front). Faces are
// (half-space, sheet) with sheet 0 = front root, 1 = back root (planes: 0). Returns −1 when F is
// in front, +1 when G is, 0 when they are indistinguishable (coincident).
struct FaceRef {
    int halfSpace = -1;
    int sheet = 0;
};
int CompareFaces(const FlatScene& scene, const FaceRef& f, const FaceRef& g, double x, double y,
                 double tolerance);
// z, dz/dx and d²z/dx² of a face at (x, y) by implicit differentiation of F(x, y, z) = 0:
//   z' = −F_x/F_z,  z'' = −(F_xx + 2 F_xz z' + F_zz z'²)/F_z
// (the seed's (5.2) lost the last two terms to the OCR; this is the full chain rule).
// False when the face has no point there.
bool FaceDerivatives(const FlatScene& scene, const FaceRef& f, double x, double y, double& z,
                     double& dz, double& d2z);

// One step of a left-to-right CSG fold: out = out op operand (tmp is scratch), with the empty
// operand identities (A ∪ ∅ = A − ∅ = A, A ∩ ∅ = ∅, ∅ ∪ B = B) taken without a sweep.
inline void CombineOperand(scene::CsgOp op, IntervalList& out, IntervalList& operand,
                           IntervalList& tmp) {
    if (operand.empty()) {
        if (op == scene::CsgOp::kIntersection) out.clear();
        return;
    }
    if (out.empty()) {  // (the caller stops an intersection or difference at an empty out)
        std::swap(out, operand);
        return;
    }
    switch (op) {
        case scene::CsgOp::kUnion:
            Union(out, operand, tmp);
            break;
        case scene::CsgOp::kIntersection:
            Intersection(out, operand, tmp);
            break;
        default:
            Difference(out, operand, tmp);
            break;
    }
    std::swap(out, tmp);
}

template <class LeafFn>
void RayEvaluator::TreeSet(int node, LeafFn&& leaf, IntervalList& out) {
    const FlatCsgNode& n = scene_.nodes[static_cast<std::size_t>(node)];
    if (n.isLeaf) {
        out.clear();
        if (n.body >= 0 && static_cast<std::size_t>(n.body) < scene_.bodies.size())
            leaf(n.body, out);
        return;
    }
    out.clear();
    IntervalList operand, tmp;
    for (std::size_t i = 0; i < n.children.size(); ++i) {
        if (i > 0 && out.empty() && n.op != scene::CsgOp::kUnion) return;  // ∅ ∩ B = ∅ − B = ∅
        TreeSet(n.children[i], leaf, i == 0 ? out : operand);
        if (i == 0) continue;
        CombineOperand(n.op, out, operand, tmp);
    }
}

// Draws everything: ESL/AEL over the rows, spans, face stacks and the span shader. The rows are
// cut into fixed bands of 32 run in parallel (oneTBB); each band starts its AEL from the ESL at
// its first row, so the image does not depend on the number of threads.
// `pixelBody[b]` marks bodies the Resolver refused (no show-edges): evaluated exactly per pixel
// over their unit's bounds. `stackBody[b]` marks bodies drawn from face stacks (bodies of kBody
// units that were not refused); the others (CSG operands, refused bodies) use the exact
// per-span evaluation. `faces` are the Resolver's show-faces the edges point at.
//
// Face stacks (settings.faceStacks): each active edge of a stack body carries its face stack
// (the faces right of it, nearest first) from row to row through pass one (§5.4's vertex
// processing: deletion after swaps next to CE, recursion through edges within the scan line,
// insertion with stacks from the neighbour) and pass two (the swap rule); pass three orders the
// toggled faces, rebuilds only where those cannot carry a stack, and verifies every crossing
// with the face test at Q (see the header comment and renderer.cpp).
void RenderScanlines(const FlatScene& scene, std::vector<ShowEdge>& edges,
                     const std::vector<ShowFace>& faces, const std::vector<Unit>& units,
                     const std::vector<bool>& pixelBody, const std::vector<bool>& stackBody,
                     const RenderSettings& settings, Frame& frame, RendererCounters& counters);

}  // namespace quadrix::scanline
