// Tile reduction of engine `raycast` (step 4 of a render, raycast.cpp): before any pixel of a
// sub-tile, the literals of its program's bodies are reduced to those that may bound the body
// somewhere in the sub-tile, bodies are proved empty there, and the sub-tile is filled as
// background or as one plane when that is proved. Each proof is made on the rectangle of pixel
// centres with margins far above rounding, and each leaves the frame bit for bit as the full
// evaluation draws it (the identities of csg_program.h; ClipTo's tie rules, math/interval_list.h).
//
// Which literals a body keeps (PrepareTile): all of the body's, in its order, except planes that
// provably never bound it anywhere in the sub-tile `r`:
//  - a plane parallel to the rays (c = 0) that holds at every pixel centre of the rectangle;
//  - a plane giving a near bound t >= r_b (far bound t <= r_b) when another plane of the same
//    body gives a near bound r_a > r_b (far bound r_a < r_b) at every pixel centre.
// r is linear in (x, y), so comparing at the rectangle's four corner centres decides the whole
// rectangle; a relative margin of 1e-9 (far above the few ulps of rounding in
// r = -(A x + B y + D)/C) keeps ties out. A dropped plane is then never the maximum (minimum)
// bound and never empties the set alone, and ClipTo with it changes no endpoint, so the result is
// bit-for-bit that of all the literals.
//
// Two levels. PrepareStrip runs the same reduction (ReduceBody) once per tile (a 256×8 strip) for
// the bodies of the tile program; PrepareTile then starts each body from the literals the strip
// kept, or takes it as empty when the strip proved it so. Every proof on the strip's rectangle
// holds on each sub-tile's rectangle inside it, and a dropped plane's dominator is kept or dropped
// for a plane that dominates both (dominance with margins is transitive), so the sub-tile's
// literals are again the body's minus droppable ones, in the body's order.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "quadrix/engines/raycast/counters.h"
#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/engines/raycast/pixel_rows.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/engines/raycast/settings.h"

namespace quadrix::raycast {

// A literal's bound at the four corners of a sub-tile (ReduceBody): side 1 = t <= r,
// -1 = t >= r, 0 = not a plane bound (kept as it is).
struct PlaneBound {
    std::int32_t tag;
    int side;
    double r[4];
};

class TileReduction {
  public:
    TileReduction(const SceneTables& tables, Settings settings, Counters& counters)
        : tables_(&tables), settings_(settings), counters_(counters) {}
    // For another render (worker.h Worker::Bind): its tables and settings. Nothing else is kept
    // from one tile to the next but scratch.
    void Bind(const SceneTables& tables, Settings settings) {
        tables_ = &tables;
        settings_ = settings;
    }

    // Once per tile: ReduceBody on the tile's rectangle for the bodies of its program.
    void PrepareStrip(const CsgProgram& program, const Rect& r);
    // Once per sub-tile: each body of the sub-tile program from the strip's literals, reduced
    // when first asked for (NodeTags, NodeEmpty): a big union's sub-tile drawn to its first depth
    // cut (kernel.h) asks only for its nearest bodies, unless a pixel is traced past the cut. The
    // answers do not depend on when they are made. `program` must stay as it is until the next
    // PrepareTile.
    void PrepareTile(const CsgProgram& program, const Rect& r);

    // The same reduction for one body on any rectangle r of the image plane (the sample tracer's
    // regions, sample_tracer.h): appends to `out` the literals of tags[0, n) (a body's, in its
    // order) that may bound the body somewhere in r and returns false, or returns true with
    // nothing appended when the body is provably empty on every ray of r. The proofs hold on the
    // whole closed rectangle, not only at pixel centres: plane bounds are linear in (x, y) and
    // ClassifyQuadric bounds the discriminant over the rectangle.
    bool ReduceLiterals(const std::int32_t* tags, std::size_t n, const Rect& r,
                        std::vector<std::int32_t>& out);

    // PrepareTile's result per node of the sub-tile program: a body's kept literals are
    // TileTags()[NodeTags(n).first, NodeTags(n).second); NodeEmpty(n): a body empty on every ray
    // of the sub-tile.
    // (TileTags may move when a later body is reduced: take it after NodeTags.)
    std::pair<std::int32_t, std::int32_t> NodeTags(std::size_t n) const {
        Reduce(n);
        return nodeTags_[n];
    }
    const std::int32_t* TileTags() const { return tileTags_.data(); }
    bool NodeEmpty(std::size_t n) const {
        const std::uint8_t state = nodeState_[n];
        return (state != kUnknown ? state : ReduceNode(n)) == kEmpty;
    }

    // Flat sub-tiles: writes the pixels of [x0, x1) × [y0, y1) when the sub-tile is provably one
    // plane (see tile_reduction.cpp); false, nothing written, otherwise.
    bool TryFlatFill(const CsgProgram& program, const Rect& r, int x0, int y0, int x1, int y1,
                     const PixelRows& out);

    // True when every solid of the sub-tile program is ∅ on every ray of the rectangle (the
    // bodies PrepareTile proved empty leave nothing, by the identities of SingleBody): the
    // sub-tile is background.
    bool AllEmpty(const CsgProgram& program, const Rect& r) const;

    // The body node that the subtree of node n is equal to on every ray of the sub-tile `r`
    // (ids included), given the bodies PrepareTile found empty there: the identities
    // A ∪ ∅ = A, A − ∅ = A, op(A) = A (math/interval_list.h) leave one body when all its
    // siblings are empty. kEmptyNode when the subtree is empty; -1 when it is not one body or a
    // node on the way does not contain the whole rectangle (MissesPoint could then cut pixels).
    static constexpr std::int32_t kEmptyNode = -2;
    std::int32_t SingleBody(const CsgProgram& p, std::int32_t n, const Rect& r) const;

  private:
    // PrepareStrip's result per FlatScene body, valid when its stamp is stripStamp_.
    struct StripBody {
        std::int32_t begin = 0, end = 0;  // its literals: stripTags_[begin, end)
        bool empty = false;
        std::uint32_t stamp = 0;
    };

    // The reduction for one body on the rectangle r: appends to `out` the literals of tags[0, n)
    // (a body's literals in its order, or a subsequence of them already reduced on a rectangle
    // containing r) that may bound the body somewhere in r, and returns true (with nothing
    // appended) when the body is provably empty on every ray of r.
    inline bool ReduceBody(const std::int32_t* tags, std::size_t n, const Rect& r,
                           std::vector<std::int32_t>& out) const;
    // PrepareTile's work for program node n, once (nothing for an operator node): its state.
    static constexpr std::uint8_t kUnknown = 0, kKept = 1, kEmpty = 2;
    static constexpr std::size_t kEagerNodes = 16;  // PrepareTile reduces smaller programs whole
    void Reduce(std::size_t n) const {
        if (nodeState_[n] == kUnknown) ReduceNode(n);
    }
    std::uint8_t ReduceNode(std::size_t n) const;
    // TryFlatFill's plane test (tile_reduction.cpp): the near plane's tag, or −1.
    inline std::int32_t FlatNearPlane(std::int32_t bodyNode, const Rect& r) const;

    const SceneTables* tables_;  // Bind
    Settings settings_;
    Counters& counters_;
    mutable std::vector<PlaneBound> bounds_;  // ReduceBody scratch (also under ReduceNode)
    std::vector<StripBody> stripBody_;
    std::vector<std::int32_t> stripTags_;
    std::uint32_t stripStamp_ = 0;
    // PrepareTile's results, made as they are asked for (Reduce): a cache, hence mutable.
    const CsgProgram* tileProgram_ = nullptr;
    Rect tileRect_;
    mutable std::vector<std::int32_t> tileTags_;
    mutable std::vector<std::pair<std::int32_t, std::int32_t>> nodeTags_;  // per program node
    // Per program node: kEmpty for a body empty on every ray of the sub-tile, kKept for the
    // others, kUnknown until reduced.
    mutable std::vector<std::uint8_t> nodeState_;
};

// Per sub-tile (tiling.cpp), so defined here.
inline bool TileReduction::AllEmpty(const CsgProgram& program, const Rect& r) const {
    if (!settings_.tileCull) return false;
    for (const ProgSolid& s : program.solids)
        if (SingleBody(program, s.root, r) != kEmptyNode) return false;
    return true;
}

}  // namespace quadrix::raycast
