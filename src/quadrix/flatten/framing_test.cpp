// Framing (window_fit.h, bounds.h) measured on rendered pictures: every quadric kind cut by
// planes, and a CSG of them, rendered through RunPipeline with the exact raycast engine and the
// automatic window; the covered rows and columns must fill the frame to within a few per cent
// (the fit leaves 2 % per side, so the larger extent should span 96 % of its side), and never
// reach past the margin (the bounds are conservative). Also: whh or whw alone, the window centred
// on vrp, unbounded solids beside bounded ones, a far-away BRL-CAD cone frustum, and the
// left-handed picture of world space.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "quadrix/pipeline/pipeline.h"

namespace quadrix {
namespace {

struct Extent {
    int c0 = 1 << 30, c1 = -1, r0 = 1 << 30, r1 = -1;
    int Cols() const { return c1 - c0 + 1; }
    int Rows() const { return r1 - r0 + 1; }
};

// Covered extent of the frame; solid >= 0 restricts it to one FlatScene solid.
Extent Covered(const Frame& f, int solid = -1) {
    Extent e;
    for (int r = 0; r < f.height; ++r)
        for (int c = 0; c < f.width; ++c) {
            if (!f.Covered(c, r)) continue;
            if (solid >= 0 && f.Solid(f.Index(c, r)) != solid) continue;
            e.c0 = std::min(e.c0, c), e.c1 = std::max(e.c1, c);
            e.r0 = std::min(e.r0, r), e.r1 = std::max(e.r1, r);
        }
    return e;
}

struct Rendered {
    bool ok = false;
    PipelineResult result;
    Diagnostics diags;
    std::string Messages() const {
        std::string s;
        for (const Diagnostic& d : diags.Items()) s += d.Format(false) + "\n";
        return s;
    }
};

Rendered Render(const std::string& text, int w = 300, int h = 300,
                std::vector<std::string> paths = {}) {
    Rendered r;
    PipelineOptions po;
    po.sceneText = text;
    po.scenePaths = std::move(paths);
    po.width = w;
    po.height = h;
    po.engine = "raycast";
    r.ok = RunPipeline(po, r.result, r.diags);
    return r;
}

// The auto-fit's promise: the larger relative extent fills 96 % of its side (2 % margin per side)
// to within 3 % of the frame — the pixel grid costs up to 2 pixels of 300, the bounds' tolerance
// (relTolerance 1e-3 of the size) less than one — and nothing lies in the margin beyond a pixel.
void ExpectFills(const Frame& f, const std::string& what) {
    Extent e = Covered(f);
    ASSERT_GE(e.c1, 0) << what << ": nothing drawn";
    double fx = double(e.Cols()) / f.width, fy = double(e.Rows()) / f.height;
    EXPECT_GE(std::max(fx, fy), 0.93) << what << ": fills " << fx << " x " << fy;
    EXPECT_LE(std::max(fx, fy), 0.97) << what << ": fills " << fx << " x " << fy;
    const int mx = static_cast<int>(0.02 * f.width) - 1, my = static_cast<int>(0.02 * f.height) - 1;
    EXPECT_GE(e.c0, mx) << what;
    EXPECT_LE(e.c1, f.width - 1 - mx) << what;
    EXPECT_GE(e.r0, my) << what;
    EXPECT_LE(e.r1, f.height - 1 - my) << what;
    // Centred: the free space left and right (top and bottom) agrees to within two pixels and
    // the bounds' tolerance.
    EXPECT_NEAR(e.c0, f.width - 1 - e.c1, 3) << what;
    EXPECT_NEAR(e.r0, f.height - 1 - e.r1, 3) << what;
}

struct KindCase {
    const char* name;
    const char* scene;
};

class FramingPerKind : public ::testing::TestWithParam<KindCase> {};

TEST_P(FramingPerKind, AutomaticWindowFitsTheVisibleExtent) {
    const KindCase& k = GetParam();
    Rendered r = Render(k.scene);
    ASSERT_TRUE(r.ok) << k.name << "\n" << r.Messages();
    ExpectFills(r.result.frame, k.name);
}

// The default view (dop .3 .3 -1) sees each of them obliquely; the cutting planes are oblique too.
const KindCase kKinds[] = {
    {"sphere_cut", "quadric qs <1 1 1 0 0 0 -2 0 0 0>; plane cut <1 1 .5 -2>; body ball (qs cut);"},
    {"ellipsoid_rotated", "solid ellipsoid egg =at 0 3 0 =r 2 1 1 =rz 30;"},
    {"ellipsoid_cut",
     "quadric egg <.25 1 4 0 0 0 0 0 0 -1>; plane cut <1 1 1 -1>; body lens (egg cut);"},
    {"cylinder_mitered",
     "quadric cyl <1 0 1 0 0 0 0 0 0 -1>; plane top <0 1 .5 -2>; plane bot <.3 -1 0 -1>;"
     "body pipe (cyl top bot);"},
    {"cone_frustum", "solid cone tip =from 0 0 0 =to 1 2 0 =r0 1 =r1 .3;"},
    {"cone_cut",
     "quadric cone <1 1 -1 0 0 0 0 0 0 0>; plane low <0 0 -1 .5>; plane high <.5 0 1 -2>;"
     "body tip (cone low high);"},
    {"paraboloid", "solid paraboloid dish =from 0 0 0 =to 1 2 .5 =r 1;"},
    {"hyperboloid_one_sheet", "solid hyperboloid reel =from 0 -1 0 =to 0 1 0 =r 1 =waist .5;"},
    {"hyperboloid_one_sheet_oblique",
     "solid hyperboloid reel =from 0 0 0 =to 2 1 1 =r 1 =waist .3;"},
    {"hyperboloid_two_sheets", "solid hyperboloid2 h =from 0 0 0 =to 0 3 0 =r 1 =gap 1;"},
    {"csg_of_them",
     "solid hyperboloid reel =from 0 -1 0 =to 0 1 0 =r 1 =waist .5;"
     "solid sphere ball =at 0 1 0 =r .6; solid cone tip =from 1.5 -1 0 =to 1.5 1 0 =r0 .5 "
     "=r1 .1; csg c ((reel - ball) | tip);"},
};

INSTANTIATE_TEST_SUITE_P(Kinds, FramingPerKind, ::testing::ValuesIn(kKinds),
                         [](const auto& info) { return std::string(info.param.name); });

// The case: the reel filled 37 of 300 rows; its extent is taller than wide in the default
// view, so it must fill the height.
TEST(Framing, OneSheetHyperboloidFillsTheFrameHeight) {
    Rendered r = Render("solid hyperboloid reel =from 0 -1 0 =to 0 1 0 =r 1 =waist .5;");
    ASSERT_TRUE(r.ok) << r.Messages();
    Extent e = Covered(r.result.frame);
    EXPECT_GE(e.Rows(), 0.8 * 300);
    EXPECT_GE(e.Rows(), 0.94 * 300);
}

// whh or whw alone sets the scale, the other follows from the aspect, and the window is centred
// on vrp: a unit sphere at vrp (1 2 3) seen along +z at 50 px per unit is a disc of radius 50
// about the image centre (150, 100), whatever the other half-size would have been.
TEST(Framing, OneWindowHalfSizeSetsTheScaleAndCentresOnVrp) {
    const std::string sphere = "solid sphere s =at 1 2 3 =r 1; solid sphere far =at 9 2 3 =r 1;";
    for (const char* window : {"whh 2", "whw 3", "whh 2 whw 3", "whw 3 whh 2"}) {
        Rendered r = Render(sphere + "view v vrp 1 2 3 dop 0 0 -1 " + window + ";", 300, 200);
        ASSERT_TRUE(r.ok) << window << "\n" << r.Messages();
        // Solid 0 is the sphere at vrp; the far one lies outside the window and is culled.
        Extent e = Covered(r.result.frame, 0);
        EXPECT_EQ(e.c0, 100) << window;
        EXPECT_EQ(e.c1, 199) << window;
        EXPECT_EQ(e.r0, 50) << window;
        EXPECT_EQ(e.r1, 149) << window;
        EXPECT_EQ(r.result.flat.solids.size(), 1u) << window;
    }
    // Both given with another aspect: the whole window fits (the smaller scale), centred on vrp.
    Rendered r = Render(sphere + "view v vrp 1 2 3 dop 0 0 -1 whh 1 whw 3;", 300, 200);
    ASSERT_TRUE(r.ok) << r.Messages();
    Extent e = Covered(r.result.frame, 0);
    EXPECT_EQ(e.c0, 100);
    EXPECT_EQ(e.c1, 199);
    EXPECT_EQ(e.r0, 50);
    EXPECT_EQ(e.r1, 149);
}

// A ground plane (a POV-Ray habit) beside a bounded solid: the fit uses the bounded one and the
// plane is drawn clipped to that window, so the sphere is framed exactly as without the plane.
TEST(Framing, UnboundedSolidsAreClippedToTheViewOfTheBoundedOnes) {
    const std::string ball = "solid sphere ball =at 0 1 0 =r 1;";
    Rendered alone = Render(ball);
    ASSERT_TRUE(alone.ok) << alone.Messages();
    for (const char* ground : {"plane g <0 1 0 0>; body ground (g);",                     // a body
                               "plane g <0 1 0 0>; body ground (g); csg u (ground);"}) {  // csg
        Rendered r = Render(std::string(ground) + ball);
        ASSERT_TRUE(r.ok) << ground << "\n" << r.Messages();
        const FlatScene& flat = r.result.flat;
        int ballSolid = -1;
        for (std::size_t i = 0; i < flat.solids.size(); ++i)
            if (flat.solids[i].name == "ball") ballSolid = static_cast<int>(i);
        ASSERT_GE(ballSolid, 0) << ground;
        // The same device map as without the ground: the sphere's quadric is the same.
        const Transform& a = alone.result.flat.projection.deviceFromWorld;
        const Transform& b = flat.projection.deviceFromWorld;
        for (const Vec3& p : {Vec3{0, 0, 0}, Vec3{1, 2, 3}})
            EXPECT_NEAR(Length(a.MapPoint(p) - b.MapPoint(p)), 0, 1e-9) << ground;
        // The plane covers the image where the sphere does not (its half below y = 0 is seen
        // from above, so the lower part of the picture is ground).
        EXPECT_EQ(r.result.frame.CoveredCount(), std::size_t(300 * 300)) << ground;
    }
    // A union with a half-space: its bounded member is what is fitted.
    Rendered u = Render("plane g <0 1 0 0>; body ground (g);" + ball + "csg u (ground | ball);");
    ASSERT_TRUE(u.ok) << u.Messages();
    EXPECT_NEAR(Length(u.result.flat.projection.deviceFromWorld.MapPoint({1, 2, 3}) -
                       alone.result.flat.projection.deviceFromWorld.MapPoint({1, 2, 3})),
                0, 1e-9);
    // Nothing bounded and no window: still an error naming the solid.
    Rendered bad = Render("plane g <0 1 0 0>;\nbody ground (g);");
    EXPECT_FALSE(bad.ok);
    EXPECT_NE(bad.Messages().find("body 'ground' at <text>:2:1 is unbounded in the view"),
              std::string::npos)
        << bad.Messages();
}

// Perspective: a ground plane reaches the image of infinity (z = d) and only the near plane bounds
// its screen box, so it is left out of the fit as well.
TEST(Framing, PerspectiveGroundPlaneIsLeftOutOfTheFit) {
    const std::string scene = "solid sphere ball =at 0 1 0 =r 1; view v vrp 0 1 0 cop 0 3 -8;";
    Rendered alone = Render(scene);
    ASSERT_TRUE(alone.ok) << alone.Messages();
    Rendered r = Render("plane g <0 1 0 0>; body ground (g);" + scene);
    ASSERT_TRUE(r.ok) << r.Messages();
    Extent a = Covered(alone.result.frame);
    ExpectFills(alone.result.frame, "perspective ball");
    int ball = r.result.flat.solids[0].name == "ball" ? 0 : 1;
    Extent b = Covered(r.result.frame, ball);
    EXPECT_NEAR(a.c0, b.c0, 1);
    EXPECT_NEAR(a.c1, b.c1, 1);
    EXPECT_NEAR(a.r0, b.r0, 1);
}

// A bounded BRL-CAD cone frustum 10 m from the origin was refused as "unbounded" (its quadric's
// A, normalised with its large constant term, passed for positive semidefinite): it must be
// fitted like any solid, for frusta close to cylinders (apex 10⁵ mm away) and 1 km away too.
TEST(Framing, FarAwayBrlcadConeFrustumIsFitted) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "quadrix_framing_test";
    std::filesystem::create_directories(dir);
    const char* frusta[] = {
        "V {10000 0 0} H {0 0 500} A {200 0 0} B {0 200 0} C {199 0 0} D {0 199 0}",
        "V {10000 0 0} H {0 0 5} A {200 0 0} B {0 200 0} C {199.99 0 0} D {0 199.99 0}",
        "V {10000 0 0} H {0 0 500} A {20 0 0} B {0 20 0} C {10 0 0} D {0 10 0}",
        "V {10000 0 0} H {0 0 500} A {200 0 0} B {0 200 0} C {100 0 0} D {0 100 0}",
        ("V {-10000 3000 2000} H {300 400 0} A {0 0 200} B {160 -120 0} C {0 0 100} "
         "D {80 -60 0}"),
        // 1 km away: bounded 50x too loosely in provisional space, refitted in device space.
        "V {1000000 0 0} H {0 0 500} A {200 0 0} B {0 200 0} C {.001 0 0} D {0 .001 0}",
    };
    int n = 0;
    for (const char* f : frusta) {
        std::filesystem::path p = dir / ("frustum" + std::to_string(n++) + ".asc");
        {
            std::ofstream out(p);
            out << "title {a cone frustum far from the origin}\nunits mm\n"
                << "put {cone.s} tgc " << f << "\n";
        }
        Rendered r = Render("", 200, 200, {p.string()});
        ASSERT_TRUE(r.ok) << f << "\n" << r.Messages();
        ExpectFills(r.result.frame, f);
    }
    std::filesystem::remove_all(dir);
}

// World space as the pictures show it: with the default view (and any view, since screen right is
// vup × vpn and screen up vpn × right) x runs right, y up and z away from the viewer — a
// left-handed frame, as in POV-Ray (docs/language.md §2).
TEST(Framing, PicturesShowWorldSpaceLeftHanded) {
    Rendered r = Render(
        "solid sphere o =at 0 0 0 =r 1; solid sphere x =at 3 0 0 =r .5;"
        "solid sphere y =at 0 3 0 =r .5; solid sphere z =at .5 .5 3 =r 1;"
        "view v dop 0 0 -1 whh 5 whw 5;",
        200, 200);
    ASSERT_TRUE(r.ok) << r.Messages();
    const FlatScene& flat = r.result.flat;
    auto index = [&](const std::string& name) {
        for (std::size_t i = 0; i < flat.solids.size(); ++i)
            if (flat.solids[i].name == name) return static_cast<int>(i);
        return -1;
    };
    const Frame& f = r.result.frame;
    Extent o = Covered(f, index("o")), x = Covered(f, index("x")), y = Covered(f, index("y"));
    EXPECT_GT(x.c0, o.c1);  // +x to the right
    EXPECT_LT(y.r1, o.r0);  // +y up (smaller rows)
    // +z away: the sphere at z = 3 is behind the one at the origin where they overlap.
    EXPECT_EQ(f.Solid(f.Index(100, 100)), index("o"));
    EXPECT_EQ(f.Solid(f.Index(110, 90)), index("o"));  // inside both discs
    EXPECT_EQ(f.Solid(f.Index(120, 80)), index("z"));  // inside z's disc only
}

}  // namespace
}  // namespace quadrix
