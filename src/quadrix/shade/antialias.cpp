#include "quadrix/shade/antialias.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <thread>

#include "quadrix/engines/raycast/sample_batch.h"
#include "quadrix/engines/raycast/sample_tracer.h"
#include "quadrix/shade/edge_pixels.h"
#include "quadrix/shade/row_shading.h"
#include "quadrix/shade/shade_budget.h"
#include "quadrix/util/parallel.h"
#include "quadrix/util/ray_work.h"

namespace quadrix {

namespace {

constexpr std::uint64_t Mix(std::uint64_t z) {  // splitmix64's finaliser
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// seed % m for 2 <= m <= 8 (Permutation's draws), by constant divisors: the compiler makes each a
// multiplication or a mask instead of a 64-bit division (the same remainder).
std::uint64_t Remainder(std::uint64_t seed, int m) {
    switch (m) {
        case 2:
            return seed % 2;
        case 3:
            return seed % 3;
        case 4:
            return seed % 4;
        case 5:
            return seed % 5;
        case 6:
            return seed % 6;
        case 7:
            return seed % 7;
        case 8:
            return seed % 8;
        default:
            return seed % static_cast<std::uint64_t>(m);
    }
}

// A permutation of 0..k-1 drawn from `seed` (Fisher–Yates).
void Permutation(int k, std::uint64_t seed, int* out) {
    for (int i = 0; i < k; ++i) out[i] = i;
    for (int i = k - 1; i > 0; --i) {
        seed = Mix(seed + 0x9e3779b97f4a7c15ULL);
        const int j = static_cast<int>(Remainder(seed, i + 1));
        std::swap(out[i], out[j]);
    }
}

// Mix(c) for c = 1 .. 16: the salts of SamplePositionsInto's permutations (2a + 1, 2a + 2 for
// a < 8), made at compile time.
constexpr std::array<std::uint64_t, 17> kSalts = [] {
    std::array<std::uint64_t, 17> t{};
    for (std::uint64_t c = 1; c <= 16; ++c) t[c] = Mix(c);
    return t;
}();

// Mitchell–Netravali cubic, B = C = 1/3, at |x| (support 2).
double Mitchell1(double x) {
    x = std::fabs(x);
    constexpr double B = 1.0 / 3, C = 1.0 / 3;
    if (x < 1)
        return ((12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B)) /
               6;
    if (x < 2)
        return ((-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x +
                (8 * B + 24 * C)) /
               6;
    return 0;
}

double Clamp01(double v) { return v > 0 ? (v < 1 ? v : 1.0) : 0.0; }

// Where the samples of pixel (x, y) probably see something: just past the deepest surface of the
// pixel and its eight neighbours (+inf when none is covered). Only a first guess for the sample
// tracer's depth windows; the samples do not depend on it.
double DepthHint(const Frame& f, int x, int y) {
    double deepest = -HUGE_VAL;
    for (int v = std::max(y - 1, 0); v <= std::min(y + 1, f.height - 1); ++v)
        for (int u = std::max(x - 1, 0); u <= std::min(x + 1, f.width - 1); ++u) {
            const double z = f.depth[f.Index(u, v)];
            if (std::isfinite(z) && z > deepest) deepest = z;
        }
    return deepest == -HUGE_VAL ? HUGE_VAL : deepest + 2 + 1e-6 * std::fabs(deepest);
}

// One thread's state for the samples: the batcher's and the tracer's.
struct SampleThread {
    SampleThread(const raycast::SampleBatcher& batcher, const raycast::SampleTracer& tracer)
        : batch(batcher), trace(tracer) {}
    raycast::SampleBatcher::Scratch batch;
    raycast::SampleScratch trace;
};

}  // namespace

std::vector<std::uint8_t> FindEdges(const Frame& frame) { return EdgePixels(frame, nullptr, {}); }

std::vector<std::uint8_t> FindEdgesAndShadingJumps(const Frame& frame, const Image& image) {
    return EdgePixels(frame, &image, {});
}

bool ValidAaSamples(int samples) {
    return samples == 0 || samples == 1 || samples == 4 || samples == 16 || samples == 64;
}

std::vector<SubPixel> SamplePositions(int samples, int i, int j) {
    SamplePositionList list;
    SamplePositionsInto(samples, i, j, list);
    return {list.at.begin(), list.at.begin() + list.n};
}

void SamplePositionsInto(int samples, int i, int j, SamplePositionList& out) {
    int k = 1;
    while (k * k < samples) ++k;
    const int n = k * k;
    out.n = 0;
    const std::uint64_t seed =
        Mix((static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) ^
            static_cast<std::uint32_t>(j));
    int col[8][8], row[8][8];  // k <= 8
    for (int a = 0; a < k; ++a) {
        Permutation(k, seed ^ kSalts[static_cast<std::size_t>(2 * a + 1)], col[a]);
        Permutation(k, seed ^ kSalts[static_cast<std::size_t>(2 * a + 2)], row[a]);
    }
    // Cell (a, b) (column a, row b): fine column a·k + col[a][b], fine row b·k + row[b][a]. For a
    // fixed a, col[a][·] is a permutation, so coarse column a uses each of its k fine columns
    // once; likewise for rows: a Latin square on the n × n fine grid. Where n is a power of two
    // (4, 16, 64: ValidAaSamples) the product by 1/n is the quotient by n, exactly.
    const bool powerOfTwo = (n & (n - 1)) == 0;
    const double inverse = 1.0 / n;
    const auto fine = [&](int cell) {
        return powerOfTwo ? (cell + 0.5) * inverse : (cell + 0.5) / n;
    };
    for (int b = 0; b < k; ++b)
        for (int a = 0; a < k; ++a)
            out.at[static_cast<std::size_t>(out.n++)] = {fine(a * k + col[a][b]),
                                                         fine(b * k + row[b][a])};
}

AntialiasStats Antialias(const Frame& frame, const FlatScene& scene, const ShadeOptions& options,
                         Image& image, std::shared_ptr<const WideNodeTrees> wide) {
    return AntialiasRowKinds(frame, scene, options, image, {}, std::move(wide));
}

AntialiasStats AntialiasRowKinds(const Frame& frame, const FlatScene& scene,
                                 const ShadeOptions& options, Image& image,
                                 const std::vector<std::uint8_t>& rows,
                                 std::shared_ptr<const WideNodeTrees> wide) {
    AntialiasStats stats;
    if (options.aaSamples < 2 || frame.width == 0 || frame.height == 0) return stats;
    const auto t0 = std::chrono::steady_clock::now();
    // With shadows, the pairs whose shading jumps too (a shadow's boundary) in the same pass.
    std::vector<std::uint8_t> edges = EdgePixels(frame, options.shadows ? &image : nullptr, rows);
    // Keep away from freeform surfaces: no point tracer for them.
    const auto firstFreeform = static_cast<std::int32_t>(scene.halfSpaces.size());
    if (!scene.freeforms.empty()) {
        std::vector<std::uint8_t> near(edges.size(), 0);
        for (int y = 0; y < frame.height; ++y) {
            if (!RowRead(rows, y)) continue;
            for (int x = 0; x < frame.width; ++x)
                if (frame.surface[frame.Index(x, y)] >= firstFreeform)
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const int u = x + dx, v = y + dy;
                            if (u >= 0 && v >= 0 && u < frame.width && v < frame.height)
                                near[frame.Index(u, v)] = 1;
                        }
        }
        for (std::size_t k = 0; k < edges.size(); ++k)
            if (near[k]) edges[k] &= static_cast<std::uint8_t>(~kEdgePixel);
    }
    if (!wide && options.spatialIndex)  // one build for the shader's shadow rays and the tracer
        wide = WideNodeTrees::Shared(scene, true);
    const PixelShader shader(frame, scene, options, wide);
    // The edge pixels go by squares of kRegion × kRegion pixels, in bands of kRegion rows (below).
    constexpr int kRegion = 8;
    const raycast::SampleTracer tracer(scene, options.spatialIndex, wide);
    const raycast::SampleBatcher batcher(scene, tracer.Tables(), frame.width, frame.height,
                                         kRegion);
    // The unquantised values only when the output wants them (ShadeOptions::linear; an 8-bit
    // file reads the bytes): 11 MB of floats at 1280×720 otherwise made and filled for nothing.
    if (options.linear && image.linear.size() != image.pixels.size()) {
        image.linear.resize(image.pixels.size());
        for (std::size_t k = 0; k < image.pixels.size(); ++k)
            image.linear[k] = static_cast<float>(image.pixels[k] / 255.0);
    }
    std::atomic<std::size_t> count{0};
    // The shading budget (shade_budget.h): as many sample rays as if every pixel were an edge
    // pixel, each of kShadeLiteralsPerRay literals.
    int side = 1;
    while (side * side < options.aaSamples) ++side;
    ShadeBudget budget("anti-aliasing", "--aa off, or a smaller --aa",
                       static_cast<std::uint64_t>(frame.width) *
                           static_cast<std::uint64_t>(frame.height) *
                           static_cast<std::uint64_t>(side * side));
    // The edge pixels go by squares of kRegion × kRegion pixels, in bands of kRegion rows: the
    // samples of a square's edge pixels are traced together, in batches of at most
    // SampleBatcher::kMaxPoints, by the engine's sub-tile path (raycast/sample_batch.h: the
    // program pruned to the band, then to the square, the bodies reduced there), then shaded.
    // Where the square's program has a wide node (SampleBatcher::SetSquare) they are traced one
    // by one by SampleTracer instead, its bodies reduced on the square (SetRegion) and its depth
    // windows started from the nearby pixels' depth (DepthHint). Both give the exact samples,
    // the same bits (the SampleBatch tests): only the time differs.
    const int bands = (frame.height + kRegion - 1) / kRegion;
    // One scratch per thread, kept across its tasks.
    PerThread<SampleThread> scratches(std::cref(batcher), std::cref(tracer));
    // The squares k0 .. k1 − 1 (row by row: square k is in band k / across) with `scratch` (one
    // thread's).
    const int across = (frame.width + kRegion - 1) / kRegion;
    auto squares = [&](int k0, int k1, SampleThread& scratch) {
        std::size_t local = 0;
        auto edge = [&](int x, int y) { return (edges[frame.Index(x, y)] & kEdgePixel) != 0; };
        SamplePositionList positions;
        // A square's samples are traced first, all of them, then shaded: the shadow rays from
        // their visible points take the reach of the box around those points
        // (PixelShader::ReachOfBox; the same colours, fewer boxes and literals tested).
        std::vector<SubPixel> at;
        std::vector<double> xs, ys;
        std::vector<raycast::Sample> hits;
        PixelShader::ShadowReach reach;
        PixelShader::MaterialCache cache;
        // Pixel (x, y)'s samples, from at[t] and hits[t] on, shaded and filtered into the image.
        // The shadow rays' literals are spent in chunks (`pending`, an atomic add a pixel was
        // 14 % of this loop's time), every chunk before the square ends: the pass stops at most
        // kSpendChunk literals and one pixel later than it would pixel by pixel, and whether it
        // passes the budget is the same (only the sum decides).
        constexpr std::uint64_t kSpendChunk = 1 << 12;
        std::uint64_t pending = 0;
        auto resample = [&](int x, int y, const scene::Color& background, std::size_t& t) {
            if (budget.Exhausted()) return false;
            const std::uint64_t work = tRayLiterals;
            ++local;
            double r = 0, g = 0, b = 0, wsum = 0;
            for (int p = 0; p < positions.n; ++p, ++t) {
                const SubPixel& s = at[t];
                const raycast::Sample& hit = hits[t];
                const scene::Color c = shader.At(x + s.u, y + s.v, hit.surface, hit.body, hit.depth,
                                                 hit.normal, background, &cache, &reach);
                const double wgt =
                    options.aaMitchell ? Mitchell1(s.u - 0.5) * Mitchell1(s.v - 0.5) : 1.0;
                r += wgt * Clamp01(c.r);
                g += wgt * Clamp01(c.g);
                b += wgt * Clamp01(c.b);
                wsum += wgt;
            }
            StoreColor(image, x, y, {r / wsum, g / wsum, b / wsum});
            pending += tRayLiterals - work;
            if (pending >= kSpendChunk) {
                budget.Spend(pending);
                pending = 0;
            }
            return true;
        };
        // Whether a row of the square, the n <= kRegion edge bytes from p, has an edge pixel, and
        // the first and the last one's offsets: eight bytes at a time (most rows have none).
        auto rowEdges = [](const std::uint8_t* p, int n, int& first, int& last) {
            std::uint64_t v = 0;
            std::memcpy(&v, p, static_cast<std::size_t>(n));
            if constexpr (std::endian::native == std::endian::little) {
                v &= 0x0101010101010101ull * kEdgePixel;
                if (v == 0) return false;
                first = std::countr_zero(v) / 8;
                last = 7 - std::countl_zero(v) / 8;
                return true;
            } else {
                first = n;
                last = -1;
                for (int k = 0; k < n; ++k)
                    if (p[k] & kEdgePixel) {
                        first = std::min(first, k);
                        last = k;
                    }
                return last >= 0;
            }
        };
        static_assert(kRegion <= 8, "rowEdges reads a square's row as eight bytes");
        int band = -1;
        auto square = [&](int x0, int y0) {
            const int x1 = std::min(frame.width, x0 + kRegion);
            const int y1 = std::min(frame.height, y0 + kRegion);
            int xlo = x1, xhi = x0 - 1, ylo = y1, yhi = y0 - 1;
            for (int y = y0; y < y1; ++y) {
                if (!RowShaded(rows, y)) continue;
                int first, last;
                if (!rowEdges(edges.data() + frame.Index(x0, y), x1 - x0, first, last)) continue;
                xlo = std::min(xlo, x0 + first);
                xhi = std::max(xhi, x0 + last);
                ylo = std::min(ylo, y);
                yhi = std::max(yhi, y);
            }
            if (xhi < xlo) return true;
            if (budget.Exhausted()) return false;
            // Sample positions are x + u, y + v with u, v in (0, 1).
            if (y0 / kRegion != band) {
                band = y0 / kRegion;
                batcher.SetBand(band, scratch.batch);
            }
            const eval::Rect region{static_cast<double>(xlo), static_cast<double>(xhi + 1),
                                    static_cast<double>(ylo), static_cast<double>(yhi + 1)};
            const bool wideHere = batcher.SetSquare(region, scratch.batch);
            if (wideHere) tracer.SetRegion(region, scratch.trace);
            at.clear();
            xs.clear();
            ys.clear();
            for (int y = ylo; y <= yhi; ++y) {
                if (!RowShaded(rows, y)) continue;
                for (int x = xlo; x <= xhi; ++x) {
                    if (!edge(x, y)) continue;
                    SamplePositionsInto(options.aaSamples, x, y, positions);
                    for (int p = 0; p < positions.n; ++p) {
                        const SubPixel& s = positions.at[static_cast<std::size_t>(p)];
                        at.push_back(s);
                        xs.push_back(x + s.u);
                        ys.push_back(y + s.v);
                    }
                }
            }
            // Traced in batches (or one by one); the box of their visible points for the shadows'
            // reach.
            hits.resize(at.size());
            const std::uint64_t work = tRayLiterals;
            if (wideHere) {
                double hint = HUGE_VAL;
                for (std::size_t t = 0; t < at.size(); ++t) {
                    if (t % static_cast<std::size_t>(positions.n) == 0)  // a pixel's first sample
                        hint = DepthHint(frame, static_cast<int>(std::floor(xs[t])),
                                         static_cast<int>(std::floor(ys[t])));
                    hits[t] = tracer.Trace(xs[t], ys[t], scratch.trace, hint);
                }
            } else {
                for (std::size_t b = 0; b < at.size(); b += raycast::SampleBatcher::kMaxPoints) {
                    const auto n = static_cast<int>(
                        std::min<std::size_t>(raycast::SampleBatcher::kMaxPoints, at.size() - b));
                    batcher.Trace(xs.data() + b, ys.data() + b, n, hits.data() + b, scratch.batch);
                }
            }
            budget.Spend(tRayLiterals - work);
            Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
            for (std::size_t t = 0; t < hits.size(); ++t) {
                if (!hits[t].Covered()) continue;
                lo = {std::min(lo.x, xs[t]), std::min(lo.y, ys[t]), std::min(lo.z, hits[t].depth)};
                hi = {std::max(hi.x, xs[t]), std::max(hi.y, ys[t]), std::max(hi.z, hits[t].depth)};
            }
            shader.ReachOfBox(lo, hi, reach);
            std::size_t t = 0;
            bool done = true;
            for (int y = ylo; y <= yhi && done; ++y) {
                if (!RowShaded(rows, y)) continue;
                const scene::Color background = shader.Background(y, frame.height);
                for (int x = xlo; x <= xhi && done; ++x)
                    if (edge(x, y)) done = resample(x, y, background, t);
            }
            budget.Spend(pending);
            pending = 0;
            return done;
        };
        for (int k = k0; k < k1; ++k)
            if (!square(k % across * kRegion, k / across * kRegion)) break;
        tracer.ClearRegion(scratch.trace);
        count += local;
    };
    if (options.aaHelperThread && SerialLoopsOnThisThread() && bands >= 2) {
        // A square at a time, to this thread or the helper, whichever is free first.
        SampleThread helperScratch(batcher, tracer);
        const std::thread::id self = std::this_thread::get_id();
        OnTwoThreads(bands * across, [&](int k) {
            squares(k, k + 1,
                    std::this_thread::get_id() == self ? scratches.Local() : helperScratch);
        });
    } else {
        ParallelFor(tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& span) {
            squares(span.begin() * across, span.end() * across, scratches.Local());
        });
    }
    budget.ThrowIfExhausted(scene);
    stats.edgePixels = count.load();
    int k = 1;
    while (k * k < options.aaSamples) ++k;
    stats.samples = stats.edgePixels * static_cast<std::size_t>(k * k);
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return stats;
}

std::size_t DrawEdgeLines(const Frame& frame, const ShadeOptions& options, Image& image) {
    return DrawEdgeLinesRowKinds(frame, options, image, {});
}

std::size_t DrawEdgeLinesRowKinds(const Frame& frame, const ShadeOptions& options, Image& image,
                                  const std::vector<std::uint8_t>& rows) {
    const std::vector<std::uint8_t> edges = EdgePixels(frame, nullptr, rows);
    std::size_t n = 0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width && RowShaded(rows, y); ++x)
            if (edges[frame.Index(x, y)] & kEdgeLine) {
                StoreColor(image, x, y, options.edgeColor);
                ++n;
            }
    return n;
}

}  // namespace quadrix
