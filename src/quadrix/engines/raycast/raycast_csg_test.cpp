// CSG through the raycast engine against an independent per-pixel oracle (point membership
// classification along the ray), plus the invariances the engine promises: culling and thread
// count never change a single bit of the Frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "quadrix/engines/engine_test_util.h"
#include "quadrix/engines/raycast/raycast.h"
#include "quadrix/flatten/test_scene_builder.h"
#include "quadrix/frame/compare.h"
#include "quadrix/math/quadratic.h"

namespace quadrix {
namespace {

using scene::CsgOp;
using testing_util::CounterOrFail;
using testing_util::FrameHasNaN;
using testing_util::SphereBounds;
using testing_util::TestSceneBuilder;

Frame Render(const FlatScene& scene, int threads = 0, RenderStats* statsOut = nullptr) {
    Frame f;
    RenderOptions options;
    options.threads = threads;
    RenderStats stats = MakeRaycastEngine()->Render(scene, options, f);
    if (statsOut) *statsOut = stats;
    EXPECT_FALSE(FrameHasNaN(f));
    return f;
}

// ---- The oracle -----------------------------------------------------------------------------

// Boolean membership of a device point in a node of the scene's CSG tree: literals by the sign of
// their HSI at the point (the oracle only evaluates points away from every surface).
bool Member(const FlatScene& s, int node, const Vec3& p) {
    const FlatCsgNode& n = s.nodes[static_cast<std::size_t>(node)];
    if (n.isLeaf) {
        const FlatBody& b = s.bodies[static_cast<std::size_t>(n.body)];
        if (b.literals.empty()) return false;
        for (const FlatLiteral& l : b.literals) {
            double v = s.halfSpaces[static_cast<std::size_t>(l.halfSpace)].Evaluate(p);
            if ((v <= 0) == l.complemented) return false;
        }
        return true;
    }
    switch (n.op) {
        case CsgOp::kUnion:
            for (int c : n.children)
                if (Member(s, c, p)) return true;
            return false;
        case CsgOp::kIntersection:
            for (int c : n.children)
                if (!Member(s, c, p)) return false;
            return true;
        case CsgOp::kDifference:
            if (!Member(s, n.children[0], p)) return false;
            for (std::size_t i = 1; i < n.children.size(); ++i)
                if (Member(s, n.children[i], p)) return false;
            return true;
    }
    return false;
}

struct OracleHit {
    bool ambiguous = false;
    bool covered = false;
    double t = 0;
    int surface = -1, solid = -1;
};

// Every surface crossing of the ray is a candidate; the solid's boundary points are the candidates
// where membership differs just before and just after (sampled at midpoints between consecutive
// candidates), and the visible one is the first boundary point on an opaque surface. Rays with two
// candidates closer than 1e-6 (near tangency, near an edge) are reported ambiguous and skipped.
OracleHit Oracle(const FlatScene& s, double x, double y) {
    struct Cand {
        double t;
        int hs;
    };
    std::vector<Cand> cands;
    for (std::size_t h = 0; h < s.halfSpaces.size(); ++h) {
        const FlatHalfSpace& hs = s.halfSpaces[h];
        if (hs.isPlane) {
            if (hs.plane.c != 0)
                cands.push_back({-(hs.plane.a * x + hs.plane.b * y + hs.plane.d) / hs.plane.c,
                                 static_cast<int>(h)});
            continue;
        }
        // Q(x, y, t) = C t² + 2 (F x + E y + J) t + Q(x, y, 0), grouped differently from the
        // engine.
        const Quadric& q = hs.quadric;
        QuadraticRoots r =
            SolveQuadratic(q.C(), q.F() * x + q.E() * y + q.J(), q.Evaluate({x, y, 0}));
        if (r.kind == RootKind::kSingle || r.kind == RootKind::kTwo)
            cands.push_back({r.t0, static_cast<int>(h)});
        if (r.kind == RootKind::kTwo) cands.push_back({r.t1, static_cast<int>(h)});
        if (r.kind == RootKind::kDouble) return {true};
    }
    std::sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) { return a.t < b.t; });
    for (std::size_t i = 1; i < cands.size(); ++i)
        if (cands[i].t - cands[i - 1].t < 1e-6 * (1 + std::fabs(cands[i].t))) return {true};
    OracleHit best;
    for (std::size_t so = 0; so < s.solids.size(); ++so) {
        auto member = [&](double t) { return Member(s, s.solids[so].root, {x, y, t}); };
        for (std::size_t i = 0; i < cands.size(); ++i) {
            double before = i == 0 ? cands[0].t - 1 : 0.5 * (cands[i - 1].t + cands[i].t);
            double after =
                i + 1 == cands.size() ? cands[i].t + 1 : 0.5 * (cands[i].t + cands[i + 1].t);
            if (member(before) == member(after)) continue;
            const FlatHalfSpace& hs = s.halfSpaces[static_cast<std::size_t>(cands[i].hs)];
            if (hs.transparent || hs.isClip) continue;
            if (!best.covered || cands[i].t < best.t) {
                best.covered = true;
                best.t = cands[i].t;
                best.surface = cands[i].hs;
                best.solid = static_cast<int>(so);
            }
            break;
        }
    }
    return best;
}

// ---- Random scenes ------------------------------------------------------------------------------

// Canonical quadrics placed by random affine maps: every kind of piece structure along a ray
// (intervals, complements of intervals, half-lines, all, nothing).
Quadric RandomQuadric(std::mt19937_64& rng, double w, double h) {
    std::uniform_real_distribution<double> u(0, 1);
    static const std::array<std::array<double, 10>, 6> kShapes = {{
        {1, 1, 1, 0, 0, 0, 0, 0, 0, -1},    // sphere
        {1, 1, 0, 0, 0, 0, 0, 0, 0, -1},    // cylinder
        {1, 1, -1, 0, 0, 0, 0, 0, 0, 0},    // double cone
        {1, 1, -1, 0, 0, 0, 0, 0, 0, -1},   // one-sheet hyperboloid
        {-1, -1, 1, 0, 0, 0, 0, 0, 0, -1},  // two-sheet hyperboloid
        {1, 1, 0, 0, 0, 0, 0, 0, -0.5, 0},  // paraboloid x² + y² − z <= 0
    }};
    Quadric q = Quadric::FromCoefficients(kShapes[static_cast<std::size_t>(u(rng) * 6) % 6]);
    double size = 5 + 20 * u(rng);
    Transform t =
        Transform::Translate({w * u(rng), h * u(rng), 100 + 100 * u(rng)}) *
        Transform::Rotate(0, 360 * u(rng)) * Transform::Rotate(1, 360 * u(rng)) *
        Transform::Scale({size * (0.5 + u(rng)), size * (0.5 + u(rng)), size * (0.5 + u(rng))});
    return q.Transformed(t);
}

FlatScene RandomCsgScene(std::mt19937_64& rng, int w, int h) {
    std::uniform_real_distribution<double> u(0, 1);
    TestSceneBuilder b(w, h);
    auto halfSpace = [&] {
        bool transparent = u(rng) < 0.15;
        if (u(rng) < 0.25) {
            Vec3 n = Normalize({u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5});
            Vec3 p{w * u(rng), h * u(rng), 100 + 100 * u(rng)};
            return b.AddPlane(n.x, n.y, n.z, -Dot(n, p), transparent);
        }
        int i = b.AddQuadric(RandomQuadric(rng, w, h).k, transparent);
        return i;
    };
    auto body = [&] {
        std::vector<std::pair<int, bool>> lits;
        int n = 1 + static_cast<int>(u(rng) * 2.5);
        for (int k = 0; k < n; ++k) lits.push_back({halfSpace(), k > 0 && u(rng) < 0.35});
        return b.AddLeaf(b.AddBody(lits));
    };
    std::function<int(int)> tree = [&](int depth) -> int {
        if (depth == 0 || u(rng) < 0.3) return body();
        CsgOp op = u(rng) < 0.4 ? CsgOp::kUnion
                                : (u(rng) < 0.5 ? CsgOp::kIntersection : CsgOp::kDifference);
        std::vector<int> kids;
        int n = 2 + static_cast<int>(u(rng) * 2);
        for (int k = 0; k < n; ++k) kids.push_back(tree(depth - 1));
        return b.AddNode(op, kids);
    };
    int solids = 1 + static_cast<int>(u(rng) * 2.5);
    for (int k = 0; k < solids; ++k) b.AddSolid(tree(2));
    return b.scene();
}

struct OracleCounts {
    long compared = 0, skipped = 0, covered = 0;
};

// Every pixel of scene number n's Frame f against the oracle (ambiguous rays counted and
// skipped): coverage, surface, solid, the body (each half-space belongs to one body in these
// scenes, so it follows from the surface) and the depth, the same roots up to the different
// grouping of the per-pixel coefficients.
void CompareToOracle(const FlatScene& scene, const Frame& f, int n, OracleCounts& c) {
    for (int j = 0; j < f.height; ++j) {
        for (int i = 0; i < f.width; ++i) {
            OracleHit o = Oracle(scene, i + 0.5, j + 0.5);
            if (o.ambiguous) {
                ++c.skipped;
                continue;
            }
            ++c.compared;
            std::size_t k = f.Index(i, j);
            ASSERT_EQ(f.Covered(i, j), o.covered) << "scene " << n << " pixel " << i << "," << j;
            if (!o.covered) continue;
            ++c.covered;
            ASSERT_EQ(f.surface[k], o.surface) << "scene " << n << " pixel " << i << "," << j;
            ASSERT_EQ(f.Solid(k), o.solid) << "scene " << n << " pixel " << i << "," << j;
            const FlatBody& body = scene.bodies[static_cast<std::size_t>(f.body[k])];
            EXPECT_TRUE(
                std::any_of(body.literals.begin(), body.literals.end(),
                            [&](const FlatLiteral& l) { return l.halfSpace == o.surface; }));
            ASSERT_NEAR(f.depth[k], o.t, 1e-9 * (1 + std::fabs(o.t)) + DepthRounding(o.t));
        }
    }
}

TEST(RaycastCsg, RandomScenesMatchThePointClassificationOracle) {
    std::mt19937_64 rng(2024);
    const int w = 48, h = 40;
    OracleCounts counts;
    for (int n = 0; n < 40; ++n) {
        FlatScene scene = RandomCsgScene(rng, w, h);
        Frame f = Render(scene);
        CompareToOracle(scene, f, n, counts);
        if (::testing::Test::HasFatalFailure()) return;
    }
    EXPECT_LT(counts.skipped, counts.compared / 100);  // the oracle's blind spots stay rare
    EXPECT_GT(counts.covered, counts.compared / 10);   // and the scenes are not mostly empty
}

// Unions and differences of more than eight operands (the tracer's filtered path: the operands
// whose bounds hold the pixel found first, trace.cpp), nested, of bounded spheres and of
// unbounded random quadrics, against the oracle; kernel=off so that every pixel goes through
// Trace.
TEST(RaycastCsg, WideUnionsAndDifferencesMatchTheOracle) {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(0, 1);
    const int w = 64, h = 48;
    OracleCounts counts;
    double csgOps = 0, cutRetries = 0;
    for (int n = 0; n < 12; ++n) {
        TestSceneBuilder b(w, h);
        auto spheres = [&](int count, double rmin, double rmax) {
            std::vector<int> leaves;
            for (int k = 0; k < count; ++k) {
                Vec3 c{w * u(rng), h * u(rng), 100 + 60 * u(rng)};
                double r = rmin + (rmax - rmin) * u(rng);
                Box3 box = SphereBounds(c, r);
                leaves.push_back(b.AddLeaf(b.AddBody({{b.AddSphere(c, r), false}}, box), box));
            }
            return leaves;
        };
        std::vector<int> inner = spheres(10, 3, 9);
        inner.push_back(b.AddLeaf(b.AddBody({{b.AddQuadric(RandomQuadric(rng, w, h).k), false}})));
        std::vector<int> outer = spheres(25, 3, 12);
        outer.insert(outer.begin() + 7, b.AddNode(CsgOp::kUnion, inner));
        // The union holds an unbounded quadric, so it and the difference keep the default
        // (unbounded) boxes: a box is a promise that the set lies inside it.
        std::vector<int> cut = {b.AddNode(CsgOp::kUnion, outer)};
        for (int s : spheres(12, 4, 10)) cut.push_back(s);
        cut.push_back(b.AddLeaf(b.AddBody({{b.AddQuadric(RandomQuadric(rng, w, h).k), false}})));
        b.AddSolid(b.AddNode(CsgOp::kDifference, cut));
        std::vector<int> second = spheres(14, 2, 6);
        b.AddSolid(b.AddNode(CsgOp::kUnion, second));
        const FlatScene& scene = b.scene();
        RenderOptions options;
        options.engineOptions = {{"kernel", "off"}};
        Frame f;
        RenderStats stats = MakeRaycastEngine()->Render(scene, options, f);
        csgOps += CounterOrFail(stats, "csg_operations");
        cutRetries += CounterOrFail(stats, "depth_cut_retries");
        CompareToOracle(scene, f, n, counts);
        if (::testing::Test::HasFatalFailure()) return;
    }
    EXPECT_LT(counts.skipped, counts.compared / 50);
    EXPECT_GT(counts.covered, counts.compared / 4);
    EXPECT_GT(csgOps, 12 * w * h);  // unions and differences were folded, not short-cut
    // Pixels went past the first depth cut, so the operands of several cut levels were merged
    // back into operand order (trace.cpp, EvaluateWide).
    EXPECT_GT(cutRetries, 100);
}

// Two coincident spheres in one wide union tie exactly everywhere; the earlier operand's surface
// is the one a union keeps, whatever the bounds. Here a loose box puts the later copy below the
// first depth cut and the earlier one above it, so the pixel's second pass meets them from two
// cut levels (trace.cpp, GroupWideOperands) and must fold them in operand order: the Frame equals
// the one where both boxes are tight (one level).
TEST(RaycastCsg, ExactTiesInAWideUnionDoNotDependOnTheBounds) {
    auto scene = [](bool looseLaterCopy) {
        TestSceneBuilder b(16, 16);
        std::vector<int> leaves;
        Box3 all;
        auto leaf = [&](const Vec3& c, double r, Box3 box) {
            leaves.push_back(b.AddLeaf(b.AddBody({{b.AddSphere(c, r), false}}, box), box));
            all.Extend(box);
        };
        // Nine small spheres in front, away from the pixels looked at: the first cut (the 9th
        // nearest zlo of the sub-tile) is theirs, 99.7.
        for (int k = 0; k < 9; ++k) leaf({1.5, 1.5, 100}, 0.3, SphereBounds({1.5, 1.5, 100}, 0.3));
        const Vec3 c{5.5, 5.5, 200};
        leaf(c, 1.8, SphereBounds(c, 1.8));  // operand 9
        Box3 later = SphereBounds(c, 1.8);
        if (looseLaterCopy) later.lo.z = 50;  // still a box of the sphere, below the first cut
        leaf(c, 1.8, later);                  // operand 10, the same sphere
        b.AddSolid(b.AddNode(CsgOp::kUnion, leaves, all), all);
        return b.scene();
    };
    RenderOptions options;
    options.engineOptions = {{"kernel", "off"}};
    Frame tight, loose;
    MakeRaycastEngine()->Render(scene(false), options, tight);
    RenderStats stats = MakeRaycastEngine()->Render(scene(true), options, loose);
    EXPECT_GT(CounterOrFail(stats, "depth_cut_retries"), 0);
    ASSERT_TRUE(tight.Covered(5, 5));
    const int earlier = tight.surface[tight.Index(5, 5)];
    EXPECT_EQ(earlier, 9);  // the ninth sphere's half-space: the earlier copy wins the tie
    EXPECT_EQ(FirstBitDifference(tight, loose), "");
}

// The per-sub-tile kernels (lanes of one interval with a cut, RunKernel for the rest) against
// Trace, bit for bit, on random trees of every operator and piece structure: kernel=off renders
// every pixel with Trace.
TEST(RaycastCsg, KernelsMatchTraceBitForBitOnRandomScenes) {
    std::mt19937_64 rng(77);
    double lanePixels = 0, scalarPixels = 0;
    for (int n = 0; n < 60; ++n) {
        const FlatScene scene = RandomCsgScene(rng, 72, 56);
        RenderOptions on, off;
        off.engineOptions = {{"kernel", "off"}};
        Frame a, b;
        RenderStats stats = MakeRaycastEngine()->Render(scene, on, a);
        MakeRaycastEngine()->Render(scene, off, b);
        ASSERT_EQ(FirstBitDifference(a, b), "") << "scene " << n;
        lanePixels +=
            CounterOrFail(stats, "kernel_pixels") - CounterOrFail(stats, "kernel_scalar_pixels");
        scalarPixels += CounterOrFail(stats, "kernel_scalar_pixels");
    }
    // Both ways of the kernel were taken, often.
    EXPECT_GT(lanePixels, 20000);
    EXPECT_GT(scalarPixels, 2000);
}

// ---- Invariances
// ----------------------------------------------------------------------------------

// Many small spheres in one union, minus a tilted cylinder, next to separate solids: bounds are
// computed by hand (exact for spheres, Everything() for the unbounded cylinder). `shells`: each
// sphere of the union hollow (minus a concentric one of 0.6 its radius, in the same body: two
// intervals where a ray passes the hole).
TestSceneBuilder ManySpheres(int w, int h, int count, std::uint64_t seed, bool shells = false) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    TestSceneBuilder b(w, h);
    std::vector<int> leaves;
    Box3 all;
    for (int k = 0; k < count; ++k) {
        Vec3 c{w * u(rng), h * u(rng), 100 + 50 * u(rng)};
        double r = 2 + 6 * u(rng);
        Box3 box = SphereBounds(c, r);
        std::vector<std::pair<int, bool>> literals{{b.AddSphere(c, r), false}};
        if (shells) literals.push_back({b.AddSphere(c, 0.6 * r), true});
        leaves.push_back(b.AddLeaf(b.AddBody(literals, box), box));
        all.Extend(box);
    }
    int u1 = b.AddNode(CsgOp::kUnion, leaves, all);
    // Cylinder of radius 10 along (1, 1, 1)/√3 through the image centre.
    Quadric cyl = Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -100})
                      .Transformed(Transform::Translate({w / 2.0, h / 2.0, 125}) *
                                   Transform::Rotate(0, 45) * Transform::Rotate(1, 35.26));
    int cylHs = b.AddQuadric(cyl.k);
    int d = b.AddNode(CsgOp::kDifference, {u1, b.AddLeaf(b.AddBody({{cylHs, false}}))}, all);
    b.AddSolid(d, all);
    // Separate solids: spheres (some overlapping the union), and a lens (intersection).
    for (int k = 0; k < 20; ++k) {
        Vec3 c{w * u(rng), h * u(rng), 90 + 80 * u(rng)};
        double r = 3 + 10 * u(rng);
        b.AddSolidOfBody(b.AddBody({{b.AddSphere(c, r), false}}, SphereBounds(c, r)));
    }
    Vec3 c1{w * 0.3, h * 0.6, 120}, c2{w * 0.3 + 10, h * 0.6, 125};
    Box3 lens = SphereBounds(c1, 15).Intersected(SphereBounds(c2, 15));
    int l1 = b.AddLeaf(b.AddBody({{b.AddSphere(c1, 15), false}}, SphereBounds(c1, 15)),
                       SphereBounds(c1, 15));
    int l2 = b.AddLeaf(b.AddBody({{b.AddSphere(c2, 15), false}}, SphereBounds(c2, 15)),
                       SphereBounds(c2, 15));
    b.AddSolid(b.AddNode(CsgOp::kIntersection, {l1, l2}, lens), lens);
    return b;
}

TEST(RaycastCsg, BoundsCullingChangesNoBit) {
    // 280 pixels wide: two 256-pixel blocks, so every pruning level is exercised. (The quadrics'
    // re-centring points come from the quadrics alone, never from bounds.)
    TestSceneBuilder b = ManySpheres(280, 130, 200, 7);
    RenderStats culled, unculled;
    Frame f = Render(b.scene(), 0, &culled);
    Frame g = Render(b.WithoutBounds(), 0, &unculled);
    EXPECT_EQ(FirstBitDifference(f, g), "");
    EXPECT_GT(f.CoveredCount(), 8000u);
    // And culling is what makes it fast: far fewer quadrics solved per pixel. (Without bounds
    // the per-sub-tile discriminant test, which needs none, still skips most misses.)
    EXPECT_LT(CounterOrFail(culled, "quadric_solves") * 2,
              CounterOrFail(unculled, "quadric_solves"));
    EXPECT_GT(CounterOrFail(unculled, "tile_bodies_empty"), 1000.0);
}

// A big union's sub-tiles (more than 8 leaves: depth cuts) go to the kernel with the tree of
// Trace's first pass; its pixels with nothing visible before the first cut are traced. Bit for
// bit what kernel=off (Trace alone) draws, with both ways taken.
TEST(RaycastCsg, KernelsUnderADepthCutMatchTraceBitForBit) {
    for (std::uint64_t seed : {11u, 12u}) {
        // Dense: 900 spheres of 2-8 pixels over 180 × 100, so most sub-tiles meet more than 8;
        // and as many shells.
        const FlatScene scenes[] = {ManySpheres(180, 100, 900, seed).scene(),
                                    ManySpheres(180, 100, 900, seed, true).scene()};
        for (const FlatScene& scene : scenes) {
            RenderOptions on, off;
            off.engineOptions = {{"kernel", "off"}};
            Frame a, c;
            const RenderStats stats = MakeRaycastEngine()->Render(scene, on, a);
            MakeRaycastEngine()->Render(scene, off, c);
            EXPECT_EQ(FirstBitDifference(a, c), "") << "seed " << seed;
            EXPECT_GT(a.CoveredCount(), 12000u);
            EXPECT_GT(CounterOrFail(stats, "kernel_cut_sub_tiles"), 100);
            // Pixels went past the first cut (traced from the kernel's sub-tiles or beside them).
            EXPECT_GT(CounterOrFail(stats, "depth_cut_retries"), 50);
        }
    }
}

TEST(RaycastCsg, ThreadCountChangesNoBit) {
    TestSceneBuilder b = ManySpheres(280, 130, 200, 8);  // not a multiple of the tile sizes
    Frame one = Render(b.scene(), 1), two = Render(b.scene(), 2), all = Render(b.scene(), 0);
    EXPECT_EQ(FirstBitDifference(one, two), "");
    EXPECT_EQ(FirstBitDifference(one, all), "");
}

TEST(RaycastCsg, ExactDepthTiesKeepTheLowerSolidIndex) {
    // Two identical spheres as solids 0 and 1; solid 1's bounds claim a nearer depth so that it is
    // visited first. Every pixel is a tie and must go to solid 0.
    const Vec3 c{32, 32, 200};
    TestSceneBuilder b(64, 64);
    int s0 = b.AddSphere(c, 20), s1 = b.AddSphere(c, 20);
    b.AddSolidOfBody(b.AddBody({{s0, false}}, SphereBounds(c, 20)));
    Box3 nearer = SphereBounds(c, 20);
    nearer.lo.z -= 50;
    b.AddSolidOfBody(b.AddBody({{s1, false}}, nearer));
    Frame f = Render(b.scene());
    ASSERT_GT(f.CoveredCount(), 1000u);
    for (std::size_t k = 0; k < f.body.size(); ++k) {
        if (f.surface[k] != Frame::kNone) {
            ASSERT_EQ(f.Solid(k), 0);
        }
    }
}

TEST(RaycastCsg, NearestSolidWinsAndDepthOrderStopsEarly) {
    // 50 sphere solids one behind the other, each larger than the image: solid 0 covers every
    // pixel nearer than solid 1 can start, so each pixel evaluates one solid and stops. (Trace's
    // rule: kernel=off, since the kernel draws these sub-tiles to their first depth cut.)
    TestSceneBuilder b(32, 32);
    for (int k = 0; k < 50; ++k) {
        Vec3 c{16, 16, 100 + 30.0 * k};
        b.AddSolidOfBody(b.AddBody({{b.AddSphere(c, 40), false}}, SphereBounds(c, 40)));
    }
    RenderOptions options;
    options.engineOptions = {{"kernel", "off"}};
    Frame f;
    const RenderStats stats = MakeRaycastEngine()->Render(b.scene(), options, f);
    ASSERT_EQ(f.CoveredCount(), 32u * 32u);
    for (std::size_t k = 0; k < f.body.size(); ++k) ASSERT_EQ(f.Solid(k), 0);
    EXPECT_EQ(CounterOrFail(stats, "depth_early_outs"), 32 * 32);
    EXPECT_EQ(CounterOrFail(stats, "pixel_solids"), 32 * 32);
}

}  // namespace
}  // namespace quadrix
