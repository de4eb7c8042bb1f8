#include "quadrix/viewer/section.h"

#include <gtest/gtest.h>

namespace quadrix::viewer {
namespace {

TEST(ViewerSection, TurnsOnThroughTheCentreFacingTheViewerAndMoves) {
    Camera cam;
    cam.toward = Normalize(Vec3{1, 2, -2});
    SectionPlane s;
    EXPECT_FALSE(s.ToPlane());
    const Vec3 centre{1, -2, 3};
    s.Toggle(cam, centre);
    ASSERT_TRUE(s.ToPlane());
    const Plane p = *s.ToPlane();
    EXPECT_NEAR(p.Evaluate(centre), 0, 1e-12);
    // The viewer's side is cut away (outside), the far side kept.
    EXPECT_GT(p.Evaluate(centre + cam.toward), 0);
    EXPECT_LT(p.Evaluate(centre - cam.toward), 0);
    s.Move(0.5);  // toward the viewer: the plane moves to centre + 0.5 toward
    EXPECT_NEAR(s.ToPlane()->Evaluate(centre + cam.toward * 0.5), 0, 1e-12);
    EXPECT_LT(s.ToPlane()->Evaluate(centre + cam.toward * 0.4), 0);
    s.Flip();  // same plane, the other side kept
    EXPECT_NEAR(s.ToPlane()->Evaluate(centre + cam.toward * 0.5), 0, 1e-12);
    EXPECT_GT(s.ToPlane()->Evaluate(centre + cam.toward * 0.4), 0);
    s.Toggle(cam, centre);
    EXPECT_FALSE(s.ToPlane());
}

}  // namespace
}  // namespace quadrix::viewer
