// The vertex table of engine `scanline`'s face stacks, seed 001 §5.4 ("Pass One"): the ends of
// the stack bodies' show-edges grouped into vertices per scan line, built once per frame, so that
// pass one (vertex_processing.h) can process each vertex of the current scan line once.
//
// §5.4's vertices. A stack edge toggles its faces on the rows whose centre lies in the half-open
// [yBottom, yTop) (ActiveEdge::ending); the scan line of row j takes the vertices with
// y in (j − ½, j + ½] (VertexBand): there the edges toggling up to row j − 1 finish and those
// toggling from row j start. An edge whose two ends lie in one band toggles on no row: it "lies
// completely within the scan line" and only links its two vertices (pass one recurses through
// it). Ends of different edges are one vertex when they lie in one band within kVertexTol in x
// and y (a vertex shared by two i-lines is computed on each; merging two distinct vertices is
// harmless, since the toggles of each cancel around it, so do those of the two together).
#pragma once

#include <vector>

#include "quadrix/engines/scanline/resolver.h"

namespace quadrix::scanline {

struct RVertex {
    double x = 0, y = 0;
    int band = 0;
    std::vector<int> finishing;  // toggling edges whose top end is here
    std::vector<int> starting;   // toggling edges whose bottom end is here
    std::vector<int> inBand;     // edges with both ends in this band
};
struct VertexTable {
    std::vector<RVertex> vertices;
    std::vector<int> bottom, top;            // per edge: the vertex of each end (−1: none)
    std::vector<char> toggling;              // per edge: a stack edge whose ends are in two bands
    std::vector<std::vector<int>> startsAt;  // per row: vertices with starting edges, x order
};
inline constexpr double kVertexTol = 1e-3;  // px

// The band (scan line) of the vertex at height y: the j with y in (j − ½, j + ½].
int VertexBand(double y);

// The vertex table of the stack bodies' show-edges (`stack[b]`: drawn from face stacks).
VertexTable BuildVertices(const std::vector<ShowEdge>& edges, const std::vector<char>& stack,
                          int h);

}  // namespace quadrix::scanline
