// Analytic scenes through the raycast engine, built by hand in device space with
// deviceFromWorld = identity (so the Frame's world normals are device normals).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "quadrix/engines/raycast/raycast.h"
#include "quadrix/flatten/test_scene_builder.h"

namespace quadrix {
namespace {

using scene::CsgOp;
using testing_util::FrameHasNaN;
using testing_util::SphereBounds;
using testing_util::TestSceneBuilder;

// Depths and normals are compared to closed forms with a relative tolerance of 1e-9. The engine's
// own error is far smaller (a few ulps from the solver, plus the rounding of the per-pixel
// coefficients, about u·|centre|² ≈ 1e-10 absolute in Q for centres within 1000 pixels, which moves
// a root by that over |dQ/dt| >= 2·0.1·r away from silhouettes); 1e-9 leaves room for the closed
// forms' own rounding.
constexpr double kRel = 1e-9;

Frame Render(const FlatScene& scene, int threads = 0, RenderStats* statsOut = nullptr) {
    Frame f;
    RenderOptions options;
    options.threads = threads;
    RenderStats stats = MakeRaycastEngine()->Render(scene, options, f);
    if (statsOut) *statsOut = stats;
    EXPECT_FALSE(FrameHasNaN(f));
    return f;
}

// The Frame's normal is packed (frame/packed_normal.h): within PackedNormal::kMaxError.
void ExpectNormal(const Vec3& got, const Vec3& want, const char* what) {
    Vec3 w = Normalize(want);
    EXPECT_NEAR(got.x, w.x, kRel + PackedNormal::kMaxError) << what;
    EXPECT_NEAR(got.y, w.y, kRel + PackedNormal::kMaxError) << what;
    EXPECT_NEAR(got.z, w.z, kRel + PackedNormal::kMaxError) << what;
}

// For each pixel: `classify(x, y)` returns +1 (must be covered), −1 (must not be) or 0 (too close
// to a silhouette to insist); `check(x, y, index)` runs on the covered pixels it must cover.
void CheckPixels(const Frame& f, const std::function<int(double, double)>& classify,
                 const std::function<void(double, double, std::size_t)>& check = nullptr) {
    int mismatches = 0;
    for (int j = 0; j < f.height; ++j) {
        for (int i = 0; i < f.width; ++i) {
            double x = i + 0.5, y = j + 0.5;
            int c = classify(x, y);
            if (c == 0) continue;
            bool covered = f.Covered(i, j);
            if (covered != (c > 0)) {
                if (++mismatches < 5)
                    ADD_FAILURE() << "pixel " << i << "," << j << " covered " << covered;
                continue;
            }
            if (covered && check) check(x, y, f.Index(i, j));
        }
    }
    EXPECT_EQ(mismatches, 0);
}

// Near a boundary where `value` (a squared distance or similar, scale s²) changes sign.
int SignWithMargin(double value, double scale) {
    if (std::fabs(value) < 1e-9 * scale) return 0;
    return value < 0 ? 1 : -1;
}

TEST(RaycastShapes, SphereAreaDepthAndNormal) {
    const Vec3 c{128, 128, 500};
    const double r = 100;
    TestSceneBuilder b(256, 256);
    int s = b.AddSphere(c, r);
    int body = b.AddBody({{s, false}}, SphereBounds(c, r));
    b.AddSolidOfBody(body);
    RenderStats stats;
    Frame f = Render(b.scene(), 0, &stats);
    // Area: the disc's pixel count approximates π r² to O(r) pixels, well inside 0.5 %.
    double area = M_PI * r * r;
    EXPECT_NEAR(static_cast<double>(f.CoveredCount()), area, 0.005 * area);
    CheckPixels(
        f,
        [&](double x, double y) {
            double d2 = (x - c.x) * (x - c.x) + (y - c.y) * (y - c.y);
            return SignWithMargin(d2 - r * r, r * r);
        },
        [&](double x, double y, std::size_t k) {
            double d2 = (x - c.x) * (x - c.x) + (y - c.y) * (y - c.y);
            EXPECT_EQ(f.surface[k], s);
            EXPECT_EQ(f.body[k], body);
            EXPECT_EQ(f.Solid(k), 0);
            if (d2 > 0.81 * r * r) return;  // silhouette band: see kRel
            double z = c.z - std::sqrt(r * r - d2);
            EXPECT_NEAR(f.depth[k], z, kRel * z + DepthRounding(z));
            ExpectNormal(f.normal[k], Vec3{x, y, z} - c, "sphere front");
        });
    EXPECT_GT(stats.counters.size(), 5u);
}

TEST(RaycastShapes, CylinderAlongTheViewAxisIsADisc) {
    // (x−cx)² + (y−cy)² − r² <= 0 has c = b = 0 along every ray: all or nothing. Capped by the
    // planes z >= 100 and z <= 300.
    const double cx = 64, cy = 60, r = 30;
    for (bool transparentFront : {false, true}) {
        TestSceneBuilder b(128, 128);
        int cyl = b.AddQuadric({1, 1, 0, 0, 0, 0, -cx, -cy, 0, cx * cx + cy * cy - r * r});
        int front = b.AddPlane(0, 0, -1, 100, transparentFront);
        int back = b.AddPlane(0, 0, 1, -300);
        b.AddSolidOfBody(b.AddBody({{cyl, false}, {front, false}, {back, false}}));
        Frame f = Render(b.scene());
        CheckPixels(
            f,
            [&](double x, double y) {
                return SignWithMargin((x - cx) * (x - cx) + (y - cy) * (y - cy) - r * r, r * r);
            },
            [&](double, double, std::size_t k) {
                // Seen through a transparent front cap, the back cap's inside is drawn.
                EXPECT_EQ(f.depth[k], transparentFront ? 300 : 100);
                EXPECT_EQ(f.surface[k], transparentFront ? back : front);
                EXPECT_EQ(f.Normal(k), Vec3(0, 0, -1));  // both face the viewer
            });
    }
    // Without caps the cylinder is infinite along every ray: no finite endpoint, nothing drawn.
    TestSceneBuilder b(64, 64);
    int cyl = b.AddQuadric({1, 1, 0, 0, 0, 0, -32, -32, 0, 2 * 32 * 32 - 100});
    b.AddSolidOfBody(b.AddBody({{cyl, false}}));
    EXPECT_EQ(Render(b.scene()).CoveredCount(), 0u);
}

TEST(RaycastShapes, ParaboloidIsLinearAlongTheRays) {
    // (x−cx)² + (y−cy)² − k (z − z0) <= 0: c = 0, b ≠ 0 along every ray; the bowl's inside is
    // z >= z0 + d²/k, seen from the front at exactly that depth.
    const double cx = 40, cy = 30, k = 8, z0 = 10;
    TestSceneBuilder b(80, 64);
    int p = b.AddQuadric({1, 1, 0, 0, 0, 0, -cx, -cy, -k / 2, cx * cx + cy * cy + k * z0});
    b.AddSolidOfBody(b.AddBody({{p, false}}));
    Frame f = Render(b.scene());
    CheckPixels(
        f, [](double, double) { return 1; },
        [&](double x, double y, std::size_t idx) {
            double z = z0 + ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / k;
            EXPECT_NEAR(f.depth[idx], z, kRel * z + DepthRounding(z));
            ExpectNormal(f.normal[idx], {2 * (x - cx), 2 * (y - cy), -k}, "paraboloid");
        });
}

TEST(RaycastShapes, DoubleConeSeenSidewaysWithItsApexOnAPixelCentre) {
    // (y−cy)² + (z−cz)² − m² (x−cx)² <= 0, axis along x, capped at |x − cx| <= 50; the apex lies on
    // the ray of pixel (64, 64), which only touches the cone there (not drawn).
    const double cx = 64.5, cy = 64.5, cz = 200, m = 0.75;
    TestSceneBuilder b(129, 129);
    int cone = b.AddQuadric(
        {-m * m, 1, 1, 0, 0, 0, m * m * cx, -cy, -cz, cy * cy + cz * cz - m * m * cx * cx});
    int right = b.AddPlane(1, 0, 0, -(cx + 50));
    int left = b.AddPlane(-1, 0, 0, cx - 50);
    b.AddSolidOfBody(b.AddBody({{cone, false}, {right, false}, {left, false}}));
    Frame f = Render(b.scene());
    EXPECT_FALSE(f.Covered(64, 64));
    CheckPixels(
        f,
        [&](double x, double y) {
            if (std::fabs(std::fabs(x - cx) - 50) < 1e-9) return 0;
            if (std::fabs(x - cx) > 50) return -1;
            double w = m * m * (x - cx) * (x - cx) - (y - cy) * (y - cy);  // (z−cz)² <= w
            return SignWithMargin(-w, 2500);
        },
        [&](double x, double y, std::size_t k) {
            double w = m * m * (x - cx) * (x - cx) - (y - cy) * (y - cy);
            EXPECT_EQ(f.surface[k], cone);
            if (w < 25) return;  // near the silhouette
            double z = cz - std::sqrt(w);
            EXPECT_NEAR(f.depth[k], z, kRel * z + DepthRounding(z));
            ExpectNormal(f.normal[k], {-m * m * (x - cx), y - cy, z - cz}, "cone");
        });
}

TEST(RaycastShapes, DoubleConeAlongTheViewAxisThroughItsApex) {
    // x² + y² − (z−cz)² <= 0 around (cx, cy), capped at |z − cz| <= 40 with a transparent front
    // cap. Each ray off the axis meets two pieces (−∞, cz − d] ∪ [cz + d, ∞); through the
    // transparent cap one sees the near nappe from inside at cz − d. The axis ray (through the
    // apex) lies inside the cone: a double root with a < 0 gives the whole line, so it sees
    // through to the back cap.
    const double cx = 32.5, cy = 32.5, cz = 100;
    TestSceneBuilder b(65, 65);
    int cone = b.AddQuadric({1, 1, -1, 0, 0, 0, -cx, -cy, cz, cx * cx + cy * cy - cz * cz});
    int front = b.AddPlane(0, 0, -1, cz - 40, true);
    int back = b.AddPlane(0, 0, 1, -(cz + 40));
    b.AddSolidOfBody(b.AddBody({{cone, false}, {front, false}, {back, false}}));
    Frame f = Render(b.scene());
    ASSERT_TRUE(f.Covered(32, 32));
    EXPECT_EQ(f.surface[f.Index(32, 32)], back);
    EXPECT_EQ(f.depth[f.Index(32, 32)], cz + 40);
    CheckPixels(
        f,
        [&](double x, double y) {
            double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            return SignWithMargin(d2 - 1600, 1600);
        },
        [&](double x, double y, std::size_t k) {
            double d = std::hypot(x - cx, y - cy);
            if (d == 0) return;
            EXPECT_EQ(f.surface[k], cone);
            EXPECT_NEAR(f.depth[k], cz - d, kRel * cz + DepthRounding(cz - d));
            // Gradient (x−cx, y−cy, −(z−cz)) = (…, d) points away from the viewer: flipped.
            ExpectNormal(f.normal[k], {-(x - cx), -(y - cy), -d}, "cone inside");
        });
}

TEST(RaycastShapes, PlaneSeenEdgeOn) {
    const Vec3 c{64, 64, 300};
    const double r = 50;
    TestSceneBuilder b(128, 128);
    int s = b.AddSphere(c, r);
    // x − 70.5 <= 0 is parallel to the rays and passes exactly through the centres of column 70.
    int p = b.AddPlane(1, 0, 0, -70.5);
    int left = b.AddBody({{s, false}, {p, false}});
    int right = b.AddBody({{s, false}, {p, true}});
    // On its own the half-space is all or nothing along each ray: no finite endpoint, no pixel.
    {
        TestSceneBuilder only(128, 128);
        int q = only.AddPlane(1, 0, 0, -70.5);
        only.AddSolidOfBody(only.AddBody({{q, false}}));
        EXPECT_EQ(Render(only.scene()).CoveredCount(), 0u);
    }
    b.AddSolidOfBody(left);
    b.AddSolidOfBody(right);
    Frame f = Render(b.scene());
    // A clean split: columns <= 70 (centre on the plane: H holds, !H does not) belong to `left`.
    CheckPixels(
        f,
        [&](double x, double y) {
            return SignWithMargin((x - c.x) * (x - c.x) + (y - c.y) * (y - c.y) - r * r, r * r);
        },
        [&](double x, double, std::size_t k) {
            EXPECT_EQ(f.surface[k], s);
            EXPECT_EQ(f.body[k], x <= 70.5 ? left : right);
        });
}

TEST(RaycastShapes, TangentSpheresMergeInAUnion) {
    // Spheres A (centre z 400) and B (centre z 500), radius 50, touch at z = 450 on the axis
    // ray of pixel (32, 32). Cut by a transparent half-space z >= 420, a ray slightly off the
    // axis sees A's back sheet (the gap between the spheres), while the axis ray sees A's and B's
    // touching intervals [420, 450] ∪ [450, 550] merged into one and shows B's back at 550.
    // (All values are exact in binary, so the touching endpoints are bit-identical.)
    const Vec3 ca{32.5, 32.5, 400}, cb{32.5, 32.5, 500};
    TestSceneBuilder b(65, 65);
    int sa = b.AddSphere(ca, 50), sb = b.AddSphere(cb, 50);
    int cut = b.AddPlane(0, 0, -1, 420, true);
    int ba = b.AddBody({{sa, false}}), bb = b.AddBody({{sb, false}}),
        bc = b.AddBody({{cut, false}});
    int u = b.AddNode(CsgOp::kUnion, {b.AddLeaf(ba), b.AddLeaf(bb)});
    b.AddSolid(b.AddNode(CsgOp::kIntersection, {u, b.AddLeaf(bc)}));
    Frame f = Render(b.scene());
    std::size_t axis = f.Index(32, 32);
    EXPECT_EQ(f.depth[axis], 550);
    EXPECT_EQ(f.surface[axis], sb);
    std::size_t off = f.Index(33, 32);  // d = 1: A's back at 400 + √(2500 − 1)
    EXPECT_NEAR(f.depth[off], 400 + std::sqrt(2499.0),
                kRel * 450 + DepthRounding(400 + std::sqrt(2499.0)));
    EXPECT_EQ(f.surface[off], sa);
    EXPECT_EQ(f.body[off], ba);

    // Side by side, touching at a pixel centre: that ray only grazes both (not drawn), and the
    // union's depth is the nearer sphere's elsewhere.
    TestSceneBuilder s(128, 64);
    const Vec3 c1{30.5, 32.5, 300}, c2{90.5, 32.5, 300};
    int h1 = s.AddSphere(c1, 30), h2 = s.AddSphere(c2, 30);
    int u2 = s.AddNode(CsgOp::kUnion,
                       {s.AddLeaf(s.AddBody({{h1, false}})), s.AddLeaf(s.AddBody({{h2, false}}))});
    s.AddSolid(u2);
    Frame g = Render(s.scene());
    EXPECT_FALSE(g.Covered(60, 32));
    CheckPixels(g, [&](double x, double y) {
        int s1 = SignWithMargin((x - c1.x) * (x - c1.x) + (y - c1.y) * (y - c1.y) - 900, 900);
        int s2 = SignWithMargin((x - c2.x) * (x - c2.x) + (y - c2.y) * (y - c2.y) - 900, 900);
        if (s1 == 1 || s2 == 1) return 1;
        return s1 == -1 && s2 == -1 ? -1 : 0;
    });
}

TEST(RaycastShapes, SphereMinusSphereShowsTheInsideBackSheet) {
    // A (r 80) minus B (r 40) sitting inside A's front: on the axis A = [420, 580], B = [390, 470],
    // A − B = [470, 580]: B's back sheet, seen from inside the hole, with B's ids.
    const Vec3 ca{64.5, 64.5, 500}, cbv{64.5, 64.5, 430};
    TestSceneBuilder b(129, 129);
    int sa = b.AddSphere(ca, 80), sb = b.AddSphere(cbv, 40);
    int ba = b.AddBody({{sa, false}}, SphereBounds(ca, 80));
    int bb = b.AddBody({{sb, false}}, SphereBounds(cbv, 40));
    b.AddSolid(
        b.AddNode(CsgOp::kDifference,
                  {b.AddLeaf(ba, SphereBounds(ca, 80)), b.AddLeaf(bb, SphereBounds(cbv, 40))},
                  SphereBounds(ca, 80)),
        SphereBounds(ca, 80));
    Frame f = Render(b.scene());
    CheckPixels(
        f,
        [&](double x, double y) {
            double d2 = (x - ca.x) * (x - ca.x) + (y - ca.y) * (y - ca.y);
            return SignWithMargin(d2 - 6400, 6400);
        },
        [&](double x, double y, std::size_t k) {
            double d2 = (x - ca.x) * (x - ca.x) + (y - ca.y) * (y - ca.y);
            double zaFront = ca.z - std::sqrt(6400 - d2);
            if (d2 > 1600 * 0.99 && d2 < 1600 * 1.01) return;  // the rim of the hole
            if (d2 < 1600) {
                double zbBack = cbv.z + std::sqrt(1600 - d2);
                if (std::fabs(zbBack - zaFront) < 1e-6) return;
                if (zbBack < zaFront) {  // B lies wholly in front of A on this ray
                    EXPECT_EQ(f.surface[k], sa);
                    EXPECT_NEAR(f.depth[k], zaFront, kRel * zaFront + DepthRounding(zaFront));
                    return;
                }
                EXPECT_EQ(f.surface[k], sb);
                EXPECT_EQ(f.body[k], bb);
                EXPECT_NEAR(f.depth[k], zbBack, kRel * zbBack + DepthRounding(zbBack));
                ExpectNormal(f.normal[k], cbv - Vec3{x, y, zbBack}, "hole wall");
            } else {
                EXPECT_EQ(f.surface[k], sa);
                EXPECT_NEAR(f.depth[k], zaFront, kRel * zaFront + DepthRounding(zaFront));
            }
        });
}

TEST(RaycastShapes, DrilledHoleShowsTheBackground) {
    // A sphere minus a cylinder along the view axis: a hole straight through.
    const Vec3 c{64, 64, 300};
    TestSceneBuilder b(128, 128);
    int s = b.AddSphere(c, 50);
    int cyl = b.AddQuadric({1, 1, 0, 0, 0, 0, -c.x, -c.y, 0, c.x * c.x + c.y * c.y - 15 * 15});
    int bs = b.AddBody({{s, false}}), bc = b.AddBody({{cyl, false}});
    b.AddSolid(b.AddNode(CsgOp::kDifference, {b.AddLeaf(bs), b.AddLeaf(bc)}));
    Frame f = Render(b.scene());
    CheckPixels(f, [&](double x, double y) {
        double d2 = (x - c.x) * (x - c.x) + (y - c.y) * (y - c.y);
        if (std::fabs(d2 - 225) < 1e-6 || std::fabs(d2 - 2500) < 1e-6) return 0;
        return d2 > 225 && d2 < 2500 ? 1 : -1;
    });
}

TEST(RaycastShapes, ComplementedLiteralsEqualTheDifference) {
    const Vec3 ca{64, 64, 300}, cbv{84, 54, 260};
    TestSceneBuilder b(128, 128);
    int sa = b.AddSphere(ca, 50), sb = b.AddSphere(cbv, 35);
    b.AddSolidOfBody(b.AddBody({{sa, false}, {sb, true}}));
    TestSceneBuilder d(128, 128);
    int da = d.AddSphere(ca, 50), db = d.AddSphere(cbv, 35);
    d.AddSolid(d.AddNode(CsgOp::kDifference, {d.AddLeaf(d.AddBody({{da, false}})),
                                              d.AddLeaf(d.AddBody({{db, false}}))}));
    Frame f = Render(b.scene()), g = Render(d.scene());
    ASSERT_GT(f.CoveredCount(), 1000u);
    for (std::size_t k = 0; k < f.depth.size(); ++k) {
        ASSERT_EQ(f.depth[k], g.depth[k]) << k;
        ASSERT_EQ(f.surface[k], g.surface[k]) << k;
        ASSERT_EQ(f.normal[k], g.normal[k]) << k;
    }
    // The complement of a sphere alone, bounded by transparent clipping planes, shows the
    // sphere's surface (where the ray leaves the complement), facing the viewer.
    TestSceneBuilder e(128, 128);
    int se = e.AddSphere(ca, 50);
    int near = e.AddClipPlane(0, 0, -1, 0), far = e.AddClipPlane(0, 0, 1, -1000);
    e.AddSolidOfBody(e.AddBody({{se, true}, {near, false}, {far, false}}));
    Frame h = Render(e.scene());
    CheckPixels(
        h,
        [&](double x, double y) {
            return SignWithMargin((x - ca.x) * (x - ca.x) + (y - ca.y) * (y - ca.y) - 2500, 2500);
        },
        [&](double x, double y, std::size_t k) {
            double d2 = (x - ca.x) * (x - ca.x) + (y - ca.y) * (y - ca.y);
            EXPECT_EQ(h.surface[k], se);
            if (d2 > 0.81 * 2500) return;
            double z = ca.z - std::sqrt(2500 - d2);
            EXPECT_NEAR(h.depth[k], z, kRel * z + DepthRounding(z));
            ExpectNormal(h.normal[k], Vec3{x, y, z} - ca, "complement");
        });
}

TEST(RaycastShapes, TransparentCutShowsTheInside) {
    // Sphere ∩ (z >= cz) with the cutting plane transparent (and, separately, as a clip plane):
    // the viewer looks into the bowl and sees the back sheet, normal facing the viewer.
    const Vec3 c{48, 48, 200};
    const double r = 40;
    for (bool clip : {false, true}) {
        TestSceneBuilder b(96, 96);
        int s = b.AddSphere(c, r);
        int cut = clip ? b.AddClipPlane(0, 0, -1, c.z) : b.AddPlane(0, 0, -1, c.z, true);
        b.AddSolidOfBody(b.AddBody({{s, false}, {cut, false}}));
        Frame f = Render(b.scene());
        CheckPixels(
            f,
            [&](double x, double y) {
                return SignWithMargin((x - c.x) * (x - c.x) + (y - c.y) * (y - c.y) - r * r, r * r);
            },
            [&](double x, double y, std::size_t k) {
                double d2 = (x - c.x) * (x - c.x) + (y - c.y) * (y - c.y);
                EXPECT_EQ(f.surface[k], s);
                if (d2 > 0.81 * r * r) return;
                double z = c.z + std::sqrt(r * r - d2);
                EXPECT_NEAR(f.depth[k], z, kRel * z + DepthRounding(z));
                ExpectNormal(f.normal[k], c - Vec3{x, y, z}, "back sheet");
            });
    }
}

TEST(RaycastShapes, TwoSheetHyperboloid) {
    // Axis along x: (x−cx)² − (y−cy)² − (z−cz)² >= k, i.e. Q = −(x−cx)² + (y−cy)² + (z−cz)² + k
    // <= 0, capped at |x − cx| <= 60: two separate sheets seen sideways.
    const double cx = 64.5, cy = 40.5, cz = 300, k = 400;
    TestSceneBuilder b(129, 81);
    int h = b.AddQuadric({-1, 1, 1, 0, 0, 0, cx, -cy, -cz, -cx * cx + cy * cy + cz * cz + k});
    int right = b.AddPlane(1, 0, 0, -(cx + 60)), left = b.AddPlane(-1, 0, 0, cx - 60);
    b.AddSolidOfBody(b.AddBody({{h, false}, {right, false}, {left, false}}));
    Frame f = Render(b.scene());
    EXPECT_FALSE(f.Covered(64, 40));  // between the sheets
    CheckPixels(
        f,
        [&](double x, double y) {
            if (std::fabs(std::fabs(x - cx) - 60) < 1e-9) return 0;
            if (std::fabs(x - cx) > 60) return -1;
            double w = (x - cx) * (x - cx) - (y - cy) * (y - cy) - k;  // (z − cz)² <= w
            return SignWithMargin(-w, 3600);
        },
        [&](double x, double y, std::size_t idx) {
            double w = (x - cx) * (x - cx) - (y - cy) * (y - cy) - k;
            EXPECT_EQ(f.surface[idx], h);
            if (w < 25) return;
            double z = cz - std::sqrt(w);
            EXPECT_NEAR(f.depth[idx], z, kRel * z + DepthRounding(z));
            ExpectNormal(f.normal[idx], {-(x - cx), y - cy, z - cz}, "hyperboloid");
        });

    // Axis along z: along each ray two pieces (a < 0). With a transparent front cap the near
    // sheet is seen from inside at cz − √(ρ² + k).
    TestSceneBuilder a(64, 64);
    const double ax = 32, ay = 32;
    int hz = a.AddQuadric({1, 1, -1, 0, 0, 0, -ax, -ay, cz, ax * ax + ay * ay - cz * cz + k});
    int front = a.AddPlane(0, 0, -1, cz - 40, true), back = a.AddPlane(0, 0, 1, -(cz + 40));
    a.AddSolidOfBody(a.AddBody({{hz, false}, {front, false}, {back, false}}));
    Frame g = Render(a.scene());
    CheckPixels(
        g,
        [&](double x, double y) {
            double rho2 = (x - ax) * (x - ax) + (y - ay) * (y - ay);
            return SignWithMargin(rho2 + k - 1600, 1600);
        },
        [&](double x, double y, std::size_t idx) {
            double rho2 = (x - ax) * (x - ax) + (y - ay) * (y - ay);
            double z = cz - std::sqrt(rho2 + k);
            EXPECT_EQ(g.surface[idx], hz);
            EXPECT_NEAR(g.depth[idx], z, kRel * z + DepthRounding(z));
        });
}

TEST(RaycastShapes, DegenerateInputsDrawNothingAndNeverNaN) {
    TestSceneBuilder b(32, 32);
    int nan = b.AddQuadric({NAN, 1, 1, 0, 0, 0, 0, 0, 0, -1});
    // x² + y² + z² + 1 <= 0 scaled by 1e300: empty, and overflows to inf away from the origin.
    int huge = b.AddQuadric({1e300, 1e300, 1e300, 0, 0, 0, 0, 0, 0, 1e300});
    b.AddSolidOfBody(b.AddBody({{nan, false}}));
    b.AddSolidOfBody(b.AddBody({{nan, true}}));
    b.AddSolidOfBody(b.AddBody({}));              // no literals: empty
    b.AddSolidOfBody(b.AddBody({{999, false}}));  // a missing half-space: empty
    b.AddSolidOfBody(b.AddBody({{huge, false}}));
    b.AddSolidOfBody(b.AddBody({{huge, true}}, Box3{}));  // empty bounds: culled
    Frame f = Render(b.scene());
    EXPECT_EQ(f.CoveredCount(), 0u);
    // An empty image.
    TestSceneBuilder z(0, 0);
    EXPECT_EQ(Render(z.scene()).depth.size(), 0u);
}

}  // namespace
}  // namespace quadrix
