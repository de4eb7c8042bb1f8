#include "quadrix/import/freeform/freeform_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace quadrix::import {
namespace {

std::string DataPath(const std::string& relative) {
    return std::string(QUADRIX_SOURCE_DIR) + "/src/quadrix/import/freeform/testdata/" + relative;
}

FreeformModel MustRead(const std::string& relative) {
    Diagnostics d;
    std::optional<FreeformModel> m = ReadFreeformFile(DataPath(relative), d);
    for (const Diagnostic& x : d.Items()) ADD_FAILURE() << x.Format();
    EXPECT_TRUE(m.has_value()) << relative;
    return m ? *m : FreeformModel{};
}

// The first error of reading `text` as `format`, "" when there is none.
std::string FirstError(std::string_view text, FreeformFormat format,
                       const std::string& name = "t") {
    Diagnostics d;
    std::optional<FreeformModel> m = ReadFreeformText(text, name, format, d);
    for (const Diagnostic& x : d.Items())
        if (x.severity == Diagnostic::Severity::kError) {
            EXPECT_FALSE(m.has_value());
            return x.Format(false);
        }
    return "";
}

// Same control points (compared as homogeneous coordinates, polynomial read as w = 1).
void ExpectSameSurfaces(const FreeformModel& a, const FreeformModel& b, double tol) {
    ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    for (std::size_t i = 0; i < a.surfaces.size(); ++i)
        for (int k = 0; k < 10; ++k) {
            double u = unit(rng), v = unit(rng);
            EXPECT_LT(Length(a.surfaces[i].Point(u, v) - b.surfaces[i].Point(u, v)), tol)
                << "surface " << i;
        }
}

TEST(ImportFreeform, NewellTeaSet) {
    FreeformModel pot = MustRead("newell/teapot.txt");
    EXPECT_EQ(pot.format, FreeformFormat::kNewell);
    ASSERT_EQ(pot.surfaces.size(), 32u);
    Box3 box;
    for (const auto& s : pot.surfaces) box.Extend(s.Bounds());
    // SOURCES.md: z ∈ [0, 3.15], x ∈ [−3, 3.525], y ∈ [−2, 2] (control hull).
    EXPECT_DOUBLE_EQ(box.lo.z, 0);
    EXPECT_DOUBLE_EQ(box.hi.z, 3.15);
    EXPECT_DOUBLE_EQ(box.lo.x, -3);
    EXPECT_DOUBLE_EQ(box.hi.x, 3.525);
    EXPECT_EQ(pot.surfaces[0].Name(), "teapot[0]");
    // Patch 21 (index 20, lid knob) has its first row collapsed to (0, 0, 3.15).
    // (de Casteljau on equal points is exact up to an ulp of the coordinates.)
    for (double u : {0.0, 0.3, 1.0})
        EXPECT_LT(Length(pot.surfaces[20].Point(u, 0) - Vec3{0, 0, 3.15}), 1e-15);
    EXPECT_EQ(MustRead("newell/teacup.txt").surfaces.size(), 26u);
    EXPECT_EQ(MustRead("newell/teaspoon.txt").surfaces.size(), 16u);
}

TEST(ImportFreeform, AllTeapotCopiesAgree) {
    FreeformModel pot = MustRead("newell/teapot.txt");
    ExpectSameSurfaces(pot, MustRead("spd/teapot_spd.txt"), 1e-12);
    ExpectSameSurfaces(pot, MustRead("bpt/teapot.bpt"), 1e-12);
    FreeformModel obj = MustRead("obj/teapot_bezier.obj");
    EXPECT_EQ(obj.format, FreeformFormat::kObj);
    ExpectSameSurfaces(pot, obj, 1e-12);
    ExpectSameSurfaces(MustRead("newell/teacup.txt"), MustRead("obj/teacup_bezier.obj"), 1e-12);
    ExpectSameSurfaces(MustRead("newell/teaspoon.txt"), MustRead("bpt/teaspoon.bpt"), 1e-12);
}

TEST(ImportFreeform, ObjNurbsSphereTorusAndWave) {
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> unit(0, 1);
    FreeformModel sphere = MustRead("obj/sphere_nurbs.obj");
    ASSERT_EQ(sphere.surfaces.size(), 1u);
    EXPECT_TRUE(sphere.surfaces[0].Rational());
    FreeformModel torus = MustRead("obj/torus_nurbs.obj");
    ASSERT_EQ(torus.surfaces.size(), 1u);
    FreeformModel wave = MustRead("obj/wave_bspline.obj");
    ASSERT_EQ(wave.surfaces.size(), 1u);
    EXPECT_FALSE(wave.surfaces[0].Rational());
    EXPECT_EQ(wave.surfaces[0].Patches().SpansU(), 4);  // knots 0 .2 .45 .7 1
    EXPECT_EQ(wave.surfaces[0].Patches().SpansV(), 3);  // knots 0 .3 .6 1
    for (int k = 0; k < 200; ++k) {
        double u = unit(rng), v = unit(rng);
        // Exact conics up to rounding: SOURCES.md measured 3.4e-16 and 1.2e-15.
        EXPECT_NEAR(Length(sphere.surfaces[0].Point(u, v)), 1, 1e-14);
        Vec3 p = torus.surfaces[0].Point(u, v);
        double ring = std::hypot(p.x, p.y) - 2;
        EXPECT_NEAR(std::hypot(ring, p.z), 0.5, 1e-14);
        // The unit normal of the sphere is radial (also at the collapsed poles, by the limit).
        std::optional<Vec3> n = sphere.surfaces[0].UnitNormal(u, v);
        ASSERT_TRUE(n.has_value());
        EXPECT_NEAR(std::fabs(Dot(*n, Normalize(sphere.surfaces[0].Point(u, v)))), 1, 1e-9);
    }
    for (double u : {0.0, 0.4, 1.0})
        for (double v : {0.0, 1.0}) {
            std::optional<Vec3> n = sphere.surfaces[0].UnitNormal(u, v);
            ASSERT_TRUE(n.has_value());
            // At the poles the limit normal is ±z (the inward step is 1e-7 of the domain).
            EXPECT_NEAR(std::fabs(n->z), 1, 1e-6);
        }
}

TEST(ImportFreeform, GeomviewFiles) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> unit(0, 1);
    FreeformModel pot = MustRead("geomview/teapot.bez");
    EXPECT_EQ(pot.format, FreeformFormat::kGeomview);
    EXPECT_EQ(pot.surfaces.size(), 28u);
    FreeformModel torus = MustRead("geomview/torus.bez");
    ASSERT_EQ(torus.surfaces.size(), 4u);
    FreeformModel octant = MustRead("geomview/octant.bez");
    ASSERT_EQ(octant.surfaces.size(), 1u);
    FreeformModel hemi = MustRead("geomview/themi.bez");  // appearance block, _ST, colours
    ASSERT_EQ(hemi.surfaces.size(), 1u);
    EXPECT_EQ(MustRead("geomview/linkA.bez").surfaces.size(), 1u);
    EXPECT_EQ(MustRead("geomview/linkB.bez").surfaces.size(), 2u);
    for (int k = 0; k < 100; ++k) {
        double u = unit(rng), v = unit(rng);
        for (const auto& s : torus.surfaces) {
            // Weights reach 0 at some control points, yet w(u, v) >= 0.25 (SOURCES.md).
            EXPECT_GE(s.HomogeneousPoint(u, v).w, 0.25 - 1e-12);
            Vec3 p = s.Point(u, v);  // axis y, R = 1, r = 0.5
            EXPECT_NEAR(std::hypot(std::hypot(p.x, p.z) - 1, p.y), 0.5, 1e-12);
        }
        EXPECT_NEAR(Length(octant.surfaces[0].Point(u, v)), 1, 1e-14);
        EXPECT_NEAR(Length(hemi.surfaces[0].Point(u, v)), 1, 1e-14);
    }
    // Bounds survive control points at infinity: the torus lies in |x|, |z| <= 1.5, |y| <= .5.
    Box3 b = torus.surfaces[0].Bounds();
    ASSERT_TRUE(b.Finite());
    EXPECT_LE(b.hi.y, 2.0);
    EXPECT_GE(b.hi.y, 0.5 - 1e-12);
}

TEST(ImportFreeform, DetectsFormats) {
    EXPECT_EQ(DetectFreeformFormat("a.OBJ", ""), FreeformFormat::kObj);
    EXPECT_EQ(DetectFreeformFormat("a.bez", ""), FreeformFormat::kGeomview);
    EXPECT_EQ(DetectFreeformFormat("a.txt", "# c\nBEZ224\n"), FreeformFormat::kGeomview);
    EXPECT_EQ(DetectFreeformFormat("a.txt", "2\n1,2,3\n"), FreeformFormat::kNewell);
    EXPECT_EQ(DetectFreeformFormat("a.txt", "1\n3 3\n0 0 0\n"), FreeformFormat::kBpt);
    EXPECT_EQ(DetectFreeformFormat("a", "v 1 2 3\n"), FreeformFormat::kObj);
}

TEST(ImportFreeform, ErrorsCarryFileLineColumn) {
    // Newell: an index past the vertex list, reported where it is written.
    std::string newell = "1\n1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,17\n16\n";
    for (int i = 0; i < 16; ++i) newell += "0,0," + std::to_string(i) + "\n";
    EXPECT_EQ(FirstError(newell, FreeformFormat::kNewell, "pot.txt"),
              "pot.txt:2:37: error: vertex index 17 is out of range 1..16");
    EXPECT_EQ(FirstError("1\n1,2,x\n", FreeformFormat::kNewell),
              "t:2:5: error: expected vertex index, found 'x'");
    EXPECT_EQ(FirstError("2\n", FreeformFormat::kNewell),
              "t:1:2: error: unexpected end of file in patch 1: expected 16 vertex indices");
    // BPT: degree range and truncation.
    EXPECT_EQ(FirstError("1\n3 99\n", FreeformFormat::kBpt),
              "t:2:3: error: degree 99 is outside 1..12");
    EXPECT_EQ(FirstError("1\n1 1\n0 0 0\n1 0 nan\n", FreeformFormat::kBpt),
              "t:4:5: error: z coordinate is not finite: 'nan'");
    // Geomview.
    EXPECT_EQ(FirstError("BEZ994\n", FreeformFormat::kGeomview),
              "t:1:1: error: expected a Geomview patch header ([ST]BBP or "
              "[C]BEZ<u><v><3|4>[_ST]) or patch data, found 'BEZ994'");
    EXPECT_EQ(FirstError("BEZ113\n0 0 0  1 0 0  0 1 0\n", FreeformFormat::kGeomview),
              "t:2:20: error: unexpected end of file, expected a control point coordinate");
    // OBJ.
    const char* obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bezier\ndeg 1 1\n";
    EXPECT_EQ(FirstError(std::string(obj) + "surf 0 1 0 1 1 2 3 9\nend\n", FreeformFormat::kObj),
              "t:7:20: error: vertex index 9 does not name a vertex (4 defined so far)");
    EXPECT_EQ(FirstError(std::string(obj) + "surf 0 1 0 1 1 2 3\nend\n", FreeformFormat::kObj),
              "t:7:1: error: surf lists 3 control points, but its degrees and parameter vectors "
              "need 2 x 2");
    EXPECT_EQ(FirstError("cstype taylor\n", FreeformFormat::kObj),
              "t:1:8: error: curve type 'taylor' is not supported (only bezier and bspline)");
    EXPECT_EQ(FirstError(std::string(obj) + "surf 0 2 0 1 1 2 3 4\nend\n", FreeformFormat::kObj),
              "t:7:1: error: the surf range [0, 2] x [0, 1] is not inside the parameter domain "
              "[0, 1] x [0, 1]");
    EXPECT_EQ(FirstError(std::string(obj) + "surf 0 1 0 1 1 2 3 4\nparm u 1 0\nend\n",
                         FreeformFormat::kObj),
              "t:8:6: error: parm u values must not decrease");
    EXPECT_EQ(FirstError(std::string(obj) + "surf 0 1 0 1 1 2 3 4\n", FreeformFormat::kObj),
              "t:7:1: error: 'surf' without a matching 'end'");
    EXPECT_EQ(FirstError("", FreeformFormat::kObj),
              "t: error: no freeform surface found (read as obj)");
}

TEST(ImportFreeform, ObjDetails) {
    // Continuation lines, v/vt/vn references, negative indices, a restricted range, a rational
    // Bézier with two segments in u, ignored attributes and warnings for trims.
    std::string text =
        "o thing\nv 0 0 0\nv 1 0 0\nv 2 0 1\nv 0 1 0\nv 1 1 0\nv 2 1 1\nvt 0 0\n"
        "cstype rat bezier\ndeg 1 1\nusemtl x\n"
        "surf 0 2 0 1 1/1 2/1/1 3//1 \\\n  -3 -2 -1\nparm u 0 1 2\nparm v 0 1\n"
        "trim 0 1 1\nend\nf 1 2 3\n";
    Diagnostics d;
    std::optional<FreeformModel> m = ReadFreeformText(text, "x.obj", FreeformFormat::kAuto, d);
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(d.WarningCount(), 2);  // trim, f
    ASSERT_EQ(m->surfaces.size(), 1u);
    const freeform::Surface& s = m->surfaces[0];
    EXPECT_EQ(s.Name(), "thing[0]");
    EXPECT_EQ(s.Patches().SpansU(), 2);
    EXPECT_NEAR(s.U1(), 2, 0);
    Vec3 p = s.Point(1.5, 0.5);  // bilinear between (1,0,0),(2,0,1),(1,1,0),(2,1,1)
    EXPECT_NEAR(p.x, 1.5, 1e-15);
    EXPECT_NEAR(p.y, 0.5, 1e-15);
    EXPECT_NEAR(p.z, 0.5, 1e-15);

    // The surf range restricts the surface.
    std::string restricted =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bezier\ndeg 1 1\n"
        "surf 0.25 0.75 0 0.5 1 2 3 4\nparm u 0 1\nparm v 0 1\nend\n";
    Diagnostics d2;
    m = ReadFreeformText(restricted, "r.obj", FreeformFormat::kObj, d2);
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(m->surfaces[0].U0(), 0.25);
    EXPECT_EQ(m->surfaces[0].V1(), 0.5);
    EXPECT_NEAR(m->surfaces[0].Point(0.25, 0.5).x, 0.25, 1e-15);
}

TEST(ImportFreeform, MutatedInputNeverCrashes) {
    // A cheap fuzz pass: byte edits of valid files must give a model or diagnostics, never a
    // crash or a hang (the sanitizer build checks memory errors too).
    const char* files[] = {"newell/teacup.txt", "obj/torus_nurbs.obj", "geomview/themi.bez",
                           "bpt/teaspoon.bpt"};
    std::mt19937_64 rng(10);
    for (const char* f : files) {
        Diagnostics d;
        std::FILE* in = std::fopen(DataPath(f).c_str(), "rb");
        ASSERT_NE(in, nullptr);
        std::string text;
        char buf[4096];
        for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, in)) > 0;) text.append(buf, n);
        std::fclose(in);
        const char alphabet[] = "0123456789-.,e/ \n#xvsurfendparm\\";
        for (int trial = 0; trial < 40; ++trial) {
            std::string t = text;
            for (int e = 0; e < 4; ++e) {
                std::size_t at = rng() % t.size();
                t[at] = alphabet[rng() % (sizeof alphabet - 1)];
            }
            Diagnostics dd;
            std::optional<FreeformModel> m = ReadFreeformText(t, f, FreeformFormat::kAuto, dd);
            EXPECT_TRUE(m.has_value() || dd.HasErrors());
        }
    }
}

}  // namespace
}  // namespace quadrix::import
