#include "quadrix/viewer/progressive.h"

#include <gtest/gtest.h>

namespace quadrix::viewer {
namespace {

TEST(ViewerProgressive, FirstFrameIsFullThenMovingFramesFitTheBudget) {
    FrameScheduler s(0.025);
    auto r = s.Next();
    ASSERT_TRUE(r);
    EXPECT_EQ(r->scale, 1);  // nothing measured yet
    EXPECT_FALSE(s.Next());  // one frame in flight at a time
    s.Delivered(*r, 0.2);
    EXPECT_TRUE(s.Final());
    EXPECT_FALSE(s.Next());
    // 0.2 s a full frame: 0.2/4 > 0.025 >= 0.2/9, so moving frames are a third of the size.
    EXPECT_EQ(s.MovingScale(), 3);
    s.ViewChanged();
    EXPECT_FALSE(s.Final());
    r = s.Next();
    ASSERT_TRUE(r);
    EXPECT_EQ(r->scale, 3);
    s.Delivered(*r, 0.2 / 9);
    // Still: the full-resolution frame of the same view follows.
    r = s.Next();
    ASSERT_TRUE(r);
    EXPECT_EQ(r->scale, 1);
    EXPECT_EQ(r->generation, s.Generation());
    s.Delivered(*r, 0.2);
    EXPECT_TRUE(s.Final());
}

TEST(ViewerProgressive, SupersededViewsAreNeverRequested) {
    FrameScheduler s(0.025);
    auto r = s.Next();
    s.Delivered(*r, 0.01);  // fast: moving frames stay at full resolution
    EXPECT_EQ(s.MovingScale(), 1);
    s.ViewChanged();
    auto a = s.Next();
    ASSERT_TRUE(a);
    s.ViewChanged();  // three moves while `a` is drawn
    s.ViewChanged();
    s.ViewChanged();
    EXPECT_FALSE(s.Next());
    s.Delivered(*a, 0.01);
    EXPECT_FALSE(s.Final());  // `a` shows an old view
    auto b = s.Next();
    ASSERT_TRUE(b);
    EXPECT_EQ(b->generation, a->generation + 3);  // straight to the latest view
    s.Delivered(*b, 0.01);
    EXPECT_TRUE(s.Final());
}

TEST(ViewerProgressive, VerySlowScenesUseTheCoarsestScale) {
    FrameScheduler s(0.025);
    auto r = s.Next();
    s.Delivered(*r, 100.0);
    EXPECT_EQ(s.MovingScale(), 16);
}

TEST(ViewerProgressive, AntialiasingIsTheStillFramesLastStage) {
    FrameScheduler s(0.025, /*antialias=*/true);
    auto r = s.Next();
    ASSERT_TRUE(r);
    EXPECT_FALSE(r->antialiased);
    EXPECT_FALSE(r->refining);  // the first frame is not a refinement
    s.Delivered(*r, 0.2);
    EXPECT_FALSE(s.Final());  // full resolution, but not anti-aliased yet
    auto aa = s.Next();
    ASSERT_TRUE(aa);
    EXPECT_EQ(aa->scale, 1);
    EXPECT_TRUE(aa->antialiased);
    EXPECT_TRUE(aa->refining);
    s.Delivered(*aa, 5.0);
    EXPECT_TRUE(s.Final());
    EXPECT_FALSE(s.Next());
    EXPECT_EQ(s.FullFrameEstimate(), 0.2);  // the anti-aliased frame's time is not a frame's
    // Moving again: reduced, then full, then anti-aliased.
    s.ViewChanged();
    r = s.Next();
    ASSERT_TRUE(r);
    EXPECT_EQ(r->scale, 3);
    EXPECT_FALSE(r->refining);
    s.Delivered(*r, 0.02);
    r = s.Next();
    ASSERT_TRUE(r);
    EXPECT_EQ(r->scale, 1);
    EXPECT_FALSE(r->antialiased);
    EXPECT_TRUE(r->refining);
}

TEST(ViewerProgressive, AStaleRefiningFrameIsCancelledAndTheNewViewAskedFor) {
    FrameScheduler s(0.025, true);
    auto r = s.Next();
    s.Delivered(*r, 0.2);
    auto aa = s.Next();  // the anti-aliased frame is being drawn...
    ASSERT_TRUE(aa && aa->refining);
    EXPECT_FALSE(s.StaleRefinementInFlight());
    s.ViewChanged();  // ...when the view moves: it is stale
    EXPECT_TRUE(s.StaleRefinementInFlight());
    EXPECT_FALSE(s.Next());  // still in flight until the worker gives it up
    s.Abandoned();
    EXPECT_FALSE(s.InFlight());
    auto next = s.Next();
    ASSERT_TRUE(next);
    EXPECT_EQ(next->generation, s.Generation());
    EXPECT_EQ(next->scale, 3);  // a moving frame
    // A moving frame in flight is never worth cancelling: it is short.
    s.ViewChanged();
    EXPECT_FALSE(s.StaleRefinementInFlight());
}

}  // namespace
}  // namespace quadrix::viewer
