// Tests of the window fit (window_fit.h) on boxes: the scale and centre of whh/whw alone and
// together, the auto-fit, axes nothing bounds, and the fit boxes of CSG nodes with unbounded
// members. The rendered consequences are in framing_test.cpp.
#include "quadrix/flatten/window_fit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/flatten/bounds.h"

namespace quadrix {
namespace {

constexpr double kInf = HUGE_VAL;

WindowRequest Request(int w, int h) {
    WindowRequest r;
    r.width = w;
    r.height = h;
    r.margin = 0.02;
    return r;
}

TEST(WindowFit, OneHalfSizeSetsTheScaleAndTheWindowIsCentredOnVrp) {
    // The boxes are not looked at when a window is given (an unbounded one here).
    const std::vector<Box3> boxes = {Box3::Everything()};
    WindowFit fit;
    WindowRequest r = Request(300, 200);
    r.whh = 2;  // 200 px over 4 units
    ASSERT_EQ(FitWindow(r, boxes, fit), WindowFitStatus::kOk);
    EXPECT_EQ(fit.k, 50);
    EXPECT_EQ(fit.ox, 150);
    EXPECT_EQ(fit.oy, 100);
    r.whh.reset();
    r.whw = 1.5;  // 300 px over 3 units
    ASSERT_EQ(FitWindow(r, boxes, fit), WindowFitStatus::kOk);
    EXPECT_EQ(fit.k, 100);
    EXPECT_EQ(fit.ox, 150);
    EXPECT_EQ(fit.oy, 100);
    r.whh = 2;  // both: the whole window fits, the smaller scale wins
    ASSERT_EQ(FitWindow(r, boxes, fit), WindowFitStatus::kOk);
    EXPECT_EQ(fit.k, 50);
    EXPECT_EQ(fit.ox, 150);
    EXPECT_EQ(fit.oy, 100);
}

TEST(WindowFit, AutoFitUsesTheBoundedAxesAndCentresTheRestOnVrp) {
    WindowFit fit;
    WindowRequest r = Request(400, 200);
    // [1, 3] × [-2, 2]: y asks for 192/4 = 48, x for 384/2 = 192; centred on (2, 0).
    std::vector<Box3> boxes = {Box3{{1, -2, -kInf}, {3, 2, kInf}}};
    ASSERT_EQ(FitWindow(r, boxes, fit), WindowFitStatus::kOk);
    EXPECT_DOUBLE_EQ(fit.k, 48);
    EXPECT_DOUBLE_EQ(fit.ox, 200 - 48 * 2);
    EXPECT_DOUBLE_EQ(fit.oy, 100);
    // An unbounded box and an empty one change nothing.
    boxes.push_back(Box3::Everything());
    boxes.push_back(Box3{});
    WindowFit again;
    ASSERT_EQ(FitWindow(r, boxes, again), WindowFitStatus::kOk);
    EXPECT_EQ(again.k, fit.k);
    EXPECT_EQ(again.ox, fit.ox);
    // Only x bounded (an infinite cylinder along screen y): the scale from x, y centred on vrp.
    boxes = {Box3{{1, -kInf, 0}, {3, kInf, 1}}};
    ASSERT_EQ(FitWindow(r, boxes, fit), WindowFitStatus::kOk);
    EXPECT_DOUBLE_EQ(fit.k, 192);
    EXPECT_DOUBLE_EQ(fit.oy, 100);
    // Nothing bounded; a point.
    boxes = {Box3::Everything(), Box3{{0, -kInf, -kInf}, {kInf, 1, 0}}};
    EXPECT_EQ(FitWindow(r, boxes, fit), WindowFitStatus::kNothingBounded);
    boxes = {Box3{{1, 1, 1}, {1, 1, 1}}};
    EXPECT_EQ(FitWindow(r, boxes, fit), WindowFitStatus::kNoExtent);
}

// nodes: 0 = body 0 (bounded), 1 = body 1 (a half-space), 2 = op(0, 1).
FlatScene TwoLeaves(scene::CsgOp op, bool boundedFirst) {
    FlatScene s;
    s.bodies.resize(2);
    for (int i = 0; i < 2; ++i) {
        FlatCsgNode leaf;
        leaf.isLeaf = true;
        leaf.body = i;
        s.nodes.push_back(leaf);
    }
    FlatCsgNode n;
    n.isLeaf = false;
    n.op = op;
    n.children = boundedFirst ? std::vector<int>{0, 1} : std::vector<int>{1, 0};
    s.nodes.push_back(n);
    return s;
}

TEST(WindowFit, CsgFitBoxesKeepTheBoundedMembers) {
    const Box3 ball{{-1, -1, -1}, {1, 1, 1}};
    const Box3 half{{-kInf, 0, -kInf}, {kInf, kInf, kInf}};
    const std::vector<Box3> bodies = {ball, half};
    struct Case {
        scene::CsgOp op;
        bool boundedFirst;
        Box3 want;  // the node's fit box in x and y
    };
    const Case cases[] = {
        {scene::CsgOp::kUnion, true, ball},
        {scene::CsgOp::kUnion, false, ball},
        {scene::CsgOp::kIntersection, true, Box3{{-1, 0, -1}, {1, 1, 1}}},
        {scene::CsgOp::kDifference, true, ball},                 // the minuend's
        {scene::CsgOp::kDifference, false, Box3::Everything()},  // an unbounded minuend
    };
    for (const Case& c : cases) {
        FlatScene s = TwoLeaves(c.op, c.boundedFirst);
        std::vector<Box3> nodes = TreeBounds(s, bodies);
        std::vector<Box3> fit = FitTreeBounds(s, bodies, nodes);
        for (int axis = 0; axis < 2; ++axis) {
            EXPECT_EQ(fit[2].lo[axis], c.want.lo[axis]) << int(c.op) << " axis " << axis;
            EXPECT_EQ(fit[2].hi[axis], c.want.hi[axis]) << int(c.op) << " axis " << axis;
        }
    }
    // Perspective: a body reaching the image of infinity (z = d = 5) counts as unbounded even
    // though its screen box is finite (only the near plane bounds it).
    FlatScene s = TwoLeaves(scene::CsgOp::kUnion, true);
    const std::vector<Box3> persp = {Box3{{-1, -1, 0}, {1, 1, 4}},
                                     Box3{{-1e4, -1e4, 0}, {1e4, 1e4, 5}}};
    std::vector<Box3> fit = FitTreeBounds(s, persp, TreeBounds(s, persp), 5.0);
    EXPECT_EQ(fit[1].lo.x, -kInf);
    EXPECT_EQ(fit[2].lo.x, -1);
    EXPECT_EQ(fit[2].hi.y, 1);
}

}  // namespace
}  // namespace quadrix
