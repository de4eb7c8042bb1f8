// The Renderer and Shader of engine `scanline` (seed 001 chapters 5 and 6).
//
// Renderer (chapter 5):
//  - Edge Start List (ESL): one bucket per scan line; a show-edge goes to the bucket of the first
//    row whose centre y = j + ½ lies in [yBottom, yTop] (closed, see renderer.cpp BuildEsl).
//  - Active Edge List (AEL): edges crossing the current scan line (CSL), kept in ascending x by
//    pass two's bubble (insertion) sort; swaps are counted as in Table 7.2. Pass one removes
//    finishing edges and inserts starting ones (horizontal show-edges never start: the Resolver
//    does not make them, and an edge whose [yBottom, yTop] holds no row centre is dropped, which
//    is what the recursive vertex processing of §5.4 achieves for edges within one scan line).
//  - Conic edges are traced with first and second differences (§5.5.2): the quadratic (5.3) of
//    the CSL, B_r += C_c, C_r += ΔC, ΔC += 2 B_c per row, then the root on the edge's leg.
//  - Pass three cuts the CSL at the x of every active edge. FACE STACKS (default, bodies drawn on
//    their own): the stack is swept along the CSL from the left (seeded, for bodies reaching the
//    image's left side, by one exact evaluation left of every crossing); at each crossing of a
//    show-edge its two show-faces change sides — a face on the stack is deleted, a face off it is
//    inserted in depth order by the §5.5.1 comparisons (depth at the crossing P; equal: depth at
//    Q half-way into the next span; equal: slope dz/dx; equal: rate d²z/dx²). The stack after
//    an edge is that edge's face stack, its head the face visible to the edge's right (§5.2).
//    Whether a face enters or leaves is not taken from parity alone but from a face test at Q
//    (the face's point lies definitely inside its body's other HSIs): the Resolver's show-edges
//    are a superset of the true boundaries, and crossings closer than 1e-4 px form one event
//    (vertices where several edges meet on or near the CSL); the test makes both harmless and
//    counts where it overrode parity (stackCorrections). The span's faces are each body's first
//    face on the stack; when several bodies share a span the nearest of them is taken per pixel,
//    since bodies of different solids may interpenetrate without a show-edge (the paper's
//    scenes had none; interpenetrationPixels counts where the head was not the nearest).
//    Deviation from ugshow: stacks are rebuilt per scan line by this sweep rather than carried
//    from row to row through the pass-two swaps; so the recursive vertex processing of §5.4 is
//    replaced by the half-open row rule for toggling (renderer.cpp ApplyEdge) plus the face
//    test, and horizontal edges need no special case.
//    EXACT path (render=exact; always for CSG operands and refused bodies): between two
//    crossings the set of faces of every body is constant (the crossings of a body's show-edges
//    are a superset of its face boundaries), so each span's stack is built once: every body
//    whose x range on this row meets the span is evaluated exactly at ONE pixel of the span (the
//    ray/half-space intervals of the body), which names its visible show-face (surface and
//    sheet); faces are inserted in depth order with the same tie-breaks.
//    Faces of different bodies may interpenetrate without a show-edge (the paper's input had
//    none), so inside a span with several faces the nearest is chosen per pixel.
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
};

struct RendererCounters {
    std::uint64_t edgesStarted = 0, edgeSwaps = 0, spans = 0, emptySpans = 0, faceInserts = 0;
    std::uint64_t depthCalcs = 0, sampleEvaluations = 0, sideEvaluations = 0;
    std::uint64_t exactPixels = 0, perPixelUnitPixels = 0, normals = 0, covered = 0;
    std::uint64_t tieBreaks = 0;
    std::uint64_t csgPixels = 0, csgTemplateBodies = 0, csgFallbackPixels = 0;
    std::uint64_t rootFallbackPixels = 0;  // a stack face had no root: pixel evaluated exactly
    // Face stacks (§5.2–5.4): faces inserted into / deleted from the stack at edge crossings,
    // the deepest stack, the sum of stack depths over stack spans (mean = sum / stackSpans),
    // exact evaluations that seed a row's stack left of every crossing, the pixels where a face
    // of another body below the head was nearer (interpenetrating bodies have no show-edge),
    // and the verification (verify=on): spans checked, spans whose stack head differs.
    std::uint64_t stackInserts = 0, stackDeletes = 0, stackMaxDepth = 0, stackDepthSum = 0;
    std::uint64_t stackSpans = 0, stackSeedEvaluations = 0, stackTieBreaks = 0;
    std::uint64_t interpenetrationPixels = 0, verifySpans = 0, verifyMismatchSpans = 0;
    // Crossings where the face test at Q overrode plain parity toggling (spurious or
    // degenerate show-edges, vertices on the CSL): see ApplyEdge in renderer.cpp.
    std::uint64_t stackCorrections = 0;
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
        if (operand.empty()) {
            if (n.op == scene::CsgOp::kIntersection) out.clear();
            continue;  // A ∪ ∅ = A − ∅ = A
        }
        if (out.empty()) {  // union: ∅ ∪ B = B
            std::swap(out, operand);
            continue;
        }
        switch (n.op) {
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
}

// Draws everything: ESL/AEL over the rows, spans, face stacks and the span shader. The rows are
// cut into fixed bands of 32 run in parallel (oneTBB); each band starts its AEL from the ESL at
// its first row, so the image does not depend on the number of threads.
// `pixelBody[b]` marks bodies the Resolver refused (no show-edges): evaluated exactly per pixel
// over their unit's bounds. `stackBody[b]` marks bodies drawn from face stacks (bodies of kBody
// units that were not refused); the others (CSG operands, refused bodies) use the exact
// per-span evaluation. `faces` are the Resolver's show-faces the edges point at.
//
// Face stacks (settings.faceStacks): per scan line, pass three walks the AEL from the left; at
// each crossing of a show-edge of a stack body, each of the edge's two show-faces is deleted
// from the stack when on it, else inserted in depth order (comparisons of §5.5.1 at the
// crossing; ties: depth one step into the span, then slope dz/dx, then rate d²z/dx²). The stack
// after an edge is that edge's face stack; its head is the face visible to the edge's right.
// An edge toggles on rows whose centre lies in the HALF-OPEN range [yBottom, yTop) (endpoints
// snapped to a row centre within 1e-9): a vertex on the CSL where a boundary passes through
// toggles once, one where it turns (V or Λ) twice or never, and edges lying within one scan
// line toggle never — the effect of the recursive vertex processing of §5.4 (see renderer.cpp).
void RenderScanlines(const FlatScene& scene, std::vector<ShowEdge>& edges,
                     const std::vector<ShowFace>& faces, const std::vector<Unit>& units,
                     const std::vector<bool>& pixelBody, const std::vector<bool>& stackBody,
                     const RenderSettings& settings, Frame& frame, RendererCounters& counters);

}  // namespace quadrix::scanline
