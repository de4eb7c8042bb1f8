// The solid statement (solids by dimensions, docs/language.md §3.13): coefficients against
// hand-written ones, membership against analytic definitions at random points, silhouettes
// against analytic areas through the raycast engine, use inside definitions, bodies and csg, and
// the errors of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>

#include "quadrix/lang/test_util.h"
#include "quadrix/pipeline/pipeline.h"

namespace quadrix::lang {
namespace {

using scene::HalfSpace;
using testing::Parse;
using testing::Parsed;

const HalfSpace* FindHs(const Parsed& r, const std::string& id) {
    for (const HalfSpace& h : r.scene.top.halfSpaces)
        if (h.id == id) return &h;
    return nullptr;
}

// Coefficients built through unit frames and 4×4 products carry rounding of a few ulps of the
// largest entry (all values here are O(1..100)); 1e-12 is far below any real mistake.
constexpr double kCoeffTol = 1e-12;

void ExpectQuadric(const Parsed& r, const std::string& id, std::array<double, 10> want) {
    const HalfSpace* h = FindHs(r, id);
    ASSERT_NE(h, nullptr) << id << "\n" << r.All();
    ASSERT_EQ(h->kind, HalfSpace::Kind::kQuadric) << id;
    for (int i = 0; i < 10; ++i)
        EXPECT_NEAR(h->quadric.k[i], want[i], kCoeffTol) << id << " coefficient "
                                                         << "ABCDEFGHJK"[i];
}

void ExpectPlane(const Parsed& r, const std::string& id, Plane want) {
    const HalfSpace* h = FindHs(r, id);
    ASSERT_NE(h, nullptr) << id << "\n" << r.All();
    ASSERT_EQ(h->kind, HalfSpace::Kind::kPlane) << id;
    EXPECT_NEAR(h->plane.a, want.a, kCoeffTol) << id;
    EXPECT_NEAR(h->plane.b, want.b, kCoeffTol) << id;
    EXPECT_NEAR(h->plane.c, want.c, kCoeffTol) << id;
    EXPECT_NEAR(h->plane.d, want.d, kCoeffTol) << id;
}

TEST(LangSolids, SphereMatchesTheLanguageTable) {
    // docs/language.md §2: the sphere of radius 2 about (1, 0, 0) is <1 1 1 0 0 0 -1 0 0 -3>.
    Parsed r = Parse("solid sphere ball =at 1 0 0 =r 2;");
    ASSERT_TRUE(r.ok) << r.All();
    ExpectQuadric(r, "ball", {1, 1, 1, 0, 0, 0, -1, 0, 0, -3});
    ASSERT_EQ(r.scene.top.bodies.size(), 1u);
    EXPECT_EQ(r.scene.top.bodies[0].id, "ball");
    ASSERT_EQ(r.scene.top.bodies[0].literals.size(), 1u);
    EXPECT_FALSE(r.scene.top.bodies[0].literals[0].complemented);
}

TEST(LangSolids, CylinderIsThePapersTube) {
    // The outer tube of seed 001 §2.1.2: <1 0 1 0 0 0 0 0 0 -4>, 2 <= y... capped at y = ±2.
    Parsed r = Parse("solid cylinder tube =from 0 -2 0 =to 0 2 0 =r 2;");
    ASSERT_TRUE(r.ok) << r.All();
    ExpectQuadric(r, "tube", {1, 0, 1, 0, 0, 0, 0, 0, 0, -4});
    ExpectPlane(r, "tube#0", {0, -1, 0, -2});  // y >= -2
    ExpectPlane(r, "tube#1", {0, 1, 0, -2});   // y <= 2
    ASSERT_EQ(r.scene.top.bodies.size(), 1u);
    EXPECT_EQ(r.scene.top.bodies[0].literals.size(), 3u);
}

TEST(LangSolids, EllipticCylinderAlongZWithUAlongY) {
    // Half-axis 3 along u = y, 1 along v = z × y = -x: x² + y²/9 - 1 <= 0.
    Parsed r = Parse("solid cylinder e =from 0 0 1 =to 0 0 5 =r 3 1 =u 0 1 0;");
    ASSERT_TRUE(r.ok) << r.All();
    ExpectQuadric(r, "e", {1, 1.0 / 9, 0, 0, 0, 0, 0, 0, 0, -1});
    ExpectPlane(r, "e#0", {0, 0, -1, 1});
    ExpectPlane(r, "e#1", {0, 0, 1, -5});
}

TEST(LangSolids, EllipsoidRotatedAboutItsCentre) {
    // Half-axes 3, 2, 1 along x, y, z turned 90° about z (x → y), centred at (1, 2, 3):
    // (x-1)²/4 + (y-2)²/9 + (z-3)² - 1 <= 0.
    Parsed r = Parse("solid ellipsoid egg =at 1 2 3 =r 3 2 1 =rz 90;");
    ASSERT_TRUE(r.ok) << r.All();
    ExpectQuadric(r, "egg",
                  {0.25, 1.0 / 9, 1, 0, 0, 0, -0.25, -2.0 / 9, -3, 0.25 + 4.0 / 9 + 9 - 1});
}

TEST(LangSolids, ConeWithApex) {
    // Radius 1 at z = 0 shrinking to an apex at z = 2: x² + y² - (1 - z/2)² <= 0,
    // i.e. x² + y² - z²/4 + z - 1: C = -1/4, 2J = 1, K = -1.
    Parsed r = Parse("solid cone k =from 0 0 0 =to 0 0 2 =r0 1 =r1 0;");
    ASSERT_TRUE(r.ok) << r.All();
    ExpectQuadric(r, "k", {1, 1, -0.25, 0, 0, 0, 0, 0, 0.5, -1});
    ExpectPlane(r, "k#0", {0, 0, -1, 0});
    ExpectPlane(r, "k#1", {0, 0, 1, -2});
}

TEST(LangSolids, ParaboloidAndHyperboloids) {
    Parsed r = Parse(
        "solid paraboloid cup =from 0 0 0 =to 0 0 4 =r 2;\n"              // x² + y² - z <= 0
        "solid hyperboloid neck =from 0 0 -1 =to 0 0 1 =r 2 =waist 1;\n"  // x²+y²-1-3z² <= 0
        "solid hyperboloid2 two =from 0 0 -2 =to 0 0 2 =r 3 =gap 2;\n");  // x²+y²-3z²+3 <= 0
    ASSERT_TRUE(r.ok) << r.All();
    ExpectQuadric(r, "cup", {1, 1, 0, 0, 0, 0, 0, 0, -0.5, 0});
    ExpectPlane(r, "cup#1", {0, 0, 1, -4});
    EXPECT_EQ(FindHs(r, "cup#0"), nullptr);  // a paraboloid needs no cap at its apex
    ExpectQuadric(r, "neck", {1, 1, -3, 0, 0, 0, 0, 0, 0, -1});
    ExpectPlane(r, "neck#0", {0, 0, -1, -1});
    ExpectQuadric(r, "two", {1, 1, -3, 0, 0, 0, 0, 0, 0, 3});
}

TEST(LangSolids, BoxByCornersAndByCentre) {
    Parsed r = Parse(
        "solid box bx =from 2 0 -1 =to -1 3 1;\n"
        "solid box c =at 5 0 0 =size 2 4 6 =rz 90 =t;\n");
    ASSERT_TRUE(r.ok) << r.All();
    ExpectPlane(r, "bx#x0", {-1, 0, 0, -1});  // x >= -1
    ExpectPlane(r, "bx#x1", {1, 0, 0, -2});   // x <= 2
    ExpectPlane(r, "bx#y1", {0, 1, 0, -3});
    ExpectPlane(r, "bx#z0", {0, 0, -1, -1});
    // Turned 90° about z: the box's x faces (at ±1) face ±y in the world; moved to x = 5.
    ExpectPlane(r, "c#x1", {0, 1, 0, -1});
    ExpectPlane(r, "c#y1", {-1, 0, 0, 5 - 2});  // its +y face now faces -x: x >= 3
    EXPECT_TRUE(FindHs(r, "c#z0")->transparent);
    EXPECT_EQ(r.scene.top.bodies.size(), 2u);
}

TEST(LangSolids, HalfSpaceByPointAndNormalMakesNoBody) {
    Parsed r = Parse("solid halfspace up =at 0 2 0 =n 0 1 0;");
    ASSERT_TRUE(r.ok) << r.All();
    ExpectPlane(r, "up", {0, 1, 0, -2});
    EXPECT_TRUE(r.scene.top.bodies.empty());
}

// --- membership at random points ----------------------------------------------------------

// True when p is inside every literal of body `id` (the reader's own data, as engines see it).
bool InBody(const Parsed& r, const std::string& id, const Vec3& p) {
    for (const scene::Body& b : r.scene.top.bodies) {
        if (b.id != id) continue;
        for (const scene::Literal& lit : b.literals) {
            const HalfSpace& h = r.scene.top.halfSpaces[lit.halfSpace];
            double f =
                h.kind == HalfSpace::Kind::kPlane ? h.plane.Evaluate(p) : h.quadric.Evaluate(p);
            if ((f <= 0) == lit.complemented) return false;
        }
        return true;
    }
    ADD_FAILURE() << "no body " << id;
    return false;
}

// Analytic membership returns a signed margin: > 0 inside, < 0 outside (any scale). Points
// within 1e-6 of the boundary are skipped: there the two sides legitimately disagree by rounding.
using Margin = std::function<double(const Vec3&)>;

void CheckMembership(const std::string& text, const std::string& id, const Margin& margin,
                     const Vec3& lo, const Vec3& hi) {
    Parsed r = Parse(text);
    ASSERT_TRUE(r.ok) << r.All();
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> u(0, 1);
    int inside = 0, checked = 0;
    for (int i = 0; i < 4000; ++i) {
        Vec3 p{lo.x + (hi.x - lo.x) * u(rng), lo.y + (hi.y - lo.y) * u(rng),
               lo.z + (hi.z - lo.z) * u(rng)};
        double m = margin(p);
        if (std::fabs(m) < 1e-6) continue;
        ++checked;
        inside += m > 0;
        ASSERT_EQ(InBody(r, id, p), m > 0) << text << " at " << p.x << " " << p.y << " " << p.z;
    }
    // The sampling box is chosen around the solid: both sides must be exercised.
    EXPECT_GT(inside, 100) << text;
    EXPECT_GT(checked - inside, 100) << text;
}

// Distance of p from the line a + t·d (d unit) and the parameter t.
void AxisCoords(const Vec3& p, const Vec3& a, const Vec3& b, double& t, double& dist, Vec3& d) {
    d = Normalize(b - a);
    t = Dot(p - a, d);
    dist = Length(p - a - d * t);
}

TEST(LangSolids, ObliqueCylinderMembership) {
    Vec3 a{1, 2, 3}, b{4, -1, 5};
    double len = Length(b - a);
    CheckMembership("solid cylinder c =from 1 2 3 =to 4 -1 5 =r 0.7;", "c",
                    [&](const Vec3& p) {
                        double t, dist;
                        Vec3 d;
                        AxisCoords(p, a, b, t, dist, d);
                        return std::min({0.7 - dist, t, len - t});
                    },
                    {0, -2, 2}, {5, 3, 6});
}

TEST(LangSolids, ObliqueEllipticCylinderMembership) {
    // Half-axis 1.5 along u (the part of (0,0,1) across the axis), 0.5 along v = w × u.
    Vec3 a{-1, 0, 0}, b{2, 1, 0};
    CheckMembership("solid cylinder e =from -1 0 0 =to 2 1 0 =r 1.5 .5 =u 0 0 1;", "e",
                    [&](const Vec3& p) {
                        Vec3 w = Normalize(b - a), uu{0, 0, 1}, vv = Cross(w, uu);
                        Vec3 q = p - a;
                        double x = Dot(q, uu) / 1.5, y = Dot(q, vv) / 0.5, t = Dot(q, w);
                        return std::min({1 - (x * x + y * y), t, Length(b - a) - t});
                    },
                    {-2, -2, -2}, {3, 3, 2});
}

TEST(LangSolids, ObliqueConeFrustumMembership) {
    Vec3 a{0, 1, 0}, b{2, 3, 1};
    double len = Length(b - a);
    CheckMembership("solid cone k =from 0 1 0 =to 2 3 1 =r0 1.2 =r1 .4;", "k",
                    [&](const Vec3& p) {
                        double t, dist;
                        Vec3 d;
                        AxisCoords(p, a, b, t, dist, d);
                        double radius = 1.2 + (0.4 - 1.2) * t / len;
                        return std::min({radius - dist, t, len - t});
                    },
                    {-1.5, -0.5, -1.5}, {3.5, 4.5, 2.5});
}

TEST(LangSolids, RotatedEllipsoidMembership) {
    Transform rot = Transform::Rotate(2, 50) * Transform::Rotate(1, 40) * Transform::Rotate(0, 30);
    CheckMembership("solid ellipsoid e =at 1 -1 2 =r 2 1 .5 =rx 30 =ry 40 =rz 50;", "e",
                    [&](const Vec3& p) {
                        Vec3 q = rot.Inverted().MapPoint(p - Vec3{1, -1, 2});
                        return 1 - (q.x * q.x / 4 + q.y * q.y + q.z * q.z / 0.25);
                    },
                    {-1.2, -3.2, -0.2}, {3.2, 1.2, 4.2});
}

TEST(LangSolids, RotatedBoxMembership) {
    Transform rot = Transform::Rotate(0, 20) * Transform::Rotate(2, 35);
    CheckMembership(
        "solid box bx =at 0 1 0 =size 2 1 3 =rz 35 =rx 20;", "bx",
        [&](const Vec3& p) {
            Vec3 q = rot.Inverted().MapPoint(p - Vec3{0, 1, 0});
            return std::min({1 - std::fabs(q.x), 0.5 - std::fabs(q.y), 1.5 - std::fabs(q.z)});
        },
        {-2, -1, -2}, {2, 3, 2});
}

TEST(LangSolids, ObliqueParaboloidMembership) {
    Vec3 a{0, 0, 0}, b{1, 2, 2};  // length 3
    CheckMembership("solid paraboloid pb =from 0 0 0 =to 1 2 2 =r 1.5;", "pb",
                    [&](const Vec3& p) {
                        double t, dist;
                        Vec3 d;
                        AxisCoords(p, a, b, t, dist, d);
                        // radius² grows linearly: 1.5² at t = 3.
                        return std::min(1.5 * 1.5 * t / 3 - dist * dist, 3 - t);
                    },
                    {-2, -2, -2}, {3, 4, 4});
}

TEST(LangSolids, ObliqueHyperboloidsMembership) {
    Vec3 a{1, 0, 0}, b{1, 4, 3};  // length 5, middle at t = 2.5
    CheckMembership("solid hyperboloid h =from 1 0 0 =to 1 4 3 =r 2 =waist .8;", "h",
                    [&](const Vec3& p) {
                        double t, dist;
                        Vec3 d;
                        AxisCoords(p, a, b, t, dist, d);
                        double z = t - 2.5;
                        double r2 = 0.64 + (4 - 0.64) * z * z / 6.25;
                        return std::min({r2 - dist * dist, t, 5 - t});
                    },
                    {-2, -1, -1}, {4, 5, 4});
    CheckMembership("solid hyperboloid2 h =from 1 0 0 =to 1 4 3 =r 2 =gap 2;", "h",
                    [&](const Vec3& p) {
                        double t, dist;
                        Vec3 d;
                        AxisCoords(p, a, b, t, dist, d);
                        double z = t - 2.5;
                        // Vertices at |z| = 1, radius 2 at |z| = 2.5: r² = 4 (z² - 1)/(6.25 - 1).
                        double r2 = 4 * (z * z - 1) / 5.25;
                        return std::min({r2 - dist * dist, t, 5 - t});
                    },
                    {-2, -1, -1}, {4, 5, 4});
}

// --- silhouettes through the raycast engine -------------------------------------------------

// Renders `text` at 256×256 with a window of half-size 1.28 looking along z: 100 px per unit,
// so an area of A square units covers 10⁴·A pixels.
double RenderedArea(const std::string& text) {
    PipelineOptions o;
    o.sceneText = text + "\nview v dop 0 0 -1 whh 1.28 whw 1.28;\n";
    o.width = o.height = 256;
    o.threads = 1;
    PipelineResult result;
    Diagnostics d;
    bool ok = RunPipeline(o, result, d);
    std::string msgs;
    for (const auto& item : d.Items()) msgs += item.Format() + "\n";
    EXPECT_TRUE(ok) << msgs;
    return static_cast<double>(result.frame.CoveredCount()) / 1e4;
}

// Simpson's rule for the silhouettes whose area is an integral of the width.
double Integrate(const std::function<double(double)>& f, double a, double b) {
    const int n = 2000;
    double h = (b - a) / n, s = f(a) + f(b);
    for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4 : 2);
    return s * h / 3;
}

// Silhouette areas are compared within 0.5%: the pixel-centre sampling error is bounded by about
// half the perimeter in pixels (300-600 px, i.e. 1-3% of these areas) but cancels along smooth
// outlines; measured errors are below 0.1%. A radius or length wrong by 1% already fails.
constexpr double kAreaTol = 0.005;

TEST(LangSolids, SilhouettesMatchAnalyticAreas) {
    struct Case {
        const char* scene;
        double area;
    };
    const double pi = M_PI;
    const Case cases[] = {
        {"solid sphere s =r 1;", pi},
        {"solid ellipsoid e =r 1.1 .6 2 =rz 30;", pi * 1.1 * 0.6},
        // Side views: axis along x.
        {"solid cylinder c =from -1 0 0 =to 1 0 0 =r .5;", 2 * 1.0},
        {"solid cylinder c =from -1 .1 0 =to 1 .1 0 =r .3 .9 =u 0 1 0;", 2 * 0.6},
        {"solid cone k =from -1 0 0 =to 1 0 0 =r0 1 =r1 .2;", (2 + 0.4) / 2 * 2},
        {"solid box bx =at .1 0 0 =size 1.5 1 3 =rz 45;", 1.5},
        {"solid paraboloid pb =from -1 0 0 =to 1 0 0 =r 1;", 4.0 / 3 * 1 * 2},
        {"solid hyperboloid h =from -1 0 0 =to 1 0 0 =r 1 =waist .4;",
         Integrate([](double z) { return 2 * std::sqrt(0.16 + 0.84 * z * z); }, -1, 1)},
        {"solid hyperboloid2 h =from -1.2 0 0 =to 1.2 0 0 =r 1 =gap 1;",
         2 * Integrate([](double z) { return 2 * std::sqrt((z * z - 0.25) / (1.44 - 0.25)); }, 0.5,
                       1.2)},
        // A unit disc less the segment above y = .5: π − (acos(.5) − .5·sqrt(.75)).
        {"solid sphere s =r 1 =hsb; solid halfspace cut =at 0 .5 0 =n 0 1 0; body cap (s cut);",
         pi - (std::acos(0.5) - 0.5 * std::sqrt(0.75))},
        // Elliptic cone, half-axis a along u = y: from 1 to .4 across the picture.
        {"solid cone k =from -1 0 0 =to 1 0 0 =r0 1 .5 =r1 .4 .2 =u 0 1 0;", (2 + 0.8) / 2 * 2},
        // The end view of a cylinder along z is its disc.
        {"solid cylinder c =from 0 0 -1 =to 0 0 1 =r .8;", pi * 0.64},
    };
    for (const Case& c : cases)
        EXPECT_NEAR(RenderedArea(c.scene) / c.area, 1.0, kAreaTol) << c.scene;
}

TEST(LangSolids, DrilledPlateThroughComplementAndCsg) {
    // A 2×2 plate seen from the front with a hole of radius .5 drilled by '!' of the cylinder's
    // infinite surface, and the same by csg difference of the capped cylinder.
    const double want = 4 - M_PI * 0.25;
    EXPECT_NEAR(RenderedArea("solid box plate =size 2 2 .2 =hsb;\n"
                             "solid cylinder hole =from 0 0 -1 =to 0 0 1 =r .5 =hsb;\n"
                             "body drilled (plate#x0 plate#x1 plate#y0 plate#y1 plate#z0 "
                             "plate#z1 !hole);") /
                    want,
                1.0, kAreaTol);
    EXPECT_NEAR(RenderedArea("solid box plate =size 2 2 .2;\n"
                             "solid cylinder peg =from 0 0 -1 =to 0 0 1 =r .5;\n"
                             "csg drilled (plate - peg);") /
                    want,
                1.0, kAreaTol);
}

TEST(LangSolids, InsideDefinitionsAndInstances) {
    // Four spheres of radius .3 from one definition placed by an array: 4·π·0.09.
    double area = RenderedArea(
        "definition bead; solid sphere s =r .3 =c 1 0 0; enddef;\n"
        "array row (bead =tx -.9) 4 =tx .6;");
    EXPECT_NEAR(area / (4 * M_PI * 0.09), 1.0, kAreaTol);
    Parsed r = Parse(
        "definition d; solid cylinder c =from 0 0 0 =to 1 0 0 =r 1; body e (!c c#0 "
        "c#1); enddef;");
    ASSERT_TRUE(r.ok) << r.All();
    ASSERT_EQ(r.scene.definitions.size(), 1u);
    EXPECT_EQ(r.scene.definitions[0].halfSpaces.size(), 3u);
    EXPECT_EQ(r.scene.definitions[0].bodies.size(), 2u);
    EXPECT_TRUE(r.scene.top.halfSpaces.empty());
}

TEST(LangSolids, OptionsOpenHsbColorAndGeneratedIds) {
    Parsed r = Parse(
        "solid cylinder =from 0 0 0 =to 0 0 1 =r 1 =open1 =c 1 .5 0;\n"
        "solid cylinder =from 0 0 0 =to 0 0 1 =r 1 =open;\n"
        "solid sphere =r 1 =hsb;\n");
    ASSERT_TRUE(r.ok) << r.All();
    EXPECT_FALSE(FindHs(r, "cylinder#1#0")->transparent);
    EXPECT_TRUE(FindHs(r, "cylinder#1#1")->transparent);
    EXPECT_FALSE(FindHs(r, "cylinder#1")->transparent);
    EXPECT_TRUE(FindHs(r, "cylinder#2#0")->transparent);
    EXPECT_TRUE(FindHs(r, "cylinder#2#1")->transparent);
    ASSERT_NE(FindHs(r, "sphere#1"), nullptr);
    ASSERT_EQ(r.scene.top.bodies.size(), 2u);  // =hsb: no body for the sphere
    ASSERT_TRUE(r.scene.top.bodies[0].color);
    EXPECT_EQ(*r.scene.top.bodies[0].color, (scene::Color{1, 0.5, 0}));
}

// --- errors ---------------------------------------------------------------------------------

struct ErrorCase {
    const char* text;
    const char* at;       // the error is at the first occurrence of this text
    const char* message;  // a part of the message
};

TEST(LangSolids, BadInputGivesPositionedErrors) {
    const ErrorCase cases[] = {
        {"solid sphere s =r 0;", "=r", "must be > 0"},
        {"solid sphere s =r -1;", "=r", "must be > 0"},
        {"solid sphere s =at 1 2 =r 1;", "=at", "takes 3 numbers"},
        {"solid sphere s =at 1 2 3 4 =r 1;", "=at", "found 4"},
        {"solid ellipsoid e =r 1 2;", "=r", "takes 3 numbers"},
        {"solid cylinder c =from 1 2 3 =to 1 2 3 =r 1;", "=to", "same point"},
        {"solid cylinder c =from 0 0 0 =r 1;", "solid", "needs =to"},
        {"solid cylinder c =from 0 0 0 =to 0 0 1 =r 1 2 3;", "=r", "takes 1 or 2 numbers"},
        {"solid cylinder c =from 0 0 0 =to 0 0 1 =r 1 =u 0 0 2;", "=u", "parallel"},
        {"solid cylinder c =from 0 0 0 =to 0 0 1 =r 1 =at 0 0 0;", "=at", "unknown option"},
        {"solid cone k =from 0 0 0 =to 0 0 1 =r0 0 =r1 0;", "=r1", "both 0"},
        {"solid cone k =from 0 0 0 =to 0 0 1 =r0 1 2 =r1 1 1;", "=r1", "same shape"},
        {"solid box bx =from 0 0 0 =to 1 0 1;", "=to", "flat"},
        {"solid box bx =at 0 0 0 =size 1 0 1;", "=size", "must be > 0"},
        {"solid box bx =at 0 0 0 =from 1 1 1 =to 2 2 2;", "=at", "not both"},
        {"solid hyperboloid h =from 0 0 0 =to 0 0 1 =r 1 =waist 1;", "=waist", "smaller"},
        {"solid hyperboloid2 h =from 0 0 0 =to 0 0 1 =r 1 =gap 1;", "=gap", "smaller"},
        {"solid halfspace h =n 0 0 0;", "=n", "zero vector"},
        {"solid blob b =r 1;", "blob", "expected a solid kind"},
        {"solid sphere s =r 1 =sx 0;", "0;", "scale factor 0"},
        {"solid sphere s =r;", "=r", "found 0"},
        // solid pipe (stmt_pipe.cpp): at the =p concerned, or at `solid` for the whole pipe.
        {"solid pipe h =p 0 0 0 2 1 =p 1 0 0 2 1 0;", "=p", "takes 6 numbers"},
        {"solid pipe h =p 0 0 0 2 1 0;", "solid", "at least 2 points"},
        {"solid pipe h =p 0 0 0 2 1 0 =p 5 0 0 0 0 0;", "=p 5", "outer diameter"},
        {"solid pipe h =p 0 0 0 2 2 0 =p 5 0 0 2 1 0;", "=p", "inner diameter"},
        {"solid pipe h =p 0 0 0 2 0 0 =p 5 0 0 2 0 -1;", "=p 5", "bend radius"},
        {"solid pipe h =p 0 0 0 2 0 0 =p 5 0 0 2 0 .5 =p 5 5 0 2 0 0;", "=p 5 0",
         "smaller than the outer radius"},
        {"solid pipe h =p 0 0 0 2 0 0 =p 5 0 0 2 0 4 =p 5 5 0 2 0 4 =p 10 5 0 2 0 0;", "=p 5 5",
         "overlap"},
        {"solid pipe h =p 0 0 0 2 0 0 =p 5 0 0 2 0 2 =p 0 0 0 2 0 0;", "=p 5", "turns"},
        {"solid pipe h =p 0 0 0 2 0 0 =p 1 0 0 2 0 0 =r 1;", "=r", "unknown option"},
    };
    for (const ErrorCase& c : cases) {
        Parsed r = Parse(c.text);
        EXPECT_FALSE(r.ok) << c.text;
        ASSERT_FALSE(r.Errors().empty()) << c.text;
        const Diagnostic& e = *r.Errors()[0];
        EXPECT_EQ(e.loc.FileName(), "test.uq");
        EXPECT_EQ(e.loc.line, 1) << c.text;
        EXPECT_EQ(e.loc.column, static_cast<int>(std::string(c.text).find(c.at)) + 1)
            << c.text << "\n"
            << r.All();
        EXPECT_NE(e.message.find(c.message), std::string::npos) << c.text << "\n" << r.All();
        // Nothing half-made is left behind.
        EXPECT_TRUE(r.scene.top.bodies.empty()) << c.text;
    }
}

// solid pipe: one body per run or bend, named as docs/language.md says, their union the csg `id`;
// membership of points of the wall, the bore and outside against the pipe's definition.
TEST(LangSolids, PipePiecesNamesAndMembership) {
    // From the origin along +x, a 90° bend of radius 3 at (6, 0, 0), then along +y; od 2, id 1.2.
    Parsed r = Parse(
        "solid pipe hose =p 0 0 0 2 1.2 0 =p 6 0 0 2 1.2 3 =p 6 5 0 2 1.2 0 =c .3 .6 .9 "
        "=open1;");
    ASSERT_TRUE(r.ok) << r.All();
    const scene::Scope& top = r.scene.top;
    ASSERT_EQ(top.bodies.size(), 3u);
    ASSERT_EQ(top.csgs.size(), 1u);
    EXPECT_EQ(top.csgs[0].id, "hose");
    ASSERT_TRUE(top.csgs[0].color.has_value());
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(top.bodies[k].id, "hose#" + std::to_string(k + 1));
        EXPECT_TRUE(top.bodies[k].usedAsOperand);
        EXPECT_EQ(top.bodies[k].literals.size(), 4u);  // outer, !bore, start and end planes
    }
    ASSERT_NE(FindHs(r, "hose#1"), nullptr);
    EXPECT_EQ(FindHs(r, "hose#1")->kind, HalfSpace::Kind::kQuadric);
    EXPECT_EQ(FindHs(r, "hose#2")->kind, HalfSpace::Kind::kQuartic);  // the bend: a torus
    ASSERT_NE(FindHs(r, "hose#2.bore"), nullptr);
    EXPECT_EQ(FindHs(r, "hose#2.bore")->kind, HalfSpace::Kind::kQuartic);
    EXPECT_FALSE(FindHs(r, "hose#1.0")->transparent);  // =open1 opens the far end only
    EXPECT_TRUE(FindHs(r, "hose#3.1")->transparent);
    // Each run ends where the next piece begins: the joint at x = 3 (tangent distance 3).
    const Plane& j = FindHs(r, "hose#1.1")->plane;
    EXPECT_NEAR(j.Evaluate({3, 0, 0}), 0, 1e-12);
    auto inside = [&](const Vec3& p) {
        for (const scene::Body& b : top.bodies) {
            bool in = true;
            for (const scene::Literal& l : b.literals) {
                const HalfSpace& h = top.halfSpaces[l.halfSpace];
                const double v = h.kind == HalfSpace::Kind::kQuartic ? h.quartic->Evaluate(p)
                                 : h.kind == HalfSpace::Kind::kPlane ? h.plane.Evaluate(p)
                                                                     : h.quadric.Evaluate(p);
                in = in && (l.complemented ? v >= 0 : v <= 0);
            }
            if (in) return true;
        }
        return false;
    };
    EXPECT_TRUE(inside({1, 0.8, 0}));   // the wall of the first run
    EXPECT_FALSE(inside({1, 0.3, 0}));  // its bore
    EXPECT_FALSE(inside({1, 1.2, 0}));  // outside
    EXPECT_TRUE(inside({6, 4, 0.8}));   // the wall of the last run
    // The bend: centre (3, 3, 0), radius 3; at 45° the centre line is at (3 + 3/√2, 3 − 3/√2).
    const double c = 3 / std::sqrt(2.0), u = 1 / std::sqrt(2.0);
    EXPECT_TRUE(inside({3 + c + 0.8 * u, 3 - c - 0.8 * u, 0}));
    EXPECT_FALSE(inside({3 + c + 0.3 * u, 3 - c - 0.3 * u, 0}));
    EXPECT_FALSE(inside({3 + c + 1.1 * u, 3 - c - 1.1 * u, 0}));
    EXPECT_FALSE(inside({-0.1, 0.8, 0}));  // before the start cap
    // =hsb: half-spaces only; a transform moves every piece.
    Parsed h = Parse("solid pipe rod =p 0 0 0 2 0 0 =p 0 4 0 2 0 0 =hsb =tx 10;");
    ASSERT_TRUE(h.ok) << h.All();
    EXPECT_TRUE(h.scene.top.bodies.empty());
    EXPECT_TRUE(h.scene.top.csgs.empty());
    ASSERT_NE(FindHs(h, "rod#1"), nullptr);
    EXPECT_NEAR(FindHs(h, "rod#1")->quadric.Evaluate({10, 2, 0}), -1, 1e-12);  // on the axis: −r²
    EXPECT_EQ(FindHs(h, "rod#1.bore"), nullptr);                               // a solid rod
    // In a csg like any solid.
    Parsed cut = Parse(
        "solid box block =at 0 0 0 =size 4 4 4;\n"
        "solid pipe drill =p -3 0 0 1 0 0 =p 3 0 0 1 0 0;\n"
        "csg holed (block - drill);");
    EXPECT_TRUE(cut.ok) << cut.All();
}

TEST(LangSolids, ClashingIdsAddNothing) {
    Parsed r = Parse("plane c#1 <0 0 1 0>;\nsolid cylinder c =from 0 0 0 =to 0 0 1 =r 1;");
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.Errors().size(), 1u);
    EXPECT_EQ(r.Errors()[0]->loc.line, 2);
    EXPECT_EQ(r.Errors()[0]->loc.column, 16);
    EXPECT_NE(r.Errors()[0]->message.find("'c#1'"), std::string::npos);
    EXPECT_EQ(r.scene.top.halfSpaces.size(), 1u);
    EXPECT_TRUE(r.scene.top.bodies.empty());
}

TEST(LangSolids, SolidIsReservedButItsKindsAreNot) {
    // The kinds are plain words after 'solid': scenes may keep using them as ids.
    Parsed ok = Parse(
        "quadric cone <1 -1 1 0 0 0 0 0 0 0>; plane box <0 1 0 -1>; "
        "body sphere (cone box);");
    EXPECT_TRUE(ok.ok) << ok.All();
    Parsed bad = Parse("plane solid <0 1 0 0>;");
    EXPECT_FALSE(bad.ok);
}

}  // namespace
}  // namespace quadrix::lang

namespace quadrix::lang {
namespace {

// Random solid statements with random, often absurd, values (huge, tiny, zero, negative): the
// reader never crashes, every error has a position, and every half-space it keeps is finite.
TEST(LangSolids, RandomStatementsNeverCrash) {
    const char* kinds[] = {"sphere",     "ellipsoid",   "cylinder",     "cone",     "box",
                           "paraboloid", "hyperboloid", "hyperboloid2", "halfspace"};
    const char* options[] = {"=at",    "=r",   "=from", "=to", "=r0",   "=r1",  "=size", "=u", "=n",
                             "=waist", "=gap", "=rz",   "=sa", "=open", "=hsb", "=t",    "=c"};
    const char* numbers[] = {"0", "1", "-1", ".5", "2", "1e300", "1e-300", "3", "-2.5", "7"};
    std::mt19937 rng(99);
    for (int trial = 0; trial < 3000; ++trial) {
        std::string text = std::string("solid ") + kinds[rng() % 9] + " s";
        int n = static_cast<int>(rng() % 8);
        for (int i = 0; i < n; ++i) {
            text += std::string(" ") + options[rng() % 17];
            int m = static_cast<int>(rng() % 4);
            for (int k = 0; k < m; ++k) text += std::string(" ") + numbers[rng() % 10];
        }
        text += ";";
        Parsed r = Parse(text);
        for (const Diagnostic* e : r.Errors()) EXPECT_GT(e->loc.column, 0) << text;
        for (const HalfSpace& h : r.scene.top.halfSpaces) {
            EXPECT_TRUE(h.kind == HalfSpace::Kind::kPlane ? h.plane.AllFinite()
                                                          : h.quadric.AllFinite())
                << text;
        }
        if (r.ok) {
            EXPECT_FALSE(r.scene.top.halfSpaces.empty()) << text;
        }
    }
}

}  // namespace
}  // namespace quadrix::lang

namespace quadrix::lang {
namespace {

// The examples of docs/language.md §3.13 read without any diagnostic (the page stays true).
TEST(LangSolids, LanguageDocExamplesRead) {
    std::ifstream in(std::string(QUADRIX_SOURCE_DIR) + "/docs/language.md");
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string doc = ss.str();
    const auto begin = doc.find("### 3.13 solid");
    ASSERT_NE(begin, std::string::npos);
    const auto end = doc.find("\n## 4.", begin);
    int blocks = 0;
    for (auto open = doc.find("```\n", begin); open < end; open = doc.find("```\n", open)) {
        const auto close = doc.find("```", open + 4);
        const std::string block = doc.substr(open + 4, close - open - 4);
        open = close + 3;
        if (block.find("[id]") != std::string::npos) continue;  // a grammar
        Parsed r = Parse(block);
        EXPECT_TRUE(r.ok) << block << "\n" << r.All();
        EXPECT_EQ(r.diags.WarningCount(), 0) << r.All();
        ++blocks;
    }
    EXPECT_GE(blocks, 1);
}

}  // namespace
}  // namespace quadrix::lang
