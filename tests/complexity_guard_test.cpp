// Complexity guards of issue 23 item 3 (docs/performance.md "Complexity guards"): scenes whose
// cost once grew superlinearly, checked for the right picture and for the counters that show the
// cost is gone. Times are not asserted (the suite runs on loaded machines); the scenes are sized
// so that the old behaviour would take minutes, the new one well under a second.
#include <gtest/gtest.h>

#include <string>

#include "quadrix/pipeline/render_context.h"

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
    EXPECT_EQ(scan.frame.solid, ray.frame.solid);
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

}  // namespace
}  // namespace quadrix
