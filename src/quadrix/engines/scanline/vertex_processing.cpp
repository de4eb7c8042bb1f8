#include "quadrix/engines/scanline/vertex_processing.h"

#include <algorithm>
#include <cmath>

namespace quadrix::scanline {

void VertexPass::Run(int j) {
    old_.swap(ael_);
    ael_.clear();
    gone_.assign(old_.size(), 0);
    lastPart_ = -1;
    markOut_ = false;
    ce_ = 0;
    const std::vector<int>& sv = ctx_.vt.startsAt[static_cast<std::size_t>(j)];
    std::size_t q = 0;
    for (;;) {
        while (ce_ < old_.size() && gone_[ce_]) ++ce_;
        while (q < sv.size() && vertexRow_[static_cast<std::size_t>(sv[q])] == j) ++q;
        const bool haveCe = ce_ < old_.size();
        if (q < sv.size() && (!haveCe || ctx_.vt.vertices[static_cast<std::size_t>(sv[q])].x <
                                             CeX(old_[ce_], sv[q], j))) {
            ProcessComponent(sv[q], j);
            continue;
        }
        if (!haveCe) break;
        const int v = FinishingVertex(old_[ce_], j);
        if (v >= 0 && vertexRow_[static_cast<std::size_t>(v)] != j) {
            ProcessComponent(v, j);
            continue;
        }
        ActiveEdge& a = old_[ce_++];
        if (v >= 0) {  // its vertex was processed without it (not expected): fallback
            if (a.Participates()) {
                ++ctx_.c.stackVertexFallbacks;
                markOut_ = true;
            }
            a.ending = true;
        }
        if (a.lastRow < j) continue;  // finishing edges of other bodies and lost ones leave
        Emit(std::move(a));
    }
    old_.clear();
}

// Where CE is at the height of vertex v (the next one with starting edges): its own top
// vertex's x if it finishes on this scan line, else x on its show-edge at v's y (the AEL's
// x are on row j − 1, up to a row below v).
inline double VertexPass::CeX(const ActiveEdge& a, int v, int j) const {
    const int top = FinishingVertex(a, j);
    if (top >= 0) return ctx_.vt.vertices[static_cast<std::size_t>(top)].x;
    const double yv = ctx_.vt.vertices[static_cast<std::size_t>(v)].y;
    const ShowEdge& s = ctx_.Edge(a.edge);
    if (!(yv >= s.yBottom && yv <= s.yTop)) return SortKey(a.x);
    const double x = s.XAt(yv);
    return std::isfinite(x) ? x : SortKey(a.x);
}

// The vertex v of scan line j where a toggling stack edge finishes, or −1.
inline int VertexPass::FinishingVertex(const ActiveEdge& a, int j) const {
    if (!a.stackEdge) return -1;
    const auto e = static_cast<std::size_t>(a.edge);
    if (!ctx_.vt.toggling[e]) return -1;
    const int v = ctx_.vt.top[e];
    return v >= 0 && ctx_.vt.vertices[static_cast<std::size_t>(v)].band == j ? v : -1;
}

// Appends an edge to the new AEL (pass one); the first stack edge after a fallback is
// marked for derivation.
inline void VertexPass::Emit(ActiveEdge&& a) {
    ael_.push_back(std::move(a));
    ActiveEdge& b = ael_.back();
    if (!b.Participates()) return;
    if (markOut_) {
        b.MarkCheck();
        markOut_ = false;
    }
    lastPart_ = static_cast<std::ptrdiff_t>(ael_.size()) - 1;
}

// A vertex and, recursively, those linked to it by edges within the scan line; then step
// (3) for all of them: their starting edges enter at CE in x order on row j.
inline void VertexPass::ProcessComponent(int v, int j) {
    const double y = j + 0.5;
    parity_.clear();
    starts_.clear();
    ProcessVertex(v, j, 0);
    newEdges_.clear();
    for (int e : starts_) {
        ActiveEdge a;
        a.edge = e;
        const double last = std::floor(SnapToRow(ctx_.Edge(e).yTop) - 0.5);
        a.lastRow = static_cast<int>(std::min(last, ctx_.frame.height - 1.0));
        a.startRow = j;
        list_.Start(a, y);
        list_.Trace(a, true);
        a.lost = !std::isfinite(a.x);
        a.ending = list_.EndsOnRow(a, j);
        newEdges_.push_back(std::move(a));
    }
    std::stable_sort(
        newEdges_.begin(), newEdges_.end(),
        [](const ActiveEdge& p, const ActiveEdge& q) { return SortKey(p.x) < SortKey(q.x); });
    for (std::size_t k = 0; k < newEdges_.size(); ++k) {
        ActiveEdge& a = newEdges_[k];
        if (a.Participates()) {
            stacks_.AddToggles(parity_, a);
            const ActiveEdge* left =
                lastPart_ >= 0 ? &ael_[static_cast<std::size_t>(lastPart_)] : nullptr;
            if (left && left->derive) {
                a.MarkFresh();  // its left neighbour is re-derived in pass three
            } else {
                stacks_.DeriveFrom(a, left);
            }
        } else {
            a.MarkFresh();  // lost: derived afresh when found
        }
        Emit(std::move(a));
    }
    if (!parity_.empty()) {
        ++ctx_.c.stackVertexFallbacks;
        markOut_ = true;
    }
}

// Steps (1) and (2) of §5.4 for vertex v; step (3) is collected in starts_.
inline void VertexPass::ProcessVertex(int v, int j, int depth) {
    vertexRow_[static_cast<std::size_t>(v)] = j;
    ++ctx_.c.stackVertices;
    if (depth > 0) ++ctx_.c.stackVertexRecursions;
    const RVertex& vx = ctx_.vt.vertices[static_cast<std::size_t>(v)];
    // The finishing edges' places in the AEL, left to right (CE first when it is one).
    found_.clear();
    for (int e : vx.finishing) {
        std::size_t i = ce_;
        while (i < old_.size() && (gone_[i] || old_[i].edge != e)) ++i;
        if (i < old_.size()) found_.push_back(i);  // else: not in the AEL (lost, dropped)
    }
    std::sort(found_.begin(), found_.end());
    for (std::size_t i : found_) {
        // (1) Moved left next to CE by successive swaps: each edge X passed takes the
        // finishing edge's stack, or toggles its faces (the swap rule of pass two).
        for (std::size_t k = i; k-- > ce_;)
            if (!gone_[k] && stacks_.SwapLeft(old_[i], old_[k])) ++ctx_.c.stackDeletionSwaps;
        // ... and deleted. An edge whose top is this row's centre stays a breakpoint for
        // this row (ActiveEdge::ending) but no longer takes part in the stacks.
        ActiveEdge& r = old_[i];
        if (r.Participates()) stacks_.AddToggles(parity_, r);
        gone_[i] = 1;
        r.pending = false;
        if (r.lastRow >= j) {
            r.ending = true;
            Emit(std::move(r));
        }
    }
    // (2) Edges lying within the scan line: their other vertex, recursively.
    for (int h : vx.inBand) {
        const auto he = static_cast<std::size_t>(h);
        if (inBandRow_[he] == j) continue;
        inBandRow_[he] = j;
        const int o = ctx_.vt.bottom[he] == v ? ctx_.vt.top[he] : ctx_.vt.bottom[he];
        if (o >= 0 && vertexRow_[static_cast<std::size_t>(o)] != j) ProcessVertex(o, j, depth + 1);
    }
    // (3) The starting edges (inserted by ProcessComponent).
    for (int e : vx.starting) starts_.push_back(e);
}

}  // namespace quadrix::scanline
