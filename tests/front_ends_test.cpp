// The three front ends that draw a scene — `quadrix render`, `quadrix uq -d png:FILE` and the
// uq> prompt (`quadrix -i`) — run the same render context (pipeline/render_context.h), so they
// must give byte-identical PNGs for every example, gallery and teapot scene. (Before the render
// context, uq rebuilt the pipeline by hand and drew the teapot scene without its teapot.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_util.h"

namespace quadrix {
namespace {

using quadrix::testing::QuadrixBinary;
using quadrix::testing::RunShell;
using quadrix::testing::SourcePath;
using quadrix::testing::TempDir;

std::string Slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> Scenes() {
    std::vector<std::string> scenes;
    for (const char* dir : {"examples", "examples/gallery"})
        for (const auto& e : std::filesystem::directory_iterator(SourcePath(dir)))
            // *_tubes.uq are definition libraries written by `quadrix pipe` and read by the
            // gallery scene of the same name; they draw nothing on their own.
            if (e.path().extension() == ".uq" &&
                e.path().filename().string().find("_tubes.uq") == std::string::npos)
                scenes.push_back(e.path().string());
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

TEST(FrontEnds, RenderUqAndThePromptGiveByteIdenticalImages) {
    const std::vector<std::string> scenes = Scenes();
    ASSERT_GE(scenes.size(), 10u);
    bool sawTeapot = false;
    for (const std::string& scene : scenes) {
        sawTeapot |= scene.find("teapot") != std::string::npos;
        TempDir dir;
        const std::string a = dir.File("render.png"), b = dir.File("uq.png"),
                          c = dir.File("prompt.png");
        // uq's png device is 512x512 (docs/devices.md), render's default size too. render's own
        // picture defaults (anti-aliasing, shadows from declared lights: docs/shading.md) are
        // switched off: uq and the prompt keep UniQuadrix's one-sample, shadowless picture.
        auto r1 = RunShell(QuadrixBinary() + " render '" + scene + "' -o '" + a +
                           "' --aa off --no-shadows");
        auto r2 = RunShell(QuadrixBinary() + " uq -d 'png:" + b + "' '" + scene + "'");
        auto r3 = RunShell("echo 'show;' | " + QuadrixBinary() + " -i -d 'png:" + c + "' '" +
                           scene + "'");
        ASSERT_EQ(r1.exitCode, 0) << scene << "\n" << r1.err;
        ASSERT_EQ(r2.exitCode, 0) << scene << "\n" << r2.err;
        ASSERT_EQ(r3.exitCode, 0) << scene << "\n" << r3.err;
        const std::string pa = Slurp(a);
        ASSERT_GT(pa.size(), 100u) << scene;
        EXPECT_TRUE(pa == Slurp(b)) << "render and uq differ on " << scene;
        EXPECT_TRUE(pa == Slurp(c)) << "render and the uq> prompt differ on " << scene;
    }
    EXPECT_TRUE(sawTeapot);
}

}  // namespace
}  // namespace quadrix
