// Sorted lists of closed intervals of the extended reals, the per-ray sets of the raycast engine
// (DESIGN.md "Engines in more detail": union, intersection and difference of sorted interval lists,
// as BRL-CAD's boolean weave does).
//
// Convention (regularised sets). A list stands for a *regular closed* subset of ℝ: a finite union
// of closed intervals [lo, hi] with lo < hi, where lo may be −∞ and hi +∞ (an infinite end is
// simply "unbounded"). The canonical form is sorted and strictly separated:
//     lo₀ < hi₀ < lo₁ < hi₁ < … ,   no NaN.
// Operations return the regularisation (closure of the interior) of the set-theoretic result:
//   - union merges touching intervals: [a,b] ∪ [b,c] = [a,c] (tangent spheres become one piece);
//   - intersection drops isolated points: [a,b] ∩ [b,c] = ∅ (touching solids share no volume);
//   - difference and complement return closures: [a,c] − [b,d] = [a,b] for b < c < d, and
//     the complement of [a,b] is [−∞,a] ∪ [b,+∞].
// This is the 1-D version of the regularised Boolean operations of solid modelling, so a solid's
// boundary points along a ray are exactly the finite interval endpoints.
//
// Ids. Every endpoint carries an int32 id chosen by the caller (the raycast engine stores a literal
// index, from which the half-space and body follow); infinite endpoints carry kNoId. Results keep
// the id of the endpoint that bounds them. Ties are resolved by a fixed symbolic rule, never by an
// epsilon: events at equal t are processed starts before ends, and the left operand before the
// right one; the id recorded is that of the event that changes the result. Hence A ∪ ∅ = A, A ∩ ℝ
// = A, A − ∅ = A exactly (ids included), and left-to-right folds give the same ids whether or not
// empty operands were dropped beforehand (which the engine's bounds culling relies on). Unions and
// intersections are moreover associative ids included; differences are not (where c starts exactly
// where a − b ends, (a − b) − c names c and a − (b ∪ c) names b).
//
// Storage is allocation-light: up to kInlineCapacity intervals live inside the object; longer
// lists move to the heap once and keep that capacity when cleared, so a list reused per pixel does
// not allocate after warm-up. Outputs must not alias inputs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

namespace quadrix {

struct Interval {
    static constexpr std::int32_t kNoId = -1;
    double lo = 0, hi = 0;
    std::int32_t loId = kNoId, hiId = kNoId;
    bool operator==(const Interval&) const = default;
};

class IntervalList {
  public:
    static constexpr std::size_t kInlineCapacity = 4;

    IntervalList() = default;
    IntervalList(const IntervalList& o);
    IntervalList& operator=(const IntervalList& o);
    IntervalList(IntervalList&& o) noexcept;
    IntervalList& operator=(IntervalList&& o) noexcept;
    ~IntervalList() = default;

    // The whole line [−∞, +∞] and a single interval (dropped when lo >= hi).
    static IntervalList All();
    static IntervalList Single(double lo, std::int32_t loId, double hi, std::int32_t hiId);

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    std::size_t capacity() const { return capacity_; }
    const Interval& operator[](std::size_t i) const { return data_[i]; }
    const Interval* begin() const { return data_; }
    const Interval* end() const { return data_ + size_; }
    const Interval& front() const { return data_[0]; }
    const Interval& back() const { return data_[size_ - 1]; }

    void clear() { size_ = 0; }
    // Keeps the first n intervals (n <= size()).
    void Truncate(std::size_t n) { size_ = n; }
    Interval* mutable_data() { return data_; }
    void reserve(std::size_t n);

    // Appends [lo, hi] after the current last interval, keeping the canonical form: an interval
    // with lo >= hi (a point or a NaN) is dropped, and one that touches or overlaps the last
    // interval (lo <= back().hi) is merged into it. Precondition: lo >= back().lo.
    void Append(double lo, std::int32_t loId, double hi, std::int32_t hiId) {  // inline: hot
        if (!(lo < hi))
            return;  // a point, an inverted interval or a NaN: not part of a regular set
        if (size_ > 0 && lo <= data_[size_ - 1].hi) {
            Interval& last = data_[size_ - 1];
            if (hi > last.hi) {
                last.hi = hi;
                last.hiId = hiId;
            }
            return;
        }
        if (size_ == capacity_) Grow(size_ + 1);
        data_[size_++] = Interval{lo, hi, loId, hiId};
    }

    // Replaces the contents by the one interval [lo, hi]; precondition lo < hi (a canonical
    // one-interval set, such as a body batch's kOne pixel).
    void AssignOne(double lo, std::int32_t loId, double hi, std::int32_t hiId) {
        data_[0] = Interval{lo, hi, loId, hiId};  // capacity >= kInlineCapacity >= 1
        size_ = 1;
    }

    // Closed membership: t lies in some [lo, hi].
    bool Contains(double t) const;
    // True when the list is in canonical form (see the file comment); for tests and DCHECKs.
    bool IsCanonical() const;
    bool operator==(const IntervalList& o) const;

  private:
    void Grow(std::size_t minCapacity);

    Interval inline_[kInlineCapacity];
    std::unique_ptr<Interval[]> heap_;
    Interval* data_ = inline_;
    std::size_t size_ = 0;
    std::size_t capacity_ = kInlineCapacity;
};

// Regularised Boolean operations (see the file comment). `out` must not alias an input.
void Union(const IntervalList& a, const IntervalList& b, IntervalList& out);
void Intersection(const IntervalList& a, const IntervalList& b, IntervalList& out);
void Difference(const IntervalList& a, const IntervalList& b, IntervalList& out);  // a − b
void Complement(const IntervalList& a, IntervalList& out);
// In place: list = list ∩ [window.lo, window.hi], the same result as Intersection(list,
// IntervalList with the single interval `window`) ids included, without a second list (the raycast
// engine clips a body's set by each half-line or interval literal this way).
void ClipTo(IntervalList& list, const Interval& window);
// ClipTo's rules for one interval v of a list against the window w, in place: it opens at the
// later start, w's on a tie, and closes at the earlier end, v's on a tie. False when what is left
// is a point or nothing (v is then to be dropped). The bodies of the engines' tracers keep their
// set as one such interval while each literal gives one piece; the batched quadric lanes clip
// their running interval (64-bit ids) by the same rules. V and W: anything with lo, hi, loId, hiId.
template <class V, class W>
inline bool ClipOne(V& v, const W& w) {
    if (!(v.lo > w.lo)) {
        v.lo = w.lo;
        v.loId = w.loId;
    }
    if (!(v.hi <= w.hi)) {
        v.hi = w.hi;
        v.hiId = w.hiId;
    }
    return v.lo < v.hi;
}

// One interval against one interval, the commonest case in the engines' CSG: the sweep's
// result written directly, from the same tie rules (events at equal t: starts before ends, a
// before b); checked against the sweep oracle, ids included, in interval_list_test.cpp. Inline:
// the raycast engine's per-pixel kernel calls them too.

// a ∪ b: opened by the first start (a's on a tie); one piece when the other starts no later than
// the first ends (a start before an end), closed by the last end (b's on a tie).
inline void UnionOfOne(const Interval& a, const Interval& b, IntervalList& out) {
    out.clear();
    const Interval& f = a.lo <= b.lo ? a : b;
    const Interval& g = a.lo <= b.lo ? b : a;
    if (g.lo <= f.hi) {
        const bool bLast = b.hi >= a.hi;
        out.Append(f.lo, f.loId, bLast ? b.hi : a.hi, bLast ? b.hiId : a.hiId);
    } else {
        out.Append(f.lo, f.loId, f.hi, f.hiId);
        out.Append(g.lo, g.loId, g.hi, g.hiId);
    }
}

// a ∩ b: opened by the later start (b's on a tie), closed by the earlier end (a's on a tie);
// Append drops the piece when they meet in a point or not at all.
inline void IntersectionOfOne(const Interval& a, const Interval& b, IntervalList& out) {
    out.clear();
    const bool openB = b.lo >= a.lo, closeA = a.hi <= b.hi;
    out.Append(openB ? b.lo : a.lo, openB ? b.loId : a.loId, closeA ? a.hi : b.hi,
               closeA ? a.hiId : b.hiId);
}

// a − b, appended to `out`. Also the piece of a list minus one interval that comes from one of
// the list's intervals: while the sweep is outside a, b's events emit nothing, so each interval
// of a canonical list can be taken on its own (their results are separated as they are).
inline void AppendDifferenceOfOne(const Interval& a, const Interval& b, IntervalList& out) {
    if (b.lo < a.lo && b.hi >= a.lo) {  // inside b when a starts: a reappears where b ends
        if (b.hi < a.hi) out.Append(b.hi, b.hiId, a.hi, a.hiId);
        return;
    }
    if (b.hi < a.lo || b.lo > a.hi) {  // b entirely before or after a
        out.Append(a.lo, a.loId, a.hi, a.hiId);
        return;
    }
    out.Append(a.lo, a.loId, b.lo, b.loId);  // b starts inside a (or where a ends)
    if (b.hi < a.hi) out.Append(b.hi, b.hiId, a.hi, a.hiId);
}

}  // namespace quadrix
