// Sort-first distributed rendering of one picture (issue 22, docs/batch.md "One big picture"):
// under `mpirun -np N quadrix render --sort-first`, every rank reads and flattens the whole
// scene for the whole picture, draws only its pixels — full-width bands of kSortFirstBandRows
// rows dealt round-robin (band b to rank b mod N, frame/pixel_region.h InterleavedBands), so
// the rows of a part in the middle of the picture are shared evenly — and sends them to rank 0,
// which puts them in place, then shades and writes as a single process would.
//
// Why the result is the same bits as one process's: the picture keeps its size and view on every
// rank (EngineRequest::region, not a smaller picture), so a pixel is computed from the same
// device coordinates by the same code; an engine either skips the work outside its region
// (raycast skips its tiles, whose rectangles and pruning do not change) or draws everything and
// is cropped. Shading (shadows, anti-aliasing, edge lines) runs on rank 0 over the whole
// composed Frame, so it sees the same neighbours as in one process.
//
// Communication: each rank > 0 sends its pixels once, 60 bytes each (depth 8, normal 24, three
// 4-byte ids): (N−1)/N of the picture reaches rank 0 in all, 1.9 GB for an 8K picture
// whatever N is — against sort-last's 2.0 GB per rank.
//
// Without MPI, or with one rank, it is ctx.Render.
#pragma once

#include "quadrix/frame/pixel_region.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix::batch {

// Rows per band: a multiple of the raycast engine's tile height (8), so no tile is split between
// ranks, and small enough that 720 rows make 45 bands.
constexpr int kSortFirstBandRows = 16;

// The pixels rank `rank` of `ranks` draws.
PixelRegion SortFirstRegion(int width, int height, int rank, int ranks);

// Stage 3 of the render context shared among the ranks. Every rank must call it (collective).
// On rank 0 `frame` is the whole picture; on the others it holds that rank's bands. false (on
// every rank) when any rank failed; its errors are in that rank's diags.
bool RenderSortFirst(RenderContext& ctx, const EngineRequest& engine, Frame& frame,
                     RenderReport& report, Diagnostics& diags);

}  // namespace quadrix::batch
