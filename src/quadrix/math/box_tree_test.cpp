// The box tree (box_tree.h): its queries visit every item whose own box test passes (boxes of
// all kinds: finite, unbounded, empty, NaN), stop when asked, and visit few items of a sparse
// scene.
#include "quadrix/math/box_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

namespace quadrix {
namespace {

std::vector<Box3> RandomBoxes(int n, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-100, 100), size(0, 6);
    std::vector<Box3> boxes;
    for (int i = 0; i < n; ++i) {
        Box3 b;
        for (int k = 0; k < 3; ++k) {
            b.lo[k] = u(rng);
            b.hi[k] = b.lo[k] + size(rng);
        }
        switch (i % 50) {
            case 7:
                b.lo.z = -HUGE_VAL;  // unbounded in depth (a ground plane)
                break;
            case 13:
                b.hi.x = HUGE_VAL;
                b.lo.y = -HUGE_VAL;
                break;
            case 21:
                b = Box3{};  // empty
                break;
            case 33:
                b.lo.y = std::nan("");
                break;
            default:
                break;
        }
        boxes.push_back(b);
    }
    return boxes;
}

bool ColumnHits(const Box3& b, double x, double y) {
    return !(x < b.lo.x || x > b.hi.x || y < b.lo.y || y > b.hi.y);
}

TEST(BoxTree, QueriesVisitEveryItemWhoseBoxPasses) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-110, 110), dir(-1, 1);
    for (int n : {0, 1, 3, 4, 5, 17, 600}) {
        const std::vector<Box3> boxes = RandomBoxes(n, rng);
        const BoxTree tree(boxes);
        EXPECT_EQ(tree.size(), static_cast<std::size_t>(n));
        std::size_t visitedTotal = 0, passedTotal = 0;
        for (int q = 0; q < 300; ++q) {
            const Vec3 p{u(rng), u(rng), u(rng)};
            Vec3 d{dir(rng), dir(rng), dir(rng)};
            if (q % 10 == 0) d.x = 0;  // axis-parallel rays take the d = 0 branch
            if (q % 10 == 1) d = {0, 0, 1};
            const double s1 = q % 3 ? HUGE_VAL : 40.0;
            std::set<std::int32_t> seen;
            tree.Segment(p, d, 1e-6, s1, [&](std::int32_t k) {
                EXPECT_TRUE(seen.insert(k).second) << "visited twice";
                return false;
            });
            for (int k = 0; k < n; ++k)
                if (BoxTree::SegmentHitsBox(boxes[static_cast<std::size_t>(k)], p, d, 1e-6, s1)) {
                    EXPECT_TRUE(seen.count(k)) << n << " " << q << " " << k;
                    ++passedTotal;
                }
            visitedTotal += seen.size();
            std::set<std::int32_t> column;
            tree.Column(p.x, p.y, [&](std::int32_t k) { column.insert(k); });
            for (int k = 0; k < n; ++k)
                if (ColumnHits(boxes[static_cast<std::size_t>(k)], p.x, p.y)) {
                    EXPECT_TRUE(column.count(k)) << n << " " << q << " " << k;
                }
        }
        // Sparse boxes: the tree visits far fewer than all (the pre-filter is worth it).
        if (n == 600) {
            EXPECT_LT(visitedTotal, 300u * 600 / 5) << passedTotal;
        }
    }
}

// The view along one direction (HalfLine): every item whose box the half-line meets (the slab
// test with s in [0, inf)) is visited, once, for random boxes of every kind, random and
// axis-aligned directions, points inside and outside the scene, and points on a box's face;
// and it culls about as well as Segment does.
TEST(BoxTree, AHalfLineViewVisitsEveryItemTheHalfLineMeets) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-110, 110), dir(-1, 1);
    std::size_t viewVisits = 0, segmentVisits = 0;
    for (int n : {0, 1, 4, 5, 17, 600}) {
        const std::vector<Box3> boxes = RandomBoxes(n, rng);
        const BoxTree tree(boxes);
        for (int di = 0; di < 12; ++di) {
            Vec3 d{dir(rng), dir(rng), dir(rng)};
            if (di == 0) d = {0, 0, 1};
            if (di == 1) d = {-1, 0, 0};
            if (di == 2) d.y = 0;
            if (di == 3) d = d * 1e-3;  // a short direction vector: the same half-lines
            const BoxTree::HalfLineView view = tree.ViewAlong(d);
            for (int q = 0; q < 60; ++q) {
                Vec3 p{u(rng), u(rng), u(rng)};
                if (q % 6 == 0 && n > 0) {  // on a face of a box: the half-line starts on it
                    const Box3& b = boxes[static_cast<std::size_t>(q) % boxes.size()];
                    if (b.Finite()) p = {b.lo.x, 0.5 * (b.lo.y + b.hi.y), b.hi.z};
                }
                if (q % 6 == 1) p = p * 1e-6;  // near the origin, boxes far away
                std::set<std::int32_t> seen;
                tree.HalfLine(view, p, [&](std::int32_t k) {
                    EXPECT_TRUE(seen.insert(k).second) << "visited twice";
                    return false;
                });
                for (int k = 0; k < n; ++k) {
                    if (BoxTree::SegmentHitsBox(boxes[static_cast<std::size_t>(k)], p, d, 0,
                                                HUGE_VAL)) {
                        EXPECT_TRUE(seen.count(k)) << n << " " << di << " " << q << " " << k;
                    }
                }
                viewVisits += seen.size();
                tree.Segment(p, d, 0, HUGE_VAL, [&](std::int32_t) {
                    ++segmentVisits;
                    return false;
                });
            }
        }
    }
    // Looser than the slab test (an unbounded box spreads over the whole view), never tighter.
    EXPECT_GE(viewVisits, segmentVisits);
    // Finite boxes (a union of spheres): not much looser, and far fewer visits than items.
    std::vector<Box3> finite;
    for (const Box3& b : RandomBoxes(2000, rng))
        if (b.Finite()) finite.push_back(b);
    const BoxTree tree(finite);
    std::size_t view = 0, segment = 0, queries = 0;
    for (int di = 0; di < 20; ++di) {
        const Vec3 d{dir(rng), dir(rng), dir(rng)};
        const BoxTree::HalfLineView v = tree.ViewAlong(d);
        for (int q = 0; q < 50; ++q, ++queries) {
            const Vec3 p{u(rng), u(rng), u(rng)};
            tree.HalfLine(v, p, [&](std::int32_t) { return ++view, false; });
            tree.Segment(p, d, 0, HUGE_VAL, [&](std::int32_t) { return ++segment, false; });
        }
    }
    EXPECT_LT(view, segment * 3 / 2);
    EXPECT_LT(view, queries * finite.size() / 10);
}

// The column grid (a tree of at least kGridItems items): ColumnBefore visits, once, every item
// whose box holds (x, y) and starts before zMax, for boxes of every kind, query points on box
// sides and on the grid's cell borders (where the cell of a point is a rounding away from its
// neighbour), far outside the scene, and NaN; and only a few others.
TEST(BoxTree, TheColumnGridVisitsEveryItemBeforeTheDepth) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-110, 110), unit(0, 1);
    for (int n : {255, 256, 3000}) {
        std::vector<Box3> boxes = RandomBoxes(n, rng);
        // A row of touching boxes: their shared sides are cell borders for some grid sizes.
        for (int i = 0; i < 40; ++i)
            boxes.push_back(Box3{{-20.0 + i, 5, -3}, {-19.0 + i, 6, 2 + 0.1 * i}});
        const BoxTree tree(boxes);
        std::size_t visited = 0, passed = 0;
        for (int q = 0; q < 2000; ++q) {
            double x = u(rng), y = u(rng);
            const Box3& b = boxes[static_cast<std::size_t>(q) % boxes.size()];
            if (q % 4 == 1 && b.Finite()) x = b.lo.x, y = b.hi.y;  // on a corner
            if (q % 4 == 2 && b.Finite()) x = b.hi.x, y = std::nextafter(b.lo.y, -HUGE_VAL);
            if (q % 4 == 3) x = -20 + q % 41, y = 5 + (q % 3) * 0.5;  // the row's sides
            if (q == 7) x = std::nan("");
            if (q == 8) x = 1e300, y = -1e300;
            const double zMax = q % 5 == 0 ? HUGE_VAL : u(rng);
            std::set<std::int32_t> seen;
            tree.ColumnBefore(x, y, zMax, [&](std::int32_t k) {
                EXPECT_TRUE(seen.insert(k).second) << "visited twice";
            });
            for (std::size_t k = 0; k < boxes.size(); ++k) {
                const Box3& c = boxes[k];
                const bool nanBox = !(c.lo.y == c.lo.y);
                if ((ColumnHits(c, x, y) || nanBox) && (zMax == HUGE_VAL || !(c.lo.z >= zMax))) {
                    EXPECT_TRUE(seen.count(static_cast<std::int32_t>(k)))
                        << n << " " << q << " " << k << " at " << x << ", " << y;
                    ++passed;
                }
            }
            visited += seen.size();
        }
        // Few visits beyond those that pass: the empty, NaN and x- or y-unbounded boxes (each
        // n / 50 of them, visited by every query whatever its depth) and the floats rounded
        // outward; all of them would be 2000 × (n + 40).
        EXPECT_LE(visited, passed + passed / 50 + 2000 * 3 * (n / 50 + 1)) << n;
    }
}

// The view's grid (a tree of at least kGridItems items): HalfLine visits every item the
// half-line meets when it starts on a box's corner farthest along d (where the half-line only
// touches that box, at the end of its w extent), on its face, or anywhere, in dense scenes.
TEST(BoxTree, TheViewGridVisitsEveryItemTheHalfLineMeets) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> u(-110, 110), dir(-1, 1);
    std::size_t checked = 0;
    for (int n : {300, 3000}) {
        const std::vector<Box3> boxes = RandomBoxes(n, rng);
        const BoxTree tree(boxes);
        for (int di = 0; di < 8; ++di) {
            Vec3 d{dir(rng), dir(rng), dir(rng)};
            if (di == 0) d = {0.3, -0.5, 1};
            const BoxTree::HalfLineView view = tree.ViewAlong(d);
            for (int q = 0; q < 300; ++q) {
                Vec3 p{u(rng), u(rng), u(rng)};
                const Box3& b = boxes[static_cast<std::size_t>(q * 7) % boxes.size()];
                if (b.Finite() && q % 3 != 2)
                    for (int k = 0; k < 3; ++k)  // the corner farthest along d, or a face's
                        p[k] = q % 3 == 1 && k == 0 ? 0.5 * (b.lo[k] + b.hi[k])
                                                    : (d[k] > 0 ? b.hi[k] : b.lo[k]);
                std::set<std::int32_t> seen;
                tree.HalfLine(view, p, [&](std::int32_t k) {
                    EXPECT_TRUE(seen.insert(k).second) << "visited twice";
                    return false;
                });
                for (int k = 0; k < n; ++k)
                    if (BoxTree::SegmentHitsBox(boxes[static_cast<std::size_t>(k)], p, d, 0,
                                                HUGE_VAL)) {
                        EXPECT_TRUE(seen.count(k)) << n << " " << di << " " << q << " " << k;
                        ++checked;
                    }
            }
        }
    }
    EXPECT_GT(checked, 10000u);  // the test looked at many hits
}

// A dense cluster of small boxes (a union of spheres): the view's grid visits an item only where
// the half-line passes its own extent, not every item of a leaf it passes (box_tree.h
// HalfLineView::items), and still every item it meets.
TEST(BoxTree, TheViewGridVisitsFewItemsTheHalfLineMisses) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-10, 10), dir(-1, 1);
    std::vector<Box3> boxes;
    for (int i = 0; i < 10000; ++i) {
        const Vec3 c{u(rng), u(rng), u(rng)};
        boxes.push_back(Box3{c - Vec3{0.5, 0.5, 0.5}, c + Vec3{0.5, 0.5, 0.5}});
    }
    const BoxTree tree(boxes);
    std::size_t visits = 0, hits = 0;
    for (int di = 0; di < 6; ++di) {
        const Vec3 d{dir(rng), dir(rng), dir(rng)};
        const BoxTree::HalfLineView view = tree.ViewAlong(d);
        for (int q = 0; q < 400; ++q) {
            // From a point of a box's face toward d, as a shadow ray from a sphere.
            const Box3& b = boxes[static_cast<std::size_t>(q * 13) % boxes.size()];
            Vec3 p{u(rng), u(rng), u(rng)};
            for (int k = 0; k < 3; ++k) p[k] = std::clamp(p[k], b.lo[k], b.hi[k]);
            p[q % 3] = d[q % 3] > 0 ? b.hi[q % 3] : b.lo[q % 3];
            std::set<std::int32_t> seen;
            tree.HalfLine(view, p, [&](std::int32_t k) {
                seen.insert(k);
                return false;
            });
            for (std::size_t k = 0; k < boxes.size(); ++k)
                if (BoxTree::SegmentHitsBox(boxes[k], p, d, 0, HUGE_VAL)) {
                    EXPECT_TRUE(seen.count(static_cast<std::int32_t>(k))) << di << " " << q;
                    ++hits;
                }
            visits += seen.size();
        }
    }
    EXPECT_GT(hits, 2400u);
    // The rectangles around the cubes' hexagonal outlines: 1.24 × the hits; every item of the
    // leaves passed was 3.5 ×.
    EXPECT_LT(visits, hits * 3 / 2);
}

TEST(BoxTree, ASegmentQueryStopsWhenAVisitSaysSo) {
    const std::vector<Box3> boxes(50, Box3{{-1, -1, -1}, {1, 1, 1}});
    const BoxTree tree(boxes);
    int visits = 0;
    EXPECT_TRUE(tree.Segment({0, 0, -5}, {0, 0, 1}, 0, HUGE_VAL, [&](std::int32_t) {
        ++visits;
        return visits == 3;
    }));
    EXPECT_EQ(visits, 3);
    EXPECT_FALSE(
        tree.Segment({5, 5, -5}, {0, 0, 1}, 0, HUGE_VAL, [](std::int32_t) { return true; }));
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// The slab test of a box of starts (SegmentsMayHitBox) is false only where SegmentHitsBox is
// false from every start in it and every later first parameter: random boxes (unbounded, empty
// and NaN ones among them), boxes of starts (points and flat ones), directions with zero
// components and of either sign; the starts tried are the corners, the centre and random points,
// and the first parameters s0 and beyond. It culls too: most boxes far from the starts.
TEST(BoxTree, SegmentsMayHitBoxPassesEveryStartThatHits) {
    std::mt19937 rng(2026);
    const std::vector<Box3> boxes = RandomBoxes(400, rng);
    std::uniform_real_distribution<double> u(-100, 100), unit(0, 1), spread(0, 8);
    int culled = 0, tested = 0;
    for (int trial = 0; trial < 300; ++trial) {
        Vec3 lo{u(rng), u(rng), u(rng)}, hi = lo;
        for (int k = 0; k < 3; ++k)
            if (trial % 3 != 0) hi[k] = lo[k] + (trial % 3 == 1 && k == 1 ? 0.0 : spread(rng));
        Vec3 d{u(rng), u(rng), u(rng)};
        if (trial % 5 == 1) d.x = 0;
        if (trial % 7 == 2) d.y = 0;
        if (trial % 11 == 3) d = {0, 0, u(rng)};
        const double s0 = trial % 2 ? 1e-6 : 0.25;
        const double s1 = trial % 4 == 0 ? HUGE_VAL : 0.5 + 2 * unit(rng);
        std::vector<Vec3> starts;
        for (int c = 0; c < 8; ++c)
            starts.push_back({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
        starts.push_back(0.5 * (lo + hi));
        for (int r = 0; r < 24; ++r)
            starts.push_back({lo.x + unit(rng) * (hi.x - lo.x), lo.y + unit(rng) * (hi.y - lo.y),
                              lo.z + unit(rng) * (hi.z - lo.z)});
        for (const Box3& b : boxes) {
            ++tested;
            const bool may = BoxTree::SegmentsMayHitBox(b, lo, hi, d, s0, s1);
            culled += !may;
            if (may) continue;
            for (const Vec3& p : starts)
                for (double later : {s0, s0 * 1.5, s0 + 0.1})
                    ASSERT_FALSE(BoxTree::SegmentHitsBox(b, p, d, later, s1))
                        << "trial " << trial << ": a start the box of starts culled hits";
        }
    }
    EXPECT_GT(culled, tested / 2) << "most boxes lie away from the starts and their segments";
}

}  // namespace
}  // namespace quadrix
