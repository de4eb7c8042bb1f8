// `quadrix export` takes render's scene and view options (issue 20 §6; SceneViewArgs in
// apps/quadrix/commands.h, one option table for both): a BRL-CAD sample exported with --top and
// --az/--el, rendered by POV-Ray, covers the pixels our render of the same options covers (away
// from ±1 px of silhouettes), and --top really selects. (The die sample is not used: through its
// pips POV-Ray finds surfaces on coincident sphere boundaries that raycast does not: 7 px.)
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "quadrix/pipeline/pipeline.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

const char* kSample = "/work/shared/data/brlcad/operators.asc";

std::string Slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(ExportViews, TopAndAzElAsRender) {
    if (!HaveProgram("povray")) GTEST_SKIP() << "povray is not installed";
    if (!FileExists(kSample)) GTEST_SKIP() << kSample << " (shared BRL-CAD samples) is absent";
    TempDir dir;
    const int w = 96, h = 80;
    CommandResult e = RunShell(fmt::format(
        "{} export --to pov --mask '{}' --top subtraction --az 40 --el 30 --size {}x{} -o '{}'",
        QuadrixBinary(), kSample, w, h, dir.File("s.pov")));
    ASSERT_EQ(e.exitCode, 0) << e.err;
    // --top selects: the whole model ("operators", four columns of examples) is a larger export.
    CommandResult all = RunShell(fmt::format(
        "{} export --to pov --mask '{}' --top operators --az 40 --el 30 --size {}x{} -o '{}'",
        QuadrixBinary(), kSample, w, h, dir.File("all.pov")));
    ASSERT_EQ(all.exitCode, 0) << all.err;
    EXPECT_LT(Slurp(dir.File("s.pov")).size() * 2, Slurp(dir.File("all.pov")).size());
    CommandResult p = RunShell(fmt::format(
        "cd '{}' && povray +Is.pov +Os.ppm +W{} +H{} -A +FP -D -V -GA +WT1", dir.path(), w, h));
    ASSERT_EQ(p.exitCode, 0) << p.err;
    Image img;
    ASSERT_TRUE(ReadPnm(dir.File("s.ppm"), img));
    ASSERT_EQ(img.width, w);
    ASSERT_EQ(img.height, h);

    PipelineOptions o;
    o.scenePaths = {kSample};
    o.topObjects = {"subtraction"};
    o.azimuth = 40;
    o.elevation = 30;
    o.width = w;
    o.height = h;
    PipelineResult r;
    Diagnostics d;
    ASSERT_TRUE(RunPipeline(o, r, d));
    const Frame& f = r.frame;
    auto boundary = [&](int x, int y) {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int u = x + dx, v = y + dy;
                if (u < 0 || v < 0 || u >= w || v >= h) continue;
                if (f.surface[f.Index(u, v)] != f.surface[f.Index(x, y)]) return true;
            }
        return false;
    };
    long covered = 0, interior = 0, edge = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            covered += f.Covered(x, y);
            if ((img.At(x, y)[0] > 127) == f.Covered(x, y)) continue;
            if (boundary(x, y))
                ++edge;
            else
                ++interior;
        }
    EXPECT_GT(covered, w * h / 6);  // the fitted view fills the picture
    EXPECT_EQ(interior, 0) << "edge mismatches " << edge << " of " << covered;
    EXPECT_LE(edge, covered / 50);

    // The same options are refused alike: --view with --az is a usage error for both.
    for (const char* cmd : {"export --to pov", "render"}) {
        CommandResult bad =
            RunShell(fmt::format("{} {} '{}' --view x --az 10 -o '{}'", QuadrixBinary(), cmd,
                                 kSample, dir.File("bad.png")));
        EXPECT_EQ(bad.exitCode, 2) << cmd;
        EXPECT_NE(bad.err.find("--view cannot be combined with --az/--el"), std::string::npos)
            << bad.err;
        EXPECT_FALSE(FileExists(dir.File("bad.png")));
    }
}

}  // namespace
}  // namespace quadrix::testing
