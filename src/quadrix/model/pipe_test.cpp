// The pipe generator (model/pipe.h): the text format and its errors, the generators, the
// bisecting miter planes, and joints of two, three and four elements that leave no gap and no
// overlap; the written UniQuadrix text reads back into the same half-spaces.
#include "quadrix/model/pipe.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "quadrix/lang/reader.h"

namespace quadrix::model {
namespace {

PipeModel Build(const std::string& text) {
    Diagnostics d;
    PipeSpec spec;
    PipeModel m;
    bool ok = ReadPipeText(text, "test.pipe", spec, d) && BuildPipes(spec, m, d);
    std::string all;
    for (const auto& item : d.Items()) all += item.Format() + "\n";
    EXPECT_TRUE(ok) << all;
    return m;
}

bool InElement(const PipeElement& e, const Vec3& p) {
    if (e.side.Evaluate(p) > 0) return false;
    for (const Plane& plane : e.ends)
        if (plane.Evaluate(p) > 0) return false;
    return true;
}

int CountContaining(const PipeModel& m, const Vec3& p) {
    int n = 0;
    for (const PipeElement& e : m.elements) n += InElement(e, p);
    return n;
}

// Every point within 0.99 r of a joint of two or more elements lies in exactly one tube: no gap
// (a point in none) and no overlap (a point in two). Random points avoid the seams themselves
// (probability 0). The 1% margin keeps away from the tubes' outer surface, where "inside" is
// decided by rounding.
void ExpectWatertightJoints(const PipeModel& m, double r) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (const PipeJoint& j : m.joints) {
        if (j.elements.size() < 2 || j.ball > 0) continue;
        for (int k = 0; k < 300; ++k) {
            Vec3 d{u(rng), u(rng), u(rng)};
            if (Length(d) > 1) continue;
            Vec3 p = j.point + d * (0.99 * r);
            ASSERT_EQ(CountContaining(m, p), 1)
                << "joint (" << j.point.x << " " << j.point.y << " " << j.point.z << ") with "
                << j.elements.size() << " elements, point " << p.x << " " << p.y << " " << p.z;
        }
    }
}

TEST(PipeText, ReadsDirectivesAndPaths) {
    PipeSpec spec;
    Diagnostics d;
    ASSERT_TRUE(
        ReadPipeText("# two paths\nradius .5\ncolor 1 0 0\npath\n0 0 0\n1 0 0 # x\n"
                     "ball .7\ncaps off\nloop\n0 0 0\n0 1 0\n1 1 0\nend\n",
                     "t.pipe", spec, d));
    ASSERT_EQ(spec.paths.size(), 2u);
    EXPECT_EQ(spec.paths[0].points.size(), 2u);
    EXPECT_EQ(spec.paths[0].radius, 0.5);
    EXPECT_EQ(spec.paths[0].ball, 0);
    EXPECT_TRUE(spec.paths[0].caps);
    EXPECT_TRUE(spec.paths[1].closed);
    EXPECT_EQ(spec.paths[1].ball, 0.7);
    EXPECT_FALSE(spec.paths[1].caps);
    ASSERT_TRUE(spec.paths[1].color);
    EXPECT_EQ(spec.paths[1].loc.line, 9);
}

TEST(PipeText, BadInputGivesPositionedErrors) {
    struct Case {
        const char* text;
        int line, column;
        const char* message;
    };
    const Case cases[] = {
        {"radius 1\nwiggle 2\n", 2, 1, "unknown directive"},
        {"0 0 0\n", 1, 1, "outside a path"},
        {"path\n0 0\n", 2, 1, "3 coordinates"},
        {"path\n0 x 0\n", 2, 3, "expected a number"},
        {"radius 0\n", 1, 8, "> 0"},
        {"radius 1 2\n", 1, 1, "takes 1 value"},
        {"radius .5\nball .2\npath\n0 0 0\n1 0 0\n", 2, 6, "smaller than the tube"},
        {"color 2 0 0\n", 1, 7, "[0, 1]"},
        {"caps maybe\n", 1, 1, "on or off"},
    };
    for (const Case& c : cases) {
        PipeSpec spec;
        Diagnostics d;
        EXPECT_FALSE(ReadPipeText(c.text, "t.pipe", spec, d)) << c.text;
        ASSERT_GE(d.ErrorCount(), 1) << c.text;
        const Diagnostic& e = d.Items()[0];
        EXPECT_EQ(e.loc.FileName(), "t.pipe");
        EXPECT_EQ(e.loc.line, c.line) << c.text;
        EXPECT_EQ(e.loc.column, c.column) << c.text;
        EXPECT_NE(e.message.find(c.message), std::string::npos) << c.text << ": " << e.message;
    }
}

TEST(PipeBuild, TooFewPointsAndOverlapsAreErrors) {
    const char* bad[] = {
        "path\n0 0 0\n0 0 0\n",         // one distinct point
        "loop\n0 0 0\n1 0 0\n",         // a loop of two points
        "path\n0 0 0\n2 0 0\n1 0 0\n",  // doubles back on itself: overlapping elements
    };
    for (const char* text : bad) {
        PipeSpec spec;
        PipeModel m;
        Diagnostics d;
        ASSERT_TRUE(ReadPipeText(text, "t.pipe", spec, d)) << text;
        EXPECT_FALSE(BuildPipes(spec, m, d)) << text;
        ASSERT_GE(d.ErrorCount(), 1);
        EXPECT_EQ(d.Items().back().loc.line, 1) << text;  // at the path's first line
    }
}

TEST(PipeGenerators, HilbertCurveHasFourToTheNMinusOneSegments) {
    for (int order = 1; order <= 5; ++order) {
        std::vector<Vec3> pts = HilbertCurve(order);
        ASSERT_EQ(pts.size(), static_cast<std::size_t>(1) << (2 * order));
        std::set<std::pair<double, double>> distinct;
        for (std::size_t i = 0; i < pts.size(); ++i) {
            distinct.insert({pts[i].x, pts[i].y});
            if (i > 0) {
                EXPECT_EQ(Length(pts[i] - pts[i - 1]), 1.0) << order << " " << i;
            }
        }
        EXPECT_EQ(distinct.size(), pts.size());  // visits every cell once
        std::string text = "radius .25\npath\n";
        for (const Vec3& p : pts) text += fmt::format("{} {} {}\n", p.x, p.y, p.z);
        PipeModel m = Build(text);
        EXPECT_EQ(m.elements.size(), (std::size_t{1} << (2 * order)) - 1) << order;
        EXPECT_EQ(m.freeEnds, 2);
    }
}

TEST(PipeGenerators, TrefoilSierpinskiAndText) {
    EXPECT_EQ(TrefoilKnot(24).size(), 24u);
    auto tri = SierpinskiTriangles(2);
    EXPECT_EQ(tri.size(), 9u);
    std::string unsupported;
    auto strokes = StrokeText("QUADRIX", &unsupported);
    EXPECT_TRUE(unsupported.empty());
    EXPECT_EQ(strokes.size(), 13u);  // Q 2, U 1, A 2, D 1, R 2, I 3, X 2
    StrokeText("Q?", &unsupported);
    EXPECT_EQ(unsupported, "?");
}

TEST(PipeMiter, TwoTubesMeetOnTheBisectingPlane) {
    // A bend of 70° at the origin: direction a along +x, b at 70° in the xy plane.
    const double angle = 70 * M_PI / 180;
    const Vec3 b{3 * std::cos(angle), 3 * std::sin(angle), 0};
    PipeModel m = Build(fmt::format("radius .4\npath\n3 0 0\n0 0 0\n{} {} 0\n", b.x, b.y));
    ASSERT_EQ(m.elements.size(), 2u);
    const PipeElement& e = m.elements[0];
    const PipeElement& f = m.elements[1];
    ASSERT_EQ(e.ends.size(), 2u);  // cap at (3,0,0), miter at the origin
    const Plane& miter = e.ends[1];
    const Vec3 n = Normalize(miter.Normal());
    const Vec3 a = {1, 0, 0}, bDir = Normalize(b);
    // Bisecting: the plane passes through the joint and makes equal angles with both axes.
    EXPECT_NEAR(miter.Evaluate({0, 0, 0}), 0, 1e-15);
    EXPECT_NEAR(Dot(n, a), -Dot(n, bDir), 1e-15);
    EXPECT_LT(Dot(n, a), 0);  // outward normal points away from e's tube
    // f's miter is the same plane with the opposite orientation.
    const Plane& fMiter = f.ends[0];
    EXPECT_NEAR(Dot(Normalize(fMiter.Normal()), n), -1, 1e-15);
    // On the plane both cylinders have the same section: each point of it inside one tube's
    // ellipse is inside the other's, and nudged to either side it belongs to that side's tube.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    const Vec3 inPlane1 = Normalize(Cross(n, {0, 0, 1})), inPlane2 = {0, 0, 1};
    int onSection = 0;
    for (int k = 0; k < 2000; ++k) {
        Vec3 p = inPlane1 * (u(rng) * 0.6) + inPlane2 * (u(rng) * 0.45);
        double se = e.side.Evaluate(p), sf = f.side.Evaluate(p);
        EXPECT_NEAR(se, sf, 1e-12);  // the same ellipse
        if (se > -1e-6) continue;    // outside the section or on its rim
        ++onSection;
        EXPECT_TRUE(InElement(e, p - n * 1e-9));
        EXPECT_FALSE(InElement(f, p - n * 1e-9));
        EXPECT_TRUE(InElement(f, p + n * 1e-9));
        EXPECT_FALSE(InElement(e, p + n * 1e-9));
    }
    EXPECT_GT(onSection, 500);
    ExpectWatertightJoints(m, 0.4);
}

TEST(PipeMiter, JointsOfThreeAndFourElementsAreWatertight) {
    // A T (three elements), an X in 3-D (four), a sharp bend and a straight joint.
    PipeModel t = Build("radius .3\npath\n-2 0 0\n0 0 0\n2 0 0\npath\n0 0 0\n0 2 0\n");
    EXPECT_EQ(t.joints[1].elements.size(), 3u);
    ExpectWatertightJoints(t, 0.3);
    PipeModel x = Build("radius .25\npath\n-2 -1 0\n0 0 0\n2 1 .5\npath\n0 2 -1\n0 0 0\n1 -2 1\n");
    ExpectWatertightJoints(x, 0.25);
    PipeModel sharp = Build("radius .2\npath\n2 0 0\n0 0 0\n2 .7 0\n");
    ExpectWatertightJoints(sharp, 0.2);
    PipeModel straight = Build("radius .2\npath\n-1 0 0\n0 0 0\n1 0 0\n");
    ExpectWatertightJoints(straight, 0.2);
}

TEST(PipeMiter, TubesAreCoveredAlongTheirLengthAndDoNotOverlap) {
    // Hilbert order 2, unit steps, radius .25: every point within 0.99 r of an element's axis
    // (between its ends) is in exactly one tube; points far from the curve are in none.
    std::string text = "radius .25\npath\n";
    for (const Vec3& p : HilbertCurve(2)) text += fmt::format("{} {} {}\n", p.x, p.y, p.z);
    PipeModel m = Build(text);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    for (const PipeElement& e : m.elements) {
        Vec3 w = e.p1 - e.p0;
        for (int k = 0; k < 200; ++k) {
            // A point of the segment plus an offset across it within 0.99 r.
            Vec3 across{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
            across = across - Normalize(w) * Dot(across, Normalize(w));
            Vec3 p = e.p0 + w * u(rng) + Normalize(across) * (0.99 * 0.25 * u(rng));
            ASSERT_EQ(CountContaining(m, p), 1) << p.x << " " << p.y << " " << p.z;
        }
    }
    EXPECT_EQ(CountContaining(m, {0.5, 0.5, 0}), 0);
}

TEST(PipeBall, BallJointsCutTubesSquareAndAddSpheres) {
    PipeModel m = Build("radius .2\nball .3\npath\n0 0 0\n1 0 0\n1 1 0\n");
    EXPECT_EQ(m.balls, 1);
    EXPECT_EQ(m.freeEnds, 2);
    // Tube 0 ends at x = 1 square: the plane x <= 1.
    const Plane& cut = m.elements[0].ends[1];
    EXPECT_NEAR(cut.a, 1, 1e-15);
    EXPECT_NEAR(cut.b, 0, 1e-15);
    EXPECT_NEAR(cut.d, -1, 1e-15);
    std::string uq = WriteUniQuadrix(m, {});
    EXPECT_NE(uq.find("quadric j1 <1 1 1 0 0 0 -1 0 0 0.91>;"), std::string::npos) << uq;
}

TEST(PipeWrite, TextReadsBackIntoTheSameHalfSpaces) {
    PipeModel m = Build(
        "radius .3\ncolor .2 .4 .6\ncaps off\nloop\n0 0 0\n2 0 1\n1 2 0\n"
        "path\n5 0 0\n6 1 1\n");
    PipeWriteOptions o;
    o.source = "t.pipe";
    o.definition = "frame";
    std::string text = WriteUniQuadrix(m, o);
    scene::Scene scene;
    Diagnostics d;
    lang::Reader reader(scene, d);
    ASSERT_TRUE(reader.ReadText(text, "out.uq")) << text;
    ASSERT_EQ(scene.definitions.size(), 1u);
    const scene::Scope& def = scene.definitions[0];
    ASSERT_EQ(def.bodies.size(), m.elements.size());
    for (std::size_t i = 0; i < m.elements.size(); ++i) {
        const PipeElement& e = m.elements[i];
        const scene::Body& b = def.bodies[i];
        ASSERT_EQ(b.literals.size(), 1 + e.ends.size());
        ASSERT_TRUE(b.color);
        const auto& side = def.halfSpaces[b.literals[0].halfSpace].quadric;
        for (int k = 0; k < 10; ++k) EXPECT_NEAR(side.k[k], e.side.k[k], 1e-14 * e.side.MaxAbs());
        for (std::size_t k = 0; k < e.ends.size(); ++k) {
            const scene::HalfSpace& h = def.halfSpaces[b.literals[1 + k].halfSpace];
            EXPECT_EQ(h.transparent, static_cast<bool>(e.endTransparent[k]));
            EXPECT_NEAR(h.plane.a, e.ends[k].a, 1e-14);
            EXPECT_NEAR(h.plane.d, e.ends[k].d, 1e-14);
        }
    }
    // Open ends: the free ends of the second path are transparent caps.
    EXPECT_TRUE(m.elements.back().endTransparent[0]);
}

}  // namespace
}  // namespace quadrix::model
