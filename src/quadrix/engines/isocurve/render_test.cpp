#include "quadrix/engines/isocurve/render.h"

#include <gtest/gtest.h>

#include <cmath>

#include "quadrix/engines/isocurve/compare.h"
#include "quadrix/engines/isocurve/view_fit.h"
#include "quadrix/import/freeform/freeform_reader.h"

namespace quadrix::isocurve {
namespace {

using freeform::Surface;

std::vector<Surface> Model(const std::string& relative) {
    Diagnostics d;
    auto m = import::ReadFreeformFile(
        std::string(QUADRIX_SOURCE_DIR) + "/src/quadrix/import/freeform/testdata/" + relative, d);
    EXPECT_TRUE(m.has_value()) << relative;
    return m ? m->surfaces : std::vector<Surface>{};
}

std::vector<FreeformDrawable> Drawables(const std::vector<Surface>& s, int first = 0,
                                        int last = 1 << 30) {
    std::vector<FreeformDrawable> d;
    for (int i = first; i < static_cast<int>(s.size()) && i <= last; ++i)
        d.push_back({&s[static_cast<std::size_t>(i)], {i, 0}});
    return d;
}

Box3 BoundsOf(const std::vector<FreeformDrawable>& d) {
    Box3 b;
    for (const FreeformDrawable& x : d) b.Extend(x.surface->Bounds());
    return b;
}

// An oblique view from above the front right, z up (the tea set's frame).
const Vec3 kToward = Normalize(Vec3{0.5, -1, 0.8});
const Vec3 kUp{0, 0, 1};

// Pixels the reference covers and the isocurve render misses.
long long Holes(const std::vector<FreeformDrawable>& d, const Projection& p, int size,
                const IsocurveOptions& o = {}) {
    Frame frame(size, size);
    RenderFreeform(d, p, o, frame);
    std::vector<std::uint8_t> ref = ReferenceMask(d, p, size, size);
    long long holes = 0, refCount = 0;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        holes += ref[i] && !frame.Covered(static_cast<int>(i % size), static_cast<int>(i / size));
        refCount += ref[i];
    }
    EXPECT_GT(refCount, size * size / 20);  // the model fills a fair part of the image
    return holes;
}

// Acceptance (issue 6): at the δ chosen for the image size, no pixel of the reference render is
// missed. 128×128 keeps the test fast; δ scales with the image, so the geometry of the test is
// the same at any size.
TEST(IsocurveRender, NoHolesOnTheTeaSet) {
    for (const char* file : {"newell/teapot.txt", "newell/teacup.txt", "newell/teaspoon.txt"}) {
        std::vector<Surface> m = Model(file);
        auto d = Drawables(m);
        Projection p = FitParallel(BoundsOf(d), kToward, kUp, 128, 128);
        EXPECT_EQ(Holes(d, p, 128), 0) << file;
    }
}

TEST(IsocurveRender, NoHolesInPerspectiveAndOnRationalSurfaces) {
    for (const char* file : {"obj/sphere_nurbs.obj", "obj/torus_nurbs.obj", "geomview/torus.bez",
                             "obj/wave_bspline.obj"}) {
        std::vector<Surface> m = Model(file);
        auto d = Drawables(m);
        Projection p =
            FitPerspective(BoundsOf(d), Normalize(Vec3{0.3, 0.8, 0.5}), {0, 0, 1}, 96, 96);
        EXPECT_EQ(Holes(d, p, 96), 0) << file;
    }
}

// Acceptance (issue 6): on the teapot lid (patches 21–28) adaptive extraction draws fewer pixels
// more than once than uniform spacing at the same δ. Algorithm 1 in either fixed direction (the
// radial curves of Figure 2 converge on the knob: 4.5 against 5.4 here); with the direction
// chosen per patch, uniform spacing also escapes the convergence and Algorithm 1 is on par
// (4.50 / 4.47 at 96 px, 4.29 / 4.47 at 128 px: dyadic spacing can be up to twice as dense as
// needed), so that case uses the automatic base (4.12 / 4.47).
TEST(IsocurveRender, LidRedundancyBelowUniform) {
    std::vector<Surface> m = Model("newell/teapot.txt");
    auto d = Drawables(m, 20, 27);
    Projection p = FitParallel(BoundsOf(d), kToward, kUp, 96, 96);
    for (auto [dir, base] : {std::pair{Direction::kConstU, 1}, std::pair{Direction::kConstV, 1},
                             std::pair{Direction::kAuto, 0}}) {
        IsocurveOptions o;
        o.direction = dir;
        o.baseCount = base;
        Comparison c = CompareCoverage(d, p, o, 96, 96);
        ASSERT_EQ(c.rows.size(), 3u);
        const MethodRow& adaptive = c.rows[0];
        const MethodRow& uniform = c.rows[1];
        EXPECT_LT(adaptive.Redundancy(), uniform.Redundancy()) << c.Format();
        EXPECT_LT(adaptive.pixelsDrawn, uniform.pixelsDrawn) << c.Format();
        EXPECT_LT(adaptive.length, uniform.length) << c.Format();
        EXPECT_EQ(adaptive.holes, 0) << c.Format();
        EXPECT_EQ(uniform.holes, 0) << c.Format();
        // Same pixels covered up to the outline overhang.
        EXPECT_NEAR(static_cast<double>(adaptive.distinctPixels),
                    static_cast<double>(uniform.distinctPixels), 0.01 * adaptive.distinctPixels);
    }
}

// With the automatic base (ExtractOptions::baseCount = 0) the finest adaptive spacing is the
// uniform one instead of the next power of two below it, and adaptive extraction wins on the
// whole teapot too (with Algorithm 1's two boundary curves it is on par there, docs/isocurve.md).
TEST(IsocurveRender, TeapotRedundancyBelowUniformWithAutoBase) {
    std::vector<Surface> m = Model("newell/teapot.txt");
    auto d = Drawables(m);
    Projection p = FitParallel(BoundsOf(d), kToward, kUp, 128, 128);
    IsocurveOptions o;
    o.baseCount = 0;
    Comparison c = CompareCoverage(d, p, o, 128, 128);
    EXPECT_LT(c.rows[0].Redundancy(), c.rows[1].Redundancy()) << c.Format();
    EXPECT_LT(c.rows[0].length, c.rows[1].length) << c.Format();
    EXPECT_EQ(c.rows[0].holes, 0) << c.Format();
}

// World point seen at a pixel: the device point (x+½, y+½, depth) mapped back.
Vec3 WorldAt(const Projection& p, const Frame& f, int x, int y) {
    return p.deviceFromWorld.Inverted().MapPoint(Vec3{x + 0.5, y + 0.5, f.depth[f.Index(x, y)]});
}

TEST(IsocurveRender, NormalsAndDepthsOfASphereAreExact) {
    std::vector<Surface> m = Model("obj/sphere_nurbs.obj");
    auto d = Drawables(m);
    for (bool perspective : {false, true}) {
        Projection p = perspective ? FitPerspective(BoundsOf(d), kToward, kUp, 128, 128)
                                   : FitParallel(BoundsOf(d), kToward, kUp, 128, 128);
        Frame frame(128, 128);
        IsocurveStats st = RenderFreeform(d, p, {}, frame);
        EXPECT_GT(st.curves, 20);
        double worstAngle = 0, sumAngle = 0, worstRadius = 0;
        int n = 0;
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x) {
                if (!frame.Covered(x, y)) continue;
                Vec3 q = WorldAt(p, frame, x, y);
                Vec3 toward = perspective ? Normalize(p.eye - q) : p.towardViewer;
                Vec3 expect = Normalize(q);
                // Away from the outline (θ ≤ 60°), where a pixel step moves along the surface by
                // at most twice its size.
                if (Dot(expect, toward) < 0.5) continue;
                Vec3 got = frame.normal[frame.Index(x, y)];
                EXPECT_NEAR(Length(got), 1, 1e-12);
                double angle = std::acos(std::min(1.0, Dot(got, expect)));
                worstAngle = std::max(worstAngle, angle);
                sumAngle += angle;
                worstRadius = std::max(worstRadius, std::fabs(Length(q) - 1));
                ++n;
            }
        ASSERT_GT(n, 2000);
        // A pixel shows the normal of the nearest curve sample, at most a disc radius (0.875 px)
        // away on the screen: ≤ 2 · 0.875 / (~55 px per unit) ≈ 0.032 rad on the unit sphere.
        EXPECT_LT(worstAngle, 0.04);
        EXPECT_LT(sumAngle / n, 0.01);
        // Depth follows the tangent plane across the disc: off by ~r²/(2R) ≈ 1.3e-4.
        EXPECT_LT(worstRadius, 1e-3);
    }
}

TEST(IsocurveRender, ComposesWithAnotherSolidByDepth) {
    // A Frame already holding a wall (as a quadric engine would leave it) on the left half of the
    // image, half a radius in front of the sphere's centre: the cap of the sphere in front of it
    // (projected radius < √¾) must win there and the wall must stay around it.
    std::vector<Surface> m = Model("obj/sphere_nurbs.obj");
    auto d = Drawables(m);
    d[0].ids = {7, 3};
    Projection p = FitParallel(BoundsOf(d), kToward, kUp, 96, 96);
    double wall = p.deviceFromWorld.MapPoint(p.towardViewer * 0.5).z;
    Frame frame(96, 96);
    frame.bodySolid = {-1, -1, -1, 2};  // body 3 is in solid 2 (the Frame's table, frame.h)
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 48; ++x) frame.Offer(frame.Index(x, y), wall, Vec3{0, 0, 1}, 99, 98);
    RenderFreeform(d, p, {}, frame);
    Transform inv = p.deviceFromWorld.Inverted();
    int sphereWins = 0, wallWins = 0;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 48; ++x) {
            // The exact front intersection of the pixel's ray with the unit sphere.
            Vec3 a = inv.MapPoint({x + 0.5, y + 0.5, 0}), b = inv.MapPoint({x + 0.5, y + 0.5, 1});
            Vec3 dir = b - a;
            double A = Dot(dir, dir), B = Dot(a, dir), C = Dot(a, a) - 1, disc = B * B - A * C;
            std::size_t i = frame.Index(x, y);
            // disc / A = 1 − (distance of the ray from the centre)²: skip the outline, where the
            // thick curves overhang.
            if (disc / A < 0.05) continue;
            double t = (-B - std::sqrt(disc)) / A;  // device z along this parallel ray is t
            if (t < wall - 0.5) {
                EXPECT_EQ(frame.surface[i], 7);
                EXPECT_EQ(frame.Solid(i), 2);
                ++sphereWins;
            } else if (t > wall + 0.5) {
                EXPECT_EQ(frame.surface[i], 99);
                ++wallWins;
            }
        }
    EXPECT_GT(sphereWins, 300);
    EXPECT_GT(wallWins, 100);
}

TEST(IsocurveRender, ProgressiveLevelsRefineToTheFinalImage) {
    std::vector<Surface> m = Model("newell/teacup.txt");
    auto d = Drawables(m);
    Projection p = FitParallel(BoundsOf(d), kToward, kUp, 64, 64);
    IsocurveOptions o;
    o.progressiveLevels = 2;
    std::vector<IsocurveStats> levels;
    Frame last;
    RenderFreeformProgressive(d, p, o, Frame(64, 64),
                              [&](int level, int count, const Frame& f, const IsocurveStats& st) {
                                  EXPECT_EQ(level, static_cast<int>(levels.size()));
                                  EXPECT_EQ(count, 3);
                                  levels.push_back(st);
                                  last = f;
                              });
    ASSERT_EQ(levels.size(), 3u);
    for (int k = 1; k < 3; ++k) {
        EXPECT_DOUBLE_EQ(levels[k].delta * 2, levels[k - 1].delta);
        EXPECT_DOUBLE_EQ(levels[k].thickness * 2, levels[k - 1].thickness);
        EXPECT_GT(levels[k].curves, levels[k - 1].curves);
    }
    Frame direct(64, 64);
    RenderFreeform(d, p, {}, direct);
    EXPECT_EQ(direct.depth, last.depth);
    EXPECT_EQ(direct.surface, last.surface);
}

TEST(IsocurveRender, OptionsAreCheckedAndReported) {
    IsocurveOptions o;
    EXPECT_EQ(ParseIsocurveOptions({{"delta", "0.01"},
                                    {"direction", "u"},
                                    {"progressive", "3"},
                                    {"thickness", "2.5"},
                                    {"uniform", "1"}},
                                   o),
              "");
    EXPECT_EQ(o.delta, 0.01);
    EXPECT_EQ(o.direction, Direction::kConstU);
    EXPECT_EQ(o.progressiveLevels, 3);
    EXPECT_TRUE(o.uniform);
    EXPECT_EQ(ParseIsocurveOptions({{"delta", "-1"}}, o),
              "engine 'isocurve': option 'delta' must be a number > 0, not '-1'");
    EXPECT_EQ(ParseIsocurveOptions({{"direction", "diagonal"}}, o),
              "engine 'isocurve': option 'direction' must be u, v or auto, not 'diagonal'");
    EXPECT_NE(ParseIsocurveOptions({{"dleta", "1"}}, o).find("has no option 'dleta'"),
              std::string::npos);

    std::vector<Surface> m = Model("geomview/octant.bez");
    auto d = Drawables(m);
    Projection p = FitParallel(BoundsOf(d), kToward, kUp, 64, 64);
    Frame frame(64, 64);
    IsocurveStats st = RenderFreeform(d, p, {}, frame);
    RenderStats rs;
    FillRenderStats(st, rs);
    EXPECT_NE(rs.report.find("curves " + std::to_string(st.curves)), std::string::npos);
    bool found = false;
    for (auto& [name, value] : rs.counters)
        if (name == "isocurve.curves") found = value == st.curves;
    EXPECT_TRUE(found);
    // δ follows the image: a two times larger image halves it.
    double d64 = DeltaForImage(d, p, 1.0);
    double d128 = DeltaForImage(d, FitParallel(BoundsOf(d), kToward, kUp, 128, 128), 1.0);
    EXPECT_NEAR(d64, 2 * d128, 1e-12);
}

}  // namespace
}  // namespace quadrix::isocurve
