// A RenderContext of one thread, or one whose threads were not given running a small job, runs
// its stages inline without oneTBB (util/parallel.h, pipeline/render_context.h), the latter with
// a helper thread for its anti-aliasing (shader.h aaHelperThread); the Frame and the picture are
// bit for bit those of two threads.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "quadrix/frame/frame.h"
#include "quadrix/io/image.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/shade/shader.h"
#include "quadrix/util/parallel.h"
#include "test_util.h"

namespace quadrix {
namespace {

struct InlineRun {
    bool inlineRun = false, inlineInside = false;
    int threads = 0;
    Frame frame;
    Image image;
};

InlineRun RenderMachinedPartWith(int threads, int w, int h) {
    InlineRun out;
    RenderContext ctx(threads);
    Diagnostics diags;
    InputRequest in;
    in.paths = {testing::SourcePath("examples/machined_part.uq")};
    ViewRequest view;
    view.width = w;
    view.height = h;
    EXPECT_TRUE(ctx.Read(in, diags) && ctx.Flatten(view, diags));
    EngineRequest engine;
    engine.engine = "raycast";
    RenderReport report;
    EXPECT_TRUE(ctx.Render(engine, out.frame, report, diags));
    ShadeOptions so;
    so.shadows = true;
    so.aaSamples = 4;  // a small job chosen inline anti-aliases on a helper thread too
    out.image = ctx.Shade(out.frame, so);
    ctx.InArena([&] { out.inlineInside = SerialLoopsOnThisThread(); });
    out.inlineRun = ctx.Inline();
    out.threads = ctx.Threads();
    return out;
}

template <class A>
bool SameBytesInline(const A& a, const A& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]) == 0;
}

void ExpectSameInlineRun(const InlineRun& a, const InlineRun& b) {
    ASSERT_EQ(a.frame.width, b.frame.width);
    ASSERT_EQ(a.frame.height, b.frame.height);
    EXPECT_TRUE(SameBytesInline(a.frame.depth, b.frame.depth));
    EXPECT_TRUE(SameBytesInline(a.frame.normal, b.frame.normal));
    EXPECT_TRUE(SameBytesInline(a.frame.surface, b.frame.surface));
    EXPECT_TRUE(SameBytesInline(a.frame.body, b.frame.body));
    EXPECT_TRUE(SameBytesInline(a.image.pixels, b.image.pixels));
    EXPECT_GT(a.image.pixels.size(), 0u);
}

TEST(InlineContext, OneThreadRunsInlineAndDrawsTheSameAsTwo) {
    const InlineRun one = RenderMachinedPartWith(1, 200, 150);
    const InlineRun two = RenderMachinedPartWith(2, 200, 150);
    EXPECT_TRUE(one.inlineRun);
    EXPECT_TRUE(one.inlineInside);
    EXPECT_EQ(one.threads, 1);
    EXPECT_FALSE(two.inlineRun);
    EXPECT_FALSE(two.inlineInside);
    EXPECT_EQ(two.threads, 2);
    EXPECT_GT(one.frame.CoveredCount(), 5000u);
    ExpectSameInlineRun(one, two);
}

TEST(InlineContext, UnspecifiedThreadsRunASmallJobInlineAndABigOneInTheArena) {
    const InlineRun small = RenderMachinedPartWith(0, 64, 64);
    EXPECT_TRUE(small.inlineRun);
    EXPECT_TRUE(small.inlineInside);
    ExpectSameInlineRun(small, RenderMachinedPartWith(2, 64, 64));
    // 129 × 128 pixels is past the small job's 128 × 128.
    const InlineRun big = RenderMachinedPartWith(0, 129, 128);
    EXPECT_FALSE(big.inlineRun);
    EXPECT_FALSE(big.inlineInside);
    ExpectSameInlineRun(big, RenderMachinedPartWith(1, 129, 128));
}

}  // namespace
}  // namespace quadrix
