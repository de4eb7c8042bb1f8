#include "quadrix/engines/isocurve/isocurve_engine.h"

#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/engines/isocurve/view_fit.h"
#include "quadrix/import/freeform/freeform_reader.h"

namespace quadrix::isocurve {
namespace {

// A FlatScene holding one quadric sphere |x − c|² <= 1 (world), seen along +z (toward the viewer
// is −z) in a parallel projection.
FlatScene SceneWithQuadricSphere(const Vec3& c, int size) {
    FlatScene s;
    s.width = s.height = size;
    Box3 frameBox{{-1.5, -1.5, -1.5}, {2.7, 1.5, 1.5}};
    s.projection = FitParallel(frameBox, {0, 0, -1}, {0, 1, 0}, size, size);
    Quadric world = Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -c.x, -c.y, -c.z, Dot(c, c) - 1});
    FlatHalfSpace h;
    h.isPlane = false;
    h.quadric = world.Transformed(s.projection.deviceFromWorld);
    h.name = "ball";
    s.halfSpaces.push_back(h);
    FlatBody b;
    b.literals.push_back({0, false});
    b.solid = 0;
    b.bounds = Box3::Everything();
    s.bodies.push_back(b);
    FlatCsgNode n;
    n.body = 0;
    n.bounds = Box3::Everything();
    s.nodes.push_back(n);
    FlatSolid sol;
    sol.root = 0;
    sol.bounds = Box3::Everything();
    s.solids.push_back(sol);
    return s;
}

TEST(IsocurveEngine, FreeformAndQuadricSpheresMeetByDepth) {
    Diagnostics d;
    auto model =
        import::ReadFreeformFile(std::string(QUADRIX_SOURCE_DIR) +
                                     "/src/quadrix/import/freeform/testdata/obj/sphere_nurbs.obj",
                                 d);
    ASSERT_TRUE(model.has_value());
    FlatScene scene = SceneWithQuadricSphere({1.2, 0, 0}, 80);
    IsocurveEngine engine(MakeEngine("raycast"), model->surfaces);
    RenderOptions options;
    options.engineOptions = {{"compare", "1"}};
    ASSERT_EQ(engine.ValidateOptions(options), "");
    Frame frame;
    RenderStats stats = engine.Render(scene, options, frame);
    ASSERT_EQ(frame.width, 80);
    EXPECT_NE(stats.report.find("isocurve: 1 surfaces"), std::string::npos) << stats.report;
    EXPECT_NE(stats.report.find("coverage comparison"), std::string::npos);

    // Along y = 0: at x = 0.5 the freeform sphere is in front (z −0.866 against −0.714), at
    // x = 0.75 the quadric one (−0.893 against −0.661); far left only the freeform one, far
    // right only the quadric.
    auto idAt = [&](double x) {
        Vec3 dev = scene.projection.deviceFromWorld.MapPoint({x, 0, 0});
        return frame.surface[frame.Index(static_cast<int>(dev.x), static_cast<int>(dev.y))];
    };
    const std::int32_t freeformId = 1;  // halfSpaces.size() + 0
    EXPECT_EQ(idAt(-0.6), freeformId);
    EXPECT_EQ(idAt(0.5), freeformId);
    EXPECT_EQ(idAt(0.75), 0);
    EXPECT_EQ(idAt(1.8), 0);

    RenderOptions bad;
    bad.engineOptions = {{"thickness", "-2"}};
    EXPECT_NE(engine.ValidateOptions(bad), "");
}

}  // namespace
}  // namespace quadrix::isocurve
