#include "quadrix/eval/ray_literal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace quadrix::eval {
namespace {

constexpr double kInf = HUGE_VAL;
constexpr std::int32_t kNo = Interval::kNoId;

FlatHalfSpace PlaneHs(double a, double b, double c, double d) {
    FlatHalfSpace h;
    h.isPlane = true;
    h.plane = {a, b, c, d};
    return h;
}
FlatHalfSpace QuadricHs(const std::array<double, 10>& k) {
    FlatHalfSpace h;
    h.isPlane = false;
    h.quadric = Quadric::FromCoefficients(k);
    return h;
}

IntervalList Set(const FlatHalfSpace& h, bool complemented, double x, double y) {
    IntervalList out;
    LiteralCounters counters;
    LiteralSetOnRay(RayHalfSpace::From(h), complemented, x, y, 7, out, counters);
    EXPECT_TRUE(out.IsCanonical());
    return out;
}

TEST(RaycastLiteral, PlanesGiveHalfLinesOrAllOrNothing) {
    // 2z − 10 <= 0: t <= 5.
    EXPECT_EQ(Set(PlaneHs(0, 0, 2, -10), false, 3, 4), IntervalList::Single(-kInf, kNo, 5, 7));
    EXPECT_EQ(Set(PlaneHs(0, 0, 2, -10), true, 3, 4), IntervalList::Single(5, 7, kInf, kNo));
    // −z + x <= 0 at x = 3: t >= 3.
    EXPECT_EQ(Set(PlaneHs(1, 0, -1, 0), false, 3, 4), IntervalList::Single(3, 7, kInf, kNo));
    // Edge-on plane x − 3 <= 0 (parallel to the rays): all, nothing, or on the plane all for H and
    // nothing for !H (regularised complement).
    EXPECT_EQ(Set(PlaneHs(1, 0, 0, -3), false, 2.5, 0), IntervalList::All());
    EXPECT_TRUE(Set(PlaneHs(1, 0, 0, -3), true, 2.5, 0).empty());
    EXPECT_TRUE(Set(PlaneHs(1, 0, 0, -3), false, 3.5, 0).empty());
    EXPECT_EQ(Set(PlaneHs(1, 0, 0, -3), true, 3.5, 0), IntervalList::All());
    EXPECT_EQ(Set(PlaneHs(1, 0, 0, -3), false, 3, 0), IntervalList::All());
    EXPECT_TRUE(Set(PlaneHs(1, 0, 0, -3), true, 3, 0).empty());
    // NaN coefficients: empty both ways.
    EXPECT_TRUE(Set(PlaneHs(NAN, 0, 1, 0), false, 1, 1).empty());
    EXPECT_TRUE(Set(PlaneHs(NAN, 0, 1, 0), true, 1, 1).empty());
}

TEST(RaycastLiteral, SphereGivesAnIntervalOrNothing) {
    // x² + y² + z² − 25 <= 0 at (3, 0): t in [−4, 4]; at (5, 0) the ray is tangent: nothing.
    auto sphere = QuadricHs({1, 1, 1, 0, 0, 0, 0, 0, 0, -25});
    EXPECT_EQ(Set(sphere, false, 3, 0), IntervalList::Single(-4, 7, 4, 7));
    IntervalList outside = Set(sphere, true, 3, 0);
    ASSERT_EQ(outside.size(), 2u);
    EXPECT_EQ(outside[0], (Interval{-kInf, -4, kNo, 7}));
    EXPECT_EQ(outside[1], (Interval{4, kInf, 7, kNo}));
    EXPECT_TRUE(Set(sphere, false, 5, 0).empty());
    EXPECT_EQ(Set(sphere, true, 5, 0), IntervalList::All());
    EXPECT_TRUE(Set(sphere, false, 6, 0).empty());
}

TEST(RaycastLiteral, ConesCylindersAndParaboloids) {
    // Double cone along z: x² + y² − z² <= 0. At distance 3 from the axis: two half-lines.
    auto cone = QuadricHs({1, 1, -1, 0, 0, 0, 0, 0, 0, 0});
    IntervalList c = Set(cone, false, 3, 0);
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c[0], (Interval{-kInf, -3, kNo, 7}));
    EXPECT_EQ(c[1], (Interval{3, kInf, 7, kNo}));
    // Through the apex (the axis): a double root with a < 0, the whole ray; !H nothing.
    EXPECT_EQ(Set(cone, false, 0, 0), IntervalList::All());
    EXPECT_TRUE(Set(cone, true, 0, 0).empty());
    // Cylinder along z, x² + y² − 4 <= 0: constant along the ray (c = 0, b = 0).
    auto cyl = QuadricHs({1, 1, 0, 0, 0, 0, 0, 0, 0, -4});
    EXPECT_EQ(Set(cyl, false, 1, 1), IntervalList::All());
    EXPECT_TRUE(Set(cyl, false, 3, 0).empty());
    EXPECT_EQ(Set(cyl, false, 2, 0), IntervalList::All());  // on the surface: Q ≡ 0, inside
    EXPECT_TRUE(Set(cyl, true, 2, 0).empty());
    // Cylinder along x, y² + z² − 4 <= 0, seen sideways: an interval, complement two pieces.
    auto side = QuadricHs({0, 1, 1, 0, 0, 0, 0, 0, 0, -4});
    EXPECT_EQ(Set(side, false, 10, 0), IntervalList::Single(-2, 7, 2, 7));
    EXPECT_EQ(Set(side, true, 10, 0).size(), 2u);
    // Paraboloid x² + y² − 2z <= 0 (2J = −2): linear along the ray, t >= (x² + y²)/2.
    auto bowl = QuadricHs({1, 1, 0, 0, 0, 0, 0, 0, -1, 0});
    EXPECT_EQ(Set(bowl, false, 2, 2), IntervalList::Single(4, 7, kInf, kNo));
    EXPECT_EQ(Set(bowl, true, 2, 2), IntervalList::Single(-kInf, kNo, 4, 7));
    // Hyperbolic "no real root" with a < 0: −z² − 1 <= 0 everywhere.
    EXPECT_EQ(Set(QuadricHs({0, 0, -1, 0, 0, 0, 0, 0, 0, -1}), false, 0, 0), IntervalList::All());
    // The empty quadric 0 <= 0 holds everywhere.
    EXPECT_EQ(Set(QuadricHs({}), false, 1, 2), IntervalList::All());
}

TEST(RaycastLiteral, QuadricCentres) {
    // (x − 3)² + 2 (y + 7)² + (z − 1000)² − 4 <= 0.
    auto c = RayHalfSpace::Centre(
        Quadric::FromCoefficients({1, 2, 1, 0, 0, 0, -3, 14, -1000, 9 + 98 + 1e6 - 4}));
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(*c, Vec3(3, -7, 1000));
    // Rounded to integers.
    c = RayHalfSpace::Centre(Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, -0.25, 0, -10.75, 0}));
    ASSERT_TRUE(c.has_value());
    EXPECT_EQ(*c, Vec3(0, 0, 11));
    // Cylinders and paraboloids have no centre point; a cone's apex is its centre.
    EXPECT_FALSE(RayHalfSpace::Centre(Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, 0, -1})));
    EXPECT_FALSE(RayHalfSpace::Centre(Quadric::FromCoefficients({1, 1, 0, 0, 0, 0, 0, 0, -1, 0})));
    EXPECT_EQ(RayHalfSpace::Centre(Quadric::FromCoefficients({1, 1, -1, 0, 0, 0, -5, 0, 6, 0})),
              Vec3(5, 0, 6));
    EXPECT_FALSE(RayHalfSpace::Centre(Quadric::FromCoefficients({NAN, 1, 1, 0, 0, 0, 0, 0, 0, 0})));
}

TEST(RaycastLiteral, RecentringKeepsTheRoots) {
    // Random ellipsoids far from the origin: the set on a ray is the same whether the quadric is
    // evaluated about the origin or about its centre, to the accuracy of the un-centred
    // evaluation (its per-pixel rounding is about u·|centre|²·|A| in Q, i.e. 1e-10 here, which
    // moves a root by that over |dQ/dt| = a·(chord length), i.e. by < 1e-8 for chords over 0.1;
    // shorter chords, near tangency, are skipped).
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0, 1);
    int compared = 0;
    for (int n = 0; n < 2000; ++n) {
        Vec3 c{500 * u(rng), 500 * u(rng), 200 + 800 * u(rng)};
        double r = 5 + 50 * u(rng);
        Transform t = Transform::Translate(c) * Transform::Rotate(0, 360 * u(rng)) *
                      Transform::Rotate(1, 360 * u(rng)) *
                      Transform::Scale({r, r * (0.3 + u(rng)), r * (0.3 + u(rng))});
        FlatHalfSpace h;
        h.isPlane = false;
        h.quadric = Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, -1}).Transformed(t);
        auto centre = RayHalfSpace::Centre(h.quadric);
        ASSERT_TRUE(centre.has_value());
        EXPECT_LE(Length(*centre - c), 1.0);  // rounded to integers: within √3/2
        double x = c.x + r * (2 * u(rng) - 1), y = c.y + r * (2 * u(rng) - 1);
        LiteralCounters counters;
        RaySet a = LiteralOnRay(RayHalfSpace::From(h, {}), false, x, y, 1, counters);
        RaySet b = LiteralOnRay(RayHalfSpace::From(h, *centre), false, x, y, 1, counters);
        if (a.count != b.count) {
            // Only possible for a nearly tangent ray.
            RaySet& hit = a.count ? a : b;
            EXPECT_LT(hit.piece[0].hi - hit.piece[0].lo, 0.1) << n;
            continue;
        }
        if (a.count == 0 || a.piece[0].hi - a.piece[0].lo < 0.1) continue;
        ASSERT_EQ(a.count, 1);
        EXPECT_NEAR(a.piece[0].lo, b.piece[0].lo, 1e-9 * c.z);
        EXPECT_NEAR(a.piece[0].hi, b.piece[0].hi, 1e-9 * c.z);
        ++compared;
    }
    EXPECT_GT(compared, 500);
}

// ClassifyQuadric's claim, tested where it matters: whenever it says no ray of a rectangle meets
// the quadric, the literal's set at every pixel centre of the rectangle is all of the ray
// (kInsideEverywhere) or nothing (kOutsideEverywhere), with and without complement; and it does
// decide most rectangles far from a quadric's silhouette (else culling would be useless).
TEST(RaycastLiteral, ClassifyQuadricOnRectanglesIsNeverWrong) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int decided = 0, farFromSilhouette = 0, rects = 0;
    for (int n = 0; n < 400; ++n) {
        // A random quadric (of any type) placed near the image region, re-centred like the engine.
        std::array<double, 10> k{};
        for (double& v : k) v = u(rng);
        k[9] = 40 * u(rng);
        const Vec3 shift{30 * u(rng), 30 * u(rng), 50 + 20 * u(rng)};
        Quadric q = Quadric::FromCoefficients(k).Transformed(Transform::Translate(shift));
        FlatHalfSpace hs;
        hs.isPlane = false;
        hs.quadric = q;
        const RayHalfSpace r = RayHalfSpace::From(hs, RayHalfSpace::Centre(q).value_or(Vec3{}));
        for (int t = 0; t < 20; ++t) {
            const double x0 = std::floor(60 * u(rng)) + 0.5, y0 = std::floor(60 * u(rng)) + 0.5;
            const int w = 1 + static_cast<int>(16 * (u(rng) + 1) / 2), h = w;
            const QuadricOnRect c = ClassifyQuadric(r, x0, x0 + w - 1, y0, y0 + h - 1);
            ++rects;
            bool anyRoot = false;
            for (int j = 0; j < h; ++j) {
                for (int i = 0; i < w; ++i) {
                    const double x = x0 + i, y = y0 + j;
                    for (bool comp : {false, true}) {
                        LiteralCounters counters;
                        const RaySet set = LiteralOnRay(r, comp, x, y, 3, counters);
                        const bool all = set.count == 1 && std::isinf(set.piece[0].lo) &&
                                         std::isinf(set.piece[0].hi);
                        const bool none = set.count == 0;
                        anyRoot |= !all && !none;
                        if (c == QuadricOnRect::kUnknown) continue;
                        const bool inside = (c == QuadricOnRect::kInsideEverywhere) != comp;
                        ASSERT_TRUE(inside ? all : none)
                            << "quadric " << n << " rect " << t << " pixel " << x << "," << y;
                    }
                }
            }
            decided += c != QuadricOnRect::kUnknown;
            farFromSilhouette += !anyRoot;
        }
    }
    // Rectangles with no root at any pixel: most of them are decided.
    EXPECT_GT(farFromSilhouette, 1000);
    EXPECT_GT(decided, farFromSilhouette / 2) << decided << " of " << farFromSilhouette;
    EXPECT_LT(decided, rects);
}

// ---- QuadricBatch: bit for bit the per-pixel loop over LiteralOnRay ---------------------------

// Room for more than the 64 pixels of a sub-tile, to check that pixels past n stay untouched.
constexpr int kBatchRoom = 80;

struct Batch {
    double lo[kBatchRoom], hi[kBatchRoom];
    std::int64_t loId[kBatchRoom], hiId[kBatchRoom];
    std::uint8_t flag[kBatchRoom];
};

// The reference: QuadricBatch's contract written out (ray_literal.h).
void ReferenceBatch(const RayHalfSpace& hs, bool complemented, std::int32_t tag, int n,
                    const double* xs, const double* ys, Batch& b, LiteralCounters& counters) {
    for (int p = 0; p < n; ++p) {
        if (b.flag[p] != kBatchLive) continue;
        const RaySet s = LiteralOnRay(hs, complemented, xs[p], ys[p], tag, counters);
        if (s.count == 0) {
            b.flag[p] = kBatchDead;
        } else if (s.count == 2) {
            b.flag[p] = kBatchScalar;
        } else {
            const Interval& v = s.piece[0];
            if (!(b.lo[p] > v.lo)) {
                b.lo[p] = v.lo;
                b.loId[p] = v.loId;
            }
            if (!(b.hi[p] <= v.hi)) {
                b.hi[p] = v.hi;
                b.hiId[p] = v.hiId;
            }
        }
    }
}

using Rng = std::mt19937_64;

double Uniform(Rng& rng, double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
}
int UniformInt(Rng& rng, int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng); }
bool Chance(Rng& rng, double p) { return Uniform(rng, 0, 1) < p; }

// What the reference did to the live pixels, to check that a test reaches every outcome.
struct BatchOutcomes {
    // One piece: both bounds now this literal's (finite ends), or otherwise (an infinite end, or
    // a bound kept by the exact comparisons).
    long dead = 0, scalar = 0, bothEnds = 0, otherPiece = 0, notLive = 0;
};

// A random starting state: mostly live pixels with (−∞, ∞) as ComputeBatch starts, else dead or
// scalar ones, finite bounds, signed zeros, NaN, and bounds equal to the literal's own endpoints
// (ties decide by the exact comparison rules).
Batch RandomBatch(Rng& rng, const RayHalfSpace& hs, bool complemented, int n, const double* xs,
                  const double* ys) {
    Batch b;
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    for (int p = 0; p < kBatchRoom; ++p) {
        const double r = Uniform(rng, 0, 1);
        b.flag[p] = r < 0.8 ? kBatchLive : r < 0.9 ? kBatchDead : kBatchScalar;
        if (Chance(rng, 0.01)) b.flag[p] = static_cast<std::uint8_t>(UniformInt(rng, 3, 255));
        b.loId[p] = Chance(rng, 0.5) ? Interval::kNoId
                                     : std::uniform_int_distribution<std::int64_t>(
                                           std::numeric_limits<std::int64_t>::min(),
                                           std::numeric_limits<std::int64_t>::max())(rng);
        b.hiId[p] = Chance(rng, 0.5) ? Interval::kNoId : UniformInt(rng, 0, 1 << 30);
        b.lo[p] = -kInf;
        b.hi[p] = kInf;
        RaySet own;
        if (p < n) {
            LiteralCounters unused;
            own = LiteralOnRay(hs, complemented, xs[p], ys[p], 5, unused);
        }
        for (double* v : {&b.lo[p], &b.hi[p]}) {
            const int kind = UniformInt(rng, 0, 9);
            if (kind == 0) *v = Uniform(rng, -200, 800);
            if (kind == 1) *v = Chance(rng, 0.5) ? 0.0 : -0.0;
            if (kind == 2) *v = Chance(rng, 0.5) ? kInf : -kInf;
            if (kind == 3 && Chance(rng, 0.2)) *v = kNaN;
            if (kind >= 4 && kind <= 6 && own.count > 0) {
                const Interval& piece = own.piece[UniformInt(rng, 0, own.count - 1)];
                *v = Chance(rng, 0.5) ? piece.lo : piece.hi;
            }
        }
    }
    return b;
}

// Runs QuadricBatch and the reference from the same state and compares every byte of every array
// (also past n) and the counters.
::testing::AssertionResult SameAsReference(const RayHalfSpace& hs, bool complemented,
                                           std::int32_t tag, int n, const double* xs,
                                           const double* ys, const Batch& start,
                                           BatchOutcomes* outcomes = nullptr) {
    Batch want = start, got = start;
    LiteralCounters wantCounters{3, 11}, gotCounters{3, 11};
    ReferenceBatch(hs, complemented, tag, n, xs, ys, want, wantCounters);
    QuadricBatch(hs, complemented, tag, n, xs, ys, got.lo, got.loId, got.hi, got.hiId, got.flag,
                 gotCounters);
    if (outcomes) {
        for (int p = 0; p < n; ++p) {
            if (start.flag[p] != kBatchLive) {
                ++outcomes->notLive;
            } else if (want.flag[p] == kBatchDead) {
                ++outcomes->dead;
            } else if (want.flag[p] == kBatchScalar) {
                ++outcomes->scalar;
            } else if (want.loId[p] == tag && want.hiId[p] == tag) {
                ++outcomes->bothEnds;
            } else {
                ++outcomes->otherPiece;
            }
        }
    }
    if (gotCounters.planes != wantCounters.planes || gotCounters.quadrics != wantCounters.quadrics)
        return ::testing::AssertionFailure()
               << "counters " << gotCounters.planes << "," << gotCounters.quadrics << " instead of "
               << wantCounters.planes << "," << wantCounters.quadrics;
    for (int p = 0; p < kBatchRoom; ++p) {
        if (std::memcmp(&got.lo[p], &want.lo[p], sizeof(double)) == 0 &&
            std::memcmp(&got.hi[p], &want.hi[p], sizeof(double)) == 0 &&
            got.loId[p] == want.loId[p] && got.hiId[p] == want.hiId[p] &&
            got.flag[p] == want.flag[p])
            continue;
        char text[640];
        std::snprintf(text, sizeof text,
                      "pixel %d of %d at (%a, %a), complemented %d, start flag %d lo %a hi %a:\n"
                      "  got  flag %d lo %a (%lld) hi %a (%lld)\n"
                      "  want flag %d lo %a (%lld) hi %a (%lld)\n"
                      "  c %a x0 %a y0 %a z0 %a hx %a hy %a h0 %a\n"
                      "  axx %a axy %a ax %a byy %a by %a k0 %a",
                      p, n, p < n ? xs[p] : 0.0, p < n ? ys[p] : 0.0, complemented, start.flag[p],
                      start.lo[p], start.hi[p], got.flag[p], got.lo[p],
                      static_cast<long long>(got.loId[p]), got.hi[p],
                      static_cast<long long>(got.hiId[p]), want.flag[p], want.lo[p],
                      static_cast<long long>(want.loId[p]), want.hi[p],
                      static_cast<long long>(want.hiId[p]), hs.c, hs.x0, hs.y0, hs.z0, hs.hx, hs.hy,
                      hs.h0, hs.axx, hs.axy, hs.ax, hs.byy, hs.by, hs.k0);
        return ::testing::AssertionFailure() << text;
    }
    return ::testing::AssertionSuccess();
}

// A random quadric of one of the usual kinds (or random coefficients), scaled, turned (by any
// angle, or by multiples of 90 degrees, which are exact and give c == 0 for cylinders and
// paraboloids along z) and moved; sometimes negated (c < 0 for a sphere: its outside) or with all
// coefficients scaled by a huge or tiny power of ten.
Quadric RandomShape(Rng& rng, Vec3& centre, double& radius) {
    static const std::array<double, 10> kShapes[] = {
        {1, 1, 1, 0, 0, 0, 0, 0, 0, -1},   // sphere / ellipsoid
        {1, 1, 0, 0, 0, 0, 0, 0, 0, -1},   // cylinder along z
        {1, 1, -1, 0, 0, 0, 0, 0, 0, 0},   // double cone
        {1, 1, -1, 0, 0, 0, 0, 0, 0, -1},  // hyperboloid of one sheet
        {1, 1, -1, 0, 0, 0, 0, 0, 0, 1},   // hyperboloid of two sheets
        {1, 1, 0, 0, 0, 0, 0, 0, -1, 0},   // elliptic paraboloid
        {1, -1, 0, 0, 0, 0, 0, 0, -1, 0},  // hyperbolic paraboloid
        {1, 0, 0, 0, 0, 0, 0, 0, 0, -1},   // two parallel planes
    };
    const int kind = UniformInt(rng, 0, 8);
    std::array<double, 10> k{};
    if (kind < 8) {
        k = kShapes[kind];
    } else {
        for (double& v : k) v = Uniform(rng, -1, 1);
    }
    radius = Uniform(rng, 2, 60);
    centre = {Uniform(rng, -100, 100), Uniform(rng, -100, 100), Uniform(rng, -100, 1000)};
    if (Chance(rng, 0.3))
        centre = {std::round(centre.x), std::round(centre.y), std::round(centre.z)};
    Transform turn;
    const int rot = UniformInt(rng, 0, 2);
    if (rot == 1) {
        turn = Transform::Rotate(0, 90.0 * UniformInt(rng, 0, 3)) *
               Transform::Rotate(1, 90.0 * UniformInt(rng, 0, 3));
    } else if (rot == 2) {
        turn = Transform::Rotate(0, Uniform(rng, 0, 360)) *
               Transform::Rotate(1, Uniform(rng, 0, 360)) *
               Transform::Rotate(2, Uniform(rng, 0, 360));
    }
    const Transform t = Transform::Translate(centre) * turn *
                        Transform::Scale({radius, radius * Uniform(rng, 0.3, 1.3),
                                          radius * Uniform(rng, 0.3, 1.3)});
    Quadric q = Quadric::FromCoefficients(k).Transformed(t);
    if (Chance(rng, 0.4))
        for (double& v : q.k) v = -v;
    if (Chance(rng, 0.15)) {
        const double f = std::pow(10.0, UniformInt(rng, -300, 300));
        for (double& v : q.k) v *= f;
    }
    return q;
}

// The engine's way (SceneTables): re-centred on the quadric's centre if it has one, else on an
// integer anchor; sometimes not re-centred, or on a non-integer point.
RayHalfSpace RecentredShape(Rng& rng, const Quadric& q) {
    FlatHalfSpace hs;
    hs.isPlane = false;
    hs.quadric = q;
    const Vec3 anchor{std::round(Uniform(rng, -300, 300)), std::round(Uniform(rng, -300, 300)), 0};
    const int how = UniformInt(rng, 0, 9);
    if (how == 0) return RayHalfSpace::From(hs);
    if (how == 1)
        return RayHalfSpace::From(
            hs, {Uniform(rng, -50, 50), Uniform(rng, -50, 50), Uniform(rng, -50, 50)});
    return RayHalfSpace::From(hs, RayHalfSpace::Centre(q).value_or(anchor));
}

// An 8×8 block of pixel centres at (ox + i + ½, oy + j + ½), then n is sometimes cut short.
int GridPixels(double ox, double oy, double* xs, double* ys) {
    for (int j = 0; j < 8; ++j) {
        for (int i = 0; i < 8; ++i) {
            xs[8 * j + i] = ox + i + 0.5;
            ys[8 * j + i] = oy + j + 0.5;
        }
    }
    return 64;
}

// The discriminant h² − c k of the ray through (x, y), as LiteralOnRay forms its parts.
double Discriminant(const RayHalfSpace& hs, double x, double y) {
    const double dx = x - hs.x0, dy = y - hs.y0;
    const double h = hs.hx * dx + hs.hy * dy + hs.h0;
    const double k = dx * (hs.axx * dx + hs.axy * dy + hs.ax) + dy * (hs.byy * dy + hs.by) + hs.k0;
    return h * h - hs.c * k;
}

// Pixels on the silhouette, where the discriminant changes sign: along rows, the two adjacent
// doubles that bracket the change (found by bisection) and a few ulps either side. Returns how
// many pixels it found (0 when no row crosses the silhouette).
int SilhouettePixels(Rng& rng, const RayHalfSpace& hs, double ox, double oy, double span,
                     double* xs, double* ys) {
    int n = 0;
    for (int row = 0; row < 24 && n + 8 <= 64; ++row) {
        const double y = Chance(rng, 0.5) ? oy + std::floor(Uniform(rng, 0, span)) + 0.5
                                          : oy + Uniform(rng, 0, span);
        double a = ox, b = ox + span;
        double da = Discriminant(hs, a, y), db = Discriminant(hs, b, y);
        // A sign change inside [a, b]: sample the row.
        bool found = (da < 0) != (db < 0);
        for (int s = 1; s <= 64 && !found; ++s) {
            const double x = ox + span * s / 64;
            const double d = Discriminant(hs, x, y);
            if ((d < 0) != (da < 0)) {
                b = x;
                db = d;
                found = true;
            }
        }
        if (!found || std::isnan(da) || std::isnan(db)) continue;
        for (int it = 0; it < 200; ++it) {
            const double m = 0.5 * (a + b);
            if (m == a || m == b) break;
            const double dm = Discriminant(hs, m, y);
            if ((dm < 0) == (da < 0)) {
                a = m;
            } else {
                b = m;
            }
        }
        double x = a;
        for (int u = 0; u < 3; ++u) x = std::nextafter(x, -kInf);
        for (int u = 0; u < 8; ++u, x = std::nextafter(x, kInf)) {
            xs[n] = x;
            ys[n] = y;
            ++n;
        }
    }
    return n;
}

TEST(RayLiteralBatch, MatchesTheScalarLoopOnShapes) {
    Rng rng(2024);
    BatchOutcomes seen;
    double xs[kBatchRoom] = {}, ys[kBatchRoom] = {};
    for (int shape = 0; shape < 2500; ++shape) {
        Vec3 centre;
        double radius = 0;
        const Quadric q = RandomShape(rng, centre, radius);
        const RayHalfSpace hs = RecentredShape(rng, q);
        for (int grid = 0; grid < 5; ++grid) {
            double ox = std::floor(centre.x + Uniform(rng, -1.3, 1.3) * radius - 4);
            double oy = std::floor(centre.y + Uniform(rng, -1.3, 1.3) * radius - 4);
            if (Chance(rng, 0.05)) {  // far away: huge pixel coordinates
                ox = std::pow(10.0, UniformInt(rng, 6, 300)) * (Chance(rng, 0.5) ? 1 : -1);
                oy = Chance(rng, 0.5) ? oy : -ox;
            }
            int n = GridPixels(ox, oy, xs, ys);
            if (Chance(rng, 0.1)) n = UniformInt(rng, 0, 64);
            const bool complemented = Chance(rng, 0.5);
            const auto tag = static_cast<std::int32_t>(UniformInt(rng, 0, 1 << 30));
            const Batch start = RandomBatch(rng, hs, complemented, n, xs, ys);
            ASSERT_TRUE(SameAsReference(hs, complemented, tag, n, xs, ys, start, &seen))
                << "shape " << shape << " grid " << grid;
        }
    }
    // Every outcome is reached often (else the comparison would prove little).
    EXPECT_GT(seen.dead, 60000);
    EXPECT_GT(seen.scalar, 80000);
    EXPECT_GT(seen.bothEnds, 25000);
    EXPECT_GT(seen.otherPiece, 120000);
    EXPECT_GT(seen.notLive, 80000);
}

TEST(RayLiteralBatch, MatchesTheScalarLoopOnSilhouettes) {
    // Rays within an ulp or so of tangency: the discriminant is ~0, so SolveQuadratic takes its
    // compensated path, finds double roots, or roots that round together.
    Rng rng(77);
    BatchOutcomes seen;
    int batches = 0;
    double xs[kBatchRoom] = {}, ys[kBatchRoom] = {};
    for (int shape = 0; shape < 3000; ++shape) {
        Vec3 centre;
        double radius = 0;
        const Quadric q = RandomShape(rng, centre, radius);
        const RayHalfSpace hs = RecentredShape(rng, q);
        const double span = 2.6 * radius + 8;
        const int n = SilhouettePixels(rng, hs, std::floor(centre.x - 0.5 * span),
                                       std::floor(centre.y - 0.5 * span), span, xs, ys);
        if (n == 0) continue;
        ++batches;
        for (bool complemented : {false, true}) {
            const Batch start = RandomBatch(rng, hs, complemented, n, xs, ys);
            ASSERT_TRUE(SameAsReference(hs, complemented, 9, n, xs, ys, start, &seen))
                << "shape " << shape;
        }
    }
    EXPECT_GT(batches, 1200);
    EXPECT_GT(seen.dead, 20000);
    EXPECT_GT(seen.scalar, 15000);
    EXPECT_GT(seen.bothEnds, 5000);
}

TEST(RayLiteralBatch, MatchesTheScalarLoopOnExtremeCoefficients) {
    // Coefficients straight into RayHalfSpace: zeros of both signs, values about the 2^±200
    // limits of SolveQuadratic's unscaled path, huge, tiny and subnormal ones, infinities and NaN;
    // pixels anywhere from 0 to 1e300.
    Rng rng(31337);
    BatchOutcomes seen;
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    auto value = [&rng]() {
        const int kind = UniformInt(rng, 0, 39);
        const double sign = Chance(rng, 0.5) ? 1 : -1;
        if (kind == 0) return sign * 0.0;
        if (kind == 1) return sign * kInf;
        if (kind == 2) return kNaN;
        if (kind == 3) return sign * std::ldexp(1.0, Chance(rng, 0.5) ? 200 : -200);
        if (kind == 4)
            return sign * std::ldexp(1.0 + Uniform(rng, -1e-15, 1e-15), UniformInt(rng, -201, 201));
        if (kind == 5) return sign * 4e-320 * Uniform(rng, 0, 1);
        if (kind <= 9) return sign * std::ldexp(Uniform(rng, 1, 2), UniformInt(rng, -1074, 1023));
        if (kind <= 14) return sign * std::ldexp(Uniform(rng, 1, 2), UniformInt(rng, -260, 260));
        if (kind <= 19) return std::round(Uniform(rng, -20, 20));
        return Uniform(rng, -100, 100);
    };
    double xs[kBatchRoom] = {}, ys[kBatchRoom] = {};
    for (int shape = 0; shape < 8000; ++shape) {
        RayHalfSpace hs;
        hs.isPlane = false;
        double* fields[] = {&hs.c,   &hs.x0,  &hs.y0, &hs.z0,  &hs.hx, &hs.hy, &hs.h0,
                            &hs.axx, &hs.axy, &hs.ax, &hs.byy, &hs.by, &hs.k0};
        // Mostly a sane quadric with one to three odd coefficients, sometimes all odd.
        const bool allOdd = Chance(rng, 0.3);
        for (double* f : fields) *f = allOdd ? value() : Uniform(rng, -3, 3);
        if (!allOdd)
            for (int m = UniformInt(rng, 1, 3); m > 0; --m)
                *fields[UniformInt(rng, 0, 12)] = value();
        if (Chance(rng, 0.2)) {  // a common scale, as a quadric scaled as a whole
            const double f = std::ldexp(1.0, UniformInt(rng, -1100, 1000));
            for (double* v : fields) *v *= f;
        }
        double ox = std::floor(Uniform(rng, -10, 10)), oy = std::floor(Uniform(rng, -10, 10));
        if (Chance(rng, 0.2)) ox = std::ldexp(Uniform(rng, -1, 1), UniformInt(rng, 0, 1000));
        if (Chance(rng, 0.2)) oy = std::ldexp(Uniform(rng, -1, 1), UniformInt(rng, 0, 1000));
        const int n = GridPixels(ox, oy, xs, ys);
        if (Chance(rng, 0.1))
            for (int p = 0; p < n; ++p) xs[p] = value(), ys[p] = value();
        const bool complemented = Chance(rng, 0.5);
        const Batch start = RandomBatch(rng, hs, complemented, n, xs, ys);
        ASSERT_TRUE(SameAsReference(hs, complemented, 123, n, xs, ys, start, &seen))
            << "case " << shape;
    }
    EXPECT_GT(seen.dead, 100000);
    EXPECT_GT(seen.scalar, 40000);
    EXPECT_GT(seen.bothEnds, 12000);
    EXPECT_GT(seen.otherPiece, 50000);
}

TEST(RayLiteralBatch, ExactTangentsApexesAndSignedZeros) {
    double xs[kBatchRoom] = {}, ys[kBatchRoom] = {};
    Rng rng(8);
    // Sphere of radius 5 about (10, 20, 300): integer pixels at distance 5 are exactly tangent
    // (disc == 0: a double root), at 3 and 4 the roots are exact integers; about the origin and
    // re-centred; a cone's apex ray (a double root with c < 0); z0 = −0 with a root at −0.
    const Quadric sphere = Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, -25})
                               .Transformed(Transform::Translate({10, 20, 300}));
    const Quadric cone = Quadric::FromCoefficients({1, 1, -1, 0, 0, 0, 0, 0, 0, 0})
                             .Transformed(Transform::Translate({10, 20, 300}));
    FlatHalfSpace hs;
    hs.isPlane = false;
    std::vector<RayHalfSpace> shapes;
    for (const Quadric& q : {sphere, cone}) {
        hs.quadric = q;
        shapes.push_back(RayHalfSpace::From(hs));
        shapes.push_back(RayHalfSpace::From(hs, {10, 20, 300}));
        Quadric neg = q;
        for (double& v : neg.k) v = -v;
        hs.quadric = neg;
        shapes.push_back(RayHalfSpace::From(hs));
        shapes.push_back(RayHalfSpace::From(hs, {10, 20, 300}));
    }
    // Q = t² + 2 h t + k with z0 = −0 and k = 0 at x = 0: roots −0 and −2 h.
    RayHalfSpace zeros;
    zeros.isPlane = false;
    zeros.c = 1;
    zeros.z0 = -0.0;
    zeros.h0 = 1;
    zeros.ax = 1;
    shapes.push_back(zeros);
    zeros.h0 = -1;
    shapes.push_back(zeros);
    zeros.c = -1;
    shapes.push_back(zeros);
    for (const RayHalfSpace& r : shapes) {
        const double offsets[][2] = {{0, 5},  {5, 0},  {3, 4}, {-4, 3}, {0, 0}, {0, -5},
                                     {-5, 0}, {4, -3}, {3, 3}, {6, 0},  {1, 1}, {-3, -4}};
        int n = 0;
        for (const auto& o : offsets) {
            for (double s : {1.0, -1.0}) {
                xs[n] = 10 + o[0] * s;
                ys[n] = 20 + o[1];
                ++n;
                xs[n] = o[0] * s;  // about the origin, for `zeros`
                ys[n] = o[1];
                ++n;
            }
        }
        for (int rep = 0; rep < 20; ++rep) {
            for (bool complemented : {false, true}) {
                const Batch start = RandomBatch(rng, r, complemented, n, xs, ys);
                ASSERT_TRUE(SameAsReference(r, complemented, 4, n, xs, ys, start));
            }
        }
    }
}

TEST(RayLiteralBatch, MatchesTheScalarLoopAtTheLimitsOfTheFastPath) {
    // With hx = 1 and by = 1 (all else 0) the ray through (x, y) has h = x and k = y exactly, so
    // each pixel is a chosen (h, k) pair. Pairs on and about the edges of the vectorised case:
    // max(|c|, |h|, |k|) about 2^±200, where SolveQuadratic starts rescaling (which matters when
    // another coefficient's products or quotients are subnormal), and |h²| + |c k| = 2 |h² − c k|
    // exactly, where it switches from the plain to the compensated discriminant.
    Rng rng(4242);
    RayHalfSpace hs;
    hs.isPlane = false;
    hs.hx = 1;
    hs.by = 1;
    double xs[kBatchRoom] = {}, ys[kBatchRoom] = {};
    auto odd = [&rng](int lo, int hi) {  // many significant bits, random exponent and sign
        return (Chance(rng, 0.5) ? 1 : -1) *
               std::ldexp(1 + Uniform(rng, 0, 1), UniformInt(rng, lo, hi));
    };
    auto nearLimit = [&rng]() {  // about 2^200 or 2^-200, within a few ulps or a factor < 2
        const double base = std::ldexp(1.0, Chance(rng, 0.5) ? 200 : -200);
        double v = Chance(rng, 0.5) ? base * Uniform(rng, 0.5, 2) : base;
        for (int u = UniformInt(rng, -2, 2); u != 0; u += u < 0 ? 1 : -1)
            v = std::nextafter(v, u < 0 ? 0.0 : kInf);
        return Chance(rng, 0.5) ? v : -v;
    };
    for (int rep = 0; rep < 3000; ++rep) {
        const bool limits = rep % 2 == 0;
        hs.c = limits && Chance(rng, 0.4) ? nearLimit() : odd(-1074, 220);
        hs.z0 = Chance(rng, 0.7) ? 0.0 : odd(-10, 10);
        int n = 0;
        for (; n < 64; ++n) {
            double h = 0, k = 0;
            if (limits) {
                // One coefficient near a limit, the others anywhere down to subnormal.
                const int big = UniformInt(rng, 0, 2);
                h = big == 0 ? nearLimit() : odd(-1074, 210);
                k = big == 1 ? nearLimit() : odd(-1074, 210);
                if (Chance(rng, 0.2)) h = 0;
            } else {
                // c k = h²/3 or 3 h² exactly (plain discriminant on the boundary), or an ulp
                // off: c a power of two, h² rounded with a significand divisible by 3.
                h = odd(-150, 150);
                const double p1 = h * h;
                if (std::fmod(std::ldexp(p1, 52 - std::ilogb(p1)), 3.0) != 0)
                    h = std::nextafter(h, kInf);
                const double q1 = h * h;
                const bool third = Chance(rng, 0.5);
                double ck = third ? q1 / 3 : 3 * q1;
                if (third ? ck * 3 != q1 : ck / 3 != q1) ck = q1 / 3;  // keep it inexact then
                const int u = UniformInt(rng, -1, 1);
                if (u != 0) ck = std::nextafter(ck, u * kInf);
                hs.c = std::ldexp(Chance(rng, 0.5) ? 1.0 : -1.0, UniformInt(rng, -20, 20));
                k = ck / hs.c;
                if (Chance(rng, 0.5)) h = -h;
            }
            xs[n] = h;
            ys[n] = k;
        }
        for (bool complemented : {false, true}) {
            const Batch start = RandomBatch(rng, hs, complemented, n, xs, ys);
            ASSERT_TRUE(SameAsReference(hs, complemented, 8, n, xs, ys, start)) << rep;
        }
    }
}

// Cut mode: a body of several quadric literals taken in literal by literal, as the engine's body
// batches do, must state per pixel its first interval exactly below its cut, against the body's
// whole interval list (the intersection of the literals' sets, in order, ids included).
TEST(RayLiteralBatch, CutModeKeepsTheFirstIntervalExactBelowTheCut) {
    Rng rng(4242);
    long cuts = 0, exact = 0, scalar = 0, emptyBelow = 0;
    double xs[kBatchRoom] = {}, ys[kBatchRoom] = {};
    for (int body = 0; body < 3000; ++body) {
        const int literals = UniformInt(rng, 2, 5);
        std::vector<RayHalfSpace> hs;
        std::vector<bool> complemented;
        Vec3 centre;
        double radius = 0;
        for (int k = 0; k < literals; ++k) {
            Vec3 c;
            double r = 0;
            Quadric q = RandomShape(rng, c, r);
            if (k == 0) {
                centre = c;
                radius = r;
            }
            hs.push_back(RecentredShape(rng, q));
            complemented.push_back(k > 0 && Chance(rng, 0.5));
        }
        const int n = GridPixels(std::floor(centre.x + Uniform(rng, -1.5, 1.5) * radius),
                                 std::floor(centre.y + Uniform(rng, -1.5, 1.5) * radius), xs, ys);
        double lo[kBatchRoom], hi[kBatchRoom], cut[kBatchRoom];
        std::int64_t loId[kBatchRoom], hiId[kBatchRoom];
        std::uint8_t flag[kBatchRoom];
        for (int p = 0; p < n; ++p) {
            lo[p] = -kInf;
            hi[p] = kInf;
            cut[p] = kInf;
            loId[p] = hiId[p] = kNo;
            flag[p] = kBatchLive;
        }
        LiteralCounters counters;
        for (int k = 0; k < literals; ++k)
            QuadricBatch(hs[k], complemented[k], 100 + k, n, xs, ys, lo, loId, hi, hiId, flag,
                         counters, cut);
        for (int p = 0; p < n; ++p) {
            IntervalList list = IntervalList::All(), literal, next;
            for (int k = 0; k < literals; ++k) {
                LiteralSetOnRay(hs[k], complemented[k], xs[p], ys[p], 100 + k, literal, counters);
                Intersection(list, literal, next);
                std::swap(list, next);
            }
            const std::string where =
                "body " + std::to_string(body) + " pixel " + std::to_string(p);
            if (flag[p] == kBatchScalar) {
                ++scalar;
                continue;
            }
            if (flag[p] == kBatchDead) {
                ASSERT_TRUE(list.empty()) << where;
                continue;
            }
            const double c = cut[p];
            if (c == kInf) {
                ++exact;
                if (lo[p] < hi[p]) {
                    ASSERT_EQ(list.size(), 1u) << where;
                    ASSERT_EQ(Interval({lo[p], hi[p], static_cast<std::int32_t>(loId[p]),
                                        static_cast<std::int32_t>(hiId[p])}),
                              list[0])
                        << where;
                } else {
                    ASSERT_TRUE(list.empty()) << where;
                }
                continue;
            }
            ++cuts;
            // (A cut promises nothing beyond it: later literals may have emptied the rest.)
            if (!(lo[p] < hi[p]) || !(lo[p] < c)) {
                ++emptyBelow;
                ASSERT_TRUE(list.empty() || list[0].lo >= c) << where;
                continue;
            }
            ASSERT_GE(list.size(), 1u) << where;
            ASSERT_EQ(list[0].lo, lo[p]) << where;
            ASSERT_EQ(list[0].loId, loId[p]) << where;
            if (hi[p] < c) {
                ASSERT_EQ(list[0].hi, hi[p]) << where;
                ASSERT_EQ(list[0].hiId, hiId[p]) << where;
                ASSERT_TRUE(list.size() == 1 || list[1].lo >= c) << where;
            } else {
                ASSERT_GE(list[0].hi, c) << where;
            }
        }
    }
    // Every kind of outcome, often.
    EXPECT_GT(cuts, 20000);
    EXPECT_GT(emptyBelow, 5000);
    EXPECT_GT(exact, 30000);
    std::printf("[ cut mode ] %ld pixels with a cut (%ld empty below it), %ld exact, %ld scalar\n",
                cuts, emptyBelow, exact, scalar);
}

TEST(RayLiteralBatch, LeavesPixelsThatAreNotLiveAlone) {
    // Nothing but dead and scalar pixels: no byte changes and nothing is counted; a plane (not
    // what QuadricBatch is for) gets the reference result too.
    Rng rng(3);
    double xs[kBatchRoom] = {}, ys[kBatchRoom] = {};
    const int n = GridPixels(-4, -4, xs, ys);
    FlatHalfSpace sphere;
    sphere.isPlane = false;
    sphere.quadric = Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, -9});
    const RayHalfSpace hs = RayHalfSpace::From(sphere, {0, 0, 0});
    Batch start = RandomBatch(rng, hs, false, n, xs, ys);
    for (int p = 0; p < kBatchRoom; ++p) start.flag[p] = p % 2 ? kBatchDead : kBatchScalar;
    Batch got = start;
    LiteralCounters counters;
    QuadricBatch(hs, false, 1, n, xs, ys, got.lo, got.loId, got.hi, got.hiId, got.flag, counters);
    EXPECT_EQ(std::memcmp(&got, &start, sizeof got), 0);
    EXPECT_EQ(counters.quadrics, 0u);
    const RayHalfSpace plane = RayHalfSpace::From(PlaneHs(0.25, -1, 2, 3));
    for (bool complemented : {false, true}) {
        start = RandomBatch(rng, plane, complemented, n, xs, ys);
        EXPECT_TRUE(SameAsReference(plane, complemented, 2, n, xs, ys, start));
    }
}

}  // namespace
}  // namespace quadrix::eval
