// Pass one of engine `scanline`'s Renderer, seed 001 §5.4 ("Pass One"), literally: a walk over
// the AEL with the current-edge pointer CE that processes the vertices of the CSL (edge ends with
// y in (j − ½, j + ½], from the vertex table of vertex_table.h): (1) each incident finishing edge
// is moved next to CE by successive swaps (the swap rule of face_stack.h, applied to every edge
// passed) and deleted; (2) the opposite vertex of each incident edge lying within the scan line
// (horizontal, or holding no row centre) is processed recursively; (3) the starting edges are
// inserted at CE with their stacks from the left neighbour's ⊕ their faces. The toggles of a
// vertex group's finishing and starting edges cancel, so nothing right of it changes; where they
// do not (an end missing from the table), the next stack edge is rebuilt in pass three (vertex
// fallback).
//
// The AEL comes from pass two of row j − 1: sorted on x at that row, every stack its left
// neighbour's ⊕ its faces. Pass one walks it with the current-edge pointer CE (ce_), copying
// the edges it passes to the new AEL, and processes the vertices of scan line j (VertexBand):
// the top vertex of CE when CE finishes, and before that every vertex with starting edges
// (VertexTable::startsAt[j], x order) that lies left of CE. A vertex is processed in three steps
// (ProcessVertex): (1) its finishing edges leave the AEL — one that is not CE is first moved
// next to CE by successive swaps, each applying the swap rule of pass two to the edge passed
// (FaceStacks::SwapLeft; counted in stackDeletionSwaps), then deleted; (2) its edges lying within
// the scan line are taken and their other vertices processed recursively; (3) its remaining
// starting edges are inserted at CE, each stack derived from its left neighbour's and the
// edge's two faces. Around a vertex (or a group of vertices linked by edges within the scan
// line) the finishing edges and the starting ones toggle the same faces, so the stack right
// of the inserted edges is the one right of the deleted edges: nothing further right changes.
// When they do not (parity_ not empty: an end missing from the vertex table, a conic leg
// lost to rounding), the next stack edge is derived again in pass three and the change is
// carried on from there (the fallback, stackVertexFallbacks).
#pragma once

#include <cstddef>
#include <vector>

#include "quadrix/engines/scanline/edge_list.h"
#include "quadrix/engines/scanline/face_stack.h"
#include "quadrix/engines/scanline/scan_context.h"
#include "quadrix/engines/scanline/vertex_table.h"

namespace quadrix::scanline {

class VertexPass {
  public:
    VertexPass(ScanContext& ctx, ActiveEdgeList& list, FaceStacks& stacks)
        : ctx_(ctx),
          list_(list),
          stacks_(stacks),
          ael_(list.Edges()),
          vertexRow_(ctx.vt.vertices.size(), -1),
          inBandRow_(ctx.edges.size(), -1) {}

    // Pass one of row j (not a band's first row; face stacks on).
    void Run(int j);

  private:
    // Where CE is at the height of vertex v (the next one with starting edges).
    inline double CeX(const ActiveEdge& a, int v, int j) const;
    // The vertex v of scan line j where a toggling stack edge finishes, or −1.
    inline int FinishingVertex(const ActiveEdge& a, int j) const;
    // Appends an edge to the new AEL.
    inline void Emit(ActiveEdge&& a);
    // A vertex and, recursively, those linked to it by edges within the scan line; then step (3).
    inline void ProcessComponent(int v, int j);
    // Steps (1) and (2) of §5.4 for vertex v; step (3) is collected in starts_.
    inline void ProcessVertex(int v, int j, int depth);

    ScanContext& ctx_;
    ActiveEdgeList& list_;
    FaceStacks& stacks_;
    std::vector<ActiveEdge>& ael_;  // the new AEL (list_.Edges())
    // The AEL of row j − 1 being walked (old_, CE = ce_, gone_: deleted), the new AEL's last stack
    // edge, a fallback mark for the next stack edge emitted, per vertex and per within-the-line
    // edge the row it was processed on, a component's starting edges and the faces its finishing
    // and starting edges toggle.
    std::vector<ActiveEdge> old_, newEdges_;
    std::vector<char> gone_;
    std::size_t ce_ = 0;
    std::ptrdiff_t lastPart_ = -1;
    bool markOut_ = false;
    std::vector<int> vertexRow_, inBandRow_, starts_, parity_;
    std::vector<std::size_t> found_;  // ProcessVertex: places of the finishing edges in old_
};

}  // namespace quadrix::scanline
