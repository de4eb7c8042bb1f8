// Cancelling a frame (pipeline/cancellation.h) through the render context: a cancelled Render
// returns false with report.cancelled and no error; cancelled mid-frame from another thread, every
// engine stops without harm, and the next frame (after Reset) is the same as a fresh render's.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "quadrix/engines/registry.h"
#include "quadrix/pipeline/render_context.h"
#include "test_util.h"

namespace quadrix {
namespace {

const char* kScene =
    "solid box block =from -1 -1 -1 =to 1 1 1;\n"
    "solid cylinder drill =from 0 -2 0 =to 0 2 0 =r .5;\n"
    "solid sphere ball =at 1 1 -1 =r .6;\n"
    "csg part ((block - drill) | ball); view front dop .4 .5 -1;";

bool ReadAndFlatten(RenderContext& ctx, int w, int h) {
    Diagnostics diags;
    InputRequest in;
    in.text = kScene;
    ViewRequest v;
    v.width = w;
    v.height = h;
    return ctx.Read(in, diags) && ctx.Flatten(v, diags);
}

TEST(RenderCancel, CancelledBeforeTheFrameDrawsNothingAndIsNoError) {
    Cancellation cancel;
    RenderContext ctx(2);
    ctx.SetCancellation(&cancel);
    ASSERT_TRUE(ReadAndFlatten(ctx, 64, 48));
    cancel.Cancel();
    Frame frame;
    RenderReport report;
    Diagnostics diags;
    EngineRequest e;
    EXPECT_FALSE(ctx.Render(e, frame, report, diags));
    EXPECT_TRUE(report.cancelled);
    EXPECT_FALSE(diags.HasErrors());
    cancel.Reset();
    report = {};
    EXPECT_TRUE(ctx.Render(e, frame, report, diags));
    EXPECT_FALSE(report.cancelled);
    EXPECT_GT(frame.CoveredCount(), 500u);
}

TEST(RenderCancel, EveryEngineStopsMidFrameAndTheNextFrameIsWhole) {
    for (const EngineInfo& info : Engines()) {
        if (info.hidden) continue;
        RenderContext fresh(2);
        ASSERT_TRUE(ReadAndFlatten(fresh, 320, 240));
        Frame expected;
        RenderReport report;
        Diagnostics diags;
        EngineRequest e;
        e.engine = info.name;
        ASSERT_TRUE(fresh.Render(e, expected, report, diags)) << info.name;

        Cancellation cancel;
        RenderContext ctx(2);
        ctx.SetCancellation(&cancel);
        ASSERT_TRUE(ReadAndFlatten(ctx, 320, 240));
        Frame frame;
        // Cancelled at several moments of the frame: before it starts, early, later.
        for (int delayUs : {0, 200, 2000}) {
            cancel.Reset();
            std::thread canceller([&] {
                std::this_thread::sleep_for(std::chrono::microseconds(delayUs));
                cancel.Cancel();
            });
            report = {};
            const bool done = ctx.Render(e, frame, report, diags);
            canceller.join();
            EXPECT_EQ(done, !report.cancelled) << info.name;
            EXPECT_FALSE(diags.HasErrors()) << info.name;
        }
        cancel.Reset();
        report = {};
        ASSERT_TRUE(ctx.Render(e, frame, report, diags)) << info.name;
        EXPECT_EQ(frame.depth, expected.depth) << info.name;
        EXPECT_EQ(frame.surface, expected.surface) << info.name;
        EXPECT_EQ(frame.bodySolid, expected.bodySolid) << info.name;
    }
}

}  // namespace
}  // namespace quadrix
