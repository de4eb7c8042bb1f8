// The fixed-point emulator: bit-exact against the integer reference on random patches, and its
// depth error against the float algorithm, bounded as a function of the word width.
#include "quadrix/engines/patch/patch_processor.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "quadrix/engines/patch/float_engine.h"
#include "quadrix/engines/patch/host_setup.h"
#include "quadrix/engines/patch/integer_reference.h"
#include "quadrix/engines/patch/patch_test_util.h"

namespace quadrix::patch {
namespace {

// A scene of random patches, prepared by the host for `widths` with one depth format.
struct Prepared {
    FlatScene scene;
    std::vector<QuadricPatch> patches;
    std::vector<HostPatch> programs;
    DepthFormat format;
};

Prepared PrepareRandom(std::uint64_t seed, int count, int size, const DatapathWidths& widths) {
    std::mt19937_64 rng(seed);
    testing::SceneBuilder b(size, size);
    for (int k = 0; k < count; ++k) testing::AddRandomPatch(b, rng);
    Prepared out;
    out.scene = b.scene();
    std::vector<HostAnalysis> analyses;
    DepthFormatBuilder fmt;
    for (int body = 0; body < static_cast<int>(out.scene.bodies.size()); ++body) {
        Conversion c = ConvertBody(out.scene, body, CapPolicy::kSkip);
        if (!c.patch) continue;
        HostAnalysis a = AnalyzePatch(*c.patch);
        if (a.empty) continue;
        out.patches.push_back(*c.patch);
        analyses.push_back(a);
        fmt.Add(a);
    }
    out.format = fmt.Build(widths);
    for (std::size_t k = 0; k < out.patches.size(); ++k) {
        std::optional<HostPatch> hp =
            PrepareFixedPatch(out.patches[k], analyses[k], out.format, widths);
        EXPECT_TRUE(hp.has_value()) << "patch " << k << " does not fit its own format";
        if (hp) out.programs.push_back(*hp);
    }
    return out;
}

void ExpectBitExact(const FixedPatch& fp, const DatapathWidths& widths, const char* what) {
    PatchProcessor proc(widths);
    proc.Load(fp);
    std::vector<PixelSignals> line;
    for (int j = 0; j < fp.window.Height(); ++j) {
        proc.ScanLine(line);
        for (int i = 0; i < fp.window.Width(); ++i)
            ASSERT_EQ(line[static_cast<std::size_t>(i)], ReferencePixel(fp, widths, i, j))
                << what << " pixel " << i << "," << j << " widths " << widths.depthBits << "/"
                << widths.normalBits;
    }
}

TEST(PatchProcessor, BitExactWithTheIntegerReferenceOnRandomPatches) {
    // Every pixel of every window, including those where F2 < 0 (the square root of a negative
    // word's bit pattern, wrapped depths: garbage the hardware computes all the same).
    const DatapathWidths configs[] = {{24, 16}, {16, 12}, {30, 22}, {12, 8}};
    int checked = 0;
    for (const DatapathWidths& w : configs) {
        const Prepared p = PrepareRandom(100 + w.depthBits, 8, 28, w);
        for (const HostPatch& hp : p.programs) {
            ExpectBitExact(hp.program, w, "host-prepared");
            ++checked;
        }
    }
    EXPECT_GE(checked, 20);
}

TEST(PatchProcessor, BitExactOnArbitraryWordsThatOverflowEverything) {
    // Random RAM contents: every adder wraps, the plane flags take every combination.
    std::mt19937_64 rng(7);
    const DatapathWidths w{24, 16};
    for (int trial = 0; trial < 12; ++trial) {
        auto word = [&](int bits) {
            return std::uniform_int_distribution<std::int64_t>(MinWord(bits), MaxWord(bits))(rng);
        };
        FixedPatch fp;
        fp.window = {3, 5, 3 + 9, 5 + 7};
        fp.f2 = {word(48), word(48), word(48), word(48), word(48), word(48)};
        fp.f1 = {word(24), word(24), word(24)};
        for (PlaneUnitProgram& u : fp.planes) {
            u.zp = {word(24), word(24), word(24)};
            u.perpendicular = rng() % 3 == 0;
            u.sgnCp = rng() % 2 == 0;
        }
        fp.nxBase = {word(24), word(24), word(24)};
        fp.nyBase = {word(24), word(24), word(24)};
        fp.nzBase = {word(24), word(24), word(24)};
        fp.e = word(16);
        fp.f = word(16);
        fp.twoC = word(16);
        ExpectBitExact(fp, w, "arbitrary");
    }
}

TEST(PatchProcessor, SkippedLinesEqualScannedLines) {
    const DatapathWidths w;
    const Prepared p = PrepareRandom(31, 3, 24, w);
    ASSERT_FALSE(p.programs.empty());
    const FixedPatch& fp = p.programs[0].program;
    PatchProcessor a(w), b(w);
    a.Load(fp);
    b.Load(fp);
    std::vector<PixelSignals> la, lb;
    const int skip = fp.window.Height() / 2;
    for (int j = 0; j < skip; ++j) a.ScanLine(la);
    b.SkipLines(skip);
    a.ScanLine(la);
    b.ScanLine(lb);
    EXPECT_EQ(la, lb);
}

struct ErrorMeasure {
    double maxErrorLsb = 0;   // over pixels where both pick the same sheet
    double maxRelative = 0;   // max error / the format's full depth range
    double maxOverBound = 0;  // max error / DepthErrorBoundLsb
    std::int64_t compared = 0, mismatched = 0, unexplained = 0, pixels = 0;
};

// Emulates every patch and compares with the float algorithm at the same pixels.
ErrorMeasure Measure(const Prepared& p, const DatapathWidths& w) {
    ErrorMeasure m;
    const double range = p.format.ulp * std::ldexp(1.0, w.depthBits);
    for (std::size_t k = 0; k < p.programs.size(); ++k) {
        const FixedPatch& fp = p.programs[k].program;
        const QuadricPatch& qp = p.patches[k];
        const double bound = DepthErrorBoundLsb(fp.window);
        PatchProcessor proc(w);
        proc.Load(fp);
        std::vector<PixelSignals> line;
        const int W = fp.window.Width(), H = fp.window.Height();
        // Float sheets of the window, to tell boundary pixels.
        std::vector<Sheet> sheets(static_cast<std::size_t>(W * H));
        std::vector<FloatPixel> fl(static_cast<std::size_t>(W * H));
        for (int j = 0; j < H; ++j)
            for (int i = 0; i < W; ++i) {
                fl[static_cast<std::size_t>(j * W + i)] =
                    EvaluatePixelFloat(qp, fp.window.x0 + i + 0.5, fp.window.y0 + j + 0.5);
                sheets[static_cast<std::size_t>(j * W + i)] =
                    fl[static_cast<std::size_t>(j * W + i)].sheet;
            }
        auto onBoundary = [&](int i, int j) {
            const Sheet s = sheets[static_cast<std::size_t>(j * W + i)];
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const int ii = i + di, jj = j + dj;
                    if (ii < 0 || jj < 0 || ii >= W || jj >= H) continue;
                    if (sheets[static_cast<std::size_t>(jj * W + ii)] != s) return true;
                }
            return false;
        };
        for (int j = 0; j < H; ++j) {
            proc.ScanLine(line);
            for (int i = 0; i < W; ++i) {
                ++m.pixels;
                const PixelSignals& s = line[static_cast<std::size_t>(i)];
                const FloatPixel& f = fl[static_cast<std::size_t>(j * W + i)];
                const bool drawn = s.zout != Zmax(w);
                const Sheet fixedSheet =
                    !drawn ? Sheet::kNone : (s.ef ? Sheet::kFront : Sheet::kBack);
                if (fixedSheet != f.sheet) {
                    ++m.mismatched;
                    if (!onBoundary(i, j)) ++m.unexplained;
                    continue;
                }
                if (!drawn) continue;
                const double err = std::fabs(p.format.ToDevice(s.zout) - f.zout) / p.format.ulp;
                ++m.compared;
                m.maxErrorLsb = std::max(m.maxErrorLsb, err);
                m.maxRelative = std::max(m.maxRelative, err * p.format.ulp / range);
                m.maxOverBound = std::max(m.maxOverBound, err / bound);
            }
        }
    }
    return m;
}

TEST(PatchProcessor, DepthErrorAgainstFloatShrinksWithTheWordWidth) {
    // Same random scene for every width; the depth error (where both pick the same sheet) stays
    // within the a-priori bound of host_setup.h, and relative to the depth range it falls by at
    // least 4× for every 4 more bits (the quantisation shrinks 16×; factor 4 leaves room for
    // the handful of worst pixels). Coverage/sheet mismatches sit on silhouettes and cut lines.
    double previous = HUGE_VAL;
    for (int d : {12, 16, 20, 24, 28}) {
        const DatapathWidths w{d, std::max(8, d - 8)};
        const Prepared p = PrepareRandom(2024, 6, 32, w);
        ASSERT_GE(p.programs.size(), 4u);
        const ErrorMeasure m = Measure(p, w);
        std::printf(
            "[patch] depth %2d bits: max error %.3f LSB (%.3g of range, %.3f of bound), "
            "%lld compared, %lld sheet/coverage mismatches (%lld off boundaries)\n",
            d, m.maxErrorLsb, m.maxRelative, m.maxOverBound, static_cast<long long>(m.compared),
            static_cast<long long>(m.mismatched), static_cast<long long>(m.unexplained));
        EXPECT_GT(m.compared, 1000);
        EXPECT_LE(m.maxOverBound, 1.0) << d;
        EXPECT_LE(m.maxRelative, previous / 4) << d;
        previous = m.maxRelative;
        if (d >= 20) {
            EXPECT_EQ(m.unexplained, 0) << d;
            EXPECT_LT(m.mismatched, m.pixels / 100) << d;
        }
    }
}

}  // namespace
}  // namespace quadrix::patch
