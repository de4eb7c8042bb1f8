// Sort-last distributed rendering of one picture (issue 22, docs/batch.md "One big picture"):
// under `mpirun -np N quadrix render --sort-last`, every rank reads and flattens the same scene
// (so every index of the flat scene is the same on every rank), draws the solids s with
// s mod N = rank (EngineRequest::share; freeform surfaces on rank 0), and rank 0 composes the N
// Frames by per-pixel minimum depth (ComposeMin, frame/frame.h) in rank order, then shades and
// writes as a single process would. A pixel's winner is the nearest surface over all shares,
// which is what one engine over the whole scene computes; coincident surfaces of different
// solids (equal depth) go to the lower rank. Communication: each rank > 0 sends its Frame once,
// 16 bytes per pixel (float depth, packed normal, surface and body ids: frame/frame.h), in pieces
// of at most 256 MiB.
//
// Without MPI, or with one rank, it is ctx.Render.
#pragma once

#include "quadrix/pipeline/render_context.h"

namespace quadrix::batch {

// Stage 3 of the render context shared among the ranks. Every rank must call it (collective).
// On rank 0 `frame` is the composed picture; on the others it is that rank's share. false (on
// every rank) when any rank failed; its errors are in that rank's diags.
bool RenderSortLast(RenderContext& ctx, const EngineRequest& engine, Frame& frame,
                    RenderReport& report, Diagnostics& diags);

}  // namespace quadrix::batch
