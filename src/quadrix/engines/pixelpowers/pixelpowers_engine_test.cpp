// Engine `pixelpowers` against the raycast oracle on hand-built device-space scenes: random CSG
// trees over convex and non-convex bodies, degenerate views (planes edge-on, cylinders along the
// rays, cone apexes), transparent clipping planes, several solids.
#include "quadrix/engines/pixelpowers/pixelpowers_engine.h"

#include <gtest/gtest.h>

#include <random>

#include "quadrix/engines/engine_test_util.h"
#include "quadrix/engines/pixelpowers/compiler.h"
#include "quadrix/engines/pixelpowers/machine.h"
#include "quadrix/engines/raycast/raycast.h"
#include "quadrix/flatten/test_scene_builder.h"
#include "quadrix/frame/compare.h"
#include "quadrix/shade/shader.h"

namespace quadrix::pixelpowers {
namespace {

using testing_util::Counter;
using testing_util::TestSceneBuilder;

Frame RenderWith(Engine& e, const FlatScene& scene, std::map<std::string, std::string> opts = {}) {
    RenderOptions o;
    o.engineOptions = std::move(opts);
    Frame f;
    e.Render(scene, o, f);
    return f;
}

void ExpectMatchesRaycast(const FlatScene& scene, const std::string& what,
                          std::size_t minCovered = 50) {
    auto pp = MakePixelPowersEngine();
    auto rc = MakeRaycastEngine();
    Frame a = RenderWith(*pp, scene), r = RenderWith(*rc, scene);
    CompareOptions exactDepth;
    exactDepth.depthTolerance = 0;  // any difference counts
    const FrameComparison g = CompareFrames(a, r, exactDepth);
    EXPECT_GE(g.coveredBoth, minCovered) << what;
    EXPECT_EQ(g.offEdgeDifferences, 0u) << what << ": " << g.firstDifference;
    // Justification: both engines compute each literal's roots with LiteralOnRay on the same
    // re-centred coefficients, so the same surface gives the same double.
    EXPECT_EQ(g.depthOverTolerance, 0u) << what;
    EXPECT_GE(static_cast<double>(g.sameSurface), 0.99 * static_cast<double>(g.coveredBoth))
        << what;
}

// Quadric x^T M x + 2 b^T x + k from a symmetric 3×3 M (row-major) and centre c:
// (x−c)^T M (x−c) + k0.
std::array<double, 10> Centred(const double m[9], const Vec3& c, double k0) {
    Vec3 mc{m[0] * c.x + m[1] * c.y + m[2] * c.z, m[3] * c.x + m[4] * c.y + m[5] * c.z,
            m[6] * c.x + m[7] * c.y + m[8] * c.z};
    return {m[0], m[4], m[8], m[1], m[5], m[2], -mc.x, -mc.y, -mc.z, Dot(c, mc) + k0};
}

Box3 Around(const Vec3& c, double r) { return {c - Vec3{r, r, r}, c + Vec3{r, r, r}}; }

// Random bodies: spheres, capped cylinders and capped double cones along random axes, and boxes
// with a spherical cavity (a complemented quadric: two pieces along a ray).
int RandomBody(TestSceneBuilder& b, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    Vec3 c{12 + 40 * u(rng), 12 + 40 * u(rng), 30 + 20 * u(rng)};
    int kind = std::uniform_int_distribution<int>(0, 3)(rng);
    if (kind == 0) {
        double r = 6 + 12 * u(rng);
        int s = b.AddSphere(c, r);
        return b.AddBody({{s, false}}, Around(c, r + 1e-6));
    }
    if (kind == 3) {  // box [c ± h] minus a sphere of radius < h√3 (a cavity that may open)
        double h = 6 + 8 * u(rng), r = h * (0.6 + 0.6 * u(rng));
        std::vector<std::pair<int, bool>> lits;
        for (int axis = 0; axis < 3; ++axis) {
            double n[3] = {0, 0, 0};
            n[axis] = 1;
            double ca = axis == 0 ? c.x : axis == 1 ? c.y : c.z;
            lits.push_back({b.AddPlane(n[0], n[1], n[2], -(ca + h)), false});
            lits.push_back({b.AddPlane(-n[0], -n[1], -n[2], ca - h), false});
        }
        lits.push_back({b.AddSphere(c + Vec3{0.3 * h, 0.2 * h, -0.4 * h}, r), true});
        return b.AddBody(lits, Around(c, h + 1e-6));
    }
    Vec3 d = Normalize(Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5});
    double h = 6 + 10 * u(rng), r = 3 + 6 * u(rng);
    double k = kind == 1 ? 1.0 : 1.0 + (r / h) * (r / h);  // cylinder: I − d dᵀ; cone: I − k d dᵀ
    double m[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m[3 * i + j] = (i == j ? 1.0 : 0.0) -
                           k * d[static_cast<std::size_t>(i)] * d[static_cast<std::size_t>(j)];
    int q = b.AddQuadric(Centred(m, c, kind == 1 ? -r * r : 0.0));
    int top = b.AddPlane(d.x, d.y, d.z, -Dot(d, c) - h);
    int bot = b.AddPlane(-d.x, -d.y, -d.z, Dot(d, c) - h);
    return b.AddBody({{q, false}, {top, false}, {bot, false}}, Around(c, h + r + 1e-6));
}

int RandomTree(TestSceneBuilder& b, std::mt19937& rng, const std::vector<int>& bodies, int depth) {
    std::uniform_real_distribution<double> u(0, 1);
    if (depth >= 3 || (depth > 0 && u(rng) < 0.35)) {
        int body = bodies[std::uniform_int_distribution<std::size_t>(0, bodies.size() - 1)(rng)];
        return b.AddLeaf(body);
    }
    static const scene::CsgOp ops[] = {scene::CsgOp::kUnion, scene::CsgOp::kIntersection,
                                       scene::CsgOp::kDifference, scene::CsgOp::kDifference};
    scene::CsgOp op = ops[std::uniform_int_distribution<int>(0, 3)(rng)];
    std::vector<int> children;
    int n = u(rng) < 0.7 ? 2 : 3;
    for (int i = 0; i < n; ++i) children.push_back(RandomTree(b, rng, bodies, depth + 1));
    return b.AddNode(op, children);
}

TEST(PixelPowersEngine, RandomCsgScenesMatchRaycast) {
    std::mt19937 rng(77);
    int nonTrivial = 0;
    for (int trial = 0; trial < 40; ++trial) {
        TestSceneBuilder b(64, 64);
        std::vector<int> bodies;
        for (int i = 0; i < 5; ++i) bodies.push_back(RandomBody(b, rng));
        b.AddSolid(RandomTree(b, rng, bodies, 0));
        // A second solid, to exercise the union of solids (per-pixel minimum, ties by index).
        b.AddSolid(b.AddLeaf(RandomBody(b, rng)));
        FlatScene withBounds = b.scene();
        FlatScene without = b.WithoutBounds();
        auto rc = MakeRaycastEngine();
        Frame r = RenderWith(*rc, withBounds);
        nonTrivial += r.CoveredCount() > 200;
        ExpectMatchesRaycast(withBounds, "trial " + std::to_string(trial), 0);
        ExpectMatchesRaycast(without, "trial " + std::to_string(trial) + " without bounds", 0);
        if (::testing::Test::HasFailure()) break;
    }
    EXPECT_GE(nonTrivial, 30);
}

// The paper's depth mode on the same random scenes: every sheet is within the tolerance, so on
// pixels showing the same surface as raycast the depth error is at most the tolerance (a 1e-9
// relative slack for rounding), and the solid differs only near edges and intersection curves,
// where a depth error of up to the tolerance can move them by a pixel or so.
TEST(PixelPowersEngine, ApproxModeStaysWithinTolerance) {
    std::mt19937 rng(91);
    const double kTolerance = 0.25;
    for (int trial = 0; trial < 20; ++trial) {
        TestSceneBuilder b(64, 64);
        std::vector<int> bodies;
        for (int i = 0; i < 5; ++i) bodies.push_back(RandomBody(b, rng));
        b.AddSolid(RandomTree(b, rng, bodies, 0));
        b.AddSolid(b.AddLeaf(RandomBody(b, rng)));
        auto pp = MakePixelPowersEngine();
        auto rc = MakeRaycastEngine();
        Frame a = RenderWith(*pp, b.scene(), {{"mode", "approx"}, {"tolerance", "0.25"}});
        Frame r = RenderWith(*rc, b.scene());
        std::size_t both = 0, sameSolid = 0, sameSurface = 0;
        double maxErr = 0;
        for (std::size_t i = 0; i < r.depth.size(); ++i) {
            if (a.surface[i] == Frame::kNone || r.surface[i] == Frame::kNone) continue;
            ++both;
            sameSolid += a.Solid(i) == r.Solid(i);
            if (a.surface[i] == r.surface[i]) {
                ++sameSurface;
                maxErr = std::max<double>(maxErr, std::fabs(a.depth[i] - r.depth[i]));
            }
        }
        EXPECT_LE(maxErr, kTolerance * (1 + 1e-9) + 1e-9) << "trial " << trial;
        EXPECT_GE(static_cast<double>(sameSolid), 0.99 * static_cast<double>(both))
            << "trial " << trial;
        EXPECT_GE(static_cast<double>(sameSurface), 0.97 * static_cast<double>(both))
            << "trial " << trial << ": " << sameSurface << " of " << both;
    }
}

// Degenerate views: a plane seen edge-on, a cylinder along the rays (C = 0, linear in z: no
// sheet), a paraboloid opening along z (C = 0 but linear in z: one root per pixel), a cone whose
// apex is in view, a two-sheet hyperboloid.
TEST(PixelPowersEngine, DegenerateViewsMatchRaycast) {
    TestSceneBuilder b(64, 64);
    // Cylinder along z: (x−20)² + (y−20)² <= 64, cut by z in [10, 50] and an edge-on plane x <= 24.
    int cyl = b.AddQuadric({1, 1, 0, 0, 0, 0, -20, -20, 0, 800 - 64});
    int z0 = b.AddPlane(0, 0, -1, 10), z1 = b.AddPlane(0, 0, 1, -50);
    int edgeOn = b.AddPlane(1, 0, 0, -24);
    int body1 = b.AddBody({{cyl, false}, {z0, false}, {z1, false}, {edgeOn, false}});
    // Paraboloid (x−44)² + (y−20)² − 4 (z − 10) <= 0, capped at z <= 40.
    int para = b.AddQuadric({1, 1, 0, 0, 0, 0, -44, -20, -2, 44 * 44 + 400 + 40});
    int cap = b.AddPlane(0, 0, 1, -40);
    int body2 = b.AddBody({{para, false}, {cap, false}});
    // Double cone along y with apex at (20, 46, 30): (x−20)² + (z−30)² − (y−46)² <= 0, |y−46|
    // <= 12.
    int cone = b.AddQuadric(
        Centred(std::array<double, 9>{1, 0, 0, 0, -1, 0, 0, 0, 1}.data(), {20, 46, 30}, 0));
    int ct = b.AddPlane(0, 1, 0, -58), cb = b.AddPlane(0, -1, 0, 34);
    int body3 = b.AddBody({{cone, false}, {ct, false}, {cb, false}});
    // Two-sheet hyperboloid along z: z'² − x'² − y'² >= 16 i.e. x'² + y'² − z'² + 16 <= 0,
    // cut to |x'|,|y'| <= 8 around (46, 46, 40).
    int hyp = b.AddQuadric(
        Centred(std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, -1}.data(), {46, 46, 40}, 16));
    int hx0 = b.AddPlane(1, 0, 0, -54), hx1 = b.AddPlane(-1, 0, 0, 38);
    int body4 = b.AddBody({{hyp, false}, {hx0, false}, {hx1, false}});
    for (int body : {body1, body2, body3, body4}) b.AddSolid(b.AddLeaf(body));
    ExpectMatchesRaycast(b.scene(), "degenerate views", 800);
}

// A transparent clipping plane cutting a sphere: raycast shows the inside of the back of the
// sphere through the cut; the compiler adds exit terms for products with transparent literals.
TEST(PixelPowersEngine, TransparentClipShowsTheBackSheet) {
    TestSceneBuilder b(48, 48);
    int s = b.AddSphere({24, 24, 40}, 18);
    int clip = b.AddClipPlane(0, 0, -1, 38);  // z >= 38 kept
    int hole = b.AddSphere({30, 24, 40}, 8);
    int body = b.AddBody({{s, false}, {clip, false}});
    int cavity = b.AddBody({{hole, false}});
    b.AddSolid(b.AddNode(scene::CsgOp::kDifference, {b.AddLeaf(body), b.AddLeaf(cavity)}));
    ExpectMatchesRaycast(b.scene(), "clip plane", 500);
}

// Normal-form sizes reach the statistics, and the explosion guard reports instead of hanging.
TEST(PixelPowersEngine, StatisticsAndExplosionGuard) {
    TestSceneBuilder b(32, 32);
    std::vector<int> leaves;
    int acc = b.AddLeaf(b.AddBody({{b.AddSphere({16, 16, 30}, 12), false}}));
    for (int level = 0; level < 14; ++level) {
        int x = b.AddLeaf(b.AddBody({{b.AddSphere({16.0 + level % 3, 16, 30}, 3), false}}));
        int y = b.AddLeaf(b.AddBody({{b.AddSphere({16, 16.0 + level % 4, 30}, 3), false}}));
        acc = b.AddNode(scene::CsgOp::kDifference,
                        {acc, b.AddNode(scene::CsgOp::kIntersection, {x, y})});
    }
    b.AddSolid(acc);
    auto pp = MakePixelPowersEngine();
    RenderOptions o;
    o.engineOptions = {{"max-products", "100"}};
    Frame f;
    RenderStats st = pp->Render(b.scene(), o, f);
    EXPECT_NE(st.report.find("exceeds 100 products"), std::string::npos) << st.report;
    double failures = -1;
    for (const auto& [k, v] : st.counters)
        if (k == "solids_not_drawn") failures = v;
    EXPECT_EQ(failures, 1);
    EXPECT_FALSE(pp->ValidateOptions(o).size());
    o.engineOptions = {{"max-product", "100"}};
    EXPECT_NE(pp->ValidateOptions(o).find("no option"), std::string::npos);
}

bool AnyWarningWith(const RenderStats& st, const std::string& text) {
    for (const std::string& w : st.warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

// Spheres and circular cylinders (capped by planes) at random, under the builder's parallel view
// (deviceFromWorld = identity): their world gradient has a constant length on the surface, so the
// paper's constant denominator is exact and only the one-cylinder sqrt approximation errs.
FlatScene ShadingScene(std::mt19937& rng, const Vec3& light) {
    std::uniform_real_distribution<double> u(0, 1);
    TestSceneBuilder b(72, 72);
    std::vector<int> leaves;
    for (int i = 0; i < 4; ++i) {
        Vec3 c{14 + 44 * u(rng), 14 + 44 * u(rng), 40 + 20 * u(rng)};
        if (i % 2 == 0) {
            double r = 8 + 10 * u(rng);
            leaves.push_back(b.AddLeaf(b.AddBody({{b.AddSphere(c, r), false}}, Around(c, r))));
            continue;
        }
        Vec3 d = Normalize(Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5});
        double h = 8 + 8 * u(rng), r = 4 + 6 * u(rng), m[9];
        for (std::size_t i2 = 0; i2 < 3; ++i2)
            for (std::size_t j = 0; j < 3; ++j)
                m[3 * i2 + j] = (i2 == j ? 1.0 : 0.0) - d[i2] * d[j];
        int q = b.AddQuadric(Centred(m, c, -r * r));
        int top = b.AddPlane(d.x, d.y, d.z, -Dot(d, c) - h);
        int bot = b.AddPlane(-d.x, -d.y, -d.z, Dot(d, c) - h);
        leaves.push_back(
            b.AddLeaf(b.AddBody({{q, false}, {top, false}, {bot, false}}, Around(c, h + r))));
    }
    b.AddSolid(b.AddNode(scene::CsgOp::kDifference,
                         {b.AddNode(scene::CsgOp::kUnion, {leaves[0], leaves[1]}), leaves[2]}));
    b.AddSolid(leaves[3]);
    FlatScene scene = b.scene();
    scene::Light l;
    l.kind = scene::Light::Kind::kParallel;
    l.intensity = 0.8;
    l.direction = light;
    scene::Light ambient;
    ambient.intensity = 0.1;
    scene.lights = {ambient, l};
    return scene;
}

// Seed 004 §III step 4 against exact Lambert shading of raycast's frame. Exact depths (mode=exact)
// so that the same pixels show the same surface and only the shading differs. Bound: the shader's
// intensity is 0.1 + 0.8·max(0, n·l) with n·l = clamp(a·l) (ShadingUnitNormal), and clamp and
// max(0,·) are 1-Lipschitz, so |Δ intensity| ≤ 0.8·|a·l − n_exact·l| ≤ 0.8·(sqrt bound reported by
// the host), the denominator being exact here (shading_denominator_spread ≈ 0, checked).
TEST(PixelPowersEngine, PaperShadingBoundedAgainstExactLambert) {
    std::mt19937 rng(2026);
    double worst = 0;
    for (int trial = 0; trial < 8; ++trial) {
        Vec3 light = Normalize(Vec3{0.6 * (rng() % 3) - 0.6, 0.3, -1});
        FlatScene scene = ShadingScene(rng, light);
        auto pp = MakePixelPowersEngine();
        auto rc = MakeRaycastEngine();
        RenderOptions o;
        o.engineOptions = {{"shading", "paper"}, {"compare", "on"}};
        Frame a, r;
        RenderStats st = pp->Render(scene, o, a);
        rc->Render(scene, RenderOptions{}, r);
        const double bound = Counter(st, "shading_sqrt_bound");
        ASSERT_GE(bound, 0) << "paper shading must report its host bound";
        // (β−α)²/(8(α+β)) ≤ β/8 and |K_z|·β/|c| ≤ w on a sphere or circular cylinder.
        EXPECT_LE(bound, 0.125 + 1e-9);
        EXPECT_LE(Counter(st, "shading_denominator_spread"), 1e-9);
        EXPECT_GT(Counter(st, "shaded_patches"), 0);
        double maxErr = 0, sumErr = 0;
        std::size_t same = 0;
        for (std::size_t i = 0; i < r.depth.size(); ++i) {
            if (a.surface[i] == Frame::kNone || a.surface[i] != r.surface[i]) continue;
            ++same;
            EXPECT_NEAR(Length(a.normal[i]), 1.0, 1e-9) << "the Frame keeps unit normals";
            double e = std::fabs(LambertIntensity(scene, a.normal[i]) -
                                 LambertIntensity(scene, r.normal[i]));
            maxErr = std::max(maxErr, e);
            sumErr += e;
        }
        ASSERT_GT(same, 500u);
        EXPECT_LE(maxErr, 0.8 * bound + 1e-9) << "trial " << trial;
        // The engine's own statistic is the same measurement.
        EXPECT_NEAR(Counter(st, "cmp_intensity_error_max"), maxErr, 1e-12);
        EXPECT_LT(sumErr / static_cast<double>(same), 0.05) << "smooth, close on average";
        worst = std::max(worst, maxErr);

        // shading=exact: the normal at ZMIN, the very computation raycast makes.
        o.engineOptions = {{"shading", "exact"}};
        Frame e;
        pp->Render(scene, o, e);
        for (std::size_t i = 0; i < r.depth.size(); ++i)
            if (e.surface[i] != Frame::kNone && e.surface[i] == r.surface[i]) {
                ASSERT_EQ(LambertIntensity(scene, e.normal[i]),
                          LambertIntensity(scene, r.normal[i]));
            }
    }
    // The approximation is really in use (a coarse one: the paper's single cylinder).
    EXPECT_GT(worst, 0.01);
}

// ShadingUnitNormal keeps the paper's n·k for the key light with a unit vector.
TEST(PixelPowersEngine, ShadingUnitNormalKeepsTheKeyLightTerm) {
    const Vec3 k = Normalize(Vec3{0.2, -0.3, -1});
    for (Vec3 a : {Vec3{0.1, 0.2, -0.9}, Vec3{0.5, -0.7, 0.4}, Vec3{0, 0, -1.3}, k * 0.7, k * 1.2,
                   Vec3{0, 0, 0}}) {
        Vec3 n = ShadingUnitNormal(a, k);
        EXPECT_NEAR(Length(n), 1.0, 1e-12);
        EXPECT_NEAR(Dot(n, k), std::clamp(Dot(a, k), -1.0, 1.0), 1e-12);
        // In the plane of a and k (when a is not along k).
        Vec3 perp = Cross(a, k);
        if (Length(perp) > 1e-9) {
            EXPECT_NEAR(Dot(n, perp), 0.0, 1e-12);
        }
    }
    EXPECT_NEAR(Dot(ShadingUnitNormal({0, 3, 4}, {}), Vec3{0, 0.6, 0.8}), 1.0, 1e-12);
}

// Every solid the engine cannot draw, and every accuracy guard that fires, is a warning.
TEST(PixelPowersEngine, WarningsNameSolidsNotDrawn) {
    TestSceneBuilder b(40, 40);
    // Spheres with boxes, as the Flattener gives them (unbounded bodies would need exit terms).
    auto sphere = [&](const Vec3& c, double r) {
        return b.AddLeaf(b.AddBody({{b.AddSphere(c, r), false}}, Around(c, r)));
    };
    int acc = sphere({20, 20, 30}, 14);
    for (int level = 0; level < 6; ++level) {
        int x = sphere({18.0 + level % 3, 20, 30}, 4);
        int y = sphere({20, 18.0 + level % 4, 30}, 4);
        acc = b.AddNode(scene::CsgOp::kDifference,
                        {acc, b.AddNode(scene::CsgOp::kIntersection, {x, y})});
    }
    b.AddSolid(acc);                    // solid #0: 2^6 products
    b.AddSolid(sphere({8, 8, 20}, 5));  // solid #1: simple
    FlatScene scene = b.scene();
    scene.solids[0].name = "maze";
    auto pp = MakePixelPowersEngine();
    RenderOptions o;
    Frame f;

    RenderStats plain = pp->Render(scene, o, f);
    EXPECT_TRUE(plain.warnings.empty()) << plain.warnings.front();

    o.engineOptions = {{"max-products", "50"}};
    // A solid past a guard is reported undrawn (the render context draws it with raycast).
    RenderStats st = pp->Render(scene, o, f);
    EXPECT_TRUE(st.warnings.empty());
    ASSERT_EQ(st.undrawn.size(), 1u);
    EXPECT_EQ(st.undrawn[0].solid, 0);
    EXPECT_NE(st.undrawn[0].reason.find("solid 'maze' not drawn"), std::string::npos);
    EXPECT_NE(st.undrawn[0].reason.find("max-products"), std::string::npos);
    EXPECT_GT(f.CoveredCount(), 0u) << "the other solid is still drawn";

    o.engineOptions = {{"max-instructions", "40"}};
    st = pp->Render(scene, o, f);
    ASSERT_EQ(st.undrawn.size(), 1u);
    EXPECT_NE(st.undrawn[0].reason.find("max-instructions"), std::string::npos);

    o.engineOptions = {{"mode", "approx"}, {"max-strips", "1"}, {"tolerance", "0.01"}};
    st = pp->Render(scene, o, f);
    EXPECT_TRUE(AnyWarningWith(st, "max-strips = 1")) << st.report;
    EXPECT_TRUE(AnyWarningWith(st, "solid #1")) << "unnamed solids are numbered";

    o.engineOptions = {{"mode", "sideways"}};
    st = pp->Render(scene, o, f);
    EXPECT_TRUE(AnyWarningWith(st, "nothing drawn"));

    // depth-bits needs a finite depth range: a half-space solid has none.
    TestSceneBuilder h(16, 16);
    h.AddSolid(h.AddLeaf(h.AddBody({{h.AddPlane(0.1, 0, -1, 20), false}})));
    o.engineOptions = {{"mode", "approx"}, {"depth-bits", "16"}};
    st = pp->Render(h.scene(), o, f);
    EXPECT_TRUE(AnyWarningWith(st, "depth-bits ignored"));
}

// Fixed-point depth words: every stored depth is a multiple of the step from the origin, and the
// error against raycast grows by at most half a step (rounding is monotone, so the envelope of
// rounded strips is the rounded envelope).
TEST(PixelPowersEngine, DepthBitsQuantiseTheDepthWords) {
    std::mt19937 rng(5);
    TestSceneBuilder b(64, 64);
    std::vector<int> bodies;
    for (int i = 0; i < 4; ++i) bodies.push_back(RandomBody(b, rng));
    b.AddSolid(
        b.AddNode(scene::CsgOp::kDifference,
                  {b.AddNode(scene::CsgOp::kUnion, {b.AddLeaf(bodies[0]), b.AddLeaf(bodies[1])}),
                   b.AddLeaf(bodies[2])}));
    b.AddSolid(b.AddLeaf(bodies[3]));
    auto pp = MakePixelPowersEngine();
    auto rc = MakeRaycastEngine();
    Frame r;
    rc->Render(b.scene(), RenderOptions{}, r);
    for (int bits : {10, 24}) {
        RenderOptions o;
        o.engineOptions = {
            {"mode", "approx"}, {"tolerance", "0.25"}, {"depth-bits", std::to_string(bits)}};
        Frame a;
        RenderStats st = pp->Render(b.scene(), o, a);
        double step = Counter(st, "depth_step");
        ASSERT_GT(step, 0);
        const double origin = Counter(st, "depth_origin");
        double maxErr = 0, offGrid = 0;
        for (std::size_t i = 0; i < r.depth.size(); ++i) {
            if (a.surface[i] == Frame::kNone) continue;
            // Off the grid by more than the Frame's rounding of depth to float (frame.h).
            double k = (a.depth[i] - origin) / step;
            offGrid = std::max(
                offGrid,
                (std::fabs(k - std::nearbyint(k)) * step - DepthRounding(a.depth[i])) / step);
            if (a.surface[i] != r.surface[i]) continue;
            maxErr = std::max<double>(maxErr, std::fabs(a.depth[i] - r.depth[i]));
        }
        // k ≤ 2^24: origin + k·step rounds at ~1e-16 relative, far below 1e-6 of a step.
        EXPECT_LT(offGrid, 1e-6) << bits << " bits";
        EXPECT_LE(maxErr, 0.25 + 0.5 * step + 1e-9 + 2 * DepthRounding(1000)) << bits << " bits";
        if (bits == 10) {
            EXPECT_GT(maxErr, 0.25 + 0.1 * step) << "10-bit words are coarse";
        }
    }
}

}  // namespace
}  // namespace quadrix::pixelpowers
