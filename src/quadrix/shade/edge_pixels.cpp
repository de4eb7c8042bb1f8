#include "quadrix/shade/edge_pixels.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>

#include "quadrix/frame/packed_normal.h"
#include "quadrix/shade/row_shading.h"
#include "quadrix/util/cpu_features.h"
#include "quadrix/util/parallel.h"

namespace quadrix {

namespace {

// A pair's code (edge_pixels.h EdgePairCode): kPixel on both, kLineA or kLineB on the nearer.
constexpr std::uint8_t kPixel = 1, kLineA = 2, kLineB = 4;
static_assert(kEdgePixel == 1 && kEdgeLine == 2, "the codes below are these bits");

// a's bits and b's bits of a code.
inline std::uint8_t BitsOfA(std::uint8_t c) { return c & 3; }
inline std::uint8_t BitsOfB(std::uint8_t c) {
    return static_cast<std::uint8_t>((c & 1) | ((c >> 1) & 2));
}

// cos(kCreaseDegrees), computed once.
double CosLimit() {
    static const double c = std::cos(kCreaseDegrees * std::numbers::pi / 180);
    return c;
}

// Whether the pair of rows (y, y + 1) touches a shaded row (row_shading.h).
bool PairShaded(const std::vector<std::uint8_t>& rows, int y) {
    return RowShaded(rows, y) || RowShaded(rows, y + 1);
}

// The luminance of the shaded image's rows, computed a row at a time into a small per-thread
// cache (a whole image of doubles was 7.4 MB of fresh memory at 1280×720). Rows that are not read
// (row_shading.h) have luminance 0.
class RowLuminance {
  public:
    // Inactive (no jumps to find) without an image or with one of another size than the Frame.
    RowLuminance(const Frame& f, const Image* image, const std::vector<std::uint8_t>& rows)
        : f_(f), image_(image), rows_(rows) {
        if (image && (image->width != f.width || image->height != f.height)) image_ = nullptr;
        if (!image_) return;
        linear_ = image_->linear.size() == image_->pixels.size();
        // 8-bit samples: the products 0.2126 · (v / 255) and so on, once per byte value; their
        // sums, in the same order, are the luminances the samples give (the same doubles).
        for (int v = 0; v < 256; ++v) {
            const double unit = v / 255.0;
            weighted_[0][v] = 0.2126 * unit;
            weighted_[1][v] = 0.7152 * unit;
            weighted_[2][v] = 0.0722 * unit;
        }
    }
    bool Active() const { return image_ != nullptr; }

    // Row y's values, kept in one of four slots (row y in slot y mod 4): the four rows a pair of
    // rows (y, y + 1) looks at, y − 1 ... y + 2, never evict one another.
    struct Cache {
        std::array<int, 4> row = {-1, -1, -1, -1};
        std::array<std::vector<double>, 4> values;
    };
    const double* Row(int y, Cache& cache) const {
        const auto slot = static_cast<std::size_t>(y & 3);
        std::vector<double>& out = cache.values[slot];
        out.resize(static_cast<std::size_t>(f_.width));
        if (cache.row[slot] == y) return out.data();
        cache.row[slot] = y;
        if (!RowRead(rows_, y)) {
            std::fill(out.begin(), out.end(), 0.0);
            return out.data();
        }
        const auto ch = static_cast<std::size_t>(image_->channels);
        const std::size_t first = f_.Index(0, y) * ch;
        if (linear_) {
            const float* v = image_->linear.data() + first;
            for (std::size_t x = 0; x < out.size(); ++x, v += ch)
                out[x] = ch >= 3 ? 0.2126 * static_cast<double>(v[0]) +
                                       0.7152 * static_cast<double>(v[1]) +
                                       0.0722 * static_cast<double>(v[2])
                                 : static_cast<double>(v[0]);
        } else {
            const std::uint8_t* v = image_->pixels.data() + first;
            for (std::size_t x = 0; x < out.size(); ++x, v += ch)
                out[x] = ch >= 3 ? weighted_[0][v[0]] + weighted_[1][v[1]] + weighted_[2][v[2]]
                                 : v[0] / 255.0;
        }
        return out.data();
    }

  private:
    const Frame& f_;
    const Image* image_;
    const std::vector<std::uint8_t>& rows_;
    bool linear_ = false;
    double weighted_[3][256] = {};
};

// The Frame's arrays as the pair tests read them.
struct EdgeArrays {
    const std::int32_t* surface;
    const std::int32_t* body;
    const PackedNormal* normal;
    const float* depth;
    std::uint8_t* e;
};

// Whether two normals of a surface make an angle above kCreaseDegrees:
// PackedNormal::AngleExceeds(a, b, cos kCreaseDegrees), which decodes both (four divisions),
// answered without decoding for the codes of nearby directions (kNearNormalCodes), the commonest
// case: the pixels of a curved surface.
inline bool Crease(PackedNormal a, PackedNormal b) {
    if (a.bits == b.bits) return false;
    const auto hi = [](std::uint32_t v) { return static_cast<std::int32_t>(v) >> 16; };
    const auto lo = [](std::uint32_t v) { return static_cast<std::int32_t>(v << 16) >> 16; };
    const int delta = std::abs(hi(a.bits) - hi(b.bits)) + std::abs(lo(a.bits) - lo(b.bits));
    if (delta <= kNearNormalCodes && a.bits != PackedNormal::kZero && b.bits != PackedNormal::kZero)
        return false;
    return PackedNormal::AngleExceeds(a, b, CosLimit());
}

// The code of one pair (edge_pixels.h EdgePairCode), its crease test by Crease when kNearFirst,
// else by AngleExceeds alone (the definition: the same answers).
template <bool kNearFirst>
[[gnu::always_inline]] inline std::uint8_t PairCode(const EdgeArrays f, std::size_t a,
                                                    std::size_t b, std::size_t a2, std::size_t b2,
                                                    bool hasA2, bool hasB2, bool jumps, double la,
                                                    double lb, double la2, double lb2) {
    const std::int32_t sa = f.surface[a];
    bool separated = sa != f.surface[b] || f.body[a] != f.body[b];
    if (!separated) {
        if (sa == Frame::kNone) return 0;  // both background: no edge, no shading
        if (kNearFirst ? Crease(f.normal[a], f.normal[b])
                       : PackedNormal::AngleExceeds(f.normal[a], f.normal[b], CosLimit())) {
            separated = true;
        } else {
            const double za = f.depth[a], zb = f.depth[b];
            double slope = 0;
            if (hasA2 && f.surface[a2] == sa) slope = std::max(slope, std::fabs(za - f.depth[a2]));
            if (hasB2 && f.surface[b2] == sa) slope = std::max(slope, std::fabs(f.depth[b2] - zb));
            separated = std::fabs(zb - za) > 4 * slope + 1e-6 * (1 + std::fabs(za));
        }
    }
    if (separated) return f.depth[b] < f.depth[a] ? (kPixel | kLineB) : (kPixel | kLineA);
    // Not separated: one surface of one body (or both background, returned above).
    if (!jumps || sa < 0) return 0;
    const double d = std::fabs(lb - la);
    const double slope = std::max(std::fabs(la - la2), std::fabs(lb2 - lb));
    return d > 4 * slope + 1.0 / 255 ? kPixel : 0;
}

// One pair's bits ORed into f.e.
inline void PairTest(const EdgeArrays f, std::size_t a, std::size_t b, std::size_t a2,
                     std::size_t b2, bool hasA2, bool hasB2, bool jumps, double la, double lb,
                     double la2, double lb2) {
    const std::uint8_t c = PairCode<true>(f, a, b, a2, b2, hasA2, hasB2, jumps, la, lb, la2, lb2);
    if (c == 0) return;
    f.e[a] |= BitsOfA(c);
    f.e[b] |= BitsOfB(c);
}

// Whether the n pixels from i are all background (surface and body kNone): every pair among
// them is then two background pixels, which have no bits (PairCode). A loop the compiler
// vectorises; the pair loops below skip such runs kSkip pairs at a time (half of a typical
// picture is background).
constexpr std::size_t kSkip = 16;
[[gnu::always_inline]] inline bool Background(const EdgeArrays f, std::size_t i, std::size_t n) {
    std::int32_t any = 0;
    for (std::size_t k = 0; k < n; ++k)
        any |= (f.surface[i + k] ^ Frame::kNone) | (f.body[i + k] ^ Frame::kNone);
    return any == 0;
}

// kSkip consecutive pairs of one line (pair k: a + k, b + k, with a2 + k and b2 + k beyond them).
struct Block {
    std::size_t a, b, a2, b2;
};

// Pair i of a block is smooth when its pixels and the two beyond them are on one surface
// (covered), the pair's two are of one body, and its normals' codes are equal or within
// kNearNormalCodes of each other, neither kZero (no crease). Such a pair's test is its depth test
// (both slope terms count: the pixels beyond exist and are on the surface) and, with jumps, its
// luminance test. Rough: non-zero when pair i is not smooth. Integer operations only, so that
// the loops over a block that use it vectorise.
[[gnu::always_inline]] inline std::int32_t Rough(const EdgeArrays f, const Block k, std::size_t i) {
    const std::int32_t s = f.surface[k.a + i];
    std::int32_t bad = (s ^ f.surface[k.b + i]) | (s ^ f.surface[k.a2 + i]) |
                       (s ^ f.surface[k.b2 + i]) | (f.body[k.a + i] ^ f.body[k.b + i]) |
                       (s >> 31);  // s < 0: kNone
    const auto p = static_cast<std::int32_t>(f.normal[k.a + i].bits);
    const auto q = static_cast<std::int32_t>(f.normal[k.b + i].bits);
    const std::int32_t du = (p >> 16) - (q >> 16);
    const std::int32_t dv = ((p << 16) >> 16) - ((q << 16) >> 16);
    const std::int32_t delta = (du < 0 ? -du : du) + (dv < 0 ? -dv : dv);
    bad |= static_cast<std::int32_t>(delta > kNearNormalCodes) |
           static_cast<std::int32_t>(p == static_cast<std::int32_t>(PackedNormal::kZero)) |
           static_cast<std::int32_t>(q == static_cast<std::int32_t>(PackedNormal::kZero));
    return bad;
}
// A smooth pair's depth test (PairCode's, both slope terms present) and luminance test (its
// last), without a branch.
[[gnu::always_inline]] inline bool DepthJumps(double a, double b, double a2, double b2) {
    const double ta = std::fabs(a - a2), tb = std::fabs(b2 - b);
    double slope = 0.0 < ta ? ta : 0.0;  // std::max(0.0, ta)
    slope = slope < tb ? tb : slope;     // std::max(slope, tb)
    return std::fabs(b - a) > 4 * slope + 1e-6 * (1 + std::fabs(a));
}
[[gnu::always_inline]] inline bool LuminanceJumps(double la, double lb, double la2, double lb2) {
    const double d = std::fabs(lb - la);
    const double ea = std::fabs(la - la2), eb = std::fabs(lb2 - lb);
    const double slope = ea < eb ? eb : ea;  // std::max(ea, eb)
    return d > 4 * slope + 1.0 / 255;
}

// Whether every pair of the block is smooth.
[[gnu::always_inline]] inline bool Smooth(const EdgeArrays f, const Block k) {
    std::int32_t bad = 0;
    for (std::size_t i = 0; i < kSkip; ++i) bad |= Rough(f, k, i);
    return bad == 0;
}

// Whether any pair of a smooth block is separated by its depth test. Without a branch, so the
// compiler vectorises it; built for AVX2 and the baseline (util/cpu_features.h: the same IEEE
// operations in the same order either way).
[[gnu::always_inline]] inline bool AnyDepthJumpBody(const float* za, const float* zb,
                                                    const float* za2, const float* zb2) {
    std::int32_t any = 0;
    for (std::size_t i = 0; i < kSkip; ++i)
        any |= static_cast<std::int32_t>(DepthJumps(za[i], zb[i], za2[i], zb2[i]));
    return any != 0;
}
// Whether any pair of a smooth block has a luminance jump, the same way.
[[gnu::always_inline]] inline bool AnyLuminanceJumpBody(const double* la, const double* lb,
                                                        const double* la2, const double* lb2) {
    std::int32_t any = 0;
    for (std::size_t i = 0; i < kSkip; ++i)
        any |= static_cast<std::int32_t>(LuminanceJumps(la[i], lb[i], la2[i], lb2[i]));
    return any != 0;
}
QUADRIX_AVX2 bool AnyLuminanceJumpAvx2(const double* la, const double* lb, const double* la2,
                                       const double* lb2) {
    return AnyLuminanceJumpBody(la, lb, la2, lb2);
}
bool AnyLuminanceJumpBaseline(const double* la, const double* lb, const double* la2,
                              const double* lb2) {
    return AnyLuminanceJumpBody(la, lb, la2, lb2);
}
QUADRIX_AVX2 bool AnyDepthJumpAvx2(const float* za, const float* zb, const float* za2,
                                   const float* zb2) {
    return AnyDepthJumpBody(za, zb, za2, zb2);
}
bool AnyDepthJumpBaseline(const float* za, const float* zb, const float* za2, const float* zb2) {
    return AnyDepthJumpBody(za, zb, za2, zb2);
}

// Whether a block of pairs whose pixels beyond exist has no bits: all smooth, with no depth jump
// and (with jumps) no luminance jump. false: the caller looks at the pairs (BlockPairs).
[[gnu::always_inline]] inline bool SmoothBlock(const EdgeArrays f, const Block k, const bool jumps,
                                               const double* la, const double* lb,
                                               const double* la2, const double* lb2) {
    // Where the block's ends are not on one surface (small features), say so at once.
    const std::int32_t s = f.surface[k.a];
    if (s != f.surface[k.a + kSkip - 1] || s != f.surface[k.b] || s != f.surface[k.b + kSkip - 1] ||
        !Smooth(f, k))
        return false;
    const float* z = f.depth;
    if (gCpuHasAvx2 ? AnyDepthJumpAvx2(z + k.a, z + k.b, z + k.a2, z + k.b2)
                    : AnyDepthJumpBaseline(z + k.a, z + k.b, z + k.a2, z + k.b2))
        return false;
    // A luminance jump somewhere: BlockPairs tests the pairs that jump.
    return !jumps || !(gCpuHasAvx2 ? AnyLuminanceJumpAvx2(la, lb, la2, lb2)
                                   : AnyLuminanceJumpBaseline(la, lb, la2, lb2));
}

// Per pair of a block whose pixels beyond exist: 1 where PairCode may be non-zero, 0 where it is
// 0 for sure. A smooth pair's code is its depth test and, with jumps and no depth jump, its
// luminance test (Rough), so a pair may have bits when it is rough, or its depth jumps, or (with
// jumps) its luminance does. Branch-free passes over the block, which the compiler vectorises
// (built for AVX2 and the baseline, util/cpu_features.h). For the blocks SmoothBlock does not
// settle: a block with one edge pixel in it has its other pairs answered here, not tested one by
// one.
[[gnu::always_inline]] inline void MayHaveBitsBody(const EdgeArrays f, const Block k,
                                                   const bool jumps, const double* la,
                                                   const double* lb, const double* la2,
                                                   const double* lb2, std::uint8_t* need) {
    std::uint8_t rough[kSkip], depth[kSkip], lum[kSkip];
    for (std::size_t i = 0; i < kSkip; ++i) rough[i] = Rough(f, k, i) != 0;
    const float* z = f.depth;
    for (std::size_t i = 0; i < kSkip; ++i)
        depth[i] = DepthJumps(z[k.a + i], z[k.b + i], z[k.a2 + i], z[k.b2 + i]);
    for (std::size_t i = 0; i < kSkip; ++i) lum[i] = 0;
    if (jumps)
        for (std::size_t i = 0; i < kSkip; ++i)
            lum[i] = LuminanceJumps(la[i], lb[i], la2[i], lb2[i]);
    for (std::size_t i = 0; i < kSkip; ++i)
        need[i] = static_cast<std::uint8_t>(rough[i] | depth[i] | lum[i]);
}
QUADRIX_AVX2 void MayHaveBitsAvx2(const EdgeArrays f, const Block k, const bool jumps,
                                  const double* la, const double* lb, const double* la2,
                                  const double* lb2, std::uint8_t* need) {
    MayHaveBitsBody(f, k, jumps, la, lb, la2, lb2, need);
}
void MayHaveBitsBaseline(const EdgeArrays f, const Block k, const bool jumps, const double* la,
                         const double* lb, const double* la2, const double* lb2,
                         std::uint8_t* need) {
    MayHaveBitsBody(f, k, jumps, la, lb, la2, lb2, need);
}

// The bits of a block of pairs whose pixels beyond exist that SmoothBlock did not settle: only the
// pairs that may have bits (MayHaveBits) are tested, one by one (PairTest, the definition).
[[gnu::always_inline]] inline void BlockPairs(const EdgeArrays f, const Block k, const bool jumps,
                                              const double* la, const double* lb, const double* la2,
                                              const double* lb2) {
    alignas(16) std::uint8_t need[kSkip];
    if (gCpuHasAvx2)
        MayHaveBitsAvx2(f, k, jumps, la, lb, la2, lb2, need);
    else
        MayHaveBitsBaseline(f, k, jumps, la, lb, la2, lb2, need);
    static_assert(kSkip == 16, "the flags are read as two 64-bit words");
    if constexpr (std::endian::native != std::endian::little) {
        for (std::size_t i = 0; i < kSkip; ++i)
            if (need[i])
                PairTest(f, k.a + i, k.b + i, k.a2 + i, k.b2 + i, true, true, jumps, la[i], lb[i],
                         la2[i], lb2[i]);
        return;
    }
    for (std::size_t half = 0; half < 2; ++half) {
        std::uint64_t v;
        std::memcpy(&v, need + 8 * half, 8);
        while (v != 0) {  // the flags are 0 or 1: bit 8j is pair 8·half + j's (little-endian)
            const auto j = static_cast<std::size_t>(std::countr_zero(v) / 8);
            v &= v - 1;
            const std::size_t i = 8 * half + j;
            PairTest(f, k.a + i, k.b + i, k.a2 + i, k.b2 + i, true, true, jumps, la[i], lb[i],
                     la2[i], lb2[i]);
        }
    }
}

// The horizontal pairs of the row starting at pixel r, and the vertical pairs of the rows starting
// at ra and rb (ra2, rb2: the rows beyond them), w pixels wide; l*: the rows' luminances. Every
// argument by value: the result's bytes are chars, which may alias anything the loop reads
// through memory, so nothing it needs is left there.
void HorizontalPairs(const EdgeArrays f, const std::size_t r, const std::size_t w, const double* l,
                     const bool jumps) {
    for (std::size_t x = 0; x + 1 < w; ++x) {
        // Pairs x ... x + kSkip − 1 join pixels x ... x + kSkip.
        if (x % kSkip == 0 && x + kSkip < w && Background(f, r + x, kSkip + 1)) {
            x += kSkip - 1;
            continue;
        }
        // Pairs x ... x + kSkip − 1 with the pixels x − 1 and x + kSkip + 1 beyond them.
        if (x % kSkip == 0 && x > 0 && x + kSkip + 1 < w) {
            const Block k{r + x, r + x + 1, r + x - 1, r + x + 2};
            if (!SmoothBlock(f, k, jumps, l + x, l + x + 1, l + x - 1, l + x + 2))
                BlockPairs(f, k, jumps, l + x, l + x + 1, l + x - 1, l + x + 2);
            x += kSkip - 1;
            continue;
        }
        const bool hasA2 = x > 0, hasB2 = x + 2 < w;
        const std::size_t xa2 = hasA2 ? x - 1 : x, xb2 = hasB2 ? x + 2 : x + 1;
        PairTest(f, r + x, r + x + 1, r + xa2, r + xb2, hasA2, hasB2, jumps, l[x], l[x + 1], l[xa2],
                 l[xb2]);
    }
}
void VerticalPairs(const EdgeArrays f, const std::size_t ra, const std::size_t rb,
                   const std::size_t ra2, const std::size_t rb2, const bool hasA2, const bool hasB2,
                   const std::size_t w, const double* la, const double* lb, const double* la2,
                   const double* lb2, const bool jumps) {
    for (std::size_t x = 0; x < w; ++x) {
        if (x % kSkip == 0 && x + kSkip <= w) {
            if (Background(f, ra + x, kSkip) && Background(f, rb + x, kSkip)) {
                x += kSkip - 1;
                continue;
            }
            if (hasA2 && hasB2) {
                const Block k{ra + x, rb + x, ra2 + x, rb2 + x};
                if (!SmoothBlock(f, k, jumps, la + x, lb + x, la2 + x, lb2 + x))
                    BlockPairs(f, k, jumps, la + x, lb + x, la2 + x, lb2 + x);
                x += kSkip - 1;
                continue;
            }
        }
        PairTest(f, ra + x, rb + x, ra2 + x, rb2 + x, hasA2, hasB2, jumps, la[x], lb[x], la2[x],
                 lb2[x]);
    }
}

}  // namespace

std::uint8_t EdgePairCode(const Frame& f, std::size_t a, std::size_t b, std::size_t a2,
                          std::size_t b2, bool hasA2, bool hasB2, bool jumps, double la, double lb,
                          double la2, double lb2) {
    // e is not written.
    const EdgeArrays arrays{f.surface.data(), f.body.data(), f.normal.data(), f.depth.data(),
                            nullptr};
    return PairCode<false>(arrays, a, b, a2, b2, hasA2, hasB2, jumps, la, lb, la2, lb2);
}

std::vector<std::uint8_t> EdgePixels(const Frame& f, const Image* image,
                                     const std::vector<std::uint8_t>& rows) {
    constexpr int kBand = 16;
    const int w = f.width, h = f.height;
    std::vector<std::uint8_t> e(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
    const EdgeArrays arrays{f.surface.data(), f.body.data(), f.normal.data(), f.depth.data(),
                            e.data()};
    const RowLuminance jumps(f, image, rows);
    const bool active = jumps.Active();
    const std::vector<double> none(static_cast<std::size_t>(w), 0.0);
    auto luminance = [&](int y, RowLuminance::Cache& cache) {
        return active ? jumps.Row(y, cache) : none.data();
    };
    const auto uw = static_cast<std::size_t>(w);
    auto horizontal = [&](int y, RowLuminance::Cache& cache) {
        if (!RowShaded(rows, y)) return;
        HorizontalPairs(arrays, f.Index(0, y), uw, luminance(y, cache), active);
    };
    auto vertical = [&](int y, RowLuminance::Cache& cache) {  // the pairs of rows (y, y + 1)
        if (!PairShaded(rows, y)) return;
        const bool hasA2 = y > 0, hasB2 = y + 2 < h;
        const int ya2 = hasA2 ? y - 1 : y, yb2 = hasB2 ? y + 2 : y + 1;
        const double* la2 = luminance(ya2, cache);
        const double* la = luminance(y, cache);
        const double* lb = luminance(y + 1, cache);
        const double* lb2 = luminance(yb2, cache);
        VerticalPairs(arrays, f.Index(0, y), f.Index(0, y + 1), f.Index(0, ya2), f.Index(0, yb2),
                      hasA2, hasB2, uw, la, lb, la2, lb2, active);
    };
    const int bands = (h + kBand - 1) / kBand;
    ParallelFor(0, bands, [&](int band) {
        RowLuminance::Cache cache;
        const int y0 = band * kBand, y1 = std::min(h, y0 + kBand);
        for (int y = y0; y < y1; ++y) {
            horizontal(y, cache);
            if (y + 1 < y1) vertical(y, cache);
        }
    });
    ParallelFor(1, bands, [&](int band) {
        RowLuminance::Cache cache;
        vertical(band * kBand - 1, cache);
    });
    return e;
}

}  // namespace quadrix
