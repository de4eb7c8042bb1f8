// Helpers shared by the math property tests: random affine transforms and running error bounds.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "quadrix/math/mat4.h"
#include "quadrix/math/vec.h"

namespace quadrix::testing_util {

constexpr double kUnitRoundoff = 0x1p-53;

// A random composition of `count` elementary transforms: translations by up to ±100, rotations by
// any angle about a random axis, scales by 10^±1 (either sign) and shears by up to ±2. The factors
// are returned too, so that tests can bound rounding with the product of their absolute values.
struct RandomTransform {
    Transform t;
    std::vector<Transform> factors;  // t = factors[0] * factors[1] * ...
};

inline RandomTransform MakeRandomTransform(std::mt19937_64& rng, int count = 6) {
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> kind(0, 3), axis(0, 2);
    RandomTransform r;
    for (int i = 0; i < count; ++i) {
        Transform f;
        switch (kind(rng)) {
            case 0:
                f = Transform::Translate({100 * u(rng), 100 * u(rng), 100 * u(rng)});
                break;
            case 1:
                f = Transform::Rotate(axis(rng), 360 * u(rng));
                break;
            case 2: {
                auto s = [&] { return std::pow(10.0, u(rng)) * (u(rng) < 0 ? -1 : 1); };
                f = Transform::Scale({s(), s(), s()});
                break;
            }
            default: {
                int to = axis(rng), from = (to + 1 + (u(rng) < 0)) % 3;
                f = Transform::Shear(to, from, 2 * u(rng));
                break;
            }
        }
        r.t = r.t * f;
        r.factors.push_back(f);
    }
    return r;
}

inline Mat4 Abs(const Mat4& m) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = std::fabs(m.m[i][j]);
    return r;
}

inline Vec4 Abs(const Vec4& v) {
    return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z), std::fabs(v.w)};
}

// |F0| |F1| ... |Fn-1|: the magnitude that bounds the rounding of the product F0 F1 ... (the
// standard running bound |fl(AB) − AB| <= γ |A||B|).
inline Mat4 AbsProduct(const std::vector<Transform>& factors, bool inverses) {
    Mat4 r = Mat4::Identity();
    if (!inverses) {
        for (const Transform& f : factors) r = r * Abs(f.Matrix());
    } else {
        for (auto it = factors.rbegin(); it != factors.rend(); ++it) r = r * Abs(it->Inverse());
    }
    return r;
}

}  // namespace quadrix::testing_util
