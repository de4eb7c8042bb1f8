// The box tree (box_tree.h): its queries visit every item whose own box test passes (boxes of
// all kinds: finite, unbounded, empty, NaN), stop when asked, and visit few items of a sparse
// scene.
#include "quadrix/math/box_tree.h"

#include <gtest/gtest.h>

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
