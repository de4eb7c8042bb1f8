#include "quadrix/engines/scanline/edge_list.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "quadrix/engines/scanline/coefficients.h"
#include "quadrix/engines/scanline/face_stack.h"
#include "quadrix/engines/scanline/vertex_table.h"

namespace quadrix::scanline {

EdgeStartList BuildEsl(const std::vector<ShowEdge>& edges, int h) {
    EdgeStartList esl(static_cast<std::size_t>(std::max(h, 0)));
    for (std::size_t e = 0; e < edges.size(); ++e) {
        const ShowEdge& s = edges[e];
        if (s.horizontal) continue;  // never active: it only links its vertices (§5.4)
        // Rows whose centre j + ½ lies in the CLOSED range [yBottom, yTop]: a row exactly on a
        // horizontal boundary keeps the edges that end there, so the bodies they bound stay
        // candidates on that row (raycast's closed half-spaces decide it at the sample pixel).
        // Crossings are breakpoints, not parity toggles, so the duplicate crossing at a vertex
        // shared by two edges is harmless.
        double first = std::ceil(SnapToRow(s.yBottom) - 0.5);
        double last = std::floor(SnapToRow(s.yTop) - 0.5);
        first = std::max(first, 0.0);
        last = std::min(last, static_cast<double>(h - 1));
        if (!(first <= last)) continue;
        esl[static_cast<std::size_t>(first)].push_back(
            {static_cast<int>(e), static_cast<int>(last)});
    }
    return esl;
}

void ActiveEdgeList::DropFinishingEdges(int j) {
    std::size_t keep = 0;
    for (std::size_t i = 0; i < ael_.size(); ++i) {
        if (ael_[i].lastRow < j) continue;
        if (keep != i) ael_[keep] = std::move(ael_[i]);
        ++keep;
    }
    ael_.resize(keep);
}

// Pass two: x on the new CSL (conic edges by differences; edges that entered in pass one are
// there already), then x order by adjacent swaps (insertion sort) with the swap rule: the
// mover's own stack is derived from its new left neighbour's when its move ends. Edges whose
// x stops being finite ("lost") leave the structure like finishing edges and "found" ones
// re-enter like new ones, both by derivation in pass three (a fallback: a leg traced past
// its VEXTRM by rounding).
void ActiveEdgeList::TraceAndSort(int j, FaceStacks& stacks) {
    bool pending = false;
    for (ActiveEdge& a : ael_) {
        if (a.startRow == j) continue;
        const bool wasLost = a.lost;
        Trace(a, false);
        const bool lost = !std::isfinite(a.x);
        if (!a.stackEdge) {
            a.lost = lost;
            continue;
        }
        if (lost && !wasLost) {
            a.lost = true;
            pending = true;
        } else if (!lost && wasLost) {
            a.found = true;  // stays transparent during the sort; fresh after it
        } else if (!lost && pending) {
            a.MarkCheck();
            pending = false;
        }
    }
    const std::size_t n = ael_.size();
    for (std::size_t i = 1; i < n; ++i) {
        std::size_t k = i;
        while (k > 0 && SortKey(ael_[k - 1].x) > SortKey(ael_[k].x)) {
            std::swap(ael_[k - 1], ael_[k]);  // the mover is now at k − 1, the edge passed at k
            if (stacks.SwapLeft(ael_[k - 1], ael_[k])) ++ctx_.c.stackSwapUpdates;
            --k;
            ++ctx_.c.edgeSwaps;
        }
        if (ael_[k].pending) stacks.ResolvePending(k);
    }
    for (ActiveEdge& a : ael_) {
        if (!a.found) continue;
        a.found = false;
        a.lost = false;
        a.MarkFresh();
    }
}

// The other starting edges (of CSG operands and refused bodies, and stack edges that toggle on no
// row; at a band's first row every edge that started on an earlier row and is still active):
// merged into x order without swaps. At a band's first row every stack is derived in pass three
// from the left neighbour's (MarkFresh).
void ActiveEdgeList::MergeStartingEdges(int j, bool bandStart) {
    const double yc = j + 0.5;
    starting_.clear();
    for (int r = bandStart ? 0 : j; r <= j; ++r) {
        for (auto [e, last] : (*esl_)[static_cast<std::size_t>(r)]) {
            if (last < j) continue;
            if (ctx_.stackOn && !bandStart && ctx_.vt.toggling[static_cast<std::size_t>(e)])
                continue;  // entered in pass one
            ActiveEdge a;
            a.edge = e;
            a.startRow = j;
            a.lastRow = last;
            Start(a, yc);
            Trace(a, true);
            a.lost = !std::isfinite(a.x);
            a.ending = EndsOnRow(a, j);
            a.MarkFresh();
            starting_.push_back(std::move(a));
        }
    }
    if (!starting_.empty()) {  // merged in: O(AEL + starting), not a swap per edge passed
        std::stable_sort(
            starting_.begin(), starting_.end(),
            [](const ActiveEdge& p, const ActiveEdge& q) { return SortKey(p.x) < SortKey(q.x); });
        merged_.clear();
        merged_.reserve(ael_.size() + starting_.size());
        std::size_t p = 0, q = 0;
        while (p < ael_.size() || q < starting_.size()) {
            const bool takeOld = q == starting_.size() ||
                                 (p < ael_.size() && SortKey(ael_[p].x) <= SortKey(starting_[q].x));
            merged_.push_back(std::move(takeOld ? ael_[p++] : starting_[q++]));
        }
        ael_.swap(merged_);
    }
}

}  // namespace quadrix::scanline
