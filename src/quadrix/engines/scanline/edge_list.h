// The edge lists of engine `scanline`'s Renderer, seed 001 §5.1 and §5.3: the Edge Start List
// (ESL), one bucket per scan line, and the Active Edge List (AEL) of the edges crossing the
// current scan line (CSL), kept in ascending x by pass two's insertion sort (adjacent swaps,
// counted as in Table 7.2). Conic edges are traced with first and second differences (§5.5.2):
// the quadratic (5.3) of the CSL, B_r += C_c, C_r += ΔC, ΔC += 2 B_c per row, then the root on the
// edge's leg. Each active edge of a face-stack body carries its face stack (face_stack.h); pass
// two applies the swap rule of §5.3 to it while sorting (FaceStacks::SwapLeft). Pass one, the
// vertex processing of §5.4, is vertex_processing.h.
#pragma once

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "quadrix/engines/scanline/coefficients.h"
#include "quadrix/engines/scanline/resolver.h"
#include "quadrix/engines/scanline/scan_context.h"

namespace quadrix::scanline {

class FaceStacks;

struct ActiveEdge {
    int edge = -1;
    int lastRow = 0;
    double x = 0;
    double br = 0, cr = 0, dcr = 0;  // conic: (5.3) at the current row and ΔC_r
    double dx = 0;                   // linear: dx/dy
    // The edge's FACE STACK (§5.2), carried from row to row: the show-faces immediately to the
    // right of the edge on the CSL, nearest first. Only edges of face-stack bodies take part
    // (`stackEdge`); the others are mere breakpoints ("transparent" for the stacks).
    std::vector<int> stack;
    bool stackEdge = false;
    // x is not finite on this row (a conic leg traced just past its end): the edge takes no
    // part in the stacks until it is found again, when its stack is derived afresh.
    bool lost = false;
    // Pass three must derive `stack` again from the left neighbour's stack (⊕ this edge's
    // faces): the band's first row, or where passes one and two could not carry the stack (a
    // vertex fallback, a change of S0, a lost conic leg found again) — FaceStacks::DeriveEdge.
    bool derive = false;
    // `stack` still holds a set that was right for this edge (so that the derived set can be
    // compared with it); false when it was given away in a swap or never set.
    bool carriedValid = true;
    // After deriving, mark the next stack edge for derivation too: always when !carriedValid,
    // else when the derived set differs from the carried one (the change runs on to the right
    // until a derived stack equals the carried one).
    bool propagate = false;
    bool found = false;  // pass two only: x finite again after being lost
    // The swap rule's state (FaceStacks::SwapLeft): the edge moved left past another in pass one or
    // two and handed its stack over; its own stack is its left neighbour's ⊕ its faces, derived
    // when its move ends (pass two) or never (pass one: it is deleted next to CE).
    bool pending = false;
    int startRow = -1;  // the row it entered the AEL (its x is already on that row)
    // Faces still to be toggled in `stack` (pass one and pass two keep the stacks as sets; the
    // faces that enter are put in depth order in pass three, where the crossing's P and Q on
    // the CSL are known: FaceStacks::ResolveToggles).
    std::vector<int> toggles;
    // On its last row, when that row's centre is the edge's top end (snapped, SnapToRow): the
    // edge stays a breakpoint (BuildEsl's closed range) but no longer toggles faces — the
    // half-open rule [yBottom, yTop) that makes a vertex exactly on a row centre toggle its
    // faces once, through the edges that leave it downwards.
    bool ending = false;

    // Takes part in the stacks on this row (a stack edge, found, not ending).
    bool Participates() const { return stackEdge && !lost && !ending; }
    // Pass three derives the stack afresh (no valid carried set to compare with) ...
    void MarkFresh() {
        derive = true;
        carriedValid = false;
        propagate = true;
    }
    // ... or derives it and compares it with the carried one.
    void MarkCheck() {
        derive = true;
        propagate = true;
    }
};

// The AEL's sort key: x, lost edges (x not finite) last.
inline double SortKey(double x) { return std::isfinite(x) ? x : HUGE_VAL; }

// An edge end within 1e-9 (relative) of a row centre j + ½ is put exactly on it: the vertex
// shared by two edges is computed separately for each (different i-lines, different rounding),
// and the half-open toggle rule of the face stacks needs both ends on the same side of the CSL.
inline double SnapToRow(double y) {
    const double r = std::round(y - 0.5) + 0.5;
    return std::fabs(y - r) <= 1e-9 * (1 + std::fabs(y)) ? r : y;
}

// The Edge Start List: per row, the edges (index, last row) that start there.
using EdgeStartList = std::vector<std::vector<std::pair<int, int>>>;
EdgeStartList BuildEsl(const std::vector<ShowEdge>& edges, int h);

// The AEL of one band of rows (each band starts it from the ESL at its first row).
class ActiveEdgeList {
  public:
    explicit ActiveEdgeList(ScanContext& ctx) : ctx_(ctx) {}

    void SetEsl(const EdgeStartList* esl) { esl_ = esl; }
    std::vector<ActiveEdge>& Edges() { return ael_; }
    const std::vector<ActiveEdge>& Edges() const { return ael_; }

    // A starting edge's tracing state at row centre y.
    void Start(ActiveEdge& a, double y);
    // Pass two for one edge: x on the CSL. Conic edges by differences (§5.5.2).
    void Trace(ActiveEdge& a, bool first);
    // The edge's top end lies on the centre of its last row j (see ActiveEdge::ending).
    bool EndsOnRow(const ActiveEdge& a, int j) const {
        return a.lastRow == j && SnapToRow(ctx_.Edge(a.edge).yTop) <= j + 0.5;
    }

    // Without face stacks (and at a band's first row): finishing edges leave the AEL.
    void DropFinishingEdges(int j);
    // Pass two (see edge_list.cpp), with the swap rule of `stacks`.
    void TraceAndSort(int j, FaceStacks& stacks);
    // The starting edges that pass one does not insert, merged into x order without swaps.
    void MergeStartingEdges(int j, bool bandStart);

  private:
    ScanContext& ctx_;
    const EdgeStartList* esl_ = nullptr;
    std::vector<ActiveEdge> ael_;
    std::vector<ActiveEdge> starting_, merged_;  // starting edges of a row, merge scratch
};

// Per edge and row, used by passes one and two (vertex_processing.cpp, edge_list.cpp).
inline void ActiveEdgeList::Start(ActiveEdge& a, double y) {
    const ShowEdge& s = ctx_.Edge(a.edge);
    a.stackEdge = ctx_.stackOn && ctx_.useStack[static_cast<std::size_t>(s.body)];
    if (s.conic) {
        const Conic2& k = s.shape;
        a.br = k.c * y + k.d;
        a.cr = (k.b * y + k.e) * y + k.f;
        a.dcr = k.b * (2 * y + 1) + k.e;
    } else {
        a.dx = -s.line.b / s.line.a;
        a.x = s.XAt(y);
    }
    ++ctx_.c.edgesStarted;
}

inline void ActiveEdgeList::Trace(ActiveEdge& a, bool first) {
    const ShowEdge& s = ctx_.Edge(a.edge);
    if (!s.conic) {
        if (!first) a.x += a.dx;
        return;
    }
    if (!first) {
        a.br += s.shape.c;
        a.cr += a.dcr;
        a.dcr += 2 * s.shape.b;
    }
    const double A = s.shape.a, B = a.br, C = a.cr;
    double disc = B * B - 4 * A * C;
    if (disc < 0) {
        if (disc < -(64 * kUnit) * (B * B + 4 * std::fabs(A * C))) {
            a.x = std::numeric_limits<double>::quiet_NaN();
            return;
        }
        disc = 0;
    }
    const double r = std::sqrt(disc), q = -0.5 * (B + (B >= 0 ? r : -r));
    const double minus = B >= 0 ? q / A : C / q, plus = B >= 0 ? C / q : q / A;
    a.x = s.leg < 0 ? minus : plus;
}

}  // namespace quadrix::scanline
