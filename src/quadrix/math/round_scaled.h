// std::llround(std::ldexp(v, e)) for moderate v and e, without the two library calls: the
// Flattener hashes every coefficient of every literal this way (TranslationReuse), and the calls
// were a sixth of that stage's instructions.
//
// For |v · 2^e| < 2^52: the product s by a power of two is exact (no overflow; a subnormal v only
// gains exponent), the conversion truncates it toward zero to t exactly, and the remainder s − t
// is exact (Sterbenz: t is 0 or lies within a factor 2 of s), so adding one away from zero when
// |s − t| >= ½ rounds half away from zero as llround does.
#pragma once

#include <cstdint>

namespace quadrix {

// Requires a finite v with |v · 2^e| < 2^52 (the caller's range; not checked in release builds).
template <int e>
inline std::int64_t RoundScaled(double v) {
    static_assert(e >= 0 && e < 52);
    constexpr double kScale = static_cast<double>(std::int64_t{1} << e);
    const double s = v * kScale;
    const auto t = static_cast<std::int64_t>(s);
    const double f = s - static_cast<double>(t);
    return t + (f >= 0.5) - (f <= -0.5);
}

}  // namespace quadrix
