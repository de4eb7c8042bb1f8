// The edge pixels of a Frame (antialias.h, item 1): which pixels an edge separates from a
// 4-neighbour, and which of them draw the one-pixel edge line. The anti-aliasing pass resamples
// the first; DrawEdgeLines paints the second.
//
// The test of one pair of 4-neighbours (a, b), with a2 the pixel beyond a and b2 the one beyond b
// on the same line (a and b themselves at the image's border, where hasA2 / hasB2 are false):
//
//   separated  their surface or body ids differ; or both are covered and their normals differ by
//              more than kCreaseDegrees (PackedNormal::AngleExceeds), or their depths jump:
//              |z_b − z_a| > 4·slope + 1e-6·(1 + |z_a|), slope the larger of |z_a − z_a2| (when
//              a2 exists and is on a's surface) and |z_b2 − z_b| (likewise), else 0. The Frame's
//              depths are floats (frame.h): a step below a few of their ulps is rounding.
//   jump       with a shaded image: not separated, covered, and the luminance L (Rec. 709 weights
//              of the image's linear values) jumps, |L_b − L_a| > 4·max(|L_a − L_a2|,
//              |L_b2 − L_b|) + 1/255 (a shadow's boundary).
//
// Both pixels of a separated or jumping pair get kEdgePixel; of a separated pair, the nearer one
// (depth_b < depth_a: b, else a, so an exact tie gives a) also gets kEdgeLine. A pixel's bits are
// the OR over its pairs, so they do not depend on the order or the thread count.
//
// How: the rows are swept in bands of 16 in parallel, each band's horizontal pairs and the
// vertical pairs within it row by row (each row's luminance made once, into a small per-thread
// cache); then the vertical pairs that straddle two bands, which no two threads share. A pair
// writes only its own two pixels. Along a line, a run of 16 pairs is first looked at whole: all
// background, it has no bits; all smooth (one surface and body, the pixels beyond on it too, no
// crease), its depth and luminance tests run in branch-free passes the compiler vectorises (AVX2
// and baseline builds, util/cpu_features.h); otherwise, or where one of those tests fires, the
// same passes made pair by pair (MayHaveBits) leave to the pair-by-pair test only the pairs that
// are not smooth or whose test fires (a run with one edge pixel in it used to test all 16). The
// crease test answers the codes of nearby directions without decoding them (kNearNormalCodes).
// EdgePixels.* tests the whole against the definition written pair by pair (EdgePairCode) on random
// Frames.
//
// (A branch-free pass over every pair was tried and was slower: the pairs of two background
// pixels, half of a typical picture, cost the scalar test two comparisons; docs/performance.md.)
#pragma once

#include <cstdint>
#include <vector>

#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"

namespace quadrix {

constexpr double kCreaseDegrees = 20;

// Per pixel: bit kEdgePixel when an edge separates it from a 4-neighbour (or, with an image, its
// brightness jumps), bit kEdgeLine when it is also the nearer pixel of a separated pair (a
// covered pixel next to the background is the nearer one).
constexpr std::uint8_t kEdgePixel = 1, kEdgeLine = 2;

// Two normals' codes (PackedNormal), neither kZero, whose halves differ by δ = |Δu| + |Δv| <=
// kNearNormalCodes units of 1/32767 make an angle of at most asin(2√3 · δ / 32767) = 18.95
// degrees, so no crease: the pair test answers them without decoding (four divisions). Why: the
// octahedral map (packed_normal.h) is continuous and piecewise linear, each piece moving a point
// of the octahedron |x|+|y|+|z| = 1 by at most 2·(|du| + |dv|) (in L1, so also in length), and
// every such point p is at least 1/√3 from the origin; so |p − q| <= 2δ/32767 = 0.1875, which is
// less than |p| (the angle is acute), and sin ∠(p, q) <= |p − q| / |p| <= 0.3248 < sin 20°. The
// squares of the cosines differ by 1.3 %, far more than the rounding of AngleExceeds' products.
constexpr int kNearNormalCodes = 3072;
static_assert(kCreaseDegrees >= 19.5, "kNearNormalCodes assumes a crease angle above 18.95°");

// The bits of every pixel of `frame`, on the rows `rows` marks kRowShaded (row_shading.h; every
// row when empty: the bits of the other rows are incomplete). `image`: the shaded picture whose
// brightness jumps count too, or null (also when its size is not the Frame's).
std::vector<std::uint8_t> EdgePixels(const Frame& frame, const Image* image,
                                     const std::vector<std::uint8_t>& rows);

// The scalar definition for one pair (above), as a code: bits & 3 are a's, (bits & 1) |
// ((bits >> 1) & 2) are b's. la, lb, la2, lb2: the luminances, read only when `jumps`. For tests,
// and the border pairs.
std::uint8_t EdgePairCode(const Frame& frame, std::size_t a, std::size_t b, std::size_t a2,
                          std::size_t b2, bool hasA2, bool hasB2, bool jumps, double la, double lb,
                          double la2, double lb2);

}  // namespace quadrix
