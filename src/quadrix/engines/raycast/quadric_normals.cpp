#include "quadrix/engines/raycast/quadric_normals.h"

#include <cmath>
#include <limits>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#include "quadrix/frame/packed_normal.h"
#include "quadrix/math/vec.h"
#include "quadrix/util/cpu_features.h"

namespace quadrix::raycast {
namespace {

constexpr int kLanes = QuadricNormals::kCapacity;
// Normalize's safe range of the squared length (math/vec.h).
constexpr double kSafeLo = vec_detail::kSafeLo, kSafeHi = vec_detail::kSafeHi;
constexpr double kMaxFinite = std::numeric_limits<double>::max();

// Pack's loops for n lanes. The steps and their order are FlatScene::WorldNormal's, then
// Normalize's safe branch, then PackedNormal::Encode's (see the header).
struct Lanes {
    int n;
    const double (*coef)[kLanes];
    const double *xs, *ys, *zs;
    std::uint32_t* code;
    std::uint8_t* scalar;
};
// Scratch between the steps.
struct Steps {
    alignas(64) double nx[kLanes], ny[kLanes], nz[kLanes], d[kLanes], r[kLanes];
};

// 1. The homogeneous gradient Q p (Quadric::HomogeneousGradient), turned to face the viewer
// (negated when its z is positive), pulled back by Mᵀ, and its squared length (Dot).
[[gnu::always_inline]] inline void Gradients(const double (&m)[4][4], const Lanes& l, Steps& s) {
    const double(*__restrict coef)[kLanes] = l.coef;
    const double* __restrict xs = l.xs;
    const double* __restrict ys = l.ys;
    const double* __restrict zs = l.zs;
    for (int i = 0; i < l.n; ++i) {
        const double px = xs[i], py = ys[i], pz = zs[i];
        const double qa = coef[0][i], qb = coef[1][i], qc = coef[2][i], qd = coef[3][i];
        const double qe = coef[4][i], qf = coef[5][i], qg = coef[6][i], qh = coef[7][i];
        const double qj = coef[8][i], qk = coef[9][i];
        double gx = qa * px + qd * py + qf * pz + qg;
        double gy = qd * px + qb * py + qe * pz + qh;
        double gz = qf * px + qe * py + qc * pz + qj;
        double gw = qg * px + qh * py + qj * pz + qk;
        const bool flip = gz > 0;
        gx = flip ? -gx : gx;
        gy = flip ? -gy : gy;
        gw = flip ? -gw : gw;
        gz = flip ? -gz : gz;
        const double ax = m[0][0] * gx + m[1][0] * gy + m[2][0] * gz + m[3][0] * gw;
        const double ay = m[0][1] * gx + m[1][1] * gy + m[2][1] * gz + m[3][1] * gw;
        const double az = m[0][2] * gx + m[1][2] * gy + m[2][2] * gz + m[3][2] * gw;
        s.nx[i] = ax;
        s.ny[i] = ay;
        s.nz[i] = az;
        s.d[i] = ax * ax + ay * ay + az * az;
    }
}

// 3. The unit vector (Normalize: each component divided by the length) and its octahedral code
// (PackedNormal::Encode; its zero-or-not-finite case, impossible for a unit vector of finite
// components, is left to the scalar path with the lengths outside the safe range).
[[gnu::always_inline]] inline void Codes(const Lanes& l, const Steps& s) {
    std::uint32_t* __restrict code = l.code;
    std::uint8_t* __restrict scalar = l.scalar;
    for (int k = 0; k < l.n; ++k) {
        const double len = s.r[k], dd = s.d[k];
        const double ux = s.nx[k] / len, uy = s.ny[k] / len, uz = s.nz[k] / len;
        const double l1 = std::fabs(ux) + std::fabs(uy) + std::fabs(uz);
        const bool ok = (dd > kSafeLo) & (dd < kSafeHi) & (l1 > 0) & (l1 <= kMaxFinite);
        const double u = ux / l1, v = uy / l1;
        const double fu = (1 - std::fabs(v)) * (u < 0 ? -1.0 : 1.0);
        const double fv = (1 - std::fabs(u)) * (v < 0 ? -1.0 : 1.0);
        const bool fold = uz < 0;
        // A lane left to the scalar path packs 0 instead of what may be a NaN or an infinity
        // here (their conversion to an integer is undefined behaviour).
        const double eu = ok ? (fold ? fu : u) : 0.0, ev = ok ? (fold ? fv : v) : 0.0;
        code[k] = PackedNormal::Snorm(eu) << 16 | PackedNormal::Snorm(ev);
        scalar[k] = ok ? 0 : 1;
    }
}

// 2, between them: the lengths (garbage where d is outside the safe range: step 3 flags those),
// by the processor's square-root instructions.
#if defined(__x86_64__) || defined(__i386__)
QUADRIX_AVX2 void PackAvx2(const double (&m)[4][4], const Lanes& l) {
    Steps s;
    Gradients(m, l, s);
    int i = 0;
    for (; i + 4 <= l.n; i += 4) _mm256_store_pd(s.r + i, _mm256_sqrt_pd(_mm256_load_pd(s.d + i)));
    for (; i < l.n; ++i) s.r[i] = std::sqrt(s.d[i]);
    Codes(l, s);
}
#endif
void PackBaseline(const double (&m)[4][4], const Lanes& l) {
    Steps s;
    Gradients(m, l, s);
    int i = 0;
#if defined(__SSE2__)
    for (; i + 2 <= l.n; i += 2) _mm_store_pd(s.r + i, _mm_sqrt_pd(_mm_load_pd(s.d + i)));
#endif
    for (; i < l.n; ++i) s.r[i] = std::sqrt(s.d[i]);
    Codes(l, s);
}

}  // namespace

void QuadricNormals::Pack(const Mat4& m) {
    double mm[4][4];
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            mm[r][c] = m.m[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
    const Lanes lanes{n_, coef_, x_, y_, z_, code_, scalar_};
#if defined(__x86_64__) || defined(__i386__)
    if (gCpuHasAvx2) {
        PackAvx2(mm, lanes);
        return;
    }
#endif
    PackBaseline(mm, lanes);
}

}  // namespace quadrix::raycast
