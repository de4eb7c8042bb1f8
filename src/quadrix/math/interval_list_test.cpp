#include "quadrix/math/interval_list.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <ostream>
#include <random>
#include <vector>

namespace quadrix {

// Readable failure messages (found by ADL from gtest).
void PrintTo(const IntervalList& l, std::ostream* os) {
    *os << "{";
    for (const Interval& v : l)
        *os << " [" << v.lo << "#" << v.loId << ", " << v.hi << "#" << v.hiId << "]";
    *os << " }";
}

namespace {

constexpr double kInf = HUGE_VAL;
constexpr std::int32_t kNo = Interval::kNoId;

IntervalList Make(std::initializer_list<Interval> v) {
    IntervalList l;
    for (const Interval& i : v) l.Append(i.lo, i.loId, i.hi, i.hiId);
    return l;
}

TEST(MathIntervalList, AppendKeepsCanonicalForm) {
    IntervalList l;
    l.Append(1, 10, 1, 11);  // a point: dropped
    EXPECT_TRUE(l.empty());
    l.Append(2, 12, 1, 13);  // inverted: dropped
    l.Append(NAN, 12, 1, 13);
    EXPECT_TRUE(l.empty());
    l.Append(0, 1, 2, 2);
    l.Append(2, 3, 4, 4);    // touches: merged, keeps the outer ids
    l.Append(3, 5, 3.5, 6);  // inside: absorbed
    l.Append(5, 7, 6, 8);
    ASSERT_EQ(l.size(), 2u);
    EXPECT_EQ(l[0], (Interval{0, 4, 1, 4}));
    EXPECT_EQ(l[1], (Interval{5, 6, 7, 8}));
    EXPECT_TRUE(l.IsCanonical());
    EXPECT_TRUE(l.Contains(0));
    EXPECT_TRUE(l.Contains(4));
    EXPECT_FALSE(l.Contains(4.5));
    EXPECT_TRUE(l.Contains(6));
    EXPECT_FALSE(l.Contains(7));
}

TEST(MathIntervalList, TangentPiecesMergeOnUnionAndVanishOnIntersection) {
    IntervalList a = IntervalList::Single(0, 1, 2, 2);
    IntervalList b = IntervalList::Single(2, 3, 5, 4);
    IntervalList out;
    Union(a, b, out);  // two tangent spheres seen through their contact point: one piece
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0], (Interval{0, 5, 1, 4}));
    Intersection(a, b, out);  // they share no volume
    EXPECT_TRUE(out.empty());
    Difference(a, b, out);  // closure: a is unchanged as a set; at the shared t = 2, b's start is
    ASSERT_EQ(out.size(), 1u);  // processed first (starts before ends) and names the end
    EXPECT_EQ(out[0], (Interval{0, 2, 1, 3}));
}

TEST(MathIntervalList, DifferenceAndComplementAreClosures) {
    IntervalList a = IntervalList::Single(0, 1, 10, 2);
    IntervalList b = Make({{2, 4, 3, 4}, {8, 12, 5, 6}});
    IntervalList out;
    Difference(a, b, out);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0], (Interval{0, 2, 1, 3}));  // the hole's walls carry b's ids
    EXPECT_EQ(out[1], (Interval{4, 8, 4, 5}));
    Complement(b, out);
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out[0], (Interval{-kInf, 2, kNo, 3}));
    EXPECT_EQ(out[1], (Interval{4, 8, 4, 5}));
    EXPECT_EQ(out[2], (Interval{12, kInf, 6, kNo}));
    Complement(IntervalList::All(), out);
    EXPECT_TRUE(out.empty());
    Complement(IntervalList(), out);
    EXPECT_EQ(out, IntervalList::All());
    Complement(Make({{-kInf, 1, kNo, 1}}), out);
    EXPECT_EQ(out, Make({{1, kInf, 1, kNo}}));
}

TEST(MathIntervalList, EmptyAndAllAreExactIdentities) {
    IntervalList a = Make({{-kInf, 1, kNo, 1}, {2, 3, 2, 3}, {4, kInf, 4, kNo}});
    IntervalList out;
    Union(a, IntervalList(), out);
    EXPECT_EQ(out, a);
    Union(IntervalList(), a, out);
    EXPECT_EQ(out, a);
    Intersection(a, IntervalList::All(), out);
    EXPECT_EQ(out, a);
    Intersection(IntervalList::All(), a, out);
    EXPECT_EQ(out, a);
    Difference(a, IntervalList(), out);
    EXPECT_EQ(out, a);
    Difference(IntervalList(), a, out);
    EXPECT_TRUE(out.empty());
    Difference(a, IntervalList::All(), out);
    EXPECT_TRUE(out.empty());
}

TEST(MathIntervalList, HeapStorageCopiesAndMoves) {
    IntervalList big;
    for (int i = 0; i < 100; ++i) big.Append(2 * i, i, 2 * i + 1, -i);
    ASSERT_EQ(big.size(), 100u);
    EXPECT_GE(big.capacity(), 100u);
    IntervalList copy = big;
    EXPECT_EQ(copy, big);
    IntervalList moved = std::move(copy);
    EXPECT_EQ(moved, big);
    IntervalList small = IntervalList::Single(0, 1, 1, 2);
    moved = small;  // heap-backed list takes an inline one
    EXPECT_EQ(moved, small);
    small = std::move(big);  // inline list steals a heap buffer
    EXPECT_EQ(small.size(), 100u);
    EXPECT_EQ(small[99], (Interval{198, 199, 99, -99}));
    size_t cap = small.capacity();
    small.clear();
    EXPECT_EQ(small.capacity(), cap);  // cleared lists keep their storage (no per-pixel allocation)
}

// Random lists whose finite endpoints lie on the integers -8..8 (so that ties and touching
// intervals are frequent), sometimes unbounded. Every endpoint gets a unique id; `idT` records
// which t each id was given to, so results can be checked to carry ids of endpoints at their t.
IntervalList RandomList(std::mt19937& rng, std::int32_t& nextId,
                        std::map<std::int32_t, double>& idT) {
    std::uniform_int_distribution<int> count(0, 4), step(0, 3), coin(0, 5);
    IntervalList l;
    int n = count(rng);
    double t = -9 + step(rng);
    for (int i = 0; i < n && t <= 8; ++i) {
        double lo = (i == 0 && coin(rng) == 0) ? -kInf : t;
        double hi = t + 1 + step(rng);
        if (hi > 8 || (i == n - 1 && coin(rng) == 0)) hi = kInf;
        std::int32_t loId = std::isinf(lo) ? kNo : nextId++;
        std::int32_t hiId = std::isinf(hi) ? kNo : nextId++;
        if (loId != kNo) idT[loId] = lo;
        if (hiId != kNo) idT[hiId] = hi;
        l.Append(lo, loId, hi, hiId);
        if (std::isinf(hi)) break;
        t = hi + 1 + step(rng);  // strictly separated, as canonical lists are
    }
    return l;
}

// Regularised membership of op(a, b) at an integer g: the closure of the interior contains g iff
// op holds just left or just right of it (no endpoint lies strictly between g ± 0.25).
bool RegularMember(const IntervalList& a, const IntervalList& b,
                   const std::function<bool(bool, bool)>& op, double g) {
    auto at = [&](double t) { return op(a.Contains(t), b.Contains(t)); };
    return at(g - 0.25) || at(g + 0.25);
}

void CheckIds(const IntervalList& out, const std::map<std::int32_t, double>& idT) {
    for (const Interval& v : out) {
        for (auto [t, id] : {std::pair{v.lo, v.loId}, std::pair{v.hi, v.hiId}}) {
            if (std::isinf(t)) {
                EXPECT_EQ(id, kNo);
            } else {
                ASSERT_TRUE(idT.count(id)) << id;
                EXPECT_EQ(idT.at(id), t);
            }
        }
    }
}

TEST(MathIntervalList, RandomOperationsMatchBruteForceMembership) {
    std::mt19937 rng(3);
    struct Op {
        const char* name;
        void (*fn)(const IntervalList&, const IntervalList&, IntervalList&);
        std::function<bool(bool, bool)> pred;
    };
    const Op ops[] = {{"union", Union, [](bool x, bool y) { return x || y; }},
                      {"intersection", Intersection, [](bool x, bool y) { return x && y; }},
                      {"difference", Difference, [](bool x, bool y) { return x && !y; }}};
    for (int n = 0; n < 3000; ++n) {
        std::int32_t nextId = 0;
        std::map<std::int32_t, double> idT;
        IntervalList a = RandomList(rng, nextId, idT), b = RandomList(rng, nextId, idT);
        ASSERT_TRUE(a.IsCanonical());
        ASSERT_TRUE(b.IsCanonical());
        for (const Op& op : ops) {
            IntervalList out;
            op.fn(a, b, out);
            ASSERT_TRUE(out.IsCanonical()) << op.name;
            CheckIds(out, idT);
            for (double t = -10; t <= 10; t += 0.25) {
                bool expect = std::floor(t) == t ? RegularMember(a, b, op.pred, t)
                                                 : op.pred(a.Contains(t), b.Contains(t));
                ASSERT_EQ(out.Contains(t), expect) << op.name << " at " << t;
            }
        }
        if (b.size() == 1) {  // ClipTo is Intersection with a one-interval list, ids included
            IntervalList clipped = a, expect;
            ClipTo(clipped, b[0]);
            Intersection(a, b, expect);
            ASSERT_EQ(clipped, expect);
        }
        IntervalList c;
        Complement(a, c);
        ASSERT_TRUE(c.IsCanonical());
        CheckIds(c, idT);
        for (double t = -10; t <= 10; t += 0.25) {
            bool expect = std::floor(t) == t ? !a.Contains(t - 0.25) || !a.Contains(t + 0.25)
                                             : !a.Contains(t);
            ASSERT_EQ(c.Contains(t), expect) << "complement at " << t;
        }
    }
}

TEST(MathIntervalList, UnionAndIntersectionFoldsAreAssociativeIdsIncluded) {
    // The engine folds n-ary unions and intersections left to right after dropping culled
    // operands; the symbolic tie rule makes the grouping irrelevant, ids included.
    std::mt19937 rng(5);
    for (int n = 0; n < 3000; ++n) {
        std::int32_t nextId = 0;
        std::map<std::int32_t, double> idT;
        IntervalList a = RandomList(rng, nextId, idT), b = RandomList(rng, nextId, idT),
                     c = RandomList(rng, nextId, idT);
        for (auto fn : {Union, Intersection}) {
            IntervalList ab, bc, left, right;
            fn(a, b, ab);
            fn(ab, c, left);
            fn(b, c, bc);
            fn(a, bc, right);
            ASSERT_EQ(left, right) << testing::PrintToString(a) << testing::PrintToString(b)
                                   << testing::PrintToString(c);
        }
        // (a − b) − c = a − (b ∪ c) as sets. (Not id for id: where c starts exactly where a − b
        // ends, the left grouping names c and the right one b; the engine always folds
        // differences left to right, so only the identity A − ∅ = A matters there.)
        IntervalList ab, left, bc, right;
        Difference(a, b, ab);
        Difference(ab, c, left);
        Union(b, c, bc);
        Difference(a, bc, right);
        ASSERT_EQ(left.size(), right.size());
        for (size_t i = 0; i < left.size(); ++i) {
            EXPECT_EQ(left[i].lo, right[i].lo);
            EXPECT_EQ(left[i].hi, right[i].hi);
        }
    }
}

// The tie rules of the file comment as an independent oracle: every endpoint of both operands
// becomes an event, the events are sorted by (t, starts before ends, a before b, list order), and
// one pass emits the pieces where op holds, naming each end by the event that opened or closed
// it. The library's sweep must give the same lists, ids included, on random lists full of ties.
namespace {
struct Event {
    double t;
    bool start;
    int operand;  // 0 = a, 1 = b
    std::size_t order;
    std::int32_t id;
};
IntervalList OracleSweep(const IntervalList& a, const IntervalList& b,
                         const std::function<bool(bool, bool)>& op) {
    std::vector<Event> ev;
    for (int o = 0; o < 2; ++o) {
        const IntervalList& l = o == 0 ? a : b;
        for (std::size_t i = 0; i < l.size(); ++i) {
            ev.push_back({l[i].lo, true, o, 2 * i, l[i].loId});
            ev.push_back({l[i].hi, false, o, 2 * i + 1, l[i].hiId});
        }
    }
    std::sort(ev.begin(), ev.end(), [](const Event& p, const Event& q) {
        if (p.t != q.t) return p.t < q.t;
        if (p.start != q.start) return p.start;
        if (p.operand != q.operand) return p.operand < q.operand;
        return p.order < q.order;
    });
    IntervalList out;
    bool in[2] = {false, false}, inOut = false;
    double startT = 0;
    std::int32_t startId = kNo;
    for (const Event& e : ev) {
        in[e.operand] = e.start;
        const bool now = op(in[0], in[1]);
        if (now == inOut) continue;
        inOut = now;
        if (now) {
            startT = e.t;
            startId = e.id;
        } else {
            out.Append(startT, startId, e.t, e.id);
        }
    }
    return out;
}
}  // namespace

TEST(MathIntervalList, SweepMatchesTheTieRuleOracleIdsIncluded) {
    std::mt19937 rng(11);
    for (int n = 0; n < 5000; ++n) {
        std::int32_t nextId = 0;
        std::map<std::int32_t, double> idT;
        IntervalList a = RandomList(rng, nextId, idT), b = RandomList(rng, nextId, idT);
        IntervalList u, i, d;
        Union(a, b, u);
        Intersection(a, b, i);
        Difference(a, b, d);
        ASSERT_EQ(u, OracleSweep(a, b, [](bool x, bool y) { return x || y; }));
        ASSERT_EQ(i, OracleSweep(a, b, [](bool x, bool y) { return x && y; }));
        ASSERT_EQ(d, OracleSweep(a, b, [](bool x, bool y) { return x && !y; }));
    }
}

// Lists against one interval (the engine's commonest multi-piece case: a body with holes minus
// the next hole), on random lists full of ties.
TEST(MathIntervalList, ListAgainstOneMatchesTheOracle) {
    std::mt19937 rng(17);
    int checked = 0;
    for (int n = 0; n < 20000; ++n) {
        std::int32_t nextId = 0;
        std::map<std::int32_t, double> idT;
        IntervalList a = RandomList(rng, nextId, idT), b = RandomList(rng, nextId, idT);
        if (b.size() != 1 || a.size() < 2) continue;
        ++checked;
        IntervalList i, d;
        Intersection(a, b, i);
        Difference(a, b, d);
        ASSERT_EQ(i, OracleSweep(a, b, [](bool x, bool y) { return x && y; }));
        ASSERT_EQ(d, OracleSweep(a, b, [](bool x, bool y) { return x && !y; }));
    }
    EXPECT_GT(checked, 1000);
}

// Every pair of single intervals with ends on a small grid (ties of every kind, unbounded ends):
// the one-interval fast paths give the oracle's lists, ids included.
TEST(MathIntervalList, OneAgainstOneMatchesTheOracleExhaustively) {
    const double grid[] = {-kInf, 0, 1, 2, 3, kInf};
    std::vector<IntervalList> singles;
    std::int32_t id = 0;
    for (double lo : grid)
        for (double hi : grid)
            if (lo < hi && !(std::isinf(lo) && lo > 0) && !(std::isinf(hi) && hi < 0)) {
                const std::int32_t loId = std::isinf(lo) ? kNo : id++;
                const std::int32_t hiId = std::isinf(hi) ? kNo : id++;
                singles.push_back(IntervalList::Single(lo, loId, hi, hiId));
            }
    ASSERT_GT(singles.size(), 12u);
    for (const IntervalList& a : singles) {
        for (const IntervalList& b : singles) {
            IntervalList u, i, d;
            Union(a, b, u);
            Intersection(a, b, i);
            Difference(a, b, d);
            ASSERT_EQ(u, OracleSweep(a, b, [](bool x, bool y) { return x || y; }));
            ASSERT_EQ(i, OracleSweep(a, b, [](bool x, bool y) { return x && y; }));
            ASSERT_EQ(d, OracleSweep(a, b, [](bool x, bool y) { return x && !y; }));
        }
    }
}

}  // namespace
}  // namespace quadrix
