// Scale-safe Length and Normalize (vec.h, issue 23): the same unit vector at every magnitude from
// the smallest subnormal to the largest double, and bit-identical results to the plain formula
// where |v|² does not over- or underflow.
#include "quadrix/math/vec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace quadrix {
namespace {

TEST(Vec3, NormalizeIsTheSameUnitVectorAtEveryScale) {
    const Vec3 dir{1, -2, 2};  // length 3
    const Vec3 unit{1.0 / 3, -2.0 / 3, 2.0 / 3};
    for (double scale : {1e-320, 1e-300, 1e-200, 1e-160, 1e-100, 1.0, 1e100, 1e160, 1e200, 1e300,
                         std::numeric_limits<double>::max() / 2}) {
        const Vec3 v = dir * scale;
        const Vec3 n = Normalize(v);
        // A few ulps: the subnormal 1e-320 carries only ~14 significant bits, so its components
        // are not exactly 1 : -2 : 2; compare against what they are.
        const double tol = scale < 1e-307 ? 1e-3 : 4e-16;
        EXPECT_NEAR(n.x, unit.x, tol) << scale;
        EXPECT_NEAR(n.y, unit.y, tol) << scale;
        EXPECT_NEAR(n.z, unit.z, tol) << scale;
        EXPECT_NEAR(Length(n), 1.0, 4e-16) << scale;
        // |v| = 3·scale, relative to the components as stored (when it is a double at all).
        if (3 * scale > std::numeric_limits<double>::max()) continue;
        const double exact = scale < 1e-307 ? Length(v) : 3 * scale;
        EXPECT_NEAR(Length(v) / exact, 1.0, 4e-16) << scale;
        EXPECT_TRUE(std::isfinite(Length(v))) << scale;
    }
}

TEST(Vec3, LargestComponentAloneIsExact) {
    const double big = std::numeric_limits<double>::max();
    EXPECT_EQ(Length(Vec3{big, 0, 0}), big);
    EXPECT_EQ(Normalize(Vec3{0, -big, 0}), (Vec3{0, -1, 0}));
    const double tiny = std::numeric_limits<double>::denorm_min();
    EXPECT_EQ(Length(Vec3{0, 0, tiny}), tiny);
    EXPECT_EQ(Normalize(Vec3{0, 0, tiny}), (Vec3{0, 0, 1}));
}

TEST(Vec3, ZeroInfinityAndNanBehaveAsBefore) {
    EXPECT_EQ(Length(Vec3{}), 0.0);
    EXPECT_EQ(Normalize(Vec3{}), (Vec3{}));
    EXPECT_TRUE(std::isinf(Length(Vec3{HUGE_VAL, 0, 0})));
    EXPECT_TRUE(std::isnan(Length(Vec3{NAN, 1, 0})));
}

TEST(Vec3, OrdinaryVectorsAreBitIdenticalToThePlainFormula) {
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> mantissa(-1, 1);
    std::uniform_int_distribution<int> exponent(-100, 100);
    for (int i = 0; i < 10000; ++i) {
        const double s = std::ldexp(1.0, exponent(rng));
        const Vec3 v{mantissa(rng) * s, mantissa(rng) * s, mantissa(rng) * s};
        const double plain = std::sqrt(Dot(v, v));
        EXPECT_EQ(Length(v), plain);
        if (plain > 0) {
            EXPECT_EQ(Normalize(v), v / plain);
        }
    }
}

}  // namespace
}  // namespace quadrix
