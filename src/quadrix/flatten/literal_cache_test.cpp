// The literal cache (literal_cache.h) changes no bit of a box: bodies of ellipsoids, mitered pipes,
// cone frustums and complemented quadrics bounded over one half-space array with and without it.
#include "quadrix/flatten/literal_cache.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "quadrix/flatten/bounds_test_bodies.h"

namespace quadrix {
namespace {

using bounds_test::Body;

bool SameBits(const Box3& a, const Box3& b) { return std::memcmp(&a, &b, sizeof(Box3)) == 0; }

TEST(LiteralCache, BoxesAreBitForBitThoseMadeWithoutIt) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1), r(0.2, 2), mag(-6, 6);
    // Every body's half-spaces in one array (as a FlatScene holds them), each body a list of
    // (index, complemented).
    std::vector<FlatHalfSpace> halfSpaces;
    std::vector<std::vector<std::pair<std::size_t, bool>>> bodies;
    auto add = [&](const Body& b) {
        std::vector<std::pair<std::size_t, bool>> lits;
        for (std::size_t i = 0; i < b.hs.size(); ++i) {
            lits.push_back({halfSpaces.size(), b.complemented[i]});
            halfSpaces.push_back(b.hs[i]);
        }
        bodies.push_back(lits);
    };
    for (int trial = 0; trial < 60; ++trial) {
        const double s = std::pow(10.0, mag(rng));
        const Transform t = Transform::Translate({5 * s * u(rng), 5 * s * u(rng), 5 * s * u(rng)}) *
                            bounds_test::RandomRotation(rng);
        Box3 exact;
        add(bounds_test::MiteredPipe(t, r(rng), 2 + u(rng), 0.8 * u(rng), -2 + u(rng), 0.8 * u(rng),
                                     exact));
        add(bounds_test::ConeFrustum(t, 0.5 + 0.4 * u(rng), 1 + 0.5 * u(rng), 3 + u(rng), exact));
        Body ell;
        ell.hs.push_back(bounds_test::QuadricHs(
            bounds_test::Ellipsoid(s * r(rng), s * r(rng), s * r(rng)).Transformed(t)));
        ell.complemented = {false};
        add(ell);
        // An ellipsoid with a complemented smaller one inside: the cache serves only the first.
        Body shell = ell;
        shell.hs.push_back(bounds_test::QuadricHs(
            bounds_test::Ellipsoid(0.1 * s, 0.1 * s, 0.1 * s).Transformed(t)));
        shell.complemented = {false, true};
        add(shell);
    }
    const LiteralCache cache = LiteralCache::Build(halfSpaces);
    std::size_t quadrics = 0;
    for (std::size_t i = 0; i < halfSpaces.size(); ++i) {
        const bool isQuadric = halfSpaces[i].IsQuadric();
        quadrics += isQuadric;
        EXPECT_EQ(cache.Find(&halfSpaces[i]) != nullptr, isQuadric) << i;
    }
    EXPECT_EQ(cache.entries.size(), quadrics);
    FlatHalfSpace elsewhere = halfSpaces[2];
    EXPECT_EQ(cache.Find(&elsewhere), nullptr);

    BoundsOptions with;
    with.literals = &cache;
    int served = 0;
    for (const auto& body : bodies) {
        std::vector<BoundLiteral> lits;
        for (const auto& [i, c] : body) {
            lits.push_back({&halfSpaces[i], c});
            served += !c && cache.Find(&halfSpaces[i]) != nullptr;
        }
        BoundsStats a, b;
        const Box3 fresh = IntersectionBounds(lits, {}, &a);
        const Box3 cached = IntersectionBounds(lits, with, &b);
        EXPECT_TRUE(SameBits(fresh, cached)) << "body of " << lits.size() << " literals";
        EXPECT_EQ(a.analyticOnly, b.analyticOnly);
        EXPECT_EQ(a.criticalPointBoxes, b.criticalPointBoxes);
        EXPECT_EQ(a.convexSolves, b.convexSolves);
        EXPECT_EQ(a.boxesPopped, b.boxesPopped);
    }
    EXPECT_GT(served, 200);  // the cache was used, not bypassed
    // HalfSpaceScale with the cached box and extent is the one that makes them, bit for bit.
    for (const FlatHalfSpace& h : halfSpaces) {
        if (const LiteralCache::Entry* e = cache.Find(&h)) {
            EXPECT_EQ(HalfSpaceScale(h, &e->box, &e->extent), HalfSpaceScale(h));
            EXPECT_EQ(HalfSpaceScale(h, &e->box), HalfSpaceScale(h));
        }
    }
}

}  // namespace
}  // namespace quadrix
