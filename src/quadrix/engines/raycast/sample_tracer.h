// Engine `raycast` at arbitrary points of the image plane: the visible point of the ray through a
// device position (x, y) that need not be a pixel centre, for the anti-aliasing pass
// (shade/antialias.h), which traces a few sub-pixel samples of the pixels where the Frame shows an
// edge, and for tests that compare a sample with the engine's pixel.
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
// Freeform surfaces are not traced (the isocurve drawer draws them, not raycast): a sample sees
// only the quadric solids.
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/engines/raycast/scene_tables.h"
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
};

class SampleTracer {
  public:
    // spatialIndex = false: no box trees, every solid and child is bounds-tested per sample (the
    // benchmark's "before"; the samples are the same).
    explicit SampleTracer(const FlatScene& scene, bool spatialIndex = true);

    // The visible point of the ray through device (x, y). Thread-safe with one scratch per
    // thread.
    Sample Trace(double x, double y, SampleScratch& scratch) const;
    Sample Trace(double x, double y) const {
        SampleScratch scratch(*this);
        return Trace(x, y, scratch);
    }
    int MaxDepth() const { return maxDepth_; }
    // Nodes with more children than this get a box tree over them.
    static constexpr std::size_t kWideNode = WideNodeTrees::kWideNode;

  private:
    // *scratch.slots[slot] = the set of node n on the ray through (x, y).
    void Node(std::int32_t n, double x, double y, SampleScratch& scratch, std::size_t slot) const;
    int Depth(std::int32_t n) const;

    const FlatScene& scene_;
    SceneTables tables_;
    std::vector<std::int32_t> byDepth_;  // solid indices by nearest device depth (bounds.lo.z)
    std::vector<std::int32_t> rank_;     // solid index → its position in byDepth_
    BoxTree solidTree_;                  // over the solids' bounds
    std::vector<BoxTree> wide_;          // trees of the wide nodes
    std::vector<std::int32_t> wideOf_;   // node → index into wide_, or -1
    int maxDepth_ = 0;
};

}  // namespace quadrix::raycast
