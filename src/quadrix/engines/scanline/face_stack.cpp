#include "quadrix/engines/scanline/face_stack.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "quadrix/engines/scanline/stack_verifier.h"
#include "quadrix/math/interval_list.h"

namespace quadrix::scanline {

// Is show-face f in front of g at the crossing P = (xe, y)? (§5.5.1.) The lesser depth at P
// decides; equal within the scene's depth tolerance (or a face without a point at P, e.g. a
// limb crossing rounded just outside the sheet), case (a): depth at Q, the point half-way to
// the next crossing (at most ½ pixel on — the scan-line analogue of "where E meets the next
// scan line", since our stacks are swept along the CSL); equal again, case (b): the lesser
// slope dz/dx at Q; then case (c): the lesser rate d²z/dx² at Q. −1: f in front, +1: g in
// front, 0: coincident (order unimportant, f goes below).
int FaceOrder::CompareAt(int f, int g, double xe, double xq, double y) {
    const FaceRef fr = ctx_.RefOf(f), gr = ctx_.RefOf(g);
    double zf, sf, cf, zg, sg, cg;
    auto tol = [&](double a, double b) {
        return ctx_.scene.depthTolerance * (1 + std::max(std::fabs(a), std::fabs(b)));
    };
    ++ctx_.c.depthCalcs;
    if (FaceDerivatives(ctx_.scene, fr, xe, y, zf, sf, cf) &&
        FaceDerivatives(ctx_.scene, gr, xe, y, zg, sg, cg) && std::fabs(zf - zg) > tol(zf, zg))
        return zf < zg ? -1 : 1;
    ++ctx_.c.stackTieBreaks;
    const bool hf = FaceDerivatives(ctx_.scene, fr, xq, y, zf, sf, cf);
    const bool hg = FaceDerivatives(ctx_.scene, gr, xq, y, zg, sg, cg);
    if (!hf || !hg) return hf ? -1 : (hg ? 1 : 0);  // a face without a point at Q is behind
    if (std::fabs(zf - zg) > tol(zf, zg)) return zf < zg ? -1 : 1;  // (a)
    if (std::fabs(sf - sg) > tol(sf, sg)) return sf < sg ? -1 : 1;  // (b)
    if (std::fabs(cf - cg) > tol(cf, cg)) return cf < cg ? -1 : 1;  // (c)
    return 0;
}

// Insertion into stack `st` in depth order: below every face it is not in front of,
// scanning from the head. Bodies of different solids may interpenetrate without a show-edge
// (the paper's scenes had none), so the order between faces of DIFFERENT bodies can go stale;
// the order among one body's faces cannot (their crossings are i-lines, hence show-edges).
// So the face is also kept below every face of its own body that is in front of it: each
// body's first face on a stack is then that body's visible face whatever the others do.
void FaceOrder::InsertInto(std::vector<int>& st, int f, double xe, double xq, double y) {
    std::size_t pos = st.size();
    for (std::size_t s = 0; s < st.size(); ++s) {
        if (CompareAt(f, st[s], xe, xq, y) < 0) {
            pos = s;
            break;
        }
    }
    const int body = ctx_.Face(f).body;
    for (std::size_t s = pos + 1; s < st.size(); ++s) {
        const int g = st[s];
        if (ctx_.Face(g).body == body && CompareAt(f, g, xe, xq, y) > 0) pos = s + 1;
    }
    st.insert(st.begin() + static_cast<std::ptrdiff_t>(pos), f);
    ctx_.c.stackMaxDepth = std::max<std::uint64_t>(ctx_.c.stackMaxDepth, st.size());
}

// Adds edge a's faces to a list of faces to toggle (two toggles of one face cancel).
void FaceStacks::AddToggles(std::vector<int>& t, const ActiveEdge& a) const {
    for (int f : ctx_.Edge(a.edge).faces) {
        if (f < 0) continue;
        auto it = std::find(t.begin(), t.end(), f);
        if (it != t.end())
            t.erase(it);
        else
            t.push_back(f);
    }
}

// The swap rule (§5.3), for pass two's sort and pass one's deletion swaps: edge e moves left
// past its neighbour x. The region right of x is now the one that was right of e: x takes
// e's stack as it is (depth order included). e's own stack is then its new left
// neighbour's ⊕ its faces (`pending`); if e moves on past another edge, that edge takes this
// stack, which is its own ⊕ e's faces: they are toggled in its stack in place. True when a
// stack changed (both edges take part in the stacks).
bool FaceStacks::SwapLeft(ActiveEdge& e, ActiveEdge& x) {
    if (!e.Participates() || !x.Participates()) return false;
    if (e.derive) {  // e's stack is not valid (a fallback): x is derived again too
        x.derive = true;
        x.carriedValid = false;
        x.propagate = x.propagate || e.propagate;
        e.pending = false;
        return true;
    }
    if (!e.pending) {
        std::swap(x.stack, e.stack);
        std::swap(x.toggles, e.toggles);
        x.carriedValid = true;  // x keeps any derive mark it had
        e.pending = true;
    } else {
        AddToggles(x.toggles, e);
    }
    return true;
}

// a's stack from its left neighbour's (S0 when `left` is null) ⊕ a's faces, as a set: the
// faces to toggle wait in a.toggles for pass three (ResolveToggles).
void FaceStacks::DeriveFrom(ActiveEdge& a, const ActiveEdge* left) {
    ++ctx_.c.stackDerivations;
    if (left) {
        a.stack.assign(left->stack.begin(), left->stack.end());
        a.toggles.assign(left->toggles.begin(), left->toggles.end());
    } else {
        a.stack.assign(seed_.begin(), seed_.end());
        a.toggles.clear();
    }
    AddToggles(a.toggles, a);
    a.carriedValid = true;
    a.pending = false;
}

// The mover's stack at the end of its move: its left neighbour's ⊕ its faces.
void FaceStacks::ResolvePending(std::size_t k) {
    ActiveEdge& a = ael_[k];
    a.pending = false;
    if (a.derive) return;  // derived in pass three
    const ActiveEdge* left = nullptr;
    for (std::size_t p = k; p-- > 0;)
        if (ael_[p].Participates()) {
            left = &ael_[p];
            break;
        }
    if (left && left->derive) {
        a.MarkFresh();
        return;
    }
    DeriveFrom(a, left);
}

// The stack left of every crossing of the row (S0): empty except for faces of bodies that
// reach the image's left side, which may be unbounded to the left (a half-space, a
// paraboloid); their faces there are the finite opaque endpoints of the body on the ray at
// xs, found by one exact evaluation per such body and row. A body can leave or enter S0
// without any show-edge (a horizontal boundary far left), so S0 is evaluated on every row;
// when it changed, the first stack edge is derived again.
void FaceStacks::SeedStack(const std::vector<int>& activeUnits, double y) {
    seedPrev_.swap(seed_);
    seed_.clear();
    aelPos_ = 0;
    cur_ = &seed_;
    double first = HUGE_VAL;
    for (const ActiveEdge& a : ael_)
        if (std::isfinite(a.x)) {
            first = a.x;
            break;
        }
    const double xs = std::min(first, 0.5) - 1;
    IntervalList l;
    for (int u : activeUnits) {
        const Unit& unit = ctx_.UnitOf(u);
        if (unit.kind != Unit::Kind::kBody || unit.x0 != 0) continue;
        const auto b = static_cast<std::size_t>(unit.body);
        if (!ctx_.useStack[b]) continue;
        ++ctx_.c.stackSeedEvaluations;
        ctx_.eval.BodySet(unit.body, xs, y, l);
        for (const Interval& v : l) {
            for (auto [t, id] : {std::pair{v.lo, v.loId}, std::pair{v.hi, v.hiId}}) {
                if (id < 0 || !std::isfinite(t)) continue;
                const int hs = ctx_.eval.TagHalfSpace(id);
                const int sheet = ctx_.eval.SheetOf(hs, t, xs, y);
                for (int f : ctx_.bodyFaces[b]) {
                    if (ctx_.Face(f).halfSpace != hs || ctx_.SheetOf(f) != sheet ||
                        Contains(seed_, f))
                        continue;
                    order_.InsertInto(seed_, f, xs, xs + 0.5, y);
                }
            }
        }
    }
    markNext_ = !SameSet(seed_, seedPrev_);
    closedAdd_.clear();
    closedDrop_.clear();
    shown_ = cur_;
}

// Pass three up to x: every AEL edge with a crossing left of x is walked. Crossings closer
// than kCluster to their neighbour form one event (a vertex on the CSL, or edges meeting
// just off it): the event's faces are checked together at Q, half-way from its last
// crossing to the next one (at most ½ px on), so that the face test at Q is never made in a
// sliver narrower than its own error estimate. True when an event straddles x (the pixel
// is then evaluated exactly: it lies within kCluster of a crossing).
bool FaceStacks::ApplyEdgesBefore(double x, double y) {
    constexpr double kCluster = 1e-4;  // pixels
    bool straddle = false;
    const std::size_t n = ael_.size();
    while (aelPos_ < n && std::isfinite(ael_[aelPos_].x) && ael_[aelPos_].x < x) {
        std::size_t end = aelPos_ + 1;
        while (end < n && std::isfinite(ael_[end].x) && ael_[end].x - ael_[end - 1].x < kCluster)
            ++end;
        const double last = ael_[end - 1].x;
        straddle = straddle || last >= x;
        double next = last + 1;
        if (end < n && std::isfinite(ael_[end].x)) next = std::min(next, ael_[end].x);
        const double xq = 0.5 * (last + next);
        ApplyEvent(aelPos_, end, xq, y);
        aelPos_ = end;
    }
    return straddle;
}

// One event (crossings [b, e) of the AEL): derive the stacks marked in pass one/two from
// the left neighbour's, then verify the event's resulting stack.
inline void FaceStacks::ApplyEvent(std::size_t b, std::size_t e, double xq, double y) {
    const std::vector<int>* before = cur_;
    std::size_t last = e;
    bool ending = false;
    for (std::size_t k = b; k < e; ++k) {
        ActiveEdge& a = ael_[k];
        ending = ending || (a.stackEdge && !a.lost && a.ending);
        if (!a.Participates()) continue;
        if (markNext_) {
            a.MarkCheck();
            markNext_ = false;
        }
        // Q of an edge inside the event lies in its own (narrow) region, up to the next
        // crossing: its stack is carried to rows where that region is wide.
        const double q = k + 1 < e ? 0.5 * (a.x + ael_[k + 1].x) : xq;
        if (!a.toggles.empty()) ResolveToggles(a, q, y);
        if (a.derive) DeriveEdge(a, *cur_, q, y);
        cur_ = &a.stack;
        last = k;
    }
    if (last != e) {
        if (ctx_.settings.checkStacks && verifier_.VerifyEvent(*before, ael_, b, e, last, xq, y))
            markNext_ = true;  // the stack was rebuilt: derive the next one too
        cur_ = &ael_[last].stack;
    }
    if (ending && ctx_.settings.checkStacks) UpdateClosedRowFaces(b, e, xq, y);
    if (last != e || ending) ShowStack(ael_[e - 1].x, xq, y);
}

// Edges whose top end lies exactly on this row's centre no longer toggle (half-open rule,
// ActiveEdge::ending), which is right for the carried stacks: below the row the boundary
// has ended. But raycast's half-spaces are closed, so on the row itself a face bounded there
// may still be on its body's boundary: a box whose bottom side y = j + ½ is an edge-on plane
// covers row j. The face test at Q decides these faces for this row only: they are shown in
// the span stacks (`shown_`) without entering the carried ones (closedRowFaces counts them).
inline void FaceStacks::UpdateClosedRowFaces(std::size_t b, std::size_t e, double xq, double y) {
    for (std::size_t k = b; k < e; ++k) {
        const ActiveEdge& a = ael_[k];
        if (!(a.stackEdge && !a.lost && a.ending)) continue;
        for (int f : ctx_.Edge(a.edge).faces) {
            if (f < 0) continue;
            const bool present = verifier_.PresentAt(f, xq, y);
            const bool carried = Contains(*cur_, f);
            auto add = std::find(closedAdd_.begin(), closedAdd_.end(), f);
            auto drop = std::find(closedDrop_.begin(), closedDrop_.end(), f);
            if (add != closedAdd_.end()) closedAdd_.erase(add);
            if (drop != closedDrop_.end()) closedDrop_.erase(drop);
            if (present == carried) continue;
            ++ctx_.c.closedRowFaces;
            (present ? closedAdd_ : closedDrop_).push_back(f);
        }
    }
}

// The stack the spans after this event are drawn from: the carried one, adjusted by the
// closed-row faces when there are any on this row.
inline void FaceStacks::ShowStack(double xe, double xq, double y) {
    if (closedAdd_.empty() && closedDrop_.empty()) {
        shown_ = cur_;
        return;
    }
    showBuf_.clear();
    for (int f : *cur_)
        if (!Contains(closedDrop_, f)) showBuf_.push_back(f);
    for (int f : closedAdd_)
        if (!Contains(showBuf_, f)) order_.InsertInto(showBuf_, f, xe, xq, y);
    shown_ = &showBuf_;
}

// Pass three, at a's crossing: the faces waiting in a.toggles leave a's stack or enter it in
// depth order (§5.5.1 at the crossing and at Q).
inline void FaceStacks::ResolveToggles(ActiveEdge& a, double xq, double y) {
    for (int f : a.toggles) {
        auto it = std::find(a.stack.begin(), a.stack.end(), f);
        if (it != a.stack.end()) {
            a.stack.erase(it);
            ++ctx_.c.stackDeriveDeletes;
        } else {
            order_.InsertInto(a.stack, f, a.x, xq, y);
            ++ctx_.c.stackDeriveInserts;
        }
    }
    a.toggles.clear();
}

// Pass three's derivation (the REBUILD, used where pass one and two cannot carry the
// stacks): the stack of edge a from its left neighbour's stack `prev` — the faces of a that
// are on prev leave, the others enter in depth order (§5.5.1 at the crossing and at Q); a
// show-edge's two faces change sides at it. Used for every stack at a band's first row, and
// afterwards only for marked edges: after a vertex fallback (VertexPass), when S0 changed
// (SeedStack), and for conic legs lost to rounding and found again (TraceAndSort). With
// `propagate`, a derived set that differs from the carried one marks the next stack edge,
// so the change is carried right until a derived stack equals the carried one.
inline void FaceStacks::DeriveEdge(ActiveEdge& a, const std::vector<int>& prev, double xq,
                                   double y) {
    ++ctx_.c.stackDerivations;
    if (!bandStartRow_) ++ctx_.c.stackRebuilds;
    a.toggles.clear();
    derived_.assign(prev.begin(), prev.end());
    const ShowEdge& e = ctx_.Edge(a.edge);
    for (int f : e.faces) {
        if (f < 0) continue;
        auto it = std::find(derived_.begin(), derived_.end(), f);
        if (it != derived_.end()) {
            derived_.erase(it);
            ++ctx_.c.stackDeriveDeletes;
        } else {
            order_.InsertInto(derived_, f, a.x, xq, y);
            ++ctx_.c.stackDeriveInserts;
        }
    }
    const bool changed = !a.carriedValid || !SameSet(derived_, a.stack);
    if (a.propagate && changed) markNext_ = true;
    if (changed) ++ctx_.c.stackDerivationsChanged;
    a.stack.swap(derived_);
    a.derive = false;
    a.carriedValid = true;
    a.propagate = false;
}

}  // namespace quadrix::scanline
