#include "quadrix/engines/raycast/tiling.h"

#include <algorithm>
#include <cstdint>

#include "quadrix/engines/raycast/pixel_rows.h"
#include "quadrix/engines/raycast/worker.h"

namespace quadrix::raycast {
namespace {

// The pixel k with centre (x, y) from its visible point (background when there is none). Its
// normal, where it is on a quadric, is left to `normals`: WriteHit adds the point, returning its
// lane, or -1 when it wrote the normal itself (a plane's, a quartic's, or the background's).
int WriteHit(const FlatScene& scene, const SceneTables& tables, const Hit& hit, std::size_t k,
             double x, double y, const PixelRows& out, Counters& counters,
             QuadricNormals& normals) {
    if (hit.tag < 0) {
        out.SetBackground(k);
        return -1;
    }
    ++counters.covered;
    const Tag& tag = tables.TagOf(hit.tag);
    out.depth[k] = static_cast<float>(hit.t);
    out.surface[k] = tag.halfSpace;
    out.body[k] = tag.body;
    const auto hsIndex = static_cast<std::size_t>(tag.halfSpace);
    if (tables.constantNormal[hsIndex]) {
        out.normal[k] = tables.packedPlaneNormal[hsIndex];
        return -1;
    }
    const FlatHalfSpace& hs = scene.halfSpaces[hsIndex];
    if (!hs.IsQuadric()) {
        out.normal[k] = PackedNormal(scene.WorldNormal(tag.halfSpace, {x, y, hit.t}));
        return -1;
    }
    return normals.Add(hs.quadric, x, y, hit.t);
}

// The pixels of a sub-tile [sx, ex) × [sy, ey) whose program is w.subTileProgram, after the
// reductions and proofs: each by SubTileHit's rule (worker.h).
void DrawSubTilePixels(const FlatScene& scene, const SceneTables& tables, int sx, int sy, int ex,
                       int ey, Worker& w, const PixelRows& out) {
    const Rect r = Centres(sx, sy, ex, ey);
    w.batches.Start(w.subTileProgram, sx, sy, ex, ey);
    // A sub-tile that is one body (SingleBody) is read straight from the body's batch; only its
    // kScalar pixels, and kCut pixels with nothing visible below the cut, are traced.
    const BodyBatch* single = w.batches.SingleBodyBatch(w.subTileProgram, r);
    if (single) ++w.counters.bodyFillTiles;
    const bool kernel = !single && w.kernel.Compile(w.subTileProgram, r);
    Hit kernelHits[kLanePixels];
    if (kernel) w.kernel.RunTile(kernelHits);
    // The normals on quadrics are made together once the sub-tile's hits are written
    // (quadric_normals.h): pixelOf[lane] is the lane's pixel, tagOf[lane] its hit's tag.
    static_assert(QuadricNormals::kCapacity >= kLanePixels, "a lane for every pixel");
    QuadricNormals& normals = w.normals;
    normals.Clear();
    std::size_t pixelOf[QuadricNormals::kCapacity];
    std::int32_t tagOf[QuadricNormals::kCapacity];
    for (int j = sy; j < ey; ++j) {
        for (int i = sx; i < ex; ++i) {
            const double x = i + 0.5, y = j + 0.5;
            w.batches.SetPixel(i, j);
            const Hit hit = SubTileHit(w, w.subTileProgram, single, kernel ? kernelHits : nullptr,
                                       w.batches.Pixel(), x, y);
            const std::size_t k = out.Index(i, j);
            const int lane = WriteHit(scene, tables, hit, k, x, y, out, w.counters, normals);
            if (lane >= 0) {
                pixelOf[lane] = k;
                tagOf[lane] = hit.tag;
            }
        }
    }
    if (normals.Size() == 0) return;
    normals.Pack(scene.projection.deviceFromWorld.Matrix());
    for (int lane = 0; lane < normals.Size(); ++lane) {
        const std::size_t k = pixelOf[lane];
        if (!normals.NeedsScalar(lane)) {
            out.normal[k].bits = normals.Code(lane);
            continue;
        }
        const double x = normals.X(lane), y = normals.Y(lane), t = normals.Z(lane);
        out.normal[k] =
            PackedNormal(scene.WorldNormal(tables.TagOf(tagOf[lane]).halfSpace, {x, y, t}));
    }
}

// One sub-tile [sx, ex) × [sy, ey) of the tile program: pruned, reduced, then filled as
// background, as one plane, or pixel by pixel.
void RenderSubTile(const FlatScene& scene, const SceneTables& tables, std::size_t bin, int sx,
                   int sy, int ex, int ey, Worker& w, const PixelRows& out) {
    ++w.counters.tiles;
    const Rect r = Centres(sx, sy, ex, ey);
    PruneProgram(w.tileProgram, w.subTileBins, bin, r, w.subTileProgram, w.stack);
    w.counters.tileSolids += w.subTileProgram.solids.size();
    w.counters.pixels += static_cast<std::uint64_t>((ex - sx) * (ey - sy));
    if (w.subTileProgram.solids.empty()) {
        out.FillBackground(sx, sy, ex, ey);
        return;
    }
    w.tracer.SetCuts(w.subTileProgram);
    w.reduction.PrepareTile(w.subTileProgram, r);
    if (w.reduction.AllEmpty(w.subTileProgram, r)) {
        ++w.counters.emptyTiles;
        out.FillBackground(sx, sy, ex, ey);
        return;
    }
    if (w.reduction.TryFlatFill(w.subTileProgram, r, sx, sy, ex, ey, out)) return;
    DrawSubTilePixels(scene, tables, sx, sy, ex, ey, w, out);
}

}  // namespace

void FillBackground(Frame& frame, int x0, int y0, int x1, int y1) {
    for (int j = y0; j < y1; ++j)
        frame.SetBackground(frame.Index(x0, j), static_cast<std::size_t>(x1 - x0));
}

std::vector<Rect> TileRects(int bx0, int by0, int bx1, int by1) {
    std::vector<Rect> rects;
    for (int y0 = by0; y0 < by1; y0 += kTileH)
        rects.push_back(Centres(bx0, y0, bx1, std::min(y0 + kTileH, by1)));
    return rects;
}

void RenderTile(const FlatScene& scene, const SceneTables& tables, const CsgProgram& block,
                const ProgramBins& bins, std::size_t bin, int x0, int y0, int x1, int y1, Worker& w,
                Frame& frame) {
    ++w.counters.coarseTiles;
    PruneProgram(block, bins, bin, Centres(x0, y0, x1, y1), w.tileProgram, w.stack);
    if (w.tileProgram.solids.empty()) {
        w.counters.pixels += static_cast<std::uint64_t>((x1 - x0) * (y1 - y0));
        FillBackground(frame, x0, y0, x1, y1);
        return;
    }
    w.reduction.PrepareStrip(w.tileProgram, Centres(x0, y0, x1, y1));
    const PixelRows out = w.tile.Rows(x0, y0);
    // The sub-tiles: one row (tiling.h), binned along x.
    w.subTileRects.clear();
    for (int sx = x0; sx < x1; sx += kSubTile)
        w.subTileRects.push_back(Centres(sx, y0, std::min(sx + kSubTile, x1), y1));
    BinProgram(w.tileProgram, w.subTileRects, true, w.subTileBins);
    // Evaluations are added to the shared budget in chunks (one atomic add per sub-tile made both
    // threads fight over its cache line: 2 % of the machined part's frame). The render still stops
    // exactly when the whole render would pass the budget (work_budget.h): only the sum decides,
    // and every chunk is added before the tile ends.
    constexpr std::uint64_t kSpendChunk = 1 << 12;
    std::uint64_t pending = 0;
    for (int sy = y0; sy < y1; sy += kSubTile) {
        for (int sx = x0; sx < x1; sx += kSubTile) {
            int ex = std::min(sx + kSubTile, x1), ey = std::min(sy + kSubTile, y1);
            // Past the work budget the render is stopped (work_budget.h): the rest is skipped.
            if (w.budget && w.budget->Exhausted()) {
                out.FillBackground(sx, sy, ex, ey);
                continue;
            }
            const std::uint64_t before = w.counters.bodies;
            RenderSubTile(scene, tables, static_cast<std::size_t>((sx - x0) / kSubTile), sx, sy, ex,
                          ey, w, out);
            pending += w.counters.bodies - before;
            if (w.budget && pending >= kSpendChunk) {
                w.budget->Spend(pending);
                pending = 0;
            }
        }
    }
    if (w.budget && pending) w.budget->Spend(pending);
    w.tile.CopyTile(x0, y0, x1, y1, frame);
}

}  // namespace quadrix::raycast
