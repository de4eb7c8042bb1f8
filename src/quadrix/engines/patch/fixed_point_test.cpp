// The arithmetic units of the processor (EP1, EP2, SRE, multiplier) against plain integer
// arithmetic (integer_reference.h).
#include "quadrix/engines/patch/fixed_point.h"

#include <gtest/gtest.h>

#include <random>

#include "quadrix/engines/patch/integer_reference.h"

namespace quadrix::patch {
namespace {

TEST(PatchFixedPoint, WrapIsTwosComplement) {
    EXPECT_EQ(Wrap(127, 8), 127);
    EXPECT_EQ(Wrap(128, 8), -128);
    EXPECT_EQ(Wrap(-129, 8), 127);
    EXPECT_EQ(Wrap(255, 8), -1);
    EXPECT_EQ(AddWrapped(MaxWord(24), 1, 24), MinWord(24));
    EXPECT_EQ(MaxWord(24), 8388607);
    EXPECT_EQ(DatapathWidths{}.Validate(), "");
    EXPECT_NE((DatapathWidths{10, 8}).Validate(), "");
    EXPECT_NE((DatapathWidths{24, 25}).Validate(), "");
    EXPECT_NE((DatapathWidths{31, 16}).Validate(), "");
}

TEST(PatchFixedPoint, Ep1StepsAreTheLinearForm) {
    std::mt19937_64 rng(1);
    for (int bits : {12, 24, 30}) {
        std::uniform_int_distribution<std::int64_t> word(MinWord(bits), MaxWord(bits));
        const Ep1Program p{word(rng), word(rng), word(rng)};  // wraps freely
        Ep1 ep;
        ep.Load(p, bits);
        for (int j = 0; j < 9; ++j) {
            for (int i = 0; i < 13; ++i) {
                // Arithmetic modulo 2^64 is exact modulo 2^bits.
                const std::uint64_t exact =
                    static_cast<std::uint64_t>(p.start) +
                    static_cast<std::uint64_t>(i) * static_cast<std::uint64_t>(p.stepX) +
                    static_cast<std::uint64_t>(j) * static_cast<std::uint64_t>(p.stepY);
                ASSERT_EQ(ep.Value(), Wrap(static_cast<std::int64_t>(exact), bits))
                    << bits << " " << i << " " << j;
                ep.StepPixel();
            }
            ep.StepLine();
        }
    }
}

TEST(PatchFixedPoint, PipelinedHalvesAddLikeOneAdder) {
    std::mt19937_64 rng(2);
    for (int bits : {24, 48, 60}) {
        std::uniform_int_distribution<std::int64_t> word(MinWord(bits), MaxWord(bits));
        for (int k = 0; k < 2000; ++k) {
            const std::int64_t a = word(rng), b = word(rng);
            ASSERT_EQ(Ep2::PipelinedAdd(a, b, bits), AddWrapped(a, b, bits));
        }
        // Carry across the halves and out of the top.
        const std::int64_t lowOnes = (std::int64_t{1} << (bits / 2)) - 1;
        EXPECT_EQ(Ep2::PipelinedAdd(lowOnes, 1, bits), lowOnes + 1);
        EXPECT_EQ(Ep2::PipelinedAdd(-1, 1, bits), 0);
    }
}

TEST(PatchFixedPoint, Ep2StepsAreTheQuadraticForm) {
    // F(i, j) = q0 + j r0 + 2B j(j+1)/2 + i (s0 + j c) + 2A i(i+1)/2, checked against a direct
    // evaluation of a quadratic with integer coefficients (the words are its differences).
    std::mt19937_64 rng(3);
    std::uniform_int_distribution<std::int64_t> coef(-100000, 100000);
    for (int trial = 0; trial < 20; ++trial) {
        const std::int64_t a = coef(rng), b = coef(rng), c = coef(rng), d = coef(rng),
                           e = coef(rng), f = coef(rng) * 1000;
        auto F = [&](std::int64_t i, std::int64_t j) {
            return a * i * i + b * j * j + c * i * j + d * i + e * j + f;
        };
        const Ep2Program p{F(0, 0), F(0, 0) - F(0, -1), F(0, 0) - F(-1, 0), 2 * a, 2 * b, c};
        Ep2 ep;
        ep.Load(p, 48);
        for (int j = 0; j < 17; ++j) {
            for (int i = 0; i < 23; ++i) {
                ASSERT_EQ(ep.Value(), F(i, j)) << i << " " << j;
                ep.StepPixel();
            }
            ep.StepLine();
        }
    }
}

TEST(PatchFixedPoint, SquareRootArrayIsExactForEverySmallRadicand) {
    for (int n : {1, 2, 3, 6}) {
        for (std::uint64_t v = 0; v < (std::uint64_t{1} << (2 * n)); ++v) {
            const SquareRootResult r = CellularSquareRoot(v, n);
            ASSERT_EQ(r.root, IntegerSqrt(v)) << n << " " << v;
            ASSERT_EQ(r.remainder, v - r.root * r.root) << n << " " << v;
        }
    }
}

TEST(PatchFixedPoint, SquareRootArrayMatchesIntegerSqrtOnWideWords) {
    std::mt19937_64 rng(4);
    for (int n : {12, 24, 30}) {
        const std::uint64_t mask = (std::uint64_t{1} << (2 * n)) - 1;
        for (int k = 0; k < 3000; ++k) {
            // Random words, perfect squares and their neighbours (the borrow's edge cases).
            std::uint64_t v = rng() & mask;
            const std::uint64_t r = rng() & ((std::uint64_t{1} << n) - 1);
            if (k % 3 == 1) v = r * r;
            if (k % 3 == 2) v = (r + 1) * (r + 1) - 1;  // r at most 2^n - 1: fits 2n bits
            ASSERT_EQ(CellularSquareRoot(v, n).root, IntegerSqrt(v)) << n << " " << v;
        }
        EXPECT_EQ(CellularSquareRoot(mask, n).root, (std::uint64_t{1} << n) - 1);
    }
}

TEST(PatchFixedPoint, MultiplierKeepsTheFloorOfTheHighHalfForEveryEightBitPair) {
    for (int a = -128; a < 128; ++a)
        for (int b = -128; b < 128; ++b) {
            const int product = a * b;
            const int expected = product >= 0 ? product / 256 : -((-product + 255) / 256);
            ASSERT_EQ(TruncatingMultiply(a, b, 8), expected) << a << " * " << b;
        }
}

TEST(PatchFixedPoint, MultiplierMatchesTheShiftedProductAtSixteenBits) {
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<std::int64_t> word(MinWord(16), MaxWord(16));
    for (int k = 0; k < 20000; ++k) {
        const std::int64_t a = word(rng), b = word(rng);
        ASSERT_EQ(TruncatingMultiply(a, b, 16), (a * b) >> 16) << a << " * " << b;
    }
    EXPECT_EQ(TruncatingMultiply(MinWord(16), MinWord(16), 16), 16384);
    EXPECT_EQ(TruncatingMultiply(-1, 1, 16), -1);  // floor, not truncation toward zero
}

TEST(PatchFixedPoint, IntegerSqrtIsExactNearSquares) {
    for (std::uint64_t r : {0ull, 1ull, 2ull, 3037000499ull, 4294967295ull}) {
        const std::uint64_t sq = r * r;
        EXPECT_EQ(IntegerSqrt(sq), r);
        if (sq > 0) {
            EXPECT_EQ(IntegerSqrt(sq - 1), r - 1);
        }
    }
}

}  // namespace
}  // namespace quadrix::patch
