// The FACE STACKS of engine `scanline`, seed 001 §5.2–5.4 (default for bodies drawn on their
// own). Every active edge of such a body carries its face stack from row to row: the show-faces
// immediately to its right on the CSL, nearest first. Each show-edge bounds two faces that change
// sides at it, so an edge's stack is its left neighbour's with the edge's faces toggled (a face on
// it leaves, one off it is inserted in depth order by the §5.5.1 comparisons: depth at the
// crossing P; equal: depth at Q, half-way into the edge's region; equal: slope dz/dx; equal: rate
// d²z/dx², FaceOrder). Passes one and two keep "stack = left neighbour's ⊕ own faces" for every
// stack edge, so the stacks change only where the AEL changes:
//   pass one   (vertex_processing.h) inserts and deletes edges at the vertices of the CSL, with
//              stacks from the left neighbour's (DeriveFrom) and the swap rule for the edges a
//              finishing edge passes on its way to CE;
//   pass two   (edge_list.h) the swap rule (SwapLeft): when edge E moves left past edge X in the
//              insertion sort, X takes E's stack as it is (the region right of X is the one that
//              was right of E); if E moves on past X', X' takes E's new stack, its own ⊕ E's
//              faces; when E's move ends, its stack is its new left neighbour's ⊕ its faces
//              (ResolvePending);
//   pass three (here) walks the AEL left to right and puts the faces that passes one and two
//              toggled into depth order at each crossing (they keep the stacks as sets). It
//              derives a stack from its left neighbour's only at a band's first row and where the
//              above cannot carry it (REBUILD, DeriveEdge: after a vertex fallback, a change of
//              S0, a conic leg lost to rounding and found again); a rebuilt set that differs from
//              the carried one rebuilds the next stack edge too.
// An edge toggles on the rows whose centre lies in the HALF-OPEN [yBottom, yTop) (ends snapped to
// a row centre within 1e-9): on its last row, when that row's centre is its top, it is a
// breakpoint only ("ending"). Raycast's closed half-spaces may still draw such a face on that row
// (a box whose side y = j + ½ is an edge-on plane): the face test at Q decides it for that row
// only, outside the carried stacks (UpdateClosedRowFaces, closedRowFaces). Crossings closer than
// 1e-4 px form one event, checked by the verifier (stack_verifier.h). The left of every crossing
// (S0) holds faces of bodies reaching the image's left side, found per row by one exact
// evaluation (SeedStack).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "quadrix/engines/scanline/edge_list.h"
#include "quadrix/engines/scanline/scan_context.h"

namespace quadrix::scanline {

class StackVerifier;

inline bool Contains(const std::vector<int>& st, int f) {
    return std::find(st.begin(), st.end(), f) != st.end();
}
inline bool SameSet(const std::vector<int>& a, const std::vector<int>& b) {
    if (a.size() != b.size()) return false;
    for (int f : a)
        if (!Contains(b, f)) return false;
    return true;
}

// The depth order of show-faces at a crossing of the CSL (§5.5.1).
class FaceOrder {
  public:
    explicit FaceOrder(ScanContext& ctx) : ctx_(ctx) {}

    // Is show-face f in front of g at the crossing P = (xe, y)? The lesser depth at P decides;
    // equal within the scene's depth tolerance (or a face without a point at P, e.g. a limb
    // crossing rounded just outside the sheet), case (a): depth at Q = (xq, y), the point
    // half-way to the next crossing (at most ½ pixel on — the scan-line analogue of "where E
    // meets the next scan line", since our stacks are swept along the CSL); equal again, case
    // (b): the lesser slope dz/dx at Q; then case (c): the lesser rate d²z/dx² at Q. −1: f in
    // front, +1: g in front, 0: coincident (order unimportant, f goes below).
    int CompareAt(int f, int g, double xe, double xq, double y);

    // Insertion into stack `st` in depth order: below every face it is not in front of, scanning
    // from the head. Bodies of different solids may interpenetrate without a show-edge (the
    // paper's scenes had none), so the order between faces of DIFFERENT bodies can go stale; the
    // order among one body's faces cannot (their crossings are i-lines, hence show-edges). So the
    // face is also kept below every face of its own body that is in front of it: each body's
    // first face on a stack is then that body's visible face whatever the others do.
    void InsertInto(std::vector<int>& st, int f, double xe, double xq, double y);

  private:
    ScanContext& ctx_;
};

class FaceStacks {
  public:
    FaceStacks(ScanContext& ctx, FaceOrder& order, StackVerifier& verifier,
               std::vector<ActiveEdge>& ael)
        : ctx_(ctx), order_(order), verifier_(verifier), ael_(ael) {}
    FaceStacks(const FaceStacks&) = delete;
    FaceStacks& operator=(const FaceStacks&) = delete;

    // ---- carrying the stacks (passes one and two) ----

    // Adds edge a's faces to a list of faces to toggle (two toggles of one face cancel).
    void AddToggles(std::vector<int>& t, const ActiveEdge& a) const;
    // The swap rule (§5.3): edge e moves left past its neighbour x; true when a stack changed.
    bool SwapLeft(ActiveEdge& e, ActiveEdge& x);
    // a's stack from its left neighbour's (S0 when `left` is null) ⊕ a's faces, as a set.
    void DeriveFrom(ActiveEdge& a, const ActiveEdge* left);
    // Pass two: the stack of the mover at AEL position k at the end of its move.
    void ResolvePending(std::size_t k);

    // ---- pass three ----

    // The row is a band's first: every stack is derived (counted apart from rebuilds).
    void SetBandStart(bool bandStart) { bandStartRow_ = bandStart; }
    // S0 of the row at y from the active units (row_bodies.h); starts the walk.
    void SeedStack(const std::vector<int>& activeUnits, double y);
    // Walks every AEL edge with a crossing left of x; true when an event straddles x.
    bool ApplyEdgesBefore(double x, double y);
    // The stack the spans after the last walked event are drawn from.
    const std::vector<int>& Shown() const { return *shown_; }

  private:
    inline void ApplyEvent(std::size_t b, std::size_t e, double xq, double y);
    inline void UpdateClosedRowFaces(std::size_t b, std::size_t e, double xq, double y);
    inline void ShowStack(double xe, double xq, double y);
    inline void ResolveToggles(ActiveEdge& a, double xq, double y);
    inline void DeriveEdge(ActiveEdge& a, const std::vector<int>& prev, double xq, double y);

    ScanContext& ctx_;
    FaceOrder& order_;
    StackVerifier& verifier_;
    std::vector<ActiveEdge>& ael_;  // the AEL (ActiveEdgeList::Edges)
    bool bandStartRow_ = false;     // the row is a band's first: every stack is derived
    // Pass three: the stack right of the last walked stack edge (or seed_), nearest first.
    const std::vector<int>* cur_ = &seed_;
    // The stack the spans are drawn from: *cur_, or showBuf_ = *cur_ adjusted by the faces of
    // edges ending on this row's centre that the face test keeps (closedAdd_) or drops.
    const std::vector<int>* shown_ = &seed_;
    std::vector<int> showBuf_, closedAdd_, closedDrop_;
    std::vector<int> seed_, seedPrev_;  // S0 on this row and on the previous one
    bool markNext_ = false;             // derive the next stack edge walked
    std::vector<int> derived_;          // scratch stack
    std::size_t aelPos_ = 0;            // pass three: the next AEL edge to apply
};

}  // namespace quadrix::scanline
