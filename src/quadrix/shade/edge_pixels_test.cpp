#include "quadrix/shade/edge_pixels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "quadrix/frame/packed_normal.h"
#include "quadrix/shade/row_shading.h"

namespace quadrix {
namespace {

// The code of a unit normal at polar angle theta, azimuth phi.
PackedNormal Direction(double theta, double phi) {
    return PackedNormal(
        Vec3{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
}

// A code whose halves are those of n moved by (du, dv) units (kept off -32768, kZero's half).
PackedNormal Moved(PackedNormal n, int du, int dv) {
    const auto clamp = [](int h) { return h < -32767 ? -32767 : (h > 32767 ? 32767 : h); };
    const int hi = clamp((static_cast<std::int32_t>(n.bits) >> 16) + du);
    const int lo = clamp((static_cast<std::int32_t>(n.bits << 16) >> 16) + dv);
    PackedNormal m;
    m.bits = static_cast<std::uint32_t>(static_cast<std::uint16_t>(hi)) << 16 |
             static_cast<std::uint16_t>(lo);
    return m;
}

// Codes whose halves differ by at most kNearNormalCodes never make a crease: random directions
// over the whole sphere (both halves of the octahedral square, across its fold), each moved by
// random offsets up to the bound and exactly on it. The largest angle met is below the bound's
// argument's asin(2√3 · kNearNormalCodes / 32767) (edge_pixels.h), and larger offsets do reach a
// crease (so the test would see a bound that is too large).
TEST(EdgePixels, NearCodesNeverMakeACrease) {
    std::mt19937_64 rng(20261207);
    std::uniform_real_distribution<double> unit(0, 1);
    std::uniform_int_distribution<int> offset(-kNearNormalCodes, kNearNormalCodes);
    const double cosLimit = std::cos(kCreaseDegrees * std::numbers::pi / 180);
    double largest = 0;
    std::size_t creasesBeyond = 0;
    for (int i = 0; i < 400000; ++i) {
        const PackedNormal a =
            Direction(std::acos(1 - 2 * unit(rng)), 2 * std::numbers::pi * unit(rng));
        int du = offset(rng);
        int dv = offset(rng);
        if (i % 2 == 0) {  // on the bound: |du| + |dv| = kNearNormalCodes
            du = du % (kNearNormalCodes + 1);
            dv = (dv < 0 ? -1 : 1) * (kNearNormalCodes - std::abs(du));
        } else if (std::abs(du) + std::abs(dv) > kNearNormalCodes) {
            dv = (dv < 0 ? -1 : 1) * (kNearNormalCodes - std::abs(du));
        }
        const PackedNormal b = Moved(a, du, dv);
        ASSERT_NE(b.bits, PackedNormal::kZero);
        ASSERT_FALSE(PackedNormal::AngleExceeds(a, b, cosLimit))
            << std::hex << a.bits << " " << b.bits;
        const Vec3 p = a, q = b;
        const double dot = p.x * q.x + p.y * q.y + p.z * q.z;
        largest = std::max(largest, std::acos(std::min(1.0, dot)) * 180 / std::numbers::pi);
        creasesBeyond += PackedNormal::AngleExceeds(a, Moved(a, 3 * du, 3 * dv), cosLimit);
    }
    const double bound =
        std::asin(2 * std::sqrt(3.0) * kNearNormalCodes / 32767) * 180 / std::numbers::pi;
    EXPECT_LT(largest, bound);
    EXPECT_LT(bound, kCreaseDegrees);
    EXPECT_GT(largest, bound / 3);
    EXPECT_GT(creasesBeyond, 1000u);
}

// A random Frame with the features the pair test tells apart: background, a few surfaces and
// bodies in patches, normals near each other (offsets below and above kNearNormalCodes, across the
// octahedral fold), some far apart and some kZero on covered pixels; depths on planes with steps,
// exact ties and single-pixel spikes; an image whose brightness jumps. A `smooth` picture has
// wider cells and few of those features, so that runs of pairs on one surface with near normals and
// no depth jump (EdgePixels' blocks of smooth pairs) are common, with a jump here and there.
struct RandomPicture {
    Frame frame;
    Image image;
};
RandomPicture MakeRandomPicture(int w, int h, bool linear, bool smooth, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0, 1);
    RandomPicture r{Frame(w, h), Image(w, h, 3)};
    Frame& f = r.frame;
    f.bodySolid = {0, 1, 2};
    // Patches: cells of cw × 5 pixels (cw from 3 to 40: runs of background longer and shorter
    // than EdgePixels skips at once), each background (half of them) or one of three surfaces.
    const int cw = (smooth ? 17 : 3) + static_cast<int>(seed % 38);
    // The odds of the features that are not smooth.
    const double rare = smooth ? 0.1 : 1;
    std::vector<int> cellSurface;
    for (int k = 0; k < (w / cw + 1) * (h / 5 + 1); ++k)
        cellSurface.push_back(unit(rng) < 0.5 ? -1 : static_cast<int>(unit(rng) * 3));
    const PackedNormal base[3] = {Direction(0.3, 0.2), Direction(1.6, 2.0), Direction(2.8, 4.0)};
    if (linear) r.image.linear.assign(r.image.pixels.size(), 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = f.Index(x, y);
            const int s = cellSurface[static_cast<std::size_t>((y / 5) * (w / cw + 1) + x / cw)];
            if (s < 0) continue;  // background as the Frame starts
            f.surface[i] = s;
            f.body[i] = unit(rng) < 0.02 * rare ? (s + 1) % 3 : s;
            const double roll = unit(rng);
            const int spread = roll < 1 - 0.4 * rare ? 300 : (roll < 1 - 0.1 * rare ? 3000 : 30000);
            std::uniform_int_distribution<int> off(-spread, spread);
            f.normal[i] =
                unit(rng) < 0.01 * rare ? PackedNormal() : Moved(base[s], off(rng), off(rng));
            double z = 10 + s + 0.01 * x + 0.02 * y + (x > w / 2 ? 0.5 : 0.0);
            if (unit(rng) < 0.01 * rare) z += 0.2;
            if (unit(rng) < 0.05 * rare) z = 10 + s;  // ties with other pixels
            f.depth[i] = static_cast<float>(z);
            for (int c = 0; c < 3; ++c) {
                const double v = (unit(rng) < 0.05 ? 0.1 : 0.7) + 0.002 * (x % 100);  // <= 0.898
                r.image.pixels[i * 3 + static_cast<std::size_t>(c)] =
                    static_cast<std::uint8_t>(v * 255);
                if (linear) r.image.linear[i * 3 + static_cast<std::size_t>(c)] = float(v);
            }
        }
    return r;
}

// The bits of every pixel from EdgePairCode, pair by pair (edge_pixels.h's definition).
std::vector<std::uint8_t> Definition(const Frame& f, const Image* image) {
    const int w = f.width, h = f.height;
    std::vector<double> lum(f.surface.size(), 0.0);
    const bool linear = image && image->linear.size() == image->pixels.size();
    if (image)
        for (std::size_t k = 0; k < lum.size(); ++k) {
            auto v = [&](int c) {
                const std::size_t i = k * 3 + static_cast<std::size_t>(c);
                return linear ? static_cast<double>(image->linear[i]) : image->pixels[i] / 255.0;
            };
            lum[k] = 0.2126 * v(0) + 0.7152 * v(1) + 0.0722 * v(2);
        }
    std::vector<std::uint8_t> e(f.surface.size(), 0);
    auto pair = [&](std::size_t a, std::size_t b, std::size_t a2, std::size_t b2, bool hasA2,
                    bool hasB2) {
        const std::uint8_t c = EdgePairCode(f, a, b, a2, b2, hasA2, hasB2, image != nullptr, lum[a],
                                            lum[b], lum[a2], lum[b2]);
        e[a] |= c & 3;
        e[b] |= (c & 1) | ((c >> 1) & 2);
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x + 1 < w; ++x)
            pair(f.Index(x, y), f.Index(x + 1, y), f.Index(x > 0 ? x - 1 : x, y),
                 f.Index(x + 2 < w ? x + 2 : x + 1, y), x > 0, x + 2 < w);
    for (int y = 0; y + 1 < h; ++y)
        for (int x = 0; x < w; ++x)
            pair(f.Index(x, y), f.Index(x, y + 1), f.Index(x, y > 0 ? y - 1 : y),
                 f.Index(x, y + 2 < h ? y + 2 : y + 1), y > 0, y + 2 < h);
    return e;
}

// EdgePixels (bands in parallel, the crease test short-cut for near codes) against the
// definition on random pictures of sizes around the bands of 16 rows, with no image, an 8-bit one
// and a float one; and on the shaded rows of a row selection (RowKinds), whose other rows are
// not compared (their bits are incomplete by design).
TEST(EdgePixels, EqualTheDefinitionPairByPair) {
    std::size_t edges = 0, creases = 0;
    for (const auto& [w, h] :
         {std::pair{1, 1}, {2, 3}, {3, 2}, {5, 17}, {17, 4}, {67, 53}, {130, 33}, {257, 40}})
        for (int mode = 0; mode < 6; ++mode) {
            const RandomPicture r =
                MakeRandomPicture(w, h, mode % 3 == 2, mode >= 3, 1000 * w + h + mode);
            const Image* image = mode % 3 == 0 ? nullptr : &r.image;
            const std::vector<std::uint8_t> expected = Definition(r.frame, image);
            const std::vector<std::uint8_t> got = EdgePixels(r.frame, image, {});
            ASSERT_EQ(got.size(), expected.size());
            std::size_t mismatches = 0;
            for (std::size_t k = 0; k < got.size(); ++k) {
                mismatches += got[k] != expected[k];
                edges += (got[k] & kEdgeLine) != 0;
            }
            EXPECT_EQ(mismatches, 0u) << w << " x " << h << " mode " << mode;
            const std::vector<std::uint8_t> rows = RowKinds({{h / 3, h / 3 + 7}}, h);
            const std::vector<std::uint8_t> some = EdgePixels(r.frame, image, rows);
            std::size_t rowMismatches = 0;
            for (int y = 0; y < h; ++y)
                if (RowShaded(rows, y))
                    for (int x = 0; x < w; ++x)
                        rowMismatches += some[r.frame.Index(x, y)] != expected[r.frame.Index(x, y)];
            EXPECT_EQ(rowMismatches, 0u) << w << " x " << h << " mode " << mode;
        }
    // The pictures have edges of every kind: count the creases between codes that differ by
    // more than the short-cut's bound on one surface.
    const RandomPicture r = MakeRandomPicture(67, 53, false, false, 7);
    const Frame& f = r.frame;
    const double cosLimit = std::cos(kCreaseDegrees * std::numbers::pi / 180);
    for (std::size_t k = 0; k + 1 < f.surface.size(); ++k)
        creases += f.surface[k] >= 0 && f.surface[k] == f.surface[k + 1] &&
                   PackedNormal::AngleExceeds(f.normal[k], f.normal[k + 1], cosLimit);
    EXPECT_GT(edges, 500u);
    EXPECT_GT(creases, 20u);
}

}  // namespace
}  // namespace quadrix
