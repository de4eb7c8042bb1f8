#include "quadrix/viewer/render_worker.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "quadrix/io/writers.h"
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

// Picks and drawings are asked for and polled, never waited for: a pick answers about the frame
// delivered last, even when the frame after it was cancelled halfway (the Frame is
// double-buffered), and a drawing is written on a thread of its own while frames go on.
TEST(ViewerRenderWorker, AsynchronousPicksAndDrawings) {
    testing::TempDir dir;
    const std::string top =
        dir.Write("top.uq", "quadric ball <1 1 1 0 0 0 0 0 0 -4>;\nbody blob <ball>;\n");
    InputRequest in;
    in.paths = {top};
    RenderWorker worker(in, 1);
    ASSERT_TRUE(worker.Load().ok);
    Camera cam;
    SceneSphere sphere;
    ASSERT_EQ(worker.InitialCamera("", 80, 60, cam, sphere), "");
    // Nothing delivered yet: the pick says so.
    worker.RequestPick(40, 30, 3);
    auto none = WaitFor([&] { return worker.TakePick(); });
    ASSERT_TRUE(none);
    EXPECT_FALSE(none->drawn);
    EXPECT_EQ(none->tag, 3);
    FrameJob job;
    job.view = cam.ToView();
    job.width = 80;
    job.height = 60;
    job.display = true;
    const FrameOutcome full = worker.RenderNow(job);
    ASSERT_EQ(full.error, "");
    EXPECT_EQ(full.display, DisplayPixels(full.image));  // encoded on the render thread
    // 0x00RRGGBB words of the PNG writer's sRGB bytes.
    std::vector<std::uint8_t> rgb = EncodeSrgb8(full.image);
    if (full.image.channels == 1) {
        std::vector<std::uint8_t> grey = rgb;
        rgb.clear();
        for (std::uint8_t v : grey) rgb.insert(rgb.end(), {v, v, v});
    }
    EXPECT_EQ(RgbBytes(full.display), rgb);
    worker.RequestPick(40, 30, 7);
    auto p = WaitFor([&] { return worker.TakePick(); });
    ASSERT_TRUE(p);
    EXPECT_TRUE(p->drawn);
    EXPECT_EQ(p->tag, 7);
    EXPECT_TRUE(p->pick.hit);
    EXPECT_EQ(p->pick.bodyName, "blob");
    // A frame panned so that the ball leaves the centre, cancelled at once: whether it was
    // abandoned or finished, the pick answers about the frame delivered last.
    Camera moved = cam;
    moved.Pan(60, 0, 60);
    job.view = moved.ToView();
    worker.Submit(job);
    worker.CancelFrame();
    auto next = WaitFor([&] { return worker.TakeFrame(); });
    ASSERT_TRUE(next);
    worker.RequestPick(40, 30, 8);
    auto q = WaitFor([&] { return worker.TakePick(); });
    ASSERT_TRUE(q);
    EXPECT_EQ(q->pick.hit, next->cancelled) << "the pick is not of the frame delivered last";
    // The drawing, on its own thread.
    ASSERT_TRUE(worker.StartDrawing(dir.File("a.svg"), cam.ToView(), 80, 60, std::nullopt, "t"));
    auto d = WaitFor([&] { return worker.TakeDrawing(); });
    ASSERT_TRUE(d);
    EXPECT_TRUE(d->ok) << d->messages;
    EXPECT_EQ(d->path, dir.File("a.svg"));
    EXPECT_TRUE(testing::FileExists(dir.File("a.svg")));
    EXPECT_FALSE(worker.DrawingInProgress());
}

}  // namespace
}  // namespace quadrix::viewer
