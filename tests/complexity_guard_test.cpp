// Complexity guards of issue 23 item 3 (docs/performance.md "Complexity guards"): scenes whose
// cost once grew superlinearly, checked for the right picture and for the counters that show the
// cost is gone. Times are not asserted (the suite runs on loaded machines); the scenes are sized
// so that the old behaviour would take minutes, the new one well under a second.
#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <new>
#include <string>

#include "quadrix/flatten/bounds.h"
#include "quadrix/flatten/bounds_internal.h"
#include "quadrix/pipeline/render_context.h"
#include "test_util.h"

namespace quadrix {
namespace {

// `n` bodies on one unit ball, unioned.
std::string CoincidentBalls(int n) {
    std::string s = "quadric ball <1 1 1 0 0 0 0 0 0 -1>;\n";
    std::string u;
    for (int i = 0; i < n; ++i) {
        s += "body b" + std::to_string(i) + " (ball);\n";
        u += (i ? " | b" : "b") + std::to_string(i);
    }
    return s + "csg u (" + u + ");\n";
}

std::string Text(const Diagnostics& diags) {
    std::string s;
    for (const Diagnostic& d : diags.Items()) s += d.Format() + "\n";
    return s;
}

struct Rendered {
    Frame frame;
    RenderReport report;
};

Rendered RenderText(const std::string& text, const std::string& engine, int size,
                    std::map<std::string, std::string> options = {}) {
    RenderContext ctx(1);
    Diagnostics diags;
    InputRequest in;
    in.text = text;
    EXPECT_TRUE(ctx.Read(in, diags)) << Text(diags);
    ViewRequest view;
    view.width = view.height = size;
    EXPECT_TRUE(ctx.Flatten(view, diags)) << Text(diags);
    EngineRequest er;
    er.engine = engine;
    er.options = std::move(options);
    Rendered r;
    EXPECT_TRUE(ctx.Render(er, r.frame, r.report, diags)) << Text(diags);
    return r;
}

double Counter(const RenderStats& st, const std::string& name) {
    for (const auto& [k, v] : st.counters)
        if (k == name) return v;
    ADD_FAILURE() << "no counter " << name;
    return -1;
}

// 300 coincident balls: the face stacks would take ~10 s (cubic in the overlap); the guard hands
// the solid to raycast and the picture is raycast's, pixel for pixel.
TEST(ComplexityGuard, ScanlineHandsDeepOverlapToRaycast) {
    const std::string text = CoincidentBalls(300);
    Rendered scan = RenderText(text, "scanline", 48);
    Rendered ray = RenderText(text, "raycast", 48);
    ASSERT_EQ(scan.report.byReference.size(), 1u);
    EXPECT_NE(scan.report.byReference[0].reason.find("max-overlap=64"), std::string::npos)
        << scan.report.byReference[0].reason;
    EXPECT_EQ(Counter(scan.report.stats, "overlap_max_depth"), 300);
    EXPECT_EQ(Counter(scan.report.stats, "overlap_solids_to_raycast"), 1);
    EXPECT_GT(ray.frame.CoveredCount(), 1000u);
    EXPECT_EQ(scan.frame.surface, ray.frame.surface);
    EXPECT_EQ(scan.frame.bodySolid, ray.frame.bodySolid);
    EXPECT_EQ(scan.frame.depth, ray.frame.depth);
}

// Below the limit the scanline engine draws the solid itself (and agrees with raycast on
// coverage), and the option moves the limit.
TEST(ComplexityGuard, ScanlineKeepsModestOverlap) {
    const std::string text = CoincidentBalls(20);
    Rendered scan = RenderText(text, "scanline", 32);
    EXPECT_TRUE(scan.report.byReference.empty());
    EXPECT_EQ(Counter(scan.report.stats, "overlap_max_depth"), 20);
    Rendered ray = RenderText(text, "raycast", 32);
    EXPECT_EQ(scan.frame.CoveredCount(), ray.frame.CoveredCount());
    Rendered low = RenderText(text, "scanline", 32, {{"max-overlap", "19"}});
    EXPECT_EQ(low.report.byReference.size(), 1u);
}

// A body of many literals is bounded over a working set grown by cutting planes
// (bounds_working_set.cpp): the box must be the one the relaxation over every literal certifies.
// Raycast's guard (engines/raycast/work_budget.h): a dense union costs pixels × operands; past
// max-evaluations body evaluations per pixel on average the render is an error naming the limit
// and the union, with no picture, and the decision is the same for any thread count. Just at the
// budget the render passes, with the same picture as without the guard.
TEST(ComplexityGuard, RaycastStopsADenseUnionPastMaxEvaluations) {
    const std::string text = CoincidentBalls(150);
    constexpr int kSize = 32;
    Rendered whole = RenderText(text, "raycast", kSize, {{"max-evaluations", "1000000"}});
    const auto evaluations =
        static_cast<std::uint64_t>(Counter(whole.report.stats, "body_evaluations"));
    const std::uint64_t pixels = kSize * kSize;
    ASSERT_GT(evaluations, 100 * pixels / 2);  // dense: every operand at every covered pixel
    const std::uint64_t enough = (evaluations + pixels - 1) / pixels;  // enough × pixels ≥ all
    for (int threads : {1, 2}) {
        for (std::uint64_t perPixel : {enough - 1, enough}) {
            RenderContext ctx(threads);
            Diagnostics diags;
            InputRequest in;
            in.text = text;
            ASSERT_TRUE(ctx.Read(in, diags)) << Text(diags);
            ViewRequest view;
            view.width = view.height = kSize;
            ASSERT_TRUE(ctx.Flatten(view, diags)) << Text(diags);
            EngineRequest er;
            er.options = {{"max-evaluations", std::to_string(perPixel)}};
            Frame frame;
            RenderReport report;
            const bool ok = ctx.Render(er, frame, report, diags);
            if (perPixel == enough) {
                EXPECT_TRUE(ok) << Text(diags);
                EXPECT_EQ(frame.depth, whole.frame.depth);
                EXPECT_EQ(frame.surface, whole.frame.surface);
            } else {
                EXPECT_FALSE(ok) << "threads " << threads;
                const std::string t = Text(diags);
                EXPECT_NE(t.find("max-evaluations=" + std::to_string(perPixel)), std::string::npos)
                    << t;
                EXPECT_NE(t.find("solid 'u' has 150 operands"), std::string::npos) << t;
            }
        }
    }
}

TEST(ComplexityGuard, WorkingSetBoundsEqualTheFullRelaxation) {
    const int n = 600;
    std::vector<FlatHalfSpace> hs(static_cast<std::size_t>(n));
    hs[0].isPlane = false;
    hs[0].quadric = Quadric::FromCoefficients({1, 1, 1, 0, 0, 0, 0, 0, 0, -1});
    for (int i = 1; i < n; ++i) {
        const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = 2.3999632 * i;
        hs[static_cast<std::size_t>(i)].plane = {r * std::cos(phi), r * std::sin(phi), z, -0.9};
    }
    std::vector<BoundLiteral> lits;
    for (const FlatHalfSpace& h : hs) lits.push_back({&h, false});
    const Box3 box = IntersectionBounds(lits);
    ASSERT_FALSE(box.Empty());
    // The reference: the relaxation over all literals at once.
    std::vector<bounds_detail::InsideFn> fns;
    for (const FlatHalfSpace& h : hs) fns.push_back(bounds_detail::MakeInsideFn(h, false));
    std::vector<const bounds_detail::InsideFn*> ptrs;
    for (const auto& f : fns) ptrs.push_back(&f);
    Box3 all{{-2, -2, -2}, {2, 2, 2}};
    bounds_detail::BoundByConvexRelaxation(ptrs, std::vector<bounds_detail::Nappe>(fns.size()), all,
                                           all, nullptr);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(box.lo[axis], all.lo[axis], 1e-6) << axis;
        EXPECT_NEAR(box.hi[axis], all.hi[axis], 1e-6) << axis;
        // The planes at 0.9 bound the ball: no side reaches the ball's own 1.
        EXPECT_LT(box.hi[axis], 0.99);
        EXPECT_GT(box.hi[axis], 0.85);
    }
}

// oneTBB carries an exception out of a worker to the thread that called parallel_for, so a
// std::bad_alloc in any parallel phase (bounds, engines, shading) reaches the command's top-level
// handler (apps/quadrix/main.cpp: "error: out of memory", exit 1) like one on the main thread.
TEST(ComplexityGuard, BadAllocInATbbWorkerReachesTheCaller) {
    bool caught = false;
    try {
        tbb::parallel_for(tbb::blocked_range<int>(0, 1000, 1),
                          [](const tbb::blocked_range<int>& r) {
                              for (int i = r.begin(); i < r.end(); ++i)
                                  if (i == 777) throw std::bad_alloc();
                          });
    } catch (const std::bad_alloc&) {
        caught = true;
    }
    EXPECT_TRUE(caught);
}

// `quadrix -i < /dev/zero`: the over-long line is an error and the exit status says so.
TEST(ComplexityGuard, InteractiveStdinDevZeroIsAnError) {
    testing::CommandResult r =
        testing::RunShell(testing::QuadrixBinary() + " -i < /dev/zero > /dev/null");
    EXPECT_NE(r.exitCode, 0) << r.err;
    EXPECT_LT(r.exitCode, 128) << r.err;
    EXPECT_NE(r.err.find("cannot read standard input: a line is longer than 256 MiB"),
              std::string::npos)
        << r.err;
}

}  // namespace
}  // namespace quadrix
