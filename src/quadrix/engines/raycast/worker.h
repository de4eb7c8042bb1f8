// Everything one thread of engine `raycast` needs, reused across tiles and pixels: the pruned
// programs of the current tile and sub-tile, the counters, and the phases of a sub-tile, each
// owning its own state — tile reduction (tile_reduction.h), body batches (body_batch.h), the
// scalar path (trace.h) and kernels (kernel.h) — plus the tile's staging copy (pixel_rows.h).
// A Worker is made in place per thread and kept from render to render (worker_pool.h), never
// copied: its phases refer to each other and to its counters.
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/engines/raycast/body_batch.h"
#include "quadrix/engines/raycast/counters.h"
#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/engines/raycast/kernel.h"
#include "quadrix/engines/raycast/pixel_rows.h"
#include "quadrix/engines/raycast/quadric_normals.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/engines/raycast/settings.h"
#include "quadrix/engines/raycast/tile_reduction.h"
#include "quadrix/engines/raycast/trace.h"
#include "quadrix/engines/raycast/work_budget.h"

namespace quadrix::raycast {

class Worker {
  public:
    // `maxDepth`: the full program's deepest node (pruned programs are no deeper).
    Worker(const SceneTables* tables, int maxDepth, Settings settings)
        : reduction(*tables, settings, counters),
          batches(*tables, settings, reduction, counters),
          tracer(*tables, maxDepth, reduction, batches, counters),
          kernel(*tables, settings, reduction, batches, tracer, counters) {}
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;

    // For another render (worker_pool.h): its tables, deepest node and settings; the counters
    // start from zero and no budget is set. The scratch, grown to what earlier renders needed,
    // is kept: nothing in it carries from one tile to the next (tiling.h).
    void Bind(const SceneTables* tables, int maxDepth, Settings settings) {
        reduction.Bind(*tables, settings);
        batches.Bind(*tables, settings);
        tracer.Bind(*tables, maxDepth);
        kernel.Bind(*tables, settings);
        counters = Counters{};
        budget = nullptr;
    }

    WorkBudget* budget = nullptr;  // the render's (work_budget.h), shared by the workers
    CsgProgram tileProgram, subTileProgram;
    ProgramBins subTileBins;  // tileProgram's over subTileRects (tiling.cpp)
    std::vector<Rect> subTileRects;
    std::vector<std::int32_t> stack;  // PruneProgram's scratch
    Counters counters;
    TileReduction reduction;
    BodyBatches batches;
    Tracer tracer;
    Kernel kernel;
    TileBuffer tile;
    QuadricNormals normals;  // a sub-tile's normals on quadrics (tiling.cpp)
};

// The visible point of pixel p at (x, y) of a sub-tile whose program is `program`, by the first of
// these that applies (tiling.cpp DrawSubTilePixels; also the samples of sample_batch.h): the
// sub-tile's single body (`single`: its batch; kScalar pixels, and kCut pixels with nothing
// visible below the cut, are traced), the sub-tile's kernel (`kernelHits`, or null when it was
// not compiled), Trace. The current pixel (BodyBatches::SetPixel/SetPixelIndex) is p.
inline Hit SubTileHit(Worker& w, const CsgProgram& program, const BodyBatch* single,
                      const Hit* kernelHits, std::size_t p, double x, double y) {
    const std::uint8_t state = single ? single->state[p] : BodyBatch::kScalar;
    if (state == BodyBatch::kEmpty) return {};
    if (state == BodyBatch::kOne) return w.batches.FirstVisibleOfOne(*single, p);
    if (state == BodyBatch::kCut) {
        // The first interval is exact below the cut; beyond it, trace.
        Hit hit;
        if (single->lo[p] < single->hi[p]) hit = w.batches.FirstVisibleOfOne(*single, p);
        if (!(hit.t < single->cut[p])) hit = w.tracer.Trace(program, x, y);
        return hit;
    }
    if (kernelHits) return kernelHits[p];
    return w.tracer.Trace(program, x, y);
}

}  // namespace quadrix::raycast
