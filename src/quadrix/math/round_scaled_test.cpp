#include "quadrix/math/round_scaled.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace quadrix {
namespace {

// RoundScaled<36> is std::llround(std::ldexp(v, 36)) on the Flattener's range, [-1, 1]: random
// doubles of every magnitude down to the subnormals, exact halves and the neighbours of halves on
// the 2^-36 grid, and the ends of the range.
TEST(RoundScaled, IsLlroundOfLdexp) {
    std::vector<double> values = {0.0,        -0.0,      1.0,         -1.0,         0x1p-37,
                                  -0x1p-37,   0x1p-36,   3 * 0x1p-37, -3 * 0x1p-37, 0x1p-1074,
                                  -0x1p-1074, 0x1p-1022, 0.5,         -0.5};
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-1074, 0);
    std::uniform_int_distribution<std::int64_t> grid(-(std::int64_t{1} << 37),
                                                     std::int64_t{1} << 37);
    for (int i = 0; i < 200000; ++i) {
        values.push_back(unit(rng));
        values.push_back(std::ldexp(unit(rng), exponent(rng)));
        // A multiple of 2^-37 (halves of the 2^-36 grid included) and its two neighbours.
        const double h = static_cast<double>(grid(rng)) * 0x1p-37;
        if (std::fabs(h) <= 1) {
            values.push_back(h);
            values.push_back(std::nextafter(h, 2.0));
            values.push_back(std::nextafter(h, -2.0));
        }
    }
    int halves = 0;
    for (double v : values) {
        if (std::fabs(v) > 1) continue;
        ASSERT_EQ(RoundScaled<36>(v), std::llround(std::ldexp(v, 36))) << v;
        const double s = std::ldexp(v, 36);
        halves += s != std::trunc(s) && s - std::trunc(s) == std::copysign(0.5, s);
    }
    EXPECT_GT(halves, 1000);
}

}  // namespace
}  // namespace quadrix
