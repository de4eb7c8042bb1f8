#include "quadrix/math/interval_list.h"

#include <algorithm>
#include <cmath>

namespace quadrix {

IntervalList::IntervalList(const IntervalList& o) { *this = o; }

IntervalList& IntervalList::operator=(const IntervalList& o) {
    if (this == &o) return *this;
    size_ = 0;
    reserve(o.size_);
    std::copy(o.data_, o.data_ + o.size_, data_);
    size_ = o.size_;
    return *this;
}

IntervalList::IntervalList(IntervalList&& o) noexcept { *this = std::move(o); }

IntervalList& IntervalList::operator=(IntervalList&& o) noexcept {
    if (this == &o) return *this;
    if (o.heap_) {
        heap_ = std::move(o.heap_);
        data_ = heap_.get();
        capacity_ = o.capacity_;
        o.data_ = o.inline_;
        o.capacity_ = kInlineCapacity;
    } else {
        // o's intervals are inline: copy them into our storage (inline fits, heap fits too).
        std::copy(o.data_, o.data_ + o.size_, data_);
    }
    size_ = o.size_;
    o.size_ = 0;
    return *this;
}

IntervalList IntervalList::All() {
    IntervalList r;
    r.Append(-HUGE_VAL, Interval::kNoId, HUGE_VAL, Interval::kNoId);
    return r;
}

IntervalList IntervalList::Single(double lo, std::int32_t loId, double hi, std::int32_t hiId) {
    IntervalList r;
    r.Append(lo, loId, hi, hiId);
    return r;
}

void IntervalList::reserve(std::size_t n) {
    if (n > capacity_) Grow(n);
}

void IntervalList::Grow(std::size_t minCapacity) {
    std::size_t cap = std::max(minCapacity, 2 * capacity_);
    std::unique_ptr<Interval[]> h(new Interval[cap]);
    std::copy(data_, data_ + size_, h.get());
    heap_ = std::move(h);
    data_ = heap_.get();
    capacity_ = cap;
}

bool IntervalList::Contains(double t) const {
    // Lists are short; a linear scan beats a binary search in practice.
    for (std::size_t i = 0; i < size_; ++i) {
        if (t < data_[i].lo) return false;
        if (t <= data_[i].hi) return true;
    }
    return false;
}

bool IntervalList::IsCanonical() const {
    for (std::size_t i = 0; i < size_; ++i) {
        const Interval& v = data_[i];
        if (std::isnan(v.lo) || std::isnan(v.hi) || !(v.lo < v.hi)) return false;
        if (i > 0 && !(data_[i - 1].hi < v.lo)) return false;
        if (v.lo == HUGE_VAL || v.hi == -HUGE_VAL) return false;
    }
    return true;
}

bool IntervalList::operator==(const IntervalList& o) const {
    return size_ == o.size_ && std::equal(data_, data_ + size_, o.data_);
}

namespace {

// The endpoints of a canonical list as a stream of events: endpoint k is interval k/2's lo (a
// start) when k is even and its hi (an end) when k is odd. The current event's t, id and kind
// are kept in members, updated once per step (the sweep compares them at every step).
struct Cursor {
    const Interval* it;
    const Interval* end;
    double t = 0;
    std::int32_t id = Interval::kNoId;
    bool start = true;  // the current event is it->lo (else it->hi)
    bool done = false;

    explicit Cursor(const IntervalList& l) : it(l.begin()), end(l.end()) {
        done = it == end;
        if (!done) {
            t = it->lo;
            id = it->loId;
        }
    }
    void Next() {
        if (start) {
            start = false;
            t = it->hi;
            id = it->hiId;
            return;
        }
        start = true;
        if (++it == end) {
            done = true;
            return;
        }
        t = it->lo;
        id = it->loId;
    }
};

// The boolean sweep ("weave"): walks the endpoints of both lists in increasing t and emits the
// pieces where op(inA, inB) holds. Ties: starts before ends (so touching intervals stay joined
// while they are being united, and a touching point of an intersection opens and closes a
// degenerate piece that Append drops), and a before b. Requires op(false, false) == false.
template <class Op>
void Sweep(const IntervalList& a, const IntervalList& b, IntervalList& out, Op op) {
    out.clear();
    Cursor ca(a), cb(b);
    bool inA = false, inB = false, inOut = false;
    double startT = 0;
    std::int32_t startId = Interval::kNoId;
    while (!ca.done || !cb.done) {
        bool takeA;
        if (cb.done) {
            takeA = true;
        } else if (ca.done) {
            takeA = false;
        } else {
            takeA = ca.t != cb.t ? ca.t < cb.t : (ca.start || !cb.start);
        }
        Cursor& c = takeA ? ca : cb;
        const double t = c.t;
        const std::int32_t id = c.id;
        (takeA ? inA : inB) = c.start;
        c.Next();
        const bool now = op(inA, inB);
        if (now == inOut) continue;
        inOut = now;
        if (now) {
            startT = t;
            startId = id;
        } else {
            out.Append(startT, startId, t, id);
        }
    }
}

}  // namespace

void Union(const IntervalList& a, const IntervalList& b, IntervalList& out) {
    if (b.empty()) {
        out = a;
    } else if (a.empty()) {
        out = b;
    } else if (a.size() == 1 && b.size() == 1) {
        UnionOfOne(a[0], b[0], out);
    } else {
        Sweep(a, b, out, [](bool x, bool y) { return x || y; });
    }
}

void Intersection(const IntervalList& a, const IntervalList& b, IntervalList& out) {
    if (a.empty() || b.empty()) {
        out.clear();
    } else if (a.size() == 1 && b.size() == 1) {
        IntersectionOfOne(a[0], b[0], out);
    } else if (b.size() == 1) {  // ClipTo is this intersection, ids included (tested)
        out = a;
        ClipTo(out, b[0]);
    } else {
        Sweep(a, b, out, [](bool x, bool y) { return x && y; });
    }
}

void Difference(const IntervalList& a, const IntervalList& b, IntervalList& out) {
    if (a.empty() || b.empty()) {
        out = a;
    } else if (b.size() == 1) {
        out.clear();
        for (const Interval& v : a) AppendDifferenceOfOne(v, b[0], out);
    } else {
        Sweep(a, b, out, [](bool x, bool y) { return x && !y; });
    }
}

void ClipTo(IntervalList& list, const Interval& w) {
    // The sweep's tie rules for one interval v of the list (operand a) against w (operand b):
    // it opens at the later start, w's on a tie (a's start is processed first, but only w's start
    // makes the result true); it closes at the earlier end, v's on a tie (a's end comes first).
    // A piece that shrinks to a point is dropped. Pieces stay sorted and separated.
    Interval* d = list.mutable_data();
    std::size_t n = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
        Interval v = d[i];
        if (v.hi < w.lo) continue;
        if (v.lo > w.hi) break;
        if (ClipOne(v, w)) d[n++] = v;
    }
    list.Truncate(n);
}

void Complement(const IntervalList& a, IntervalList& out) {
    out.clear();
    double lo = -HUGE_VAL;
    std::int32_t loId = Interval::kNoId;
    for (const Interval& v : a) {
        out.Append(lo, loId, v.lo, v.loId);  // drops the empty piece before a leading −∞
        lo = v.hi;
        loId = v.hiId;
    }
    out.Append(lo, loId, HUGE_VAL, Interval::kNoId);
}

}  // namespace quadrix
