// Sort-first distributed rendering of one picture (issue 22, docs/batch.md "One big picture"):
// under `mpirun -np N quadrix render --sort-first`, every rank reads and flattens the whole
// scene for the whole picture, draws only its pixels — full-width bands of kSortFirstBandRows
// rows dealt round-robin (band b to rank b mod N, frame/pixel_region.h InterleavedBands), so
// the rows of a part in the middle of the picture are shared evenly — shades its own rows, and
// sends the shaded rows to rank 0, which only puts them in place and writes.
//
// Why the result is the same bits as one process's: the picture keeps its size and view on every
// rank (EngineRequest::region, not a smaller picture), so a pixel is computed from the same
// device coordinates by the same code; an engine either skips the work outside its region
// (raycast skips its tiles, whose rectangles and pruning do not change) or draws everything and
// is cropped. A pixel's shading reads its own Frame entry, except where the anti-aliasing and the
// edge lines compare it with neighbours up to kShadeHaloRows (2) rows away (shade/row_shading.h,
// shade/antialias.h): before shading, each rank receives those rows of the
// Frame from the ranks that drew them (the halo exchange, peer to peer), so its rows see the same
// neighbours as in one process. The fast model's mean normals are the whole picture's: for it the
// Frame is gathered and rank 0 shades everything, as before.
//
// Communication: the halo, 2 + 2 rows of Frame (16 bytes a pixel: float depth, packed normal,
// two 4-byte ids; frame/frame.h) per band of 16 between neighbouring ranks; then each rank > 0
// sends its shaded rows to rank 0: 1 or 3 bytes a pixel, plus 4 or 12 of Image::linear when the
// image has it (16-bit PNG, EXR, anti-aliasing). When an output needs the Frame (a .qxf dump, EXR
// layers, --stats) its pixels are gathered too: (N−1)/N of the picture at 16 bytes a pixel.
//
// Without MPI, or with one rank, it is ctx.Render and ctx.Shade.
#pragma once

#include <vector>

#include "quadrix/frame/pixel_region.h"
#include "quadrix/io/image.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/shade/row_shading.h"

namespace quadrix::batch {

// Rows per band: a multiple of the raycast engine's tile height (8), so no tile is split between
// ranks, and small enough that 720 rows make 45 bands.
constexpr int kSortFirstBandRows = 16;

// The pixels rank `rank` of `ranks` draws, and the same as row spans (its shading rows).
PixelRegion SortFirstRegion(int width, int height, int rank, int ranks);
std::vector<RowSpan> SortFirstRows(int width, int height, int rank, int ranks);

// Stage 3 of the render context shared among the ranks, the Frame gathered on rank 0. Every rank
// must call it (collective). On rank 0 `frame` is the whole picture; on the others it holds that
// rank's bands. false (on every rank) when any rank failed; its errors are in that rank's diags.
bool RenderSortFirst(RenderContext& ctx, const EngineRequest& engine, Frame& frame,
                     RenderReport& report, Diagnostics& diags);

// Stages 3 and 4 shared among the ranks (collective): each rank draws and shades its rows with
// `shade` (the whole picture's options, the picture defaults applied) and rank 0 gathers the
// shaded rows into `image`; with needFrame the Frame too (else rank 0's `frame` holds its own
// rows and the 2-row halo only). On the other ranks `image` and `frame` hold their rows. false
// (on every rank) when any rank failed to draw.
bool RenderShadeSortFirst(RenderContext& ctx, const EngineRequest& engine,
                          const ShadeOptions& shade, bool needFrame, Frame& frame, Image& image,
                          RenderReport& report, Diagnostics& diags);

}  // namespace quadrix::batch
