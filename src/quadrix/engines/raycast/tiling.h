// The tiling of engine `raycast` (step 3 of a render, raycast.cpp): the image is cut into
// 256×256 blocks, 256×8 tiles and 8×8 sub-tiles; each level prunes its parent's CSG program
// against its pixel centres (csg_program.h), so a sub-tile sees only the solids and leaves whose
// bounds reach it. RenderTile draws one tile: per sub-tile the reductions and proofs of
// tile_reduction.h, then the pixels by the first fast path that applies (a single body's batch,
// a kernel, else Trace), into the tile's staging copy (pixel_rows.h) and from there into the
// Frame. Every pixel's result depends only on the scene and its tile rectangles, never on the
// thread that ran it.
#pragma once

#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/frame/frame.h"

namespace quadrix::raycast {

constexpr int kBlock = 256;  // first pruning level (pixels per side)
// Second level: strips, not squares. A tile's sub-tiles then write eight rows of the frame's
// five arrays, one after the other along each row; a 64×64 tile writes 64 rows at once, whose
// pages and streams thrash the TLB and the prefetchers (the machined part at 1280×720: 21 → 17
// ms a frame, docs/performance.md).
constexpr int kTileW = 256, kTileH = 8;
constexpr int kSubTile = 8;  // last level: the pixels of a sub-tile share one program
constexpr int kLanePixels = kSubTile * kSubTile;

class Worker;

// The pixel centres of the pixel rectangle [x0, x1) × [y0, y1).
inline Rect Centres(int x0, int y0, int x1, int y1) {
    return {x0 + 0.5, x1 - 0.5, y0 + 0.5, y1 - 0.5};
}

// The frame is sized without clearing (Frame::ResizeForOverwrite): every pixel is written, by
// the tile that owns it, as a hit or as background.
void FillBackground(Frame& frame, int x0, int y0, int x1, int y1);

// Tiles are whole rows of a block, and sub-tiles one row of a tile: the rectangles pruned from
// one program are disjoint along one axis, so each program is binned over them
// (eval::ProgramBins).
static_assert(kTileW == kBlock && kTileH == kSubTile);

// The tiles of the block [bx0, bx1) × [by0, by1) in order, as pixel-centre rectangles (the bins
// of the block's program).
std::vector<Rect> TileRects(int bx0, int by0, int bx1, int by1);

// Renders one 256×8 tile (pixel rectangle [x0, x1) × [y0, y1)) from its block's program; `bins`
// are the block program's over TileRects and `bin` this tile's.
void RenderTile(const FlatScene& scene, const SceneTables& tables, const CsgProgram& block,
                const ProgramBins& bins, std::size_t bin, int x0, int y0, int x1, int y1, Worker& w,
                Frame& frame);

}  // namespace quadrix::raycast
