// Shadow rays through the CSG (shadows.h) against analytic answers: a ray misses a sphere
// exactly when its distance from the centre exceeds the radius; CSG differences let light
// through their holes.
#include "quadrix/shade/shadows.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "quadrix/math/quadratic.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/shade/lighting.h"
#include "quadrix/shade/shader.h"
#include "quadrix/util/ray_work.h"
#include "test_util.h"

namespace quadrix {
namespace {

Quadric SphereQ(const Vec3& c, double r) {
    return Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -c.x, -c.y, -c.z, Dot(c, c) - r * r});
}

// Solid 0 = sphere A minus sphere B (B may be far away: then it is just A).
FlatScene Spheres(const Vec3& a, double ra, const Vec3& b, double rb) {
    FlatScene s;
    for (const Quadric& q : {SphereQ(a, ra), SphereQ(b, rb)}) {
        FlatHalfSpace h;
        h.isPlane = false;
        h.quadric = q;
        s.halfSpaces.push_back(h);
    }
    for (int k = 0; k < 2; ++k) {
        FlatBody body;
        body.literals = {{k, false}};
        s.bodies.push_back(body);
        FlatCsgNode leaf;
        leaf.body = k;
        leaf.bounds = {{-1e9, -1e9, -1e9}, {1e9, 1e9, 1e9}};
        s.nodes.push_back(leaf);
    }
    FlatCsgNode diff;
    diff.isLeaf = false;
    diff.op = scene::CsgOp::kDifference;
    diff.children = {0, 1};
    diff.bounds = {a - Vec3{ra, ra, ra}, a + Vec3{ra, ra, ra}};
    s.nodes.push_back(diff);
    FlatSolid solid;
    solid.root = 2;
    s.solids.push_back(solid);
    return s;
}

// A plane literal's set on a line (SolveQuadratic answers its root inline for coefficients in
// the unscaled range, quadratic.h) is where the general solver puts it: the half-line up to or from
// its one root, the whole line or nothing when the line is parallel to the plane. Coefficients from
// 2^-300 to 2^300 (both sides of the in-place range), zero components, lines parallel to the
// plane, and a NaN.
TEST(ShadeShadows, APlanesSetOnALineIsTheSolversHalfLine) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> exponent(-300, 300);
    std::size_t cases = 0, wrong = 0, single = 0;
    for (int q = 0; q < 200000; ++q) {
        const double scale = std::ldexp(1.0, exponent(rng));
        FlatHalfSpace h;
        h.isPlane = true;
        h.plane = {u(rng) * scale, q % 7 == 0 ? 0.0 : u(rng) * scale, u(rng) * scale,
                   u(rng) * scale * (q % 3 == 0 ? 1e3 : 1.0)};
        const Vec3 p{u(rng) * 10, u(rng) * 10, u(rng) * 10};
        Vec3 d{u(rng), u(rng), u(rng)};
        if (q % 11 == 0) d = {-h.plane.b, h.plane.a, 0};  // parallel to the plane
        if (q == 12345) h.plane.d = std::nan("");
        const Plane& pl = h.plane;
        // OnLine's polynomial (shadows.cpp), in the same order of operations.
        const double hh = 0.5 * (pl.a * d.x + pl.b * d.y + pl.c * d.z), c = pl.Evaluate(p);
        const QuadraticRoots r = detail::SolveQuadraticGeneral(0, hh, c);
        IntervalList expected;
        if (r.kind == RootKind::kAll || ((r.kind == RootKind::kNone) && hh == 0 && c <= 0)) {
            expected.Append(-HUGE_VAL, Interval::kNoId, HUGE_VAL, Interval::kNoId);
        } else if (r.kind == RootKind::kSingle) {
            ++single;
            if (hh > 0)
                expected.Append(-HUGE_VAL, Interval::kNoId, r.t0, Interval::kNoId);
            else
                expected.Append(r.t0, Interval::kNoId, HUGE_VAL, Interval::kNoId);
        }
        const IntervalList got = ShadowTester::LiteralOnLine(h, false, p, d);
        ++cases;
        bool same = got.size() == expected.size();
        for (std::size_t i = 0; same && i < got.size(); ++i)
            same = got[i].lo == expected[i].lo && got[i].hi == expected[i].hi;
        wrong += !same;
    }
    EXPECT_EQ(wrong, 0u) << "of " << cases;
    EXPECT_GT(single, cases / 2);
}

TEST(ShadeShadows, RaysAreBlockedExactlyWhenTheyMeetTheSphere) {
    const Vec3 c{10, -3, 7};
    const double r = 2.5;
    const FlatScene s = Spheres(c, r, {1e6, 0, 0}, 1);
    const ShadowTester t(s);
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    int blocked = 0, checked = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 p = c + Vec3{u(rng), u(rng), u(rng)} * 12;
        if (Length(p - c) < r + 0.01) continue;
        // Half the rays aimed near the sphere, so that both answers are common.
        const Vec3 aim =
            i % 2 ? c - p + Vec3{u(rng), u(rng), u(rng)} * 3 : Vec3{u(rng), u(rng), u(rng)};
        const Vec3 d = Normalize(aim) * (1 + 3 * std::fabs(u(rng)));
        // Distance from c to the half-line p + s d, s > 0.
        const double s0 = std::max(0.0, Dot(c - p, d) / Dot(d, d));
        const double dist = Length(p + d * s0 - c);
        if (std::fabs(dist - r) < 1e-6) continue;  // grazing: either answer is right
        const bool want = dist < r && s0 > 0;
        EXPECT_EQ(t.Blocked(p, d, HUGE_VAL), want) << i;
        // A segment that ends before the sphere is never blocked.
        const double near = Length(p - c) - r;  // the sphere is at least this far along the ray
        EXPECT_FALSE(t.Blocked(p, d, 0.99 * near / Length(d))) << i;
        blocked += want;
        ++checked;
    }
    EXPECT_GT(blocked, 800);
    EXPECT_LT(blocked, checked - 800);
    EXPECT_GT(checked, 3000);
}

TEST(ShadeShadows, AHoleLetsTheLightThroughAndASurfaceDoesNotShadowItself) {
    // A ball with a ball-shaped bite taken out of its top (y < 0 is up in device space).
    const FlatScene s = Spheres({0, 0, 0}, 2, {0, -2, 0}, 1.2);
    const ShadowTester t(s);
    const Vec3 up{0, -1, 0};
    EXPECT_TRUE(t.Blocked({0, 5, 0}, up, HUGE_VAL));    // below: the ball is in the way
    EXPECT_TRUE(t.Blocked({1.5, 5, 0}, up, HUGE_VAL));  // beside the bite: still the ball
    // On the floor of the bite, looking up through it: free (the bite's floor is at y = −0.8).
    EXPECT_FALSE(t.Blocked({0, -0.8, 0}, up, HUGE_VAL));
    // A point on the ball's outside looking away from it: not shadowed by its own surface.
    const Vec3 side = Normalize(Vec3{1, 0.3, -0.2}) * 2;
    EXPECT_FALSE(t.Blocked(side, Normalize(side), HUGE_VAL));
    // Planes: a half-space literal on a line is a half-line.
    FlatHalfSpace floor;
    floor.plane = {0, 1, 0, -3};  // y <= 3
    const IntervalList set = ShadowTester::LiteralOnLine(floor, false, {0, 0, 0}, {0, 1, 0});
    ASSERT_EQ(set.size(), 1u);
    EXPECT_EQ(set[0].hi, 3);
    EXPECT_TRUE(std::isinf(set[0].lo));
    const IntervalList out = ShadowTester::LiteralOnLine(floor, true, {0, 0, 0}, {0, 1, 0});
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].lo, 3);
}

// (∪ Aᵢ) − B₁ − B₂ answered operand by operand (ShadowTester::DistributedDifference) against
// the same set written ∪ (Aᵢ − B₁ − B₂), which the tester answers with its union path: the same
// answer on every ray. Balls of random sizes packed in a box, two drills through them; a few
// operands (plain loops) and many (box trees: more than kWideNode operands).
FlatScene BallsMinusDrills(int balls, bool distributed, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1), size(0.3, 1.2);
    FlatScene s;
    auto addQuadric = [&](const Quadric& q) {
        FlatHalfSpace h;
        h.isPlane = false;
        h.quadric = q;
        s.halfSpaces.push_back(h);
        return static_cast<int>(s.halfSpaces.size()) - 1;
    };
    auto addLeaf = [&](std::vector<FlatLiteral> lits, const Box3& box) {
        FlatBody body;
        body.literals = std::move(lits);
        s.bodies.push_back(body);
        FlatCsgNode leaf;
        leaf.body = static_cast<int>(s.bodies.size()) - 1;
        leaf.bounds = box;
        s.nodes.push_back(leaf);
        return static_cast<int>(s.nodes.size()) - 1;
    };
    auto addNode = [&](scene::CsgOp op, std::vector<int> children, const Box3& box) {
        FlatCsgNode n;
        n.isLeaf = false;
        n.op = op;
        n.children = std::move(children);
        n.bounds = box;
        s.nodes.push_back(n);
        return static_cast<int>(s.nodes.size()) - 1;
    };
    const Box3 all{{-10, -10, -10}, {10, 10, 10}};
    // Two drills: infinite cylinders along z and along x (radius 1.5), boxes clipped to `all`.
    const int dz = addQuadric(Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, -1, 0, 0, 1 - 2.25}));
    const int dx = addQuadric(Quadric::FromCoefficients({0, 1, 1, 0, 0, 0, 0, 0, -2, 4 - 2.25}));
    std::vector<Vec3> centres;
    std::vector<double> radii;
    for (int i = 0; i < balls; ++i) {
        centres.push_back(Vec3{u(rng), u(rng), u(rng)} * 6);
        radii.push_back(size(rng));
    }
    auto ball = [&](int i) {
        const Vec3 c = centres[static_cast<std::size_t>(i)];
        const double r = radii[static_cast<std::size_t>(i)];
        const int q = addQuadric(SphereQ(c, r));
        return addLeaf({{q, false}}, {c - Vec3{r, r, r}, c + Vec3{r, r, r}});
    };
    auto drills = [&] {
        return std::vector<int>{addLeaf({{dz, false}}, all), addLeaf({{dx, false}}, all)};
    };
    int root;
    if (distributed) {
        std::vector<int> terms;
        for (int i = 0; i < balls; ++i) {
            std::vector<int> kids{ball(i)};
            for (int d : drills()) kids.push_back(d);
            terms.push_back(addNode(scene::CsgOp::kDifference, kids,
                                    s.nodes[static_cast<std::size_t>(kids[0])].bounds));
        }
        root = addNode(scene::CsgOp::kUnion, terms, all);
    } else {
        std::vector<int> kids;
        for (int i = 0; i < balls; ++i) kids.push_back(ball(i));
        const int u = addNode(scene::CsgOp::kUnion, kids, all);
        std::vector<int> diff{u};
        for (int d : drills()) diff.push_back(d);
        root = addNode(scene::CsgOp::kDifference, diff, all);
    }
    FlatSolid solid;
    solid.root = root;
    solid.bounds = all;
    s.solids.push_back(solid);
    return s;
}

TEST(ShadeShadows, ADifferenceOfAUnionAnswersAsItsDistributedForm) {
    for (int balls : {5, 200}) {
        const FlatScene nested = BallsMinusDrills(balls, false, 23);
        const FlatScene distributed = BallsMinusDrills(balls, true, 23);
        const ShadowTester a(nested), b(distributed);
        std::mt19937 rng(31);
        std::uniform_real_distribution<double> u(-1, 1);
        int blocked = 0;
        const int rays = 4000;
        for (int i = 0; i < rays; ++i) {
            const Vec3 p = Vec3{u(rng), u(rng), u(rng)} * 9;
            // Half the rays aimed at the balls' region, so that both answers are common.
            const Vec3 aim =
                i % 2 ? Vec3{u(rng), u(rng), u(rng)} * 6 - p : Vec3{u(rng), u(rng), u(rng)};
            const Vec3 d = Normalize(aim) * (0.5 + std::fabs(u(rng)));
            const double sMax = i % 3 ? HUGE_VAL : 4 * std::fabs(u(rng));
            const bool want = b.Blocked(p, d, sMax);
            EXPECT_EQ(a.Blocked(p, d, sMax), want) << balls << " balls, ray " << i;
            blocked += want;
        }
        // Both answers common (the test would pass vacuously otherwise).
        EXPECT_GT(blocked, rays / 40) << balls;
        EXPECT_LT(blocked, rays - rays / 40) << balls;
    }
}

// A parallel light under a parallel view: the shader makes views of the box trees along the light
// (AddDirection), which test a tree node with five comparisons, looser than the slab test, never
// tighter. The answers are those without the views, on every ray, in directions along the axes
// and oblique ones, for a few operands and for many (box trees).
TEST(ShadeShadows, ViewsAlongALightGiveTheSameAnswers) {
    for (int balls : {5, 200})
        for (bool distributed : {false, true}) {
            const FlatScene scene = BallsMinusDrills(balls, distributed, 29);
            ShadowTester t(scene);
            const Vec3 directions[] = {{0, 0, -1}, {1, 0, 0}, {0.3, -0.5, 0.8}, {-2, 1, 0.5}};
            std::vector<int> ids;
            for (const Vec3& d : directions) ids.push_back(t.AddDirection(d));
            std::mt19937 rng(37);
            std::uniform_real_distribution<double> u(-1, 1);
            int blocked = 0, rays = 0;
            for (int i = 0; i < 3000; ++i) {
                const std::size_t k = static_cast<std::size_t>(i) % ids.size();
                const Vec3& d = directions[k];
                // Half the rays aimed through the balls' region, so that both answers are common.
                const Vec3 p = i % 2 ? Vec3{u(rng), u(rng), u(rng)} * 8
                                     : Vec3{u(rng), u(rng), u(rng)} * 3 -
                                           Normalize(d) * (3 + 6 * std::fabs(u(rng)));
                const bool want = t.Blocked(p, d, HUGE_VAL);
                const DeviceRay ray{d, HUGE_VAL, Length(d), ids[k]};
                EXPECT_EQ(t.Blocked(p, ray), want) << balls << " " << distributed << " ray " << i;
                blocked += want;
                ++rays;
            }
            EXPECT_GT(blocked, rays / 40) << balls;
            EXPECT_LT(blocked, rays - rays / 40) << balls;
        }
}

// The values of a list's endpoints (BodyOnSegment's fast path does not keep ids).
std::vector<std::pair<double, double>> Ends(const IntervalList& l) {
    std::vector<std::pair<double, double>> v;
    for (const Interval& i : l) v.emplace_back(i.lo, i.hi);
    return v;
}

TEST(ShadeShadows, TheOneIntervalBodyPathGivesTheListsEndpointsAndCount) {
    // Bodies of random planes (some scaled by 2^±300, past the inline root's range) and quadrics
    // of every kind (ellipsoids, cylinders, cones, hyperboloids: a of either sign, two-piece
    // sets), complemented or not, some with a torus, on random segments, many of them grazing
    // (planes parallel to the ray, rays through a cone's apex): the fast path's endpoints and
    // literal count against the lists'.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    FlatScene s;
    const QuarticSurface torus = *QuarticSurface::Torus({0.5, 0, 0}, {0, 0, 1}, 2, 0.7);
    auto add = [&](int kind) {
        FlatHalfSpace h;
        if (kind == 0) {
            h.isPlane = true;
            h.plane = Plane{u(rng), u(rng), u(rng), u(rng)};
        } else if (kind == 1) {
            // A plane containing the x axis direction: rays along x are parallel to it.
            h.isPlane = true;
            h.plane = Plane{0, u(rng), u(rng), u(rng)};
        } else if (kind == 6) {
            // Coefficients far outside the range the solvers take inline (quadratic.h): the
            // general solver's root.
            const double scale = rng() % 2 ? 0x1p300 : 0x1p-300;
            h.isPlane = true;
            h.plane = Plane{scale * u(rng), scale * u(rng), scale * u(rng), scale * u(rng)};
        } else if (kind == 2) {
            h.SetQuartic(torus);
        } else {
            const double sign = kind == 3 ? 1.0 : (kind == 4 ? -1.0 : 0.0);
            h.isPlane = false;
            h.quadric = Quadric::FromCoefficients(
                {1 + std::fabs(u(rng)), 1 + sign * std::fabs(u(rng)), sign * std::fabs(u(rng)),
                 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng), u(rng), u(rng), u(rng),
                 kind == 5 ? 0.0 : u(rng)});
        }
        s.halfSpaces.push_back(h);
        return static_cast<int>(s.halfSpaces.size()) - 1;
    };
    for (int b = 0; b < 400; ++b) {
        FlatBody body;
        const int n = 1 + static_cast<int>(rng() % 6);
        for (int i = 0; i < n; ++i) {
            const int kind = static_cast<int>(rng() % 12);
            body.literals.push_back(
                {add(kind < 6 ? kind : (kind < 8 ? 0 : (kind < 10 ? 6 : 3))), rng() % 3 == 0});
        }
        s.bodies.push_back(body);
    }
    const ShadowTester t(s);
    int checked = 0, split = 0, nonEmpty = 0;
    for (int b = 0; b < 400; ++b) {
        for (int r = 0; r < 40; ++r) {
            const Vec3 p{u(rng) * 3, u(rng) * 3, u(rng) * 3};
            const Vec3 d = r % 4 == 0
                               ? Vec3{1, 0, 0}
                               : (r % 4 == 1 ? Vec3{0, 0, 0} - p : Vec3{u(rng), u(rng), u(rng)});
            const double s0 = r % 5 == 0 ? -HUGE_VAL : 0.01 * u(rng);
            const double s1 = r % 3 == 0 ? HUGE_VAL : (r % 7 == 0 ? s0 : 2 + u(rng));
            const std::uint64_t c0 = tRayLiterals;
            const IntervalList want = t.BodyOnSegment(b, p, d, s0, s1, true);
            const std::uint64_t c1 = tRayLiterals;
            const IntervalList got = t.BodyOnSegment(b, p, d, s0, s1, false);
            const std::uint64_t c2 = tRayLiterals;
            EXPECT_EQ(Ends(got), Ends(want)) << "body " << b << " ray " << r;
            EXPECT_EQ(c2 - c1, c1 - c0) << "body " << b << " ray " << r;
            EXPECT_TRUE(got.IsCanonical());
            ++checked;
            split += want.size() > 1;
            nonEmpty += !want.empty();
        }
    }
    // Both kinds of answer common, and sets of two pieces among them (else the test proves
    // little).
    EXPECT_GT(nonEmpty, checked / 10);
    EXPECT_LT(nonEmpty, checked - checked / 10);
    EXPECT_GT(split, checked / 100);
}

// A shadow ray from a pixel of a rendered picture, told the surface it starts on (the Frame's
// surface and body), tries that surface's literal first (shadows.h): the same answer as without
// the origin at every covered pixel of the machined part, in directions toward and away from its
// faces, and, on the rays that leave the surface (the only ones the shader casts: a light behind
// a face gives no ray), fewer literals evaluated (the block's faces empty it after one literal,
// not after those before them in its list of 14).
// The outward normal, in device space, of the origin's body at p on its surface: the surface's
// half-space's gradient, negated for a complemented literal of the body.
Vec3 BodyOutward(const FlatScene& flat, const ShadowOrigin& origin, const Vec3& p) {
    const FlatHalfSpace& h = flat.halfSpaces[static_cast<std::size_t>(origin.halfSpace)];
    Vec3 outward = h.isPlane ? h.plane.Normal() : h.quadric.Gradient(p);
    for (const FlatLiteral& l : flat.bodies[static_cast<std::size_t>(origin.body)].literals)
        if (l.halfSpace == origin.halfSpace) {
            if (l.complemented) outward = Vec3{0, 0, 0} - outward;
            break;
        }
    return outward;
}

TEST(ShadeShadows, TheSurfaceARayStartsOnIsTriedFirstWithTheSameAnswers) {
    RenderContext ctx(1);
    Frame frame;
    ASSERT_TRUE(testing::RenderToFrame(ctx, "examples/machined_part.uq", 160, 120, frame));
    const FlatScene& flat = ctx.Flat();
    const ShadowTester t(flat);
    const Vec3 directions[] = {{0.3, -1, -0.6}, {-0.8, -0.2, -0.5}, {0.1, 0.7, -0.7}, {1, 0, 0}};
    std::uint64_t withOrigin = 0, without = 0;
    int covered = 0, blocked = 0, rays = 0, leaving = 0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            const std::size_t i = frame.Index(x, y);
            if (frame.surface[i] == Frame::kNone) continue;
            ++covered;
            const Vec3 p{x + 0.5, y + 0.5, frame.depth[i]};
            const ShadowOrigin origin{frame.body[i], frame.surface[i]};
            const Vec3 outward = BodyOutward(flat, origin, p);
            for (const Vec3& d : directions) {
                const DeviceRay ray{d, HUGE_VAL, Length(d)};
                const std::uint64_t c0 = tRayLiterals;
                const bool want = t.Blocked(p, ray);
                const std::uint64_t c1 = tRayLiterals;
                EXPECT_EQ(t.Blocked(p, ray, origin), want) << x << " " << y;
                if (Dot(outward, d) > 0) {
                    withOrigin += tRayLiterals - c1;
                    without += c1 - c0;
                    ++leaving;
                }
                blocked += want;
                ++rays;
            }
        }
    ASSERT_GT(covered, 3000);
    EXPECT_GT(blocked, rays / 10);
    EXPECT_LT(blocked, rays - rays / 10);
    ASSERT_GT(leaving, rays / 4);
    std::printf(
        "[ shadows ] %d rays from the machined part, %d leaving their surface: %.2f "
        "literals a ray with the origin, %.2f without\n",
        rays, leaving, static_cast<double>(withOrigin) / leaving,
        static_cast<double>(without) / leaving);
    // Measured: 2.91 and 6.37 (2.84 before PastOrigin, which makes a tool's set once more for
    // a ray that meets the part beyond it).
    EXPECT_LT(static_cast<double>(withOrigin), 0.6 * static_cast<double>(without));
}

// A ray from a subtracted tool's surface (a hole's wall, a slot's floor) that starts inside the
// tool: the part is looked at only beyond the tool (ShadowTester::PastOrigin), with the answers
// of the ray without an origin at every covered pixel, in directions into and out of the
// surfaces; the difference as a plain node, inside a union, and with a union as its minuend (the
// distributed form).
TEST(ShadeShadows, RaysFromASubtrahendLookOnlyBeyondItWithTheSameAnswers) {
    const std::string common = R"(
plane right <1 0 0 -10>;  plane left <-1 0 0 -10>;
plane top <0 1 0 -10>;  plane bottom <0 -1 0 -10>;
plane back <0 0 1 -10>;  plane front <0 0 -1 -10>;
body block (right left top bottom back front);
quadric hq <1 0 1 0 0 0 0 0 0 -9>;
plane hlo <0 -1 0 -12>;  plane hhi <0 1 0 -12>;
body hole (hq hlo hhi);
plane sr <1 0 0 -8>;  plane sl <-1 0 0 4>;  plane sf <0 -1 0 6>;  plane st <0 1 0 -12>;
plane sb <0 0 1 -12>;  plane sfr <0 0 -1 -12>;
body slot (sr sl sf st sb sfr);
quadric ball <1 1 1 0 0 0 -20 0 0 364>;
quadric bore <0 1 1 0 0 0 0 0 0 -4>;
body b1 (ball);  body b2 (bore);
view v dop .9 1.1 -1.3;
)";
    const char* solids[] = {"csg part (block - hole - slot);",
                            "csg part ((block - hole - slot) | (b1 - b2));",
                            "csg part ((block | b1) - hole - slot - b2);"};
    const Vec3 directions[] = {{0.3, -1, -0.6}, {-0.8, -0.2, -0.5}, {0.1, 0.7, -0.7},
                               {1, 0, 0},       {0, 0, 1},          {-0.2, 0.9, 0.4}};
    for (const char* solid : solids) {
        RenderContext ctx(1);
        Frame frame;
        InputRequest in;
        in.text = common + solid;
        Diagnostics diags;
        ASSERT_TRUE(testing::RenderToFrame(ctx, in, 160, 120, frame, diags)) << solid;
        const FlatScene& flat = ctx.Flat();
        const ShadowTester t(flat);
        // The bodies of the tools: those whose name ends in hole, slot or b2.
        auto tool = [&](int body) {
            const std::string& n = flat.bodies[static_cast<std::size_t>(body)].name;
            for (const char* end : {"hole", "slot", "b2"})
                if (n.size() >= std::strlen(end) && n.ends_with(end)) return true;
            return false;
        };
        std::uint64_t withOrigin = 0, without = 0;
        int fromTools = 0, blocked = 0, rays = 0;
        for (int y = 0; y < frame.height; ++y)
            for (int x = 0; x < frame.width; ++x) {
                const std::size_t i = frame.Index(x, y);
                if (frame.surface[i] == Frame::kNone) continue;
                const Vec3 p{x + 0.5, y + 0.5, frame.depth[i]};
                const ShadowOrigin origin{frame.body[i], frame.surface[i]};
                // The tool's outward normal: the part's surface faces the other way, and the
                // shader casts rays only toward lights on the part's side, into the tool.
                const Vec3 toolOut = BodyOutward(flat, origin, p);
                for (const Vec3& d : directions) {
                    const DeviceRay ray{d, HUGE_VAL, Length(d)};
                    const std::uint64_t c0 = tRayLiterals;
                    const bool want = t.Blocked(p, ray);
                    const std::uint64_t c1 = tRayLiterals;
                    ASSERT_EQ(t.Blocked(p, ray, origin), want) << solid << " " << x << " " << y;
                    if (tool(origin.body) && Dot(toolOut, d) < 0 && !want) {
                        withOrigin += tRayLiterals - c1;
                        without += c1 - c0;
                        ++fromTools;
                    }
                    blocked += want;
                    ++rays;
                }
            }
        EXPECT_GT(fromTools, 200) << solid;
        EXPECT_GT(blocked, rays / 20) << solid;
        EXPECT_LT(blocked, rays - rays / 20) << solid;
        // The rays that gain: those that leave the part through the tool (a lit hole wall).
        // One that meets the part beyond the tool pays for the tool's set first, about as many
        // literals as it saves.
        std::printf(
            "[ shadows ] %s: %d rays from the tools into them and out, %.2f literals a "
            "ray with the origin, %.2f without\n",
            solid, fromTools, static_cast<double>(withOrigin) / fromTools,
            static_cast<double>(without) / fromTools);
        // Measured: 11.19 against 12.72, 9.62 against 10.97, 9.26 against 12.12 (the same
        // without PastOrigin: the tool's literal of the surface does not empty it).
        EXPECT_LT(static_cast<double>(withOrigin), 0.95 * static_cast<double>(without)) << solid;
    }
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// The machined part at 160 × 120 (its Frame and flat scene), and a second parallel light from
// the left whose shadows fall where the key light's do not: the scene of the tests below.
void MachinedPart(RenderContext& ctx, Frame& frame, FlatScene& flat) {
    ASSERT_TRUE(testing::RenderToFrame(ctx, "examples/machined_part.uq", 160, 120, frame));
    flat = ctx.Flat();
}
scene::Light SideLight() {
    scene::Light side;
    side.kind = scene::Light::Kind::kParallel;
    side.direction = Normalize(Vec3{-1, 0.3, -0.4});
    side.intensity = 0.4;
    return side;
}

// 8-bit shading with shadows under a parallel view and parallel lights repeats a pixel's bytes
// where its (surface, body), normal and blocked lights repeat the previous pixel's (shader.cpp
// ShadeRowLocal): the bytes must be those of shading every pixel, which the linear
// output still does. One light and two (two bits of the mask).
TEST(ShadeShadows, EightBitRunsWithShadowsGiveTheBytesOfShadingEveryPixel) {
    RenderContext ctx(1);
    Frame frame;
    FlatScene flat;
    ASSERT_NO_FATAL_FAILURE(MachinedPart(ctx, frame, flat));
    for (int lights = 1; lights <= 2; ++lights) {
        if (lights == 2) flat.lights.push_back(SideLight());
        {
            ShadeOptions o;
            o.shadows = true;
            const PixelShader shader(frame, flat, o);
            ASSERT_TRUE(shader.LocalShading());
            // Both kinds of pixel are there: some lit, some shadowed by each light.
            std::uint64_t anyBlocked = 0;
            int shadowed = 0;
            for (int y = 0; y < frame.height; ++y)
                for (int x = 0; x < frame.width; ++x) {
                    const std::size_t i = frame.Index(x, y);
                    if (frame.surface[i] == Frame::kNone) continue;
                    const std::uint64_t m =
                        shader.ShadowMask(x + 0.5, y + 0.5, frame.surface[i], frame.body[i],
                                          frame.depth[i], frame.normal[i]);
                    anyBlocked |= m;
                    shadowed += m != 0;
                }
            EXPECT_GT(shadowed, 10);
            o.linear = false;
            const Image runs = Shade(frame, flat, o);
            o.linear = true;
            const Image each = Shade(frame, flat, o);
            ASSERT_EQ(runs.channels, 3);
            EXPECT_EQ(runs.pixels, each.pixels) << lights << " lights";
            if (lights == 2) {
                EXPECT_EQ(anyBlocked & 6, 6u) << "both lights block somewhere";
            }
        }
    }
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// The reach of a run of pixels (ShadowTester::MayMeet) changes no answer of Blocked: over the
// machined part at 160 × 120 with its key light and a second parallel light, every covered
// pixel's ray toward a light its surface faces (the rays the shader asks) with its run's mask
// (runs of 1, 7, 32 and 160 pixels) gives Blocked's answer without one. Most runs' masks leave
// nodes out, and the rays answered by their origin body alone evaluate no more literals than the
// walk did.
TEST(ShadowReach, ARunsMaskGivesTheAnswerOfEveryRay) {
    RenderContext ctx(1);
    Frame frame;
    FlatScene flat;
    ASSERT_NO_FATAL_FAILURE(MachinedPart(ctx, frame, flat));
    ASSERT_LE(flat.nodes.size(), ShadowTester::kReachNodes);
    flat.lights.push_back(SideLight());
    ShadowTester tester(flat);
    const Mat4 deviceFromWorld = flat.projection.deviceFromWorld.Matrix();
    const std::uint64_t all =
        flat.nodes.size() == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << flat.nodes.size()) - 1;
    int lights = 0;
    for (const scene::Light& l : flat.lights) {
        if (l.kind != scene::Light::Kind::kParallel) continue;
        ++lights;
        DeviceRay ray =
            DeviceShadowRay(deviceFromWorld, Vec4(IncidentLight(l, {}).toLight, 0.0), {}, {});
        ASSERT_GT(ray.length, 0);
        ASSERT_EQ(ray.sMax, HUGE_VAL);
        ray.view = tester.AddDirection(ray.d);
        const Vec3 toLight = IncidentLight(l, {}).toLight;
        for (int run : {1, 7, 32, 160}) {
            int rays = 0, blocked = 0, runs = 0, pruned = 0;
            std::uint64_t literalsWith = 0, literalsWithout = 0;
            for (int y = 0; y < frame.height; ++y)
                for (int x0 = 0; x0 < frame.width; x0 += run) {
                    const int x1 = std::min(frame.width, x0 + run);
                    double zLo = HUGE_VAL, zHi = -HUGE_VAL;
                    for (int x = x0; x < x1; ++x) {
                        const std::size_t i = frame.Index(x, y);
                        if (frame.surface[i] == Frame::kNone) continue;
                        zLo = std::min(zLo, static_cast<double>(frame.depth[i]));
                        zHi = std::max(zHi, static_cast<double>(frame.depth[i]));
                    }
                    if (!(zLo <= zHi)) continue;
                    const std::uint64_t reach =
                        tester.MayMeet({x0 + 0.5, y + 0.5, zLo}, {x1 - 0.5, y + 0.5, zHi}, ray);
                    ++runs;
                    pruned += (reach & all) != all;
                    for (int x = x0; x < x1; ++x) {
                        const std::size_t i = frame.Index(x, y);
                        if (frame.surface[i] == Frame::kNone) continue;
                        if (!(Dot(Vec3(frame.normal[i]), toLight) > 0)) continue;
                        const Vec3 p{x + 0.5, y + 0.5, frame.depth[i]};
                        const ShadowOrigin origin{frame.body[i], frame.surface[i]};
                        std::uint64_t before = tRayLiterals;
                        const bool with = tester.Blocked(p, ray, origin, reach);
                        literalsWith += tRayLiterals - before;
                        before = tRayLiterals;
                        const bool without = tester.Blocked(p, ray, origin);
                        literalsWithout += tRayLiterals - before;
                        ASSERT_EQ(with, without) << "light " << lights << ", runs of " << run
                                                 << ", pixel (" << x << ", " << y << ")";
                        ++rays;
                        blocked += with;
                    }
                }
            EXPECT_GT(blocked, 20) << "light " << lights << ", runs of " << run;
            EXPECT_LT(blocked, rays - 1000) << "light " << lights << ", runs of " << run;
            if (run <= 32) {
                EXPECT_GT(2 * pruned, runs) << "light " << lights << ", runs of " << run;
                EXPECT_LE(literalsWith, literalsWithout)
                    << "light " << lights << ", runs of " << run;
            }
        }
    }
    EXPECT_EQ(lights, 2);
}

// A scene of more nodes than a mask has bits gets kReachAll: no pruning, the walk as before.
TEST(ShadowReach, AScenePastSixtyFourNodesHasNoReach) {
    FlatScene s = Spheres({0, 0, 0}, 1, {5, 0, 0}, 1);
    while (s.nodes.size() <= ShadowTester::kReachNodes) s.nodes.push_back(s.nodes[0]);
    const ShadowTester tester(s);
    const DeviceRay ray{{0, 0, 1}, HUGE_VAL, 1};
    EXPECT_EQ(tester.MayMeet({-9, -9, -9}, {-8, -8, -8}, ray), ShadowTester::kReachAll);
    const FlatScene small = Spheres({0, 0, 0}, 1, {5, 0, 0}, 1);
    const ShadowTester smallTester(small);
    EXPECT_NE(smallTester.MayMeet({-9, -9, -9}, {-8, -8, -8}, ray), ShadowTester::kReachAll);
}

}  // namespace
}  // namespace quadrix

namespace quadrix {
namespace {

// MayMeet's second test (ShadowTester::BodyBehindAPlane) leaves out a leaf whose box the rays
// meet when one of its body's planes has every start outside it and every ray leaving it: a slab
// 0 <= y <= 1 and a half-space y >= 5 (a complemented literal), both with boxes that hold every
// start; starts at 2 <= y <= 3. Going up the rays leave the slab (its bit cleared) but not the
// half-space; going down the reverse; along x (parallel to both planes) neither is left out.
// Blocked gives the same answers with the mask as without it.
TEST(ShadowReach, ALeafBehindOneOfItsPlanesIsLeftOut) {
    FlatScene s;
    auto plane = [&](double b, double d) {
        FlatHalfSpace h;
        h.isPlane = true;
        h.plane = {0, b, 0, d};
        s.halfSpaces.push_back(h);
        return static_cast<int>(s.halfSpaces.size()) - 1;
    };
    const int top = plane(1, -1), bottom = plane(-1, 0), high = plane(1, -5);
    FlatBody slab, above;
    slab.literals = {{top, false}, {bottom, false}};  // y <= 1, y >= 0
    above.literals = {{high, true}};                  // not y <= 5
    s.bodies = {slab, above};
    for (int k = 0; k < 2; ++k) {
        FlatCsgNode leaf;
        leaf.body = k;
        leaf.bounds = {{-1e9, -1e9, -1e9}, {1e9, 1e9, 1e9}};
        s.nodes.push_back(leaf);
    }
    FlatCsgNode both;
    both.isLeaf = false;
    both.op = scene::CsgOp::kUnion;
    both.children = {0, 1};
    both.bounds = {{-1e9, -1e9, -1e9}, {1e9, 1e9, 1e9}};
    s.nodes.push_back(both);
    s.solids.push_back(FlatSolid{});
    s.solids.back().root = 2;
    const ShadowTester tester(s);
    const Vec3 lo{0, 2, 0}, hi{1, 3, 1};
    auto reachAlong = [&](const Vec3& d) {
        const DeviceRay ray{d, HUGE_VAL, Length(d)};
        const std::uint64_t reach = tester.MayMeet(lo, hi, ray);
        for (double x : {0.0, 0.5, 1.0})
            for (double y : {2.0, 2.5, 3.0})
                for (double z : {0.0, 1.0}) {
                    const Vec3 p{x, y, z};
                    EXPECT_EQ(tester.Blocked(p, ray, {}, reach), tester.Blocked(p, ray, {}));
                }
        return reach & 7;
    };
    EXPECT_EQ(reachAlong({0, 1, 0}), 6u) << "up: the slab left out";
    EXPECT_EQ(reachAlong({0, -1, 0}), 5u) << "down: the half-space above left out";
    EXPECT_EQ(reachAlong({1, 0, 0}), 7u) << "along the planes: neither";
    EXPECT_EQ(reachAlong({0.3, 1, -0.2}), 6u);
}

}  // namespace
}  // namespace quadrix
