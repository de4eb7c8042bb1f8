// SampleBatcher (sample_batch.h) against SampleTracer (sample_tracer.h), the definition of a
// sample: at random points of every square of every example and gallery scene, of a perspective
// scene and of a union of many spheres minus a drill, each batch's samples are SampleTracer's,
// bit for bit (depth, normal, surface, body, solid).
#include "quadrix/engines/raycast/sample_batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "quadrix/pipeline/pipeline.h"

namespace quadrix::raycast {
namespace {

FlatScene Load(const PipelineOptions& po) {
    PipelineResult pr;
    Diagnostics diags;
    EXPECT_TRUE(ReadAndFlatten(po, pr, diags));
    return pr.flat;
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every square of side `side` of a w × h image, band by band as the anti-aliasing pass goes: a
// few batches of random points in each (a batch of one point, of a row of points, of up to
// kMaxPoints points spread over the square, and of points crowded near one spot), traced by the
// batcher whether or not SetSquare found a wide node there. `covered`: the number of covered
// samples compared; `wide`: the squares SetSquare said hold a wide node.
void CompareOnScene(const FlatScene& scene, int w, int h, const std::string& name, int side,
                    int& covered, int& wide) {
    const SampleTracer tracer(scene);
    const SampleBatcher batcher(scene, tracer.Tables(), w, h, side);
    SampleBatcher::Scratch scratch(batcher);
    SampleScratch tracerScratch(tracer);
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    covered = wide = 0;
    double xs[SampleBatcher::kMaxPoints], ys[SampleBatcher::kMaxPoints];
    Sample got[SampleBatcher::kMaxPoints];
    for (int y0 = 0; y0 < h; y0 += side) {
        const int y1 = std::min(h, y0 + side);
        batcher.SetBand(y0 / side, scratch);
        for (int x0 = 0; x0 < w; x0 += side) {
            const int x1 = std::min(w, x0 + side);
            wide += batcher.SetSquare({static_cast<double>(x0), static_cast<double>(x1),
                                       static_cast<double>(y0), static_cast<double>(y1)},
                                      scratch);
            for (int kind = 0; kind < 4; ++kind) {
                const int n = kind == 0   ? 1
                              : kind == 1 ? 8
                              : kind == 2 ? SampleBatcher::kMaxPoints
                                          : 16;
                const double cx = x0 + unit(rng) * (x1 - x0), cy = y0 + unit(rng) * (y1 - y0);
                const double rowY = y0 + unit(rng) * (y1 - y0);
                for (int p = 0; p < n; ++p) {
                    if (kind == 3) {  // crowded: within 0.05 pixel of (cx, cy), in the square
                        xs[p] = std::clamp(cx + 0.1 * (unit(rng) - 0.5), double(x0), double(x1));
                        ys[p] = std::clamp(cy + 0.1 * (unit(rng) - 0.5), double(y0), double(y1));
                    } else {
                        xs[p] = x0 + unit(rng) * (x1 - x0);
                        ys[p] = kind == 1 ? rowY : y0 + unit(rng) * (y1 - y0);
                    }
                }
                batcher.Trace(xs, ys, n, got, scratch);
                for (int p = 0; p < n; ++p) {
                    const Sample want = tracer.Trace(xs[p], ys[p], tracerScratch);
                    const Sample& g = got[p];
                    ASSERT_EQ(g.surface, want.surface) << name << " at " << xs[p] << "," << ys[p];
                    ASSERT_EQ(g.body, want.body) << name << " at " << xs[p] << "," << ys[p];
                    ASSERT_EQ(g.solid, want.solid) << name << " at " << xs[p] << "," << ys[p];
                    ASSERT_TRUE(SameBits(g.depth, want.depth))
                        << name << " at " << xs[p] << "," << ys[p] << ": " << g.depth << " vs "
                        << want.depth;
                    ASSERT_TRUE(SameBits(g.normal.x, want.normal.x) &&
                                SameBits(g.normal.y, want.normal.y) &&
                                SameBits(g.normal.z, want.normal.z))
                        << name << " at " << xs[p] << "," << ys[p];
                    covered += want.Covered();
                }
            }
        }
    }
}

TEST(SampleBatch, EqualsSampleTracerOnEveryExample) {
    std::vector<std::string> files;
    for (const char* dir : {"examples", "examples/gallery"})
        for (const auto& e :
             std::filesystem::directory_iterator(std::string(QUADRIX_SOURCE_DIR) + "/" + dir))
            // (*_tubes.uq hold definitions only, drawn by the gallery scene that reads them.)
            if (e.path().extension() == ".uq" && !e.path().stem().string().ends_with("_tubes"))
                files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    ASSERT_GE(files.size(), 12u);
    for (const std::string& f : files) {
        PipelineOptions po;
        po.scenePaths = {f};
        po.width = 96;
        po.height = 72;
        const FlatScene scene = Load(po);
        int covered = 0, wide = 0;
        CompareOnScene(scene, 96, 72, f, 8, covered, wide);
        if (HasFatalFailure()) return;
        EXPECT_GT(covered, 100) << f;
        EXPECT_EQ(wide, 0) << f;  // no union of more than kWideOperands operands
    }
}

TEST(SampleBatch, EqualsSampleTracerUnderPerspectiveAndOnBigUnions) {
    // A perspective view of a CSG part, and 600 spheres unioned minus a drill (a wide union: the
    // engine's depth cuts and bins, the tracer's depth windows and trees).
    std::string spheres = "csg many ((";
    for (int i = 0; i < 600; ++i) {
        spheres += "ball" + std::to_string(i) + (i + 1 < 600 ? " | " : "");
    }
    spheres += ") - drill);\n";
    std::string defs;
    for (int i = 0; i < 600; ++i)
        defs += "solid sphere ball" + std::to_string(i) + " =at " + std::to_string(i % 25 - 12) +
                " " + std::to_string((i / 25) % 6 - 3) + " " + std::to_string(i / 150) +
                " =r .7;\n";
    defs += "solid cylinder drill =from 0 0 -5 =to 0 0 9 =r 2.5;\n";
    const std::string scenes[] = {
        "solid box block =at 0 0 0 =size 4 2 3; solid cylinder hole =from 0 -2 0 =to 0 2 0 "
        "=r .6; solid sphere dome =at 1 1 1 =r 1.2;\n"
        "csg part (block - hole | dome);\n"
        "view eye vrp 0 0 0 cop 6 5 9 whh 3;\n",
        defs + spheres + "view v dop 1 2 3;\n"};
    int k = 0;
    for (const std::string& text : scenes) {
        PipelineOptions po;
        po.sceneText = text;
        po.width = 120;
        po.height = 90;
        const FlatScene scene = Load(po);
        ASSERT_FALSE(scene.solids.empty()) << k;
        int covered = 0, wide = 0;
        CompareOnScene(scene, 120, 90, "scene " + std::to_string(k), 8, covered, wide);
        if (HasFatalFailure()) return;
        EXPECT_GT(covered, 1000) << k;
        if (k == 1) {  // the spheres: squares of both kinds
            EXPECT_GT(wide, 20) << k;
            EXPECT_LT(wide, 15 * 12) << k;
        }
        ++k;
    }
}

}  // namespace
}  // namespace quadrix::raycast
