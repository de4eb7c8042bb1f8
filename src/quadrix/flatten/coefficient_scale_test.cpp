// RescaleExponent and LargestMagnitude (coefficient_scale.h) against their definitions: the
// exponent from ilogb, and nested std::fmax of the magnitudes, for every kind of double.
#include "quadrix/flatten/coefficient_scale.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace quadrix {
namespace {

int ReferenceExponent(double big) {
    if (!(big > 0) || !std::isfinite(big)) return 0;
    const int e = std::ilogb(big);
    return e > kRescaleExponent || e < -kRescaleExponent ? -e : 0;
}

std::vector<double> AwkwardDoubles() {
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> v{0.0,
                          -0.0,
                          inf,
                          -inf,
                          std::nan(""),
                          1.0,
                          -1.0,
                          std::numeric_limits<double>::denorm_min(),
                          std::numeric_limits<double>::min(),
                          std::numeric_limits<double>::max()};
    for (double edge : {0x1p-64, 0x1p65, 0x1p-65, 0x1p64}) {
        v.push_back(edge);
        v.push_back(std::nextafter(edge, 0.0));
        v.push_back(std::nextafter(edge, inf));
    }
    std::mt19937_64 rng(20261205);
    for (int i = 0; i < 200000; ++i) {
        std::uint64_t bits = rng();
        double d;
        std::memcpy(&d, &bits, sizeof d);
        // Quiet NaNs only: glibc's fmax answers NaN for a signalling NaN (IEEE 754-2008's
        // maxNum), which no arithmetic or reader makes.
        if (std::isnan(d)) {
            bits |= std::uint64_t{1} << 51;
            std::memcpy(&d, &bits, sizeof d);
        }
        v.push_back(d);  // every exponent, subnormals, NaNs and infinities included
    }
    return v;
}

TEST(CoefficientScale, RescaleExponentIsIlogbsAnswer) {
    for (double d : AwkwardDoubles()) {
        EXPECT_EQ(RescaleExponent(d), ReferenceExponent(d)) << d;
        EXPECT_EQ(RescaleExponent(std::fabs(d)), ReferenceExponent(std::fabs(d))) << d;
    }
}

TEST(CoefficientScale, LargestMagnitudeIsNestedFmax) {
    const std::vector<double> v = AwkwardDoubles();
    std::mt19937 pick(7);
    std::uniform_int_distribution<std::size_t> any(0, v.size() - 1);
    std::uniform_int_distribution<std::size_t> special(0, 21);  // the hand-picked ones
    for (int i = 0; i < 100000; ++i) {
        double x[4];
        for (double& e : x) e = i % 3 == 0 ? v[special(pick)] : v[any(pick)];
        const double ref = std::fmax(std::fmax(std::fabs(x[0]), std::fabs(x[1])),
                                     std::fmax(std::fabs(x[2]), std::fabs(x[3])));
        const double got = LargestMagnitude(x[0], x[1], x[2], x[3]);
        // All four NaN: fmax gives NaN, LargestMagnitude 0; the exponent is 0 for both.
        if (std::isnan(ref)) {
            EXPECT_EQ(got, 0.0);
        } else {
            EXPECT_EQ(got, ref) << x[0] << " " << x[1] << " " << x[2] << " " << x[3];
        }
        EXPECT_EQ(RescaleExponent(got), ReferenceExponent(ref));
    }
}

}  // namespace
}  // namespace quadrix
