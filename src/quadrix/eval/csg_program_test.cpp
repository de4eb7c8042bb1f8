#include "quadrix/eval/csg_program.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <string>

#include "quadrix/flatten/test_scene_builder.h"

namespace quadrix::eval {
namespace {

using scene::CsgOp;
using testing_util::TestSceneBuilder;

Box3 BoxXY(double x0, double x1, double y0, double y1, double z0 = 0, double z1 = 10) {
    return {{x0, y0, z0}, {x1, y1, z1}};
}

// Four bodies in four screen quadrants of a 100×100 image; only their bounds matter here.
struct Quadrants {
    TestSceneBuilder b{100, 100};
    int body[4];
    int leaf[4];
    Quadrants() {
        int p = b.AddPlane(0, 0, 1, -1);
        const Box3 boxes[4] = {BoxXY(0, 40, 0, 40, 5), BoxXY(60, 100, 0, 40, 1),
                               BoxXY(0, 40, 60, 100, 3), BoxXY(60, 100, 60, 100, 2)};
        for (int i = 0; i < 4; ++i) {
            body[i] = b.AddBody({{p, false}}, boxes[i]);
            leaf[i] = b.AddLeaf(body[i], boxes[i]);
        }
    }
};

TEST(RaycastProgram, PruningSimplifiesTheTree) {
    Quadrants q;
    int u = q.b.AddNode(CsgOp::kUnion, {q.leaf[0], q.leaf[1], q.leaf[2]}, BoxXY(0, 100, 0, 100));
    int d = q.b.AddNode(CsgOp::kDifference, {u, q.leaf[3]}, BoxXY(0, 100, 0, 100));
    q.b.AddSolid(d, BoxXY(0, 100, 0, 100));
    CsgProgram full, pruned;
    BuildProgram(q.b.scene(), full);
    ASSERT_EQ(full.solids.size(), 1u);
    EXPECT_EQ(full.maxDepth, 2);
    std::vector<std::int32_t> stack;

    // Top-left quadrant: the union keeps one leaf, the subtrahend misses → the solid is leaf 0.
    PruneProgram(full, {0.5, 39.5, 0.5, 39.5}, pruned, stack);
    ASSERT_EQ(pruned.solids.size(), 1u);
    const ProgNode& root = pruned.nodes[static_cast<std::size_t>(pruned.solids[0].root)];
    EXPECT_EQ(root.kind, NodeKind::kBody);
    EXPECT_EQ(root.first, q.body[0]);
    EXPECT_EQ(pruned.solids[0].zlo, 5);  // tightened from the union's 1 to the leaf's 5

    // Bottom-right: the minuend (the union) misses → ∅ − B = ∅, no solid.
    PruneProgram(full, {60.5, 99.5, 60.5, 99.5}, pruned, stack);
    EXPECT_TRUE(pruned.solids.empty());

    // A strip across the top: union of leaves 0 and 1, difference collapsed.
    PruneProgram(full, {0.5, 99.5, 0.5, 39.5}, pruned, stack);
    ASSERT_EQ(pruned.solids.size(), 1u);
    const ProgNode& u2 = pruned.nodes[static_cast<std::size_t>(pruned.solids[0].root)];
    EXPECT_EQ(u2.kind, NodeKind::kUnion);
    ASSERT_EQ(u2.count, 2);
    EXPECT_EQ(pruned.solids[0].zlo, 1);

    // Everything: nothing pruned; pruning a pruned program is idempotent.
    PruneProgram(full, {0.5, 99.5, 0.5, 99.5}, pruned, stack);
    EXPECT_EQ(pruned.nodes.size(), full.nodes.size());
    CsgProgram again;
    PruneProgram(pruned, {0.5, 99.5, 0.5, 99.5}, again, stack);
    EXPECT_EQ(again.nodes.size(), pruned.nodes.size());
    EXPECT_TRUE(stack.empty());
}

TEST(RaycastProgram, IntersectionWithAMissingOperandIsEmpty) {
    Quadrants q;
    int i = q.b.AddNode(CsgOp::kIntersection, {q.leaf[0], q.leaf[1]}, Box3::Everything());
    q.b.AddSolid(i);
    CsgProgram full, pruned;
    BuildProgram(q.b.scene(), full);
    // The intersection's bounds are tightened to the (empty) overlap of its operands' boxes.
    EXPECT_TRUE(full.solids.empty());
}

TEST(RaycastProgram, SolidsAreSortedByNearestDepthThenIndex) {
    Quadrants q;
    for (int k : {0, 1, 2, 3}) q.b.AddSolid(q.leaf[k], Box3::Everything());
    int e = q.b.AddBody({{0, false}}, Box3{});  // empty bounds: never drawn
    q.b.AddSolidOfBody(e);
    CsgProgram full;
    BuildProgram(q.b.scene(), full);
    ASSERT_EQ(full.solids.size(), 4u);
    EXPECT_EQ(full.solids[0].solid, 1);  // zlo 1
    EXPECT_EQ(full.solids[1].solid, 3);  // zlo 2
    EXPECT_EQ(full.solids[2].solid, 2);  // zlo 3
    EXPECT_EQ(full.solids[3].solid, 0);  // zlo 5
}

// ---------------------------------------------------------------------------------------------
// Screen-space bins (ProgramBins): pruning with them gives the same program as without, on
// random programs of wide unions, differences and intersections, NaN and infinite bounds, over
// a row of sub-tiles and a column of tiles.

namespace bins_test {

bool SameDouble(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool SameRect(const Rect& a, const Rect& b) {
    return SameDouble(a.x0, b.x0) && SameDouble(a.x1, b.x1) && SameDouble(a.y0, b.y0) &&
           SameDouble(a.y1, b.y1);
}

void ExpectSamePrograms(const CsgProgram& a, const CsgProgram& b, const std::string& where) {
    ASSERT_EQ(a.nodes.size(), b.nodes.size()) << where;
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
        const ProgNode &x = a.nodes[i], &y = b.nodes[i];
        EXPECT_TRUE(SameRect(x.xy, y.xy) && SameDouble(x.zlo, y.zlo) && x.kind == y.kind &&
                    x.first == y.first && x.count == y.count)
            << where << " node " << i;
    }
    EXPECT_EQ(a.children, b.children) << where;
    ASSERT_EQ(a.solids.size(), b.solids.size()) << where;
    for (std::size_t i = 0; i < a.solids.size(); ++i)
        EXPECT_TRUE(a.solids[i].solid == b.solids[i].solid &&
                    a.solids[i].root == b.solids[i].root &&
                    SameRect(a.solids[i].xy, b.solids[i].xy) &&
                    SameDouble(a.solids[i].zlo, b.solids[i].zlo))
            << where << " solid " << i;
    EXPECT_EQ(a.maxDepth, b.maxDepth) << where;
}

// A random program over a 256 × 256 block: solids of bodies, and of wide nodes of up to 60
// operands nested two deep.
CsgProgram RandomProgram(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> pos(-20, 276), size(0, 40), unit(0, 1);
    CsgProgram p;
    auto rect = [&] {
        const double u = unit(rng);
        if (u < 0.02) return Rect{std::nan(""), std::nan(""), 0, 255};
        if (u < 0.04) return Rect{-HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL};
        if (u < 0.3) {  // ends exactly on the bins' edges (k + 0.5, k + 7.5 in steps of 8)
            auto edge = [&] {
                return 8.0 * static_cast<double>(rng() % 33) + (rng() % 2 ? 0.5 : 7.5);
            };
            const double x0 = edge(), x1 = x0 + 8.0 * static_cast<double>(rng() % 3);
            const double y0 = edge(), y1 = y0 + 8.0 * static_cast<double>(rng() % 3);
            return Rect{x0, x1, y0, y1};
        }
        const double x = pos(rng), y = pos(rng);
        return Rect{x, x + size(rng), y, y + size(rng)};
    };
    auto body = [&] {
        ProgNode n;
        n.xy = rect();
        n.zlo = pos(rng);
        n.kind = NodeKind::kBody;
        n.first = static_cast<std::int32_t>(rng() % 1000);
        p.nodes.push_back(n);
        return static_cast<std::int32_t>(p.nodes.size() - 1);
    };
    std::function<std::int32_t(int)> node = [&](int depth) -> std::int32_t {
        if (depth >= 2 || unit(rng) < 0.3) return body();
        std::vector<std::int32_t> kids;
        const int count = 1 + static_cast<int>(rng() % 60);
        for (int i = 0; i < count; ++i) kids.push_back(node(depth + 1));
        ProgNode n;
        const double k = unit(rng);
        n.kind = k < 0.5    ? NodeKind::kUnion
                 : k < 0.85 ? NodeKind::kDifference
                            : NodeKind::kIntersection;
        n.xy = unit(rng) < 0.5 ? Rect{-HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL} : rect();
        n.zlo = -HUGE_VAL;
        n.first = static_cast<std::int32_t>(p.children.size());
        n.count = count;
        p.children.insert(p.children.end(), kids.begin(), kids.end());
        p.nodes.push_back(n);
        return static_cast<std::int32_t>(p.nodes.size() - 1);
    };
    const int solids = 1 + static_cast<int>(rng() % 40);
    for (int s = 0; s < solids; ++s) {
        const std::int32_t root = node(0);
        const ProgNode& r = p.nodes[static_cast<std::size_t>(root)];
        p.solids.push_back({s, root, r.xy, r.zlo});
    }
    p.maxDepth = 3;
    return p;
}

}  // namespace bins_test

TEST(RaycastProgram, BinnedPruningIsThePruningOfEveryOperand) {
    std::mt19937_64 rng(5);
    std::vector<std::int32_t> stack;
    int binnedNodes = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const CsgProgram program = bins_test::RandomProgram(rng);
        for (const bool alongX : {true, false}) {
            // 32 sub-tiles of 8 pixels in a row (x), or 32 tiles of 8 rows in a column (y); the
            // last one cut short as at an image edge.
            std::vector<Rect> rects;
            for (int k = 0; k < 32; ++k) {
                const double a = 8 * k + 0.5, b = std::min(8 * k + 7.5, 250.5);
                if (a > b) break;
                rects.push_back(alongX ? Rect{a, b, 100.5, 107.5} : Rect{0.5, 255.5, a, b});
            }
            ProgramBins bins;
            BinProgram(program, rects, alongX, bins);
            for (std::int32_t w : bins.binnedOf) binnedNodes += w >= 0;
            for (std::size_t k = 0; k < rects.size(); ++k) {
                CsgProgram whole, binned;
                PruneProgram(program, rects[k], whole, stack);
                PruneProgram(program, bins, k, rects[k], binned, stack);
                bins_test::ExpectSamePrograms(whole, binned,
                                              "trial " + std::to_string(trial) + " bin " +
                                                  std::to_string(k) + (alongX ? " x" : " y"));
            }
        }
    }
    EXPECT_GT(binnedNodes, 100);  // the bins were used, not bypassed
}

}  // namespace
}  // namespace quadrix::eval
