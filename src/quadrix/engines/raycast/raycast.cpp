// Engine `raycast` (see raycast.h): the engine's face — its name, its option schema and Draw, which
// drives the phases below, one file each in engines/raycast/. Structure of a render:
//
//  1. Tables (scene_tables.h): per half-space its coefficients regrouped for rays along z
//     (RayHalfSpace); per literal of every body a global "tag" naming (half-space, body,
//     complemented, opaque). Tags are the ids carried by interval endpoints, so the visible
//     endpoint names its surface and body.
//  2. The scene's solids become one CsgProgram (csg_program.h), sorted by nearest depth.
//  3. Tiling (tiling.h): the image is cut into 256×256 blocks, 256×8 tiles and 8×8 sub-tiles,
//     run in parallel (oneTBB, nested parallel_for, in the arena of the caller: Engine::Render
//     makes one of RenderOptions::threads when it is > 0), one Worker per thread (worker.h), kept
//     by the engine from render to render (worker_pool.h). Each level prunes its parent's program
//     against its pixel centres, so a sub-tile sees only the solids and leaves whose bounds reach
//     it, and pruning a 10,000-leaf union costs one walk per block rather than one per sub-tile.
//  4. Per sub-tile, before any pixel (tile_reduction.h): its bodies' literals are reduced
//     (planes that cannot bound a body there dropped, bodies proved empty; once per tile, then
//     per sub-tile: PrepareStrip, PrepareTile), and the sub-tile is filled as background or as
//     one plane when that is proved (AllEmpty, TryFlatFill). Bodies covering the sub-tile are
//     evaluated for all its pixels at once when first needed (body_batch.h, vectorised).
//  5. The pixels of the rest, by the first of these that applies: one body left (its batch);
//     a small tree of bodies (kernel.h: postfix code run over lanes of pixels,
//     kernel_lanes.h); otherwise Trace (trace.h). Trace visits the solids by nearest depth
//     until the best depth found is nearer than the next solid can be; a solid's interval list
//     is computed by recursion over its pruned tree (bodies clip their literals' sets into each
//     other, operators fold their operands left to right, with short cuts on ∅) using lists
//     preallocated per thread, so no pixel allocates once warm. The solid's visible point is its
//     first finite endpoint whose surface is opaque (transparent half-spaces and clipping planes
//     bound but are not drawn); across solids the nearest wins and exact ties keep the lower
//     solid index. Every fast path gives Trace's result bit for bit (the engine options switch
//     them off to show it: Settings, settings.h).
//  6. A tile's pixels are written into a per-thread staging copy, then into the Frame row by row
//     (pixel_rows.h).
//
// Every pixel's result depends only on the scene and the pixel's tile rectangles, never on the
// thread that ran it, so renders are bit-for-bit reproducible for any thread count.
#include "quadrix/engines/raycast/raycast.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "quadrix/engines/engine_limit.h"
#include "quadrix/engines/raycast/counters.h"
#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/engines/raycast/settings.h"
#include "quadrix/engines/raycast/tiling.h"
#include "quadrix/engines/raycast/worker_pool.h"
#include "quadrix/util/parallel.h"

namespace quadrix {
namespace raycast {
namespace {

// Engine options (--engine-opt KEY=VALUE), both "on" by default; switching them off changes
// speed only, never a bit of the frame (RaycastOptions.* tests), which is how their effect is
// measured:
//   batch=on|off      body batches over the pixels of a sub-tile (body_batch.h);
//   tile-cull=on|off  per-sub-tile proofs: bodies empty there (crossing plane bounds, quadrics no
//                     ray meets), quadric literals that hold on every ray, and flat sub-tiles
//                     filled directly (TileReduction::TryFlatFill);
//   kernel=on|off     small sub-tile programs compiled to postfix code over body batches and run
//                     per pixel without Evaluate's recursion (kernel.h; needs batch).
// and one complexity guard, which changes no pixel of a render it lets through:
//   max-evaluations=N body evaluations per pixel on average (default 4,096) past which the
//                     render stops with EngineLimitError (work_budget.h).

const OptionSchema& RaycastSchema() {
    using O = OptionSpec;
    static const OptionSchema kSchema{
        O::Bool("batch", "on", "body batches over the pixels of a sub-tile"),
        O::Bool("tile-cull", "on",
                "per-sub-tile proofs (empty bodies, literals that always hold, flat fills)"),
        O::Bool("kernel", "on",
                "sub-tile programs compiled to postfix code over body batches (needs batch)"),
        O::Int("max-evaluations", "4096", 1, 1e9,
               "body evaluations per pixel on average past which the render stops with an "
               "error (a dense union costs pixels x operands; work_budget.h)"),
    };
    return kSchema;
}

Settings ReadSettings(const EngineOptions& options) {
    Settings st;
    st.batch = options.Bool("batch");
    st.tileCull = options.Bool("tile-cull");
    st.kernel = options.Bool("kernel");
    return st;
}

class RaycastEngine final : public Engine {
  public:
    std::string_view Name() const override { return "raycast"; }
    const OptionSchema& Schema() const override { return RaycastSchema(); }

  protected:
    RenderStats Draw(const FlatScene& scene, const EngineOptions& options, Frame& frame) override {
        auto start = std::chrono::steady_clock::now();
        int width = std::max(scene.width, 0), height = std::max(scene.height, 0);
        frame.ResizeForOverwrite(width, height);
        SceneTables tables(scene);
        CsgProgram full;
        BuildProgram(scene, full);

        int blocksX = (width + kBlock - 1) / kBlock, blocksY = (height + kBlock - 1) / kBlock;
        constexpr int kTilesX = kBlock / kTileW, kTilesY = kBlock / kTileH;
        const Settings settings = ReadSettings(options);
        RenderWorkers workers(pool_, &tables, full.maxDepth, settings);
        // A region (sort-first): the blocks and tiles outside it are skipped (Engine::Render
        // makes their pixels background); those inside are the same rectangles, pruned the same
        // way, as in a render of the whole picture, so their pixels are the same bits.
        const PixelRegion* region = Region();
        WorkBudget budget(static_cast<std::uint64_t>(options.Int("max-evaluations")),
                          static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height));
        // Blocks own their pruned program (not the thread: a thread waiting in the nested loop may
        // run another block); tiles use per-thread scratch, held by no task across a wait.
        auto renderBlock = [&](int b) {
            int bx0 = (b % blocksX) * kBlock, by0 = (b / blocksX) * kBlock;
            int bx1 = std::min(bx0 + kBlock, width), by1 = std::min(by0 + kBlock, height);
            if (region && !region->Intersects(bx0, by0, bx1, by1)) return;
            CsgProgram block;
            std::vector<std::int32_t> stack;
            PruneProgram(full, Centres(bx0, by0, bx1, by1), block, stack);
            // The block's tiles are its rows (tiling.h): its program binned over them.
            ProgramBins bins;
            BinProgram(block, TileRects(bx0, by0, bx1, by1), false, bins);
            ++workers.Local().counters.blocks;
            if (block.solids.empty()) {
                workers.Local().counters.pixels +=
                    static_cast<std::uint64_t>((bx1 - bx0) * (by1 - by0));
                if (!region) {
                    FillBackground(frame, bx0, by0, bx1, by1);
                    return;
                }
                for (const PixelRect& r : region->rects) {  // only the region's pixels
                    const int x0 = std::max(r.x0, bx0), y0 = std::max(r.y0, by0);
                    const int x1 = std::min(r.x1, bx1), y1 = std::min(r.y1, by1);
                    if (x0 < x1 && y0 < y1) FillBackground(frame, x0, y0, x1, y1);
                }
                return;
            }
            ParallelFor(tbb::blocked_range<int>(0, kTilesX * kTilesY, 1),
                        [&](const tbb::blocked_range<int>& range) {
                            Worker& w = workers.Local();
                            w.budget = &budget;
                            for (int k = range.begin(); k < range.end(); ++k) {
                                int x0 = bx0 + (k % kTilesX) * kTileW;
                                int y0 = by0 + (k / kTilesX) * kTileH;
                                if (x0 >= bx1 || y0 >= by1) continue;
                                if (region && !region->Intersects(x0, y0, x0 + kTileW, y0 + kTileH))
                                    continue;
                                RenderTile(scene, tables, block, bins,
                                           static_cast<std::size_t>((y0 - by0) / kTileH), x0, y0,
                                           std::min(x0 + kTileW, bx1), std::min(y0 + kTileH, by1),
                                           w, frame);
                            }
                        });
        };
        ParallelFor(tbb::blocked_range<int>(0, blocksX * blocksY, 1),
                    [&](const tbb::blocked_range<int>& range) {
                        for (int b = range.begin(); b < range.end(); ++b) renderBlock(b);
                    });

        Counters total;
        workers.ForEach([&](const Worker& w) { total.Add(w.counters); });
        if (budget.Exhausted()) {
            // Name the solid of most operands (a flat union's root holds them all).
            std::size_t widest = 0;
            auto operands = [&](std::size_t s) {
                return full.nodes[static_cast<std::size_t>(full.solids[s].root)].count;
            };
            for (std::size_t s = 1; s < full.solids.size(); ++s)
                if (operands(s) > operands(widest)) widest = s;
            const FlatSolid& named =
                scene.solids[static_cast<std::size_t>(full.solids[widest].solid)];
            throw EngineLimitError(fmt::format(
                "raycast: the render needs more than {} body evaluations (max-evaluations={} "
                "per pixel on average): too many bodies cover the same pixels (solid '{}' has "
                "{} operands; a dense union costs pixels x operands). Raise the limit with "
                "--engine-opt max-evaluations=N, or render fewer pixels",
                budget.Limit(), budget.PerPixel(), named.name, operands(widest)));
        }
        RenderStats stats;
        stats.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        CounterValues counters(kRaycastCounters);
        counters.Set(CounterId::solids, full.solids.size());
        counters.Set(CounterId::programNodes, full.nodes.size());
        total.Record(counters);
        counters.AppendTo(stats.counters);
        return stats;
    }

  private:
    WorkerPool pool_;  // the Workers, kept from render to render (worker_pool.h)
};

}  // namespace
}  // namespace raycast

std::unique_ptr<Engine> MakeRaycastEngine() { return std::make_unique<raycast::RaycastEngine>(); }

}  // namespace quadrix
