// Body batches of engine `raycast` ("SIMD over pixels"; step 4 of a render, raycast.cpp). The
// first time a body is needed in a sub-tile, its set is computed for every pixel of the sub-tile
// at once, literal by literal over arrays of pixels (the plane loop has no branches and is
// vectorised by the compiler), with EvaluateBody's exact arithmetic and tie rules (trace.h):
// r = -(px x + py y + pd)/c, a near bound replaces lo unless lo > r, a far bound replaces hi
// unless hi <= r, in the body's literal order. lo only grows and hi only shrinks, so "empty once
// lo >= hi" needs no early exit. A pixel where anything is out of the ordinary — a non-finite
// bound, a plane parallel to the rays that does not simply hold, a quadric set of two pieces — is
// marked kScalar and evaluated by EvaluateBody's scalar loop when asked; every other pixel gets
// the very interval, ids included, that loop would give.
// kCut: the pixel's set has more than one interval; [lo, hi] is its first (∅ when lo >= hi) and
// is exact on t < cut (QuadricBatch's cut mode, ray_literal.h). EvaluateBody takes kCut as
// kScalar.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "quadrix/engines/raycast/counters.h"
#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/engines/raycast/settings.h"
#include "quadrix/engines/raycast/tile_reduction.h"
#include "quadrix/engines/raycast/tiling.h"

namespace quadrix::raycast {

struct BodyBatch {
    static constexpr std::uint8_t kEmpty = 0, kOne = 1, kScalar = 2, kCut = 3;
    double lo[kLanePixels], hi[kLanePixels], cut[kLanePixels];
    std::int64_t loId[kLanePixels], hiId[kLanePixels];  // 64-bit: vectorises with the doubles
    std::uint8_t state[kLanePixels];
};

// The batches of the current sub-tile, its pixel centres and the current pixel.
class BodyBatches {
  public:
    static constexpr std::int32_t kNoBatch = -1, kNoBatchWanted = -2;

    BodyBatches(const SceneTables& tables, Settings settings, const TileReduction& reduction,
                Counters& counters)
        : tables_(&tables), settings_(settings), reduction_(reduction), counters_(counters) {}
    // For another render (worker.h Worker::Bind).
    void Bind(const SceneTables& tables, Settings settings) {
        tables_ = &tables;
        settings_ = settings;
    }

    // Called by RenderTile before the pixels of a sub-tile [x0, x1) × [y0, y1): the bodies whose
    // bounds cover the whole sub-tile are wanted (batched when first needed).
    void Start(const CsgProgram& program, int x0, int y0, int x1, int y1);
    // The same for n <= kLanePixels points (xs[p], ys[p]) of the closed rectangle r that are not
    // pixel centres (the anti-aliasing's samples, sample_batch.h): pixel p is point p. Nothing
    // here depends on the points forming a grid; only which bodies are batched (a policy) looks
    // at them.
    void StartAt(const CsgProgram& program, const Rect& r, const double* xs, const double* ys,
                 int n);

    // Some body of the sub-tile may have a batch (and batch=on).
    bool On() const { return batchOn_; }
    // Whether the body of program node n is wanted (it has or may get a batch).
    bool Wanted(std::int32_t node) const {
        return nodeBatch_[static_cast<std::size_t>(node)] != kNoBatchWanted;
    }
    // The batch of the body of program node n, computed when first asked; null when the body is
    // not wanted.
    const BodyBatch* Find(std::int32_t node) {
        std::int32_t b = nodeBatch_[static_cast<std::size_t>(node)];
        if (b == kNoBatchWanted) return nullptr;
        if (b == kNoBatch) b = Compute(node);
        return &batches_[static_cast<std::size_t>(b)];
    }
    // The kernel's policy (kernel.h): a body whose bounds cover at least half of the sub-tile's
    // pixel centres is wanted too (Start wants only those covering all of them): its pixels then
    // stay in the kernel's lanes. Smaller ones (a sphere of a big union) are evaluated only where
    // needed.
    void WantIfHalfCovered(std::int32_t node, const Rect& xy);
    // The body of program node n wanted whatever its bounds cover (the kernel under a depth cut).
    void Want(std::int32_t node);

    // The batch of the body the sub-tile program reduces to (TileReduction::SingleBody) when
    // there is one and batches are on; every pixel of the sub-tile then sees exactly that body's
    // set, so its visible point is FirstVisibleOfOne of the batch (or, at kScalar pixels,
    // Trace's).
    const BodyBatch* SingleBodyBatch(const CsgProgram& program, const Rect& r);

    // FirstVisible of the one-interval set of pixel p of SingleBodyBatch's batch: its near end
    // when it is finite and on an opaque surface, else its far end on the same terms, else
    // nothing.
    Hit FirstVisibleOfOne(const BodyBatch& batch, std::size_t p) const {
        Hit h;
        double t;
        std::int32_t tag;
        if (tables_->VisibleEnd(batch.lo[p], static_cast<std::int32_t>(batch.loId[p]), batch.hi[p],
                                static_cast<std::int32_t>(batch.hiId[p]), t, tag))
            h = {t, tag, singleSolid_};
        return h;
    }

    // The current pixel, row-major in the sub-tile (Start's pixels only).
    void SetPixel(int i, int j) {
        pixel_ = static_cast<std::size_t>((j - tileY0_) * tileW_ + (i - tileX0_));
    }
    void SetPixelIndex(std::size_t p) { pixel_ = p; }
    std::size_t Pixel() const { return pixel_; }
    // The sub-tile's pixel count and the pixel centres, row-major.
    int PixelCount() const { return tileW_ * tileH_; }
    const double* Xs() const { return xs_; }
    const double* Ys() const { return ys_; }

  private:
    // The batch of the body of program node `node` (Find): its index.
    std::int32_t Compute(std::int32_t node);
    // Start's and StartAt's shared part: the bodies whose bounds contain r are wanted.
    inline void WantCovering(const CsgProgram& program, const Rect& r);

    const SceneTables* tables_;  // Bind
    Settings settings_;
    const TileReduction& reduction_;
    Counters& counters_;
    std::vector<BodyBatch> batches_;
    std::vector<std::int32_t> nodeBatch_;  // per node: batch index, kNoBatch(Wanted)
    std::size_t batchesUsed_ = 0;
    std::size_t bodyBatchesWanted_ = 0;  // Start's count
    std::size_t extraBatches_ = 0;       // bodies wanted beyond Start's (WantIfHalfCovered)
    bool batchOn_ = false;
    int tileX0_ = 0, tileY0_ = 0, tileW_ = 0, tileH_ = 0;
    std::size_t pixel_ = 0;          // the current pixel, row-major in the sub-tile
    std::int32_t singleSolid_ = -1;  // the solid of SingleBodyBatch's body
    double xs_[kLanePixels] = {}, ys_[kLanePixels] = {};
    bool grid_ = true;  // Start's pixel centres (else StartAt's points)
};

inline void BodyBatches::WantCovering(const CsgProgram& program, const Rect& r) {
    batchesUsed_ = 0;
    extraBatches_ = 0;
    nodeBatch_.assign(program.nodes.size(), kNoBatchWanted);
    // Only bodies whose bounds cover the whole sub-tile are batched: they are likely wanted at
    // most of its pixels (a small body in a big union — spheres — is evaluated where needed
    // only).
    std::size_t wanted = 0;
    for (std::size_t n = 0; n < program.nodes.size(); ++n) {
        const ProgNode& node = program.nodes[n];
        if (node.kind != NodeKind::kBody) continue;
        // (Bounds first: only the covering bodies are reduced here, tile_reduction.h.)
        if (node.xy.x0 <= r.x0 && node.xy.x1 >= r.x1 && node.xy.y0 <= r.y0 && node.xy.y1 >= r.y1 &&
            !reduction_.NodeEmpty(n)) {
            nodeBatch_[n] = kNoBatch;
            ++wanted;
        }
    }
    batchOn_ = wanted > 0 && settings_.batch;
    bodyBatchesWanted_ = wanted;
    if (batches_.size() < wanted) batches_.resize(wanted);
}

// Per sub-tile (tiling.cpp), so defined here.
inline void BodyBatches::Start(const CsgProgram& program, int x0, int y0, int x1, int y1) {
    tileX0_ = x0;
    tileY0_ = y0;
    tileW_ = x1 - x0;
    tileH_ = y1 - y0;
    grid_ = true;
    WantCovering(program, {x0 + 0.5, x1 - 0.5, y0 + 0.5, y1 - 0.5});
    for (int j = 0; j < tileH_; ++j)
        for (int i = 0; i < tileW_; ++i) {
            xs_[j * tileW_ + i] = x0 + i + 0.5;
            ys_[j * tileW_ + i] = y0 + j + 0.5;
        }
}

inline void BodyBatches::StartAt(const CsgProgram& program, const Rect& r, const double* xs,
                                 const double* ys, int n) {
    tileX0_ = tileY0_ = 0;
    tileW_ = n;
    tileH_ = 1;
    grid_ = false;
    WantCovering(program, r);
    for (int p = 0; p < n; ++p) {
        xs_[p] = xs[p];
        ys_[p] = ys[p];
    }
}

}  // namespace quadrix::raycast
