// Engine `raycast` at arbitrary points of the image plane: the visible point of the ray through a
// device position (x, y) that need not be a pixel centre. It is the definition of a sample: the
// anti-aliasing pass (shade/antialias.h), which traces a few sub-pixel samples of the pixels where
// the Frame shows an edge, takes its samples from the engine's sub-tile path (sample_batch.h,
// tested equal to this tracer) and from this tracer where a square of them holds a wide union
// (its depth windows below are faster there); tests compare a sample with the engine's pixel.
//
// Same definitions as the engine (raycast.h, trace.h), evaluated the simplest way: the ray
// x(t) = (x, y, t) meets each literal in the set LiteralOnRay gives (eval/ray_literal.h, from the
// engine's own SceneTables, so the same re-centred coefficients and tags); bodies intersect their
// literals' sets, CSG nodes fold their children's lists left to right (math/interval_list.h); a
// solid's visible point is its first finite endpoint on an opaque surface (SceneTables::
// VisibleEnd), and across solids the nearest wins, exact ties keeping the lower solid index. No
// tile reduction, batches or depth cuts: those are proven to give this result bit for bit, so at
// a pixel centre a sample equals the engine's pixel (SampleTracer tests), and elsewhere it is the
// exact picture at that point. Solids are visited by nearest depth behind an (x, y) bounds test.
//
// Acceleration (math/box_tree.h): a box tree over the solids' (x, y) bounds gives the solids
// whose bounds contain the sample, visited in the same nearest-depth order as before; one over
// the children of each wide CSG node (a union, or a difference's subtrahends, of more than
// kWideNode children) gives the children whose bounds contain it, folded in their order in the
// node, as before. Skipped children were ∅ on the ray (A ∪ ∅ = A − ∅ = A, and Union(∅, B) = B
// exactly), so a sample is bit for bit what it was without the trees; the literal evaluation
// (LiteralOnRay) is untouched.
//
// Depth windows (solids with a wide node and finite depth bounds): a column through a cluster of
// 10,000 spheres meets hundreds of them, but its visible point is on one of the first few. The
// solid's set is first made only before zMax = lo + (hi − lo)/64 of its depth bounds: a child
// whose box starts at or beyond zMax is ∅ there and skipped, like one whose box misses the column.
// Set operations commute with the restriction to z < zMax, and the folds (interval_list.h) are
// sweeps whose result before a depth depends only on the endpoints before it, so the list so made
// equals the whole set before zMax, endpoint ids included; its intervals wholly before zMax are
// exact. When the first visible end lies in them (strictly before zMax), it is the solid's visible
// point, bit for bit; otherwise the window grows (1/64, 1/32, … 1/2, then the whole set; a caller's
// depth hint, when it lies inside the solid's depth bounds, is tried first). A solid
// whose window decided nothing while the best point so far lies before zMax cannot win and is left.
//
// Regions (SetRegion): the anti-aliasing pass traces a few samples in each of the edge pixels of a
// small square, so it names the rectangle they lie in first. Each body a sample then meets is
// reduced on that rectangle the engine's way, once (TileReduction::ReduceLiterals,
// tile_reduction.h): the planes that never bound it anywhere in the rectangle and the quadrics
// that hold on all of every ray there are left out, and a body proved empty on every ray there is
// ∅ without a literal evaluated. The reduction's proofs hold on the whole rectangle and each leaves
// the body's set bit for bit, endpoint ids included, so the samples are the same as without a
// region; only fewer literals are evaluated (a machined block's 14 planes are one or two near a
// silhouette).
//
// Freeform surfaces are not traced (the isocurve drawer draws them, not raycast): a sample sees
// only the quadric solids.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "quadrix/engines/raycast/counters.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/engines/raycast/tile_reduction.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/flatten/wide_node_trees.h"
#include "quadrix/math/box_tree.h"
#include "quadrix/math/interval_list.h"
#include "quadrix/math/vec.h"

namespace quadrix::raycast {

// What a Frame pixel holds, for one sample: depth (+inf and kNone ids for the background),
// world-space unit normal facing the viewer, half-space, body and solid.
struct Sample {
    double depth = HUGE_VAL;
    Vec3 normal{};
    std::int32_t surface = -1, body = -1, solid = -1;
    bool Covered() const { return surface >= 0; }
};

class SampleTracer;

// The rectangle the next samples lie in (SampleTracer::SetRegion) and its bodies' literals
// reduced there, each the first time a sample meets the body since the rectangle was set.
struct SampleRegion {
    explicit SampleRegion(const SceneTables& tables) : reduction(tables, Settings{}, counters) {}
    // `reduction` refers to `counters`: never copied or moved (SampleScratch holds it by pointer).
    SampleRegion(const SampleRegion&) = delete;
    SampleRegion& operator=(const SampleRegion&) = delete;
    struct Body {
        std::uint32_t stamp = 0;          // reduced on the rectangle of this stamp
        bool empty = false;               // proved empty on every ray of it
        std::int32_t begin = 0, end = 0;  // the kept literals: tags[begin, end)
    };
    Counters counters;  // (unused: the reduction's own tallies)
    TileReduction reduction;
    Rect rect;
    std::uint32_t stamp = 0;  // of the current rectangle (0: none set yet)
    bool active = false;
    std::vector<Body> bodies;  // per FlatScene body
    std::vector<std::int32_t> tags;
};

// Interval lists reused from sample to sample (one per thread): slot d holds the result of a
// tree node at depth d, which also uses d+1 (operand) and d+2 (scratch); results move between
// slots by swapping pointers, so no sample allocates once warm.
struct SampleScratch {
    explicit SampleScratch(const SampleTracer& tracer);
    std::vector<IntervalList> lists;
    std::vector<IntervalList*> slots;
    // Children of the wide nodes being folded, met by the sample (a stack, sample_tracer.cpp);
    // the solids met by the sample.
    std::vector<std::int32_t> hits;
    std::vector<std::int32_t> solids;
    // The region of SetRegion (made with the first one; a pointer, so the scratch can move).
    std::unique_ptr<SampleRegion> region;
};

class SampleTracer {
  public:
    // spatialIndex = false: no box trees, every solid and child is bounds-tested per sample (the
    // benchmark's "before"; the samples are the same).
    // `wide`: the scene's wide-node trees made once for every tracer of one flat scene
    // (WideNodeTrees::Shared); null: made here.
    explicit SampleTracer(const FlatScene& scene, bool spatialIndex = true,
                          std::shared_ptr<const WideNodeTrees> wide = nullptr);

    // The visible point of the ray through device (x, y). Thread-safe with one scratch per
    // thread. depthHint: a depth the visible point probably lies before (the anti-aliasing pass
    // gives the nearby pixels' deepest): the first depth window tried; the sample is the same
    // whatever the hint (see Depth windows), only its cost changes.
    Sample Trace(double x, double y, SampleScratch& scratch, double depthHint = HUGE_VAL) const;
    Sample Trace(double x, double y) const {
        SampleScratch scratch(*this);
        return Trace(x, y, scratch);
    }
    // Until ClearRegion, the samples traced with `scratch` lie in the closed rectangle r of the
    // image plane (x0 <= x <= x1, y0 <= y <= y1): the bodies they meet are reduced on r (see
    // Regions above). The samples are the same with or without a region.
    void SetRegion(const Rect& r, SampleScratch& scratch) const;
    void ClearRegion(SampleScratch& scratch) const;
    int MaxDepth() const { return maxDepth_; }
    // The engine's tables of the scene (shared with SampleBatcher, sample_batch.h).
    const SceneTables& Tables() const { return tables_; }
    // Nodes with more children than this get a box tree over them.
    static constexpr std::size_t kWideNode = WideNodeTrees::kWideNode;

  private:
    // *scratch.slots[slot] = the set of node n on the ray through (x, y), exact before zMax
    // (children that start at or beyond zMax are skipped; see Depth windows above).
    void Node(std::int32_t n, double x, double y, double zMax, SampleScratch& scratch,
              std::size_t slot) const;
    int Depth(std::int32_t n) const;
    bool HasWideNode(std::int32_t n) const;
    // The first visible end of `set`, made exact before zMax: kFound (t, tag set) when it lies
    // before zMax; kNone when zMax is infinite and the set has none; else kUndecided.
    enum class Window { kFound, kNone, kUndecided };
    Window FirstVisible(const IntervalList& set, double zMax, double& t, std::int32_t& tag) const;
    static constexpr int kWindows = 6;
    static constexpr double kWindowFraction[kWindows] = {1.0 / 64, 1.0 / 32, 1.0 / 16,
                                                         1.0 / 8,  1.0 / 4,  1.0 / 2};

    const FlatScene& scene_;
    SceneTables tables_;
    std::vector<std::int32_t> byDepth_;  // solid indices by nearest device depth (bounds.lo.z)
    std::vector<std::int32_t> rank_;     // solid index → its position in byDepth_
    BoxTree solidTree_;                  // over the solids' bounds
    // The trees of the wide nodes (shared, kept alive here) and, read per node visited, their
    // arrays: wideOf_[node] = index into wide_, or -1.
    std::shared_ptr<const WideNodeTrees> wideTrees_;
    const BoxTree* wide_ = nullptr;
    const std::int32_t* wideOf_ = nullptr;
    std::vector<char> windowed_;  // per solid: traced in depth windows
    int maxDepth_ = 0;
};

}  // namespace quadrix::raycast
