#include "quadrix/viewer/render_worker.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "test_util.h"

namespace quadrix::viewer {
namespace {

template <class F>
auto WaitFor(F take) {
    for (int i = 0; i < 2000; ++i) {
        if (auto r = take()) return r;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return decltype(take()){};
}

// The render thread reads, draws reduced and full frames of a camera, and on a reload with an
// error keeps the last good scene (and says where the error is); a fixed file is read again.
TEST(ViewerRenderWorker, FramesReloadAndKeepingTheLastGoodScene) {
    testing::TempDir dir;
    const std::string part = dir.Write("part.uq", "quadric ball <1 1 1 0 0 0 0 0 0 -4>;\n");
    const std::string top = dir.Write("top.uq", "read \"part.uq\";\nbody blob <ball>;\n");
    InputRequest in;
    in.paths = {top};
    int wakes = 0;
    RenderWorker worker(in, 1, [&] { ++wakes; });
    LoadOutcome load = worker.Load();
    ASSERT_TRUE(load.ok) << load.messages;
    // Both the top file and the file it reads are watched.
    EXPECT_NE(std::find(load.files.begin(), load.files.end(), part), load.files.end());
    Camera cam;
    SceneSphere sphere;
    ASSERT_EQ(worker.InitialCamera("", 80, 60, cam, sphere), "");
    EXPECT_NEAR(Length(sphere.centre), 0, 1e-9);
    EXPECT_GE(sphere.radius, 2);

    FrameJob job;
    job.view = cam.ToView();
    job.width = 80;
    job.height = 60;
    job.request.scale = 3;
    worker.Submit(job);
    auto reduced = WaitFor([&] { return worker.TakeFrame(); });
    ASSERT_TRUE(reduced);
    EXPECT_EQ(reduced->error, "");
    EXPECT_EQ(reduced->image.width, 27);  // ceil(80 / 3)
    EXPECT_EQ(reduced->image.height, 20);
    EXPECT_GE(wakes, 1);
    job.request.scale = 1;
    const FrameOutcome full = worker.RenderNow(job);
    ASSERT_EQ(full.error, "");
    EXPECT_EQ(full.image.width, 80);
    // The centre pixel is the ball.
    EXPECT_NE(worker.PickText(40, 30).find("body blob half-space ball"), std::string::npos)
        << worker.PickText(40, 30);

    // An error in the read file: the reload fails at its position, the scene stays.
    dir.Write("part.uq", "quadric ball <1 1 1 0 0 0 0 0 0 -4>;\nquadric oops <1 2>;\n");
    worker.ReloadAsync();
    auto bad = WaitFor([&] { return worker.TakeReload(); });
    ASSERT_TRUE(bad);
    EXPECT_FALSE(bad->ok);
    EXPECT_EQ(bad->firstError.rfind(part + ":2:", 0), 0u) << bad->firstError;
    const FrameOutcome still = worker.RenderNow(job);
    ASSERT_EQ(still.error, "");
    EXPECT_EQ(still.image.pixels, full.image.pixels);

    // Fixed: a smaller ball, a different picture.
    dir.Write("part.uq", "quadric ball <1 1 1 0 0 0 0 0 0 -1>;\n");
    worker.ReloadAsync();
    auto good = WaitFor([&] { return worker.TakeReload(); });
    ASSERT_TRUE(good);
    EXPECT_TRUE(good->ok) << good->messages;
    const FrameOutcome changed = worker.RenderNow(job);
    ASSERT_EQ(changed.error, "");
    EXPECT_NE(changed.image.pixels, full.image.pixels);
}

}  // namespace
}  // namespace quadrix::viewer
