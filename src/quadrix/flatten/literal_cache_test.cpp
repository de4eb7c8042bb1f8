// The literal cache (literal_cache.h) changes no bit of a box: bodies of ellipsoids, mitered pipes,
// cone frustums and complemented quadrics bounded over one half-space array with and without it.
#include "quadrix/flatten/literal_cache.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <random>
#include <thread>
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

bool SameEntry(const LiteralCache::Entry& a, const LiteralCache::Entry& b) {
    return std::memcmp(&a.fn.a, &b.fn.a, sizeof a.fn.a) == 0 &&
           std::memcmp(&a.fn.b, &b.fn.b, sizeof a.fn.b) == 0 && a.fn.k == b.fn.k &&
           a.fn.lamMin == b.fn.lamMin && a.fn.lamMax == b.fn.lamMax && SameBits(a.box, b.box) &&
           std::memcmp(&a.centre, &b.centre, sizeof a.centre) == 0 && a.hasCentre == b.hasCentre &&
           a.extent == b.extent;
}

// Half-spaces as a walk appends them: planes and quadrics mixed, in a reserved array.
std::vector<FlatHalfSpace> MixedHalfSpaces(std::size_t n, std::size_t reserve) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1, 1), r(0.2, 2);
    std::vector<FlatHalfSpace> hs;
    hs.reserve(reserve);
    for (std::size_t i = 0; i < n; ++i) {
        if (i % 3 == 2) {
            FlatHalfSpace p;
            p.isPlane = true;
            p.plane = {u(rng), u(rng), u(rng), u(rng)};
            hs.push_back(p);
        } else {
            const Transform t = Transform::Translate({50 * u(rng), 50 * u(rng), 50 * u(rng)}) *
                                bounds_test::RandomRotation(rng);
            hs.push_back(bounds_test::QuadricHs(
                bounds_test::Ellipsoid(r(rng), r(rng), r(rng)).Transformed(t)));
        }
    }
    return hs;
}

void ExpectSameCache(const LiteralCache& got, const std::vector<FlatHalfSpace>& hs) {
    const LiteralCache want = LiteralCache::Build(hs);
    ASSERT_EQ(got.entries.size(), want.entries.size());
    ASSERT_EQ(got.slot, want.slot);
    EXPECT_EQ(got.base, hs.data());
    EXPECT_EQ(got.size, hs.size());
    for (std::size_t k = 0; k < want.entries.size(); ++k)
        ASSERT_TRUE(SameEntry(got.entries[k], want.entries[k])) << "entry " << k;
}

// The builder's thread makes entries while half-spaces are appended; Finish makes the rest. The
// cache is Build's, entry for entry, bit for bit: appended in bursts with the walk ending normally,
// stopped mid-way (Finish before Finished), and told the array grows (the thread stops before it
// moves; the entries it made are kept).
TEST(LiteralCacheBuilder, MakesBuildsEntriesWhileTheWalkAppends) {
    const std::size_t n = 3 * LiteralCacheBuilder::kMinHalfSpaces;
    const std::vector<FlatHalfSpace> all = MixedHalfSpaces(n, n);
    for (int mode = 0; mode < 3; ++mode) {
        SCOPED_TRACE(mode);
        std::vector<FlatHalfSpace> hs;
        // mode 2: room for half of them, so the array grows once mid-way.
        hs.reserve(mode == 2 ? n / 2 : n);
        LiteralCacheBuilder builder;
        builder.Started(hs, n);
        for (std::size_t i = 0; i < n; ++i) {
            if (hs.size() == hs.capacity()) builder.Growing();
            hs.push_back(all[i]);
            if (mode != 2 || i < n / 2) builder.Appended(hs.size());
            if (mode == 1 && i == n / 3) break;  // a walk that fails part-way
        }
        if (mode != 1) builder.Finished();
        if (mode == 0) {
            // The thread ends once it has made every entry (at idle priority it may wait for
            // a processor while others are busy: up to 30 s).
            for (int wait = 0; wait < 6000 && !builder.ThreadEnded(); ++wait)
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
            ASSERT_TRUE(builder.ThreadEnded());
        }
        ExpectSameCache(builder.Finish(hs), hs);
        if (mode == 0) {
            EXPECT_EQ(builder.MadeAlongside(), 2 * n / 3);  // every quadric's entry
        }
    }
    // Too few half-spaces for a thread: Finish makes them all, the same.
    std::vector<FlatHalfSpace> few = MixedHalfSpaces(300, 300);
    LiteralCacheBuilder small;
    small.Started(few, few.size());
    small.Finished();
    ExpectSameCache(small.Finish(few), few);
}

}  // namespace
}  // namespace quadrix
