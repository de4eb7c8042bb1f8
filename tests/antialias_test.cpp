// Anti-aliasing and edge lines (shade/antialias.h) and the sub-pixel tracer under them
// (engines/raycast/sample_tracer.h), against the raycast engine and analytic coverage.
//
// The disc: a sphere under ambient light 1 shades to exactly 1 wherever it is seen, on a black
// background, so a pixel's linear value is the share of its samples that see the sphere, and the
// box filter's result is the pixel's coverage estimate. The sphere's outline in device space is
// the circle where the ray's discriminant h² − c·k vanishes (ray_literal.h), whose centre and
// radius are read off the device quadric; the coverage of a pixel's square by that disc is
// integrated numerically (20,000 midpoints across the square: error < 1e-4, far below the 1/16
// bound).
#include "quadrix/shade/antialias.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>

#include "quadrix/engines/raycast/sample_tracer.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/shade/shader.h"
#include "quadrix/shade/shadows.h"
#include "quadrix/util/ray_work.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

PipelineResult Render(const std::string& text, int w, int h) {
    PipelineOptions o;
    o.sceneText = text;
    o.width = w;
    o.height = h;
    PipelineResult r;
    Diagnostics d;
    EXPECT_TRUE(RunPipeline(o, r, d)) << text;
    return r;
}

PipelineResult RenderFile(const std::string& path, int w, int h) {
    PipelineOptions o;
    o.scenePaths = {SourcePath(path)};
    o.width = w;
    o.height = h;
    PipelineResult r;
    Diagnostics d;
    EXPECT_TRUE(RunPipeline(o, r, d)) << path;
    return r;
}

// The device-space outline of a sphere seen along z: centre (cx, cy) and radius.
struct Circle {
    double cx, cy, r;
};
Circle Outline(const Quadric& q) {
    // Along the ray: c = C, h = F x + E y + J, k = A x² + B y² + 2D xy + 2G x + 2H y + K.
    // disc(x, y) = h² − c k = qxx x² + qxy xy + qyy y² + lx x + ly y + d0.
    const double c = q.C();
    const double qxx = q.F() * q.F() - c * q.A(), qyy = q.E() * q.E() - c * q.B();
    const double qxy = 2 * q.E() * q.F() - 2 * c * q.D();
    const double lx = 2 * q.F() * q.J() - 2 * c * q.G(), ly = 2 * q.E() * q.J() - 2 * c * q.H();
    const double d0 = q.J() * q.J() - c * q.K();
    EXPECT_NEAR(qxy, 0, 1e-9 * std::fabs(qxx));
    EXPECT_NEAR(qxx, qyy, 1e-9 * std::fabs(qxx));
    const double cx = -lx / (2 * qxx), cy = -ly / (2 * qxx);
    const double dc = d0 - qxx * (cx * cx + cy * cy);
    return {cx, cy, std::sqrt(dc / -qxx)};
}

double Coverage(const Circle& d, int i, int j) {
    constexpr int kSteps = 20000;
    double sum = 0;
    for (int s = 0; s < kSteps; ++s) {
        const double u = i + (s + 0.5) / kSteps - d.cx;
        const double half = d.r * d.r - u * u;
        if (half <= 0) continue;
        const double root = std::sqrt(half);
        const double lo = std::max<double>(j, d.cy - root),
                     hi = std::min<double>(j + 1, d.cy + root);
        if (hi > lo) sum += hi - lo;
    }
    return sum / kSteps;
}

const char* kDisc =
    "quadric ball <1 1 1 0 0 0 0 0 0 -1>; body disc <ball>; light 1;\n"
    "view v vrp .0123 .0456 0 whh 1.37;\n";

struct EdgeError {
    double mean = 0, max = 0;
    int pixels = 0;
};

// The coverage error of the shaded disc, over the pixels the disc's outline crosses.
EdgeError DiscError(int samples, bool mitchell = false) {
    PipelineResult r = Render(kDisc, 64, 64);
    const Circle c = Outline(r.flat.halfSpaces.at(0).quadric);
    EXPECT_GT(c.r, 20);  // the disc fills most of the picture
    ShadeOptions so;
    so.aaSamples = samples;
    so.aaMitchell = mitchell;
    Image img = Shade(r.frame, r.flat, so);
    Antialias(r.frame, r.flat, so, img);
    EXPECT_EQ(img.channels, 1);
    EdgeError e;
    for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 64; ++i) {
            const double cov = Coverage(c, i, j);
            const double v = img.linear[static_cast<std::size_t>(j) * 64 + i];
            if (cov == 0 || cov == 1) {
                EXPECT_EQ(v, cov) << "pixel " << i << "," << j << " away from the outline";
                continue;
            }
            const double err = std::fabs(v - cov);
            e.mean += err;
            e.max = std::max(e.max, err);
            ++e.pixels;
        }
    e.mean /= std::max(e.pixels, 1);
    return e;
}

TEST(Antialias, DiscEdgeErrorIsBelowASixteenthOfAPixelAtSixteenSamples) {
    const EdgeError off = DiscError(0), aa4 = DiscError(4), aa16 = DiscError(16),
                    aa64 = DiscError(64), mitchell = DiscError(16, true);
    RecordProperty("mean_error_off", std::to_string(off.mean));
    RecordProperty("mean_error_16", std::to_string(aa16.mean));
    EXPECT_GT(off.pixels, 100);
    // Without anti-aliasing a pixel is 0 or 1: the mean error of a crossing pixel is near ¼.
    EXPECT_GT(off.mean, 0.15);
    EXPECT_LE(aa16.mean, 1.0 / 16) << "max " << aa16.max;
    EXPECT_LT(aa64.mean, aa16.mean);
    EXPECT_LT(aa16.mean, aa4.mean);
    // Stratified: no crossing pixel is off by more than a quarter (two fine strata of 16... with
    // margin) at 16 samples, an eighth at 64.
    EXPECT_LE(aa16.max, 0.25);
    EXPECT_LE(aa64.max, 0.125);
    EXPECT_LE(mitchell.mean, 0.1);
    std::printf(
        "disc edge error, mean (max) over %d crossing pixels: off %.4f (%.3f), 4: %.4f "
        "(%.3f), 16: %.4f (%.3f), 64: %.4f (%.3f), 16 mitchell %.4f\n",
        aa16.pixels, off.mean, off.max, aa4.mean, aa4.max, aa16.mean, aa16.max, aa64.mean, aa64.max,
        mitchell.mean);
}

TEST(Antialias, SamplePositionsAreALatinSquareOfCells) {
    for (int n : {4, 16, 64}) {
        const int k = static_cast<int>(std::lround(std::sqrt(n)));
        for (int pixel = 0; pixel < 20; ++pixel) {
            const auto s = SamplePositions(n, pixel * 7, pixel * 13 - 50);
            ASSERT_EQ(s.size(), static_cast<std::size_t>(n));
            std::set<int> cols, rows, cells;
            for (const SubPixel& p : s) {
                ASSERT_GE(p.u, 0);
                ASSERT_LT(p.u, 1);
                ASSERT_GE(p.v, 0);
                ASSERT_LT(p.v, 1);
                const int fc = static_cast<int>(p.u * n), fr = static_cast<int>(p.v * n);
                cols.insert(fc);
                rows.insert(fr);
                cells.insert((fr / k) * k + fc / k);
            }
            EXPECT_EQ(cols.size(), static_cast<std::size_t>(n));
            EXPECT_EQ(rows.size(), static_cast<std::size_t>(n));
            EXPECT_EQ(cells.size(), static_cast<std::size_t>(n));
        }
        // Deterministic, and not the same pattern in every pixel.
        EXPECT_EQ(SamplePositions(n, 3, 4)[1].u, SamplePositions(n, 3, 4)[1].u);
    }
    EXPECT_NE(SamplePositions(16, 3, 4)[0].u, SamplePositions(16, 4, 3)[0].u);
}

// The positions are those of the plain statement of the pattern (splitmix64's finaliser, Fisher–
// Yates with 64-bit remainders, quotients by n), which SamplePositionsInto computes with
// constant divisors, a table of salts and products by 1/n: the same doubles, bit for bit, at
// every sample count (9 and 36 too, whose n is not a power of two).
TEST(Antialias, SamplePositionsEqualThePlainStatementOfThePattern) {
    const auto mix = [](std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    };
    const auto permutation = [&](int k, std::uint64_t seed, int* out) {
        for (int i = 0; i < k; ++i) out[i] = i;
        for (int i = k - 1; i > 0; --i) {
            seed = mix(seed + 0x9e3779b97f4a7c15ULL);
            std::swap(out[i], out[seed % static_cast<std::uint64_t>(i + 1)]);
        }
    };
    for (int n : {4, 9, 16, 36, 64}) {
        const int k = static_cast<int>(std::lround(std::sqrt(n)));
        for (int pixel = 0; pixel < 200; ++pixel) {
            const int i = pixel * 37 - 900, j = pixel * 11 + 5;
            const std::uint64_t seed =
                mix((static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) ^
                    static_cast<std::uint32_t>(j));
            int col[8][8], row[8][8];
            for (int a = 0; a < k; ++a) {
                permutation(k, seed ^ mix(2 * static_cast<std::uint64_t>(a) + 1), col[a]);
                permutation(k, seed ^ mix(2 * static_cast<std::uint64_t>(a) + 2), row[a]);
            }
            const std::vector<SubPixel> got = SamplePositions(n, i, j);
            ASSERT_EQ(got.size(), static_cast<std::size_t>(n));
            std::size_t t = 0;
            for (int b = 0; b < k; ++b)
                for (int a = 0; a < k; ++a, ++t) {
                    EXPECT_EQ(got[t].u, (a * k + col[a][b] + 0.5) / n) << n << " " << pixel;
                    EXPECT_EQ(got[t].v, (b * k + row[b][a] + 0.5) / n) << n << " " << pixel;
                }
        }
    }
}

// At pixel centres the sample tracer is the engine: same ids, same depth, same normal.
TEST(SampleTracer, EqualsTheRaycastEngineAtPixelCentres) {
    for (const char* path :
         {"examples/machined_part.uq", "examples/stack_of_bundles.uq", "examples/tube.uq"}) {
        PipelineResult r = RenderFile(path, 96, 72);
        const raycast::SampleTracer tracer(r.flat);
        int covered = 0;
        for (int j = 0; j < r.frame.height; ++j)
            for (int i = 0; i < r.frame.width; ++i) {
                const std::size_t k = r.frame.Index(i, j);
                const raycast::Sample s = tracer.Trace(i + 0.5, j + 0.5);
                ASSERT_EQ(s.surface, r.frame.surface[k]) << path << " " << i << "," << j;
                ASSERT_EQ(s.body, r.frame.body[k]) << path << " " << i << "," << j;
                ASSERT_EQ(s.solid, r.frame.Solid(k)) << path << " " << i << "," << j;
                if (!s.Covered()) continue;
                ++covered;
                // The Frame's depth and normal are the tracer's, rounded and packed (frame.h).
                ASSERT_EQ(static_cast<float>(s.depth), r.frame.depth[k])
                    << path << " " << i << "," << j;
                ASSERT_EQ(PackedNormal(s.normal), r.frame.normal[k])
                    << path << " " << i << "," << j;
            }
        EXPECT_GT(covered, 500) << path;
    }
}

// Wide CSG nodes and many solids (the box trees of sample_tracer.h and shadows.h): a union of 40
// spheres minus 12, and 30 loose spheres.
std::string WideScene() {
    std::string t;
    auto sphere = [&](const std::string& id, double x, double y, double z, double r) {
        t += fmt::format("quadric {} <1 1 1 0 0 0 {} {} {} {}>; body b{} ({});\n", id, -x, -y, -z,
                         x * x + y * y + z * z - r * r, id, id);
    };
    for (int i = 0; i < 40; ++i)
        sphere(fmt::format("u{}", i), 3 * std::sin(i * 1.7), 3 * std::cos(i * 2.3),
               std::sin(i * 0.9), 0.9);
    for (int j = 0; j < 12; ++j)
        sphere(fmt::format("h{}", j), 3 * std::cos(j * 1.1), 3 * std::sin(j * 1.9), -0.8, 0.6);
    for (int k = 0; k < 30; ++k)
        sphere(fmt::format("f{}", k), 7 + 2 * std::sin(k * 0.7), 4 * std::cos(k * 1.3),
               2 * std::sin(k * 2.1), 0.5);
    t += "csg lump ((";
    for (int i = 0; i < 40; ++i) t += fmt::format("{}bu{}", i ? " | " : "", i);
    t += ")";
    for (int j = 0; j < 12; ++j) t += fmt::format(" - bh{}", j);
    t += ");\nlight .2; light .8 .3 1 -.5;\nview v dop .2 .3 -1;\n";
    return t;
}

// The box trees change no sample and no shadow: the tracer with and without them gives the same
// samples bit for bit (pixel centres: the engine's pixels; and points between them), and the
// shadow tester the same answers.
TEST(SampleTracer, BoxTreesChangeNoSampleAndNoShadow) {
    PipelineResult r = Render(WideScene(), 120, 90);
    std::size_t wide = 0;
    for (const FlatCsgNode& n : r.flat.nodes) wide += !n.isLeaf && n.children.size() > 8;
    ASSERT_GE(wide, 2u);  // the union, and the difference's 12 subtrahends
    ASSERT_GT(r.flat.solids.size(), 30u);
    const raycast::SampleTracer indexed(r.flat), plain(r.flat, false);
    int covered = 0;
    for (int j = 0; j < r.frame.height; ++j)
        for (int i = 0; i < r.frame.width; ++i) {
            const std::size_t k = r.frame.Index(i, j);
            const raycast::Sample s = indexed.Trace(i + 0.5, j + 0.5);
            ASSERT_EQ(s.surface, r.frame.surface[k]) << i << "," << j;
            ASSERT_EQ(s.solid, r.frame.Solid(k)) << i << "," << j;
            if (s.Covered()) {
                ASSERT_EQ(static_cast<float>(s.depth), r.frame.depth[k]) << i << "," << j;
            }
            covered += s.Covered();
            const raycast::Sample a = indexed.Trace(i + 0.37, j + 0.81),
                                  b = plain.Trace(i + 0.37, j + 0.81);
            ASSERT_EQ(a.surface, b.surface) << i << "," << j;
            ASSERT_EQ(a.body, b.body) << i << "," << j;
            ASSERT_EQ(a.solid, b.solid) << i << "," << j;
            ASSERT_EQ(a.depth, b.depth) << i << "," << j;
        }
    EXPECT_GT(covered, 1500);
    const ShadowTester shadowIndexed(r.flat), shadowPlain(r.flat, false);
    const Vec3 toLight = r.flat.projection.deviceFromWorld.MapVector({.3, 1, -.5});
    int blocked = 0, lit = 0;
    for (int j = 0; j < r.frame.height; j += 2)
        for (int i = 0; i < r.frame.width; i += 2) {
            const std::size_t k = r.frame.Index(i, j);
            if (r.frame.surface[k] == Frame::kNone) continue;
            const Vec3 p{i + 0.5, j + 0.5, r.frame.depth[k]};
            const bool a = shadowIndexed.Blocked(p, toLight, HUGE_VAL);
            ASSERT_EQ(a, shadowPlain.Blocked(p, toLight, HUGE_VAL)) << i << "," << j;
            (a ? blocked : lit) += 1;
        }
    EXPECT_GT(blocked, 30);
    EXPECT_GT(lit, 30);
}

// The wide-node trees are made once per flat scene and shared (RenderContext::Shade keeps them
// for the shadow rays and the samples): the picture with shadows and anti-aliasing is the one made
// with trees of its own and the one made without trees, again from the kept trees, and after the
// scene is flattened anew (another size: other bounds) the one a fresh context makes, so the
// trees of the earlier flat scene are not used for it.
TEST(SampleTracer, SharedWideTreesChangeNoPicture) {
    InputRequest in;
    in.text = WideScene();
    ShadeOptions so;
    so.shadows = true;
    so.aaSamples = 4;
    ShadeOptions plain = so;
    plain.spatialIndex = false;
    RenderContext ctx;
    Frame frame;
    Diagnostics diags;
    ASSERT_TRUE(RenderToFrame(ctx, in, 120, 90, frame, diags));
    const Image shared = ctx.Shade(frame, so);
    EXPECT_EQ(shared.pixels, ctx.Shade(frame, so).pixels);  // the kept trees
    Image own = Shade(frame, ctx.Flat(), so);
    Antialias(frame, ctx.Flat(), so, own);
    EXPECT_EQ(shared.pixels, own.pixels);
    EXPECT_EQ(shared.pixels, ctx.Shade(frame, plain).pixels);
    Frame other;
    ASSERT_TRUE(RenderToFrame(ctx, in, 96, 128, other, diags));
    RenderContext fresh;
    Frame again;
    ASSERT_TRUE(RenderToFrame(fresh, in, 96, 128, again, diags));
    const Image second = ctx.Shade(other, so);
    EXPECT_EQ(second.pixels, fresh.Shade(again, so).pixels);
    EXPECT_EQ(second.pixels, ctx.Shade(other, plain).pixels);
    std::set<std::uint8_t> values(second.pixels.begin(), second.pixels.end());
    EXPECT_GT(values.size(), 20u);  // shaded, with shadows and edges
}

// The sample tracer's depth windows (sample_tracer.h) and its depth hint change no sample: a
// cluster of 300 spheres of many sizes minus a drill, cut by a transparent front clipping plane (so
// rays also enter through a transparent face, whose interval's visible end is its far one), traced
// with the windows and any hint (none, a good one, one too near, one far before the scene, NaN)
// gives bit for bit what the tracer without box trees or windows gives, at pixel centres the
// engine's pixel.
TEST(SampleTracer, DepthWindowsAndHintsChangeNoSample) {
    std::string t;
    for (int i = 0; i < 300; ++i)
        t += fmt::format("solid sphere s{} =at {:.5f} {:.5f} {:.5f} =r {:.4f};\n", i,
                         4 * std::sin(i * 1.37) * std::cos(i * 0.61),
                         4 * std::cos(i * 2.11) * std::sin(i * 0.43), 4 * std::sin(i * 0.77),
                         0.1 + 0.6 * std::fabs(std::sin(i * 0.91)));
    t += "solid cylinder drill =from 0 0 -6 =to 0 0 6 =r 1.5;\ncsg cluster ((";
    for (int i = 0; i < 300; ++i) t += fmt::format("{}s{}", i ? " | " : "", i);
    t += ") - drill);\n";
    // Pearls: six big spheres each holding a small one just behind its front (as the view sees it),
    // so a window that dropped a child straddling its end would find the small one.
    const Vec3 toViewer = Normalize(Vec3{-.2, -.3, 1});
    for (int k = 0; k < 6; ++k) {
        const Vec3 c{8, -5 + 2.6 * k, 0}, tiny = c + 0.65 * toViewer;
        t += fmt::format("solid sphere big{} =at {} {} {} =r 1.2;\n", k, c.x, c.y, c.z);
        t += fmt::format("solid sphere tiny{} =at {:.5f} {:.5f} {:.5f} =r .3;\n", k, tiny.x, tiny.y,
                         tiny.z);
    }
    t += "csg pearls (";
    for (int k = 0; k < 6; ++k) t += fmt::format("{}big{} | tiny{}", k ? " | " : "", k, k);
    t += ");\nlight .2; light .8 .3 1 -.5;\nview v dop .2 .3 -1 fbp -1.5 20;\n";
    PipelineResult r = Render(t, 96, 72);
    std::size_t wide = 0;
    for (const FlatCsgNode& n : r.flat.nodes) wide += !n.isLeaf && n.children.size() > 8;
    ASSERT_GE(wide, 1u);
    const raycast::SampleTracer windowed(r.flat), plain(r.flat, false);
    raycast::SampleScratch scratch(windowed);
    int covered = 0;
    for (int j = 0; j < r.frame.height; ++j)
        for (int i = 0; i < r.frame.width; ++i) {
            const std::size_t k = r.frame.Index(i, j);
            const raycast::Sample c = windowed.Trace(i + 0.5, j + 0.5, scratch,
                                                     static_cast<double>(r.frame.depth[k]) + 2);
            ASSERT_EQ(c.surface, r.frame.surface[k]) << i << "," << j;
            ASSERT_EQ(c.body, r.frame.body[k]) << i << "," << j;
            if (c.Covered()) {
                ASSERT_EQ(static_cast<float>(c.depth), r.frame.depth[k]) << i << "," << j;
                ++covered;
            }
            const double x = i + 0.37, y = j + 0.81;
            const raycast::Sample want = plain.Trace(x, y);
            const double z = r.frame.depth[k];
            for (double hint : {HUGE_VAL, z + 2, z - 5, -1e9, std::nan(""), want.depth + 0.5,
                                want.depth + 3, want.depth + 20}) {
                const raycast::Sample got = windowed.Trace(x, y, scratch, hint);
                ASSERT_EQ(got.surface, want.surface) << i << "," << j << " hint " << hint;
                ASSERT_EQ(got.body, want.body) << i << "," << j << " hint " << hint;
                ASSERT_EQ(got.solid, want.solid) << i << "," << j << " hint " << hint;
                ASSERT_EQ(got.depth, want.depth) << i << "," << j << " hint " << hint;
            }
        }
    EXPECT_GT(covered, 1500);
    // The front plane cuts the cluster: without it, many pixels see a surface nearer by more than
    // a pixel (the same window: fbp has no effect on the fit, docs/language.md).
    std::string uncut = t;
    uncut.replace(uncut.find(" fbp"), std::string(" fbp -1.5 20").size(), "");
    PipelineResult whole = Render(uncut, 96, 72);
    int throughTheCut = 0;
    for (std::size_t k = 0; k < r.frame.depth.size(); ++k)
        throughTheCut +=
            r.frame.surface[k] != Frame::kNone && whole.frame.depth[k] < r.frame.depth[k] - 1;
    EXPECT_GT(throughTheCut, 200);
}

// Regions change no sample (sample_tracer.h, Regions): samples traced after SetRegion, in the
// rectangle, equal those traced without one, field by field and bit for bit, over squares of 8
// pixels (as the anti-aliasing pass makes them), single pixels, thin strips and rectangles with
// fractional corners, including samples on the rectangle's border. And the regions do leave out
// literals: the machined part's samples evaluate fewer than half of them.
TEST(SampleTracer, RegionsChangeNoSample) {
    struct Case {
        std::string name;
        PipelineResult r;
    };
    std::vector<Case> cases;
    for (const char* path :
         {"examples/machined_part.uq", "examples/stack_of_bundles.uq", "examples/tube.uq"})
        cases.push_back({path, RenderFile(path, 96, 72)});
    cases.push_back({"wide", Render(WideScene(), 96, 72)});
    for (Case& c : cases) {
        const raycast::SampleTracer tracer(c.r.flat);
        raycast::SampleScratch plain(tracer), regioned(tracer);
        const int w = c.r.frame.width, h = c.r.frame.height;
        std::uint64_t withRegion = 0, without = 0;
        int covered = 0, n = 0;
        auto check = [&](const eval::Rect& rect, double x, double y) {
            std::uint64_t before = tRayLiterals;
            const raycast::Sample want = tracer.Trace(x, y, plain);
            without += tRayLiterals - before;
            before = tRayLiterals;
            const raycast::Sample got = tracer.Trace(x, y, regioned);
            withRegion += tRayLiterals - before;
            const std::string at = fmt::format("{} ({}, {}) in [{}, {}] x [{}, {}]", c.name, x, y,
                                               rect.x0, rect.x1, rect.y0, rect.y1);
            ASSERT_EQ(got.surface, want.surface) << at;
            ASSERT_EQ(got.body, want.body) << at;
            ASSERT_EQ(got.solid, want.solid) << at;
            ASSERT_EQ(got.depth, want.depth) << at;
            ASSERT_EQ(got.normal.x, want.normal.x) << at;
            ASSERT_EQ(got.normal.y, want.normal.y) << at;
            ASSERT_EQ(got.normal.z, want.normal.z) << at;
            covered += got.Covered();
            ++n;
        };
        // Squares of 8 pixels, each sampled on a 5 × 5 grid that includes its border.
        for (int y0 = 0; y0 < h; y0 += 8)
            for (int x0 = 0; x0 < w; x0 += 8) {
                const eval::Rect rect{double(x0), double(std::min(w, x0 + 8)), double(y0),
                                      double(std::min(h, y0 + 8))};
                tracer.SetRegion(rect, regioned);
                for (int a = 0; a <= 4; ++a)
                    for (int b = 0; b <= 4; ++b)
                        check(rect, rect.x0 + (rect.x1 - rect.x0) * a / 4,
                              rect.y0 + (rect.y1 - rect.y0) * b / 4);
            }
        // Single pixels, strips and rectangles with fractional corners.
        for (int k = 0; k < 400; ++k) {
            const double x0 = std::fmod(k * 7.31, w - 3.0), y0 = std::fmod(k * 3.77, h - 3.0);
            const double dx = k % 3 == 0 ? 1.0 : (k % 3 == 1 ? 0.01 : 2.6);
            const double dy = k % 4 == 0 ? 1.0 : (k % 4 == 1 ? 2.3 : 0.37);
            const eval::Rect rect{x0, x0 + dx, y0, y0 + dy};
            tracer.SetRegion(rect, regioned);
            for (double u : {0.0, 0.13, 0.5, 0.87, 1.0})
                check(rect, x0 + u * dx, y0 + (1 - u) * dy);
        }
        EXPECT_GT(covered, n / 4) << c.name;
        EXPECT_LE(withRegion, without) << c.name;
        if (c.name == "examples/machined_part.uq") {
            EXPECT_LT(2 * withRegion, without);
        }
        // Cleared: the samples are again traced without a region, anywhere.
        tracer.ClearRegion(regioned);
        for (int k = 0; k < 50; ++k) {
            const double x = std::fmod(k * 5.3, double(w)), y = std::fmod(k * 2.9, double(h));
            const raycast::Sample a = tracer.Trace(x, y, regioned), b = tracer.Trace(x, y, plain);
            ASSERT_EQ(a.surface, b.surface) << c.name;
            ASSERT_EQ(a.depth, b.depth) << c.name;
        }
    }
}

// Anti-aliasing changes edge pixels only, and only towards their samples' mean.
TEST(Antialias, InteriorPixelsAreNotResampled) {
    PipelineResult r = RenderFile("examples/machined_part.uq", 160, 120);
    ShadeOptions so;
    const Image plain = Shade(r.frame, r.flat, so);
    so.aaSamples = 16;
    Image aa = Shade(r.frame, r.flat, so);
    const AntialiasStats st = Antialias(r.frame, r.flat, so, aa);
    const std::vector<std::uint8_t> edges = FindEdges(r.frame);
    std::size_t edgePixels = 0, changed = 0;
    for (int j = 0; j < 120; ++j)
        for (int i = 0; i < 160; ++i) {
            const std::size_t k = r.frame.Index(i, j);
            edgePixels += (edges[k] & kEdgePixel) != 0;
            const std::size_t c = k * static_cast<std::size_t>(plain.channels);
            bool same = true;
            for (int ch = 0; ch < plain.channels; ++ch)
                same &= plain.linear[c + ch] == aa.linear[c + ch];
            if (!(edges[k] & kEdgePixel)) {
                ASSERT_TRUE(same) << "interior pixel " << i << "," << j << " changed";
            }
            changed += !same;
        }
    EXPECT_EQ(st.edgePixels, edgePixels);
    EXPECT_EQ(st.samples, 16 * edgePixels);
    EXPECT_GT(changed, edgePixels / 4);  // most edge pixels are mixed
    EXPECT_LT(edgePixels, 160u * 120u / 4);
}

// The anti-aliasing pass against its definition (antialias.h), with shadows: every pixel that
// FindEdgesAndShadingJumps marks is the box-filtered mean of its samples, each traced alone by
// SampleTracer (no region, no depth hint) and shaded alone by PixelShader::At (no material
// cache, no reach), bit for bit, bytes and floats; every other pixel is Shade's. The pass traces
// a square's samples together and shades them with the reach of their box
// (PixelShader::ReachOfBox): this checks that none of that changes a colour. The machined part
// under its own lights and a low side light, whose shadows fall across the holes.
TEST(Antialias, WithShadowsEqualsItsDefinition) {
    PipelineResult r = RenderFile("examples/machined_part.uq", 160, 120);
    scene::Light side;
    side.kind = scene::Light::Kind::kParallel;
    side.direction = {-1, .35, .2};
    side.intensity = .5;
    r.flat.lights.push_back(side);
    for (int samples : {4, 16}) {
        ShadeOptions so;
        so.shadows = true;
        so.aaSamples = samples;
        const Image plain = Shade(r.frame, r.flat, so);
        Image aa = plain;
        const AntialiasStats st = Antialias(r.frame, r.flat, so, aa);
        const std::vector<std::uint8_t> edges = FindEdgesAndShadingJumps(r.frame, plain);
        const PixelShader shader(r.frame, r.flat, so);
        const raycast::SampleTracer tracer(r.flat);
        Image expected = plain;
        std::size_t edgePixels = 0, shadowed = 0;
        for (int j = 0; j < r.frame.height; ++j)
            for (int i = 0; i < r.frame.width; ++i) {
                if (!(edges[r.frame.Index(i, j)] & kEdgePixel)) continue;
                ++edgePixels;
                const scene::Color background = shader.Background(j, r.frame.height);
                double red = 0, green = 0, blue = 0;
                const std::vector<SubPixel> at = SamplePositions(samples, i, j);
                for (const SubPixel& s : at) {
                    const raycast::Sample hit = tracer.Trace(i + s.u, j + s.v);
                    const scene::Color c = shader.At(i + s.u, j + s.v, hit.surface, hit.body,
                                                     hit.depth, hit.normal, background);
                    red += std::clamp(c.r, 0.0, 1.0);
                    green += std::clamp(c.g, 0.0, 1.0);
                    blue += std::clamp(c.b, 0.0, 1.0);
                    if (hit.Covered() && shader.ShadowMask(i + s.u, j + s.v, hit.surface, hit.body,
                                                           hit.depth, hit.normal) != 0)
                        ++shadowed;
                }
                const double n = static_cast<double>(at.size());
                StoreColor(expected, i, j, {red / n, green / n, blue / n});
            }
        EXPECT_EQ(st.edgePixels, edgePixels) << samples;
        EXPECT_GT(edgePixels, 1000u) << samples;
        EXPECT_GT(shadowed, 500u) << samples;  // samples with a light blocked
        ASSERT_EQ(aa.pixels.size(), expected.pixels.size());
        std::size_t differ = 0;
        for (std::size_t k = 0; k < aa.pixels.size(); ++k)
            differ += aa.pixels[k] != expected.pixels[k] || aa.linear[k] != expected.linear[k];
        EXPECT_EQ(differ, 0u) << samples << " samples";
    }
}

// An 8-bit output (ShadeOptions::linear false) reads only the bytes: the anti-aliasing and the
// edge lines then write the bytes alone and make no Image::linear, and the bytes are those of the
// run that keeps the floats (shadow boundaries included: their test reads the bytes or floats
// that Shade made, as before the anti-aliasing).
TEST(Antialias, AnEightBitOutputGetsTheSameBytesWithoutTheFloats) {
    PipelineResult r = RenderFile("examples/machined_part.uq", 200, 150);
    for (const bool shadows : {false, true}) {
        ShadeOptions so;
        so.shadows = shadows;
        so.aaSamples = 4;
        so.edges = true;
        Image floats = Shade(r.frame, r.flat, so);
        const AntialiasStats a = Antialias(r.frame, r.flat, so, floats);
        DrawEdgeLines(r.frame, so, floats);
        so.linear = false;
        Image bytes = Shade(r.frame, r.flat, so);
        ASSERT_TRUE(bytes.linear.empty());
        const AntialiasStats b = Antialias(r.frame, r.flat, so, bytes);
        EXPECT_GT(DrawEdgeLines(r.frame, so, bytes), 100u);
        EXPECT_TRUE(bytes.linear.empty()) << shadows;
        ASSERT_EQ(floats.linear.size(), floats.pixels.size());
        EXPECT_GT(b.edgePixels, 500u);
        EXPECT_EQ(a.edgePixels, b.edgePixels);
        EXPECT_TRUE(std::equal(floats.pixels.begin(), floats.pixels.end(), bytes.pixels.begin()))
            << shadows;
    }
}

// A shadow's boundary is not an edge of the Frame (one surface of one body on both sides), but
// with shadows on its pixels are resampled too (FindEdgesAndShadingJumps): on a flat floor under
// one parallel light, a pixel is fully lit, fully shadowed, or — only next to the shadow's boundary
// — in between. Without resampling there would be no pixel in between.
TEST(Antialias, ShadowBoundariesAreResampled) {
    PipelineResult r = Render(
        "solid box floor =at 0 -1 0 =size 8 .2 8; solid sphere ball =at 0 .5 0 =r .8;\n"
        "light .2; light sun .8 .6 1 .3;\n"
        "view v vrp 0 -1 0 cop 0 20 -.01 whh 3.5;\n",
        96, 96);
    ShadeOptions so;
    so.shadows = true;
    const Image plain = Shade(r.frame, r.flat, so);
    so.aaSamples = 16;
    Image aa = Shade(r.frame, r.flat, so);
    Antialias(r.frame, r.flat, so, aa);
    // The floor's two values in the plain picture: lit and shadowed.
    const std::int32_t floorBody = r.frame.body[r.frame.Index(2, 2)];
    ASSERT_GE(floorBody, 0);
    std::set<float> values;
    for (std::size_t k = 0; k < r.frame.body.size(); ++k)
        if (r.frame.body[k] == floorBody &&
            r.frame.surface[k] == r.frame.surface[r.frame.Index(2, 2)])
            values.insert(plain.linear[k]);
    ASSERT_EQ(values.size(), 2u) << "the floor is lit or shadowed, nothing else";
    const float shadowed = *values.begin(), lit = *values.rbegin();
    ASSERT_LT(shadowed, lit);
    std::size_t between = 0, boundary = 0;
    for (int j = 1; j + 1 < 96; ++j)
        for (int i = 1; i + 1 < 96; ++i) {
            const std::size_t k = r.frame.Index(i, j);
            if (r.frame.body[k] != floorBody) continue;
            bool nearBoundary = false, nearOther = false;
            for (int d = 0; d < 4; ++d) {
                const std::size_t n =
                    r.frame.Index(i + (d == 0) - (d == 1), j + (d == 2) - (d == 3));
                if (r.frame.body[n] != floorBody)
                    nearOther = true;
                else if (plain.linear[n] != plain.linear[k])
                    nearBoundary = true;
            }
            if (nearOther) continue;
            const float v = aa.linear[k];
            EXPECT_GE(v, shadowed - 1e-6f);
            EXPECT_LE(v, lit + 1e-6f);
            if (!nearBoundary) {
                // Away from the boundary (and from the ball's silhouette) nothing changes.
                EXPECT_EQ(v, plain.linear[k]) << i << "," << j;
                continue;
            }
            ++boundary;
            between += v > shadowed + 1e-6f && v < lit - 1e-6f;
        }
    EXPECT_GT(boundary, 20u);
    EXPECT_GT(between, boundary / 3) << between << " of " << boundary;
}

// FindEdgesAndShadingJumps against its definition (antialias.h, item 1), written out here with a
// whole image of luminances: FindEdges' bits, plus kEdgePixel on both pixels of every pair of
// 4-neighbours on one surface of one body whose luminance L jumps, |L_b − L_a| > 4 · max(|L_a −
// L_a2|, |L_b2 − L_b|) + 1/255 (a2, b2 the next pixels outward, or a, b at the border). The
// picture is 96 × 75, so that the shadow's boundary crosses the implementation's bands of 16 rows
// (and their last, shorter one), with 8-bit and with float pixels; and the bits do not depend on
// where the bands fall (the picture moved down in taller Frames).
TEST(Antialias, ShadingJumpsAreTheDefinitionsPairs) {
    const int w = 96, h = 75;
    PipelineResult r = Render(
        "solid box floor =at 0 -1 0 =size 8 .2 8 =c .9 .6 .3;\n"
        "solid sphere ball =at 0 .5 0 =r .8 =c steelblue;\n"
        "light .2; light sun .8 .6 1 .3;\n"
        "view v vrp 0 -1 0 cop 0 20 -.01 whh 3.5;\n",
        w, h);
    const Frame& f = r.frame;
    for (bool linear : {false, true}) {
        ShadeOptions so;
        so.shadows = true;
        so.linear = linear;
        const Image image = Shade(f, r.flat, so);
        ASSERT_EQ(image.linear.size() == image.pixels.size(), linear);
        ASSERT_EQ(image.channels, 3);
        std::vector<double> lum(f.surface.size());
        for (std::size_t k = 0; k < lum.size(); ++k) {
            auto v = [&](int c) {
                const std::size_t i = k * 3 + static_cast<std::size_t>(c);
                return linear ? static_cast<double>(image.linear[i]) : image.pixels[i] / 255.0;
            };
            lum[k] = 0.2126 * v(0) + 0.7152 * v(1) + 0.0722 * v(2);
        }
        std::vector<std::uint8_t> expected = FindEdges(f);
        auto pair = [&](std::size_t a, std::size_t b, std::size_t a2, std::size_t b2) {
            if (f.surface[a] < 0 || f.surface[a] != f.surface[b] || f.body[a] != f.body[b]) return;
            const double slope = std::max(std::fabs(lum[a] - lum[a2]), std::fabs(lum[b2] - lum[b]));
            if (std::fabs(lum[b] - lum[a]) > 4 * slope + 1.0 / 255) {
                expected[a] |= kEdgePixel;
                expected[b] |= kEdgePixel;
            }
        };
        for (int y = 0; y < h; ++y)
            for (int x = 0; x + 1 < w; ++x)
                pair(f.Index(x, y), f.Index(x + 1, y), f.Index(x > 0 ? x - 1 : x, y),
                     f.Index(x + 2 < w ? x + 2 : x + 1, y));
        for (int y = 0; y + 1 < h; ++y)
            for (int x = 0; x < w; ++x)
                pair(f.Index(x, y), f.Index(x, y + 1), f.Index(x, y > 0 ? y - 1 : y),
                     f.Index(x, y + 2 < h ? y + 2 : y + 1));
        const std::vector<std::uint8_t> edges = FindEdges(f);
        const std::vector<std::uint8_t> got = FindEdgesAndShadingJumps(f, image);
        std::size_t jumps = 0, mismatches = 0;
        std::set<int> rows;
        for (std::size_t k = 0; k < got.size(); ++k) {
            mismatches += got[k] != expected[k];
            if ((got[k] & kEdgePixel) && !(edges[k] & kEdgePixel)) {
                ++jumps;
                rows.insert(static_cast<int>(k) / w);
            }
        }
        EXPECT_EQ(mismatches, 0u) << "linear " << linear;
        // The shadow's boundary adds pixels of its own, on rows either side of band edges.
        EXPECT_GT(jumps, 40u) << "linear " << linear;
        int straddled = 0;  // band edges (rows 16k − 1 and 16k) with the boundary on both sides
        for (int y = 16; y < h; y += 16) straddled += rows.count(y - 1) && rows.count(y);
        EXPECT_GE(straddled, 1) << "linear " << linear;

        // The same picture 1 ... 16 rows lower in a taller Frame (background above): the
        // bands' edges fall on every row of the picture in turn (the ball's outline is level
        // at its top and bottom), and a pixel's bits, which depend on the pixels up to 2 rows
        // away, are the same away from the picture's top and bottom.
        for (int shift = 1; shift <= 16; ++shift) {
            Frame g(w, h + shift);
            g.bodySolid = f.bodySolid;
            Image moved(w, h + shift, image.channels);
            if (linear) moved.linear.assign(moved.pixels.size(), 0.0f);
            for (std::size_t k = 0; k < f.surface.size(); ++k) {
                const std::size_t m = k + static_cast<std::size_t>(shift * w);
                g.depth[m] = f.depth[k];
                g.normal[m] = f.normal[k];
                g.surface[m] = f.surface[k];
                g.body[m] = f.body[k];
                for (std::size_t c = 0; c < 3; ++c) {
                    moved.pixels[m * 3 + c] = image.pixels[k * 3 + c];
                    if (linear) moved.linear[m * 3 + c] = image.linear[k * 3 + c];
                }
            }
            const std::vector<std::uint8_t> gotMoved = FindEdgesAndShadingJumps(g, moved);
            std::size_t differ = 0;
            for (int y = 2; y + 2 < h; ++y)
                for (int x = 0; x < w; ++x)
                    differ += got[f.Index(x, y)] != gotMoved[g.Index(x, y + shift)];
            EXPECT_EQ(differ, 0u) << "linear " << linear << ", moved " << shift << " rows";
        }
    }
}

// Edge lines: one pixel wide, on the covered side of a silhouette, and every silhouette pixel.
TEST(EdgeLines, TheDiscsOutlineIsOnePixelWide) {
    PipelineResult r = Render(kDisc, 64, 64);
    ShadeOptions so;
    so.edges = true;
    so.edgeColor = {0.5, 0.5, 0.5};
    Image img = Shade(r.frame, r.flat, so);
    const std::size_t lines = DrawEdgeLines(r.frame, so, img);
    const Frame& f = r.frame;
    std::size_t outline = 0;
    for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 64; ++i) {
            bool bordersBackground = false;
            for (auto [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const int u = i + di, v = j + dj;
                if (u >= 0 && v >= 0 && u < 64 && v < 64 && !f.Covered(u, v))
                    bordersBackground = true;
            }
            const bool line = f.Covered(i, j) && bordersBackground;
            outline += line;
            const float v = img.linear[static_cast<std::size_t>(j) * 64 + i];
            EXPECT_EQ(v == 0.5f, line) << i << "," << j;
        }
    EXPECT_EQ(lines, outline);
    EXPECT_GT(outline, 100u);
}

// The render command: --aa, --aa-filter, --edges and --no-shadows are accepted, bad levels are
// usage errors with nothing written.
TEST(Antialias, RenderCommandOptions) {
    const std::string out = ::testing::TempDir() + "/aa_cli.png";
    const std::string scene = SourcePath("examples/machined_part.uq");
    for (const char* opts : {"--aa off", "--aa 4", "--aa 64 --aa-filter mitchell", "--edges",
                             "--no-shadows", "--shadows --aa 16"}) {
        std::remove(out.c_str());
        const CommandResult r =
            RunShell(QuadrixBinary() + " render " + scene + " -o " + out + " --size 64x48 " + opts);
        EXPECT_EQ(r.exitCode, 0) << opts << "\n" << r.err;
        EXPECT_TRUE(FileExists(out)) << opts;
    }
    std::remove(out.c_str());
    const CommandResult bad =
        RunShell(QuadrixBinary() + " render " + scene + " -o " + out + " --aa 8");
    EXPECT_EQ(bad.exitCode, 2) << bad.err;
    EXPECT_NE(bad.err.find("--aa"), std::string::npos) << bad.err;
    EXPECT_FALSE(FileExists(out));
    const CommandResult both =
        RunShell(QuadrixBinary() + " render " + scene + " -o " + out + " --shadows --no-shadows");
    EXPECT_NE(both.exitCode, 0);
}

}  // namespace
}  // namespace quadrix::testing
