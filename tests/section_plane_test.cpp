// The section plane (FlattenOptions::section, ViewRequest::section; docs/viewer.md): one opaque
// plane literal added to every body at flatten time, so the cut faces are the plane's own and
// every engine draws them. Checked analytically on raycast (a sphere cut through its centre shows
// a disc of the plane, facing the viewer, at the plane's depth; the window is that of the uncut
// scene), then every registered engine against raycast on cut CSG, as all_engines_test does.
#include "quadrix/pipeline/section_plane.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "quadrix/engines/registry.h"
#include "quadrix/flatten/flattener.h"
#include "quadrix/frame/compare.h"
#include "quadrix/pipeline/render_context.h"
#include "test_util.h"

namespace quadrix {
namespace {

ViewRequest Sized(int w, int h, std::optional<Plane> section) {
    ViewRequest v;
    v.width = w;
    v.height = h;
    v.section = section;
    return v;
}

bool RenderScene(RenderContext& ctx, const std::string& text, const ViewRequest& view,
                 const std::string& engine, Frame& frame) {
    Diagnostics diags;
    InputRequest in;
    in.text = text;
    if (!ctx.Read(in, diags) || !ctx.Flatten(view, diags)) return false;
    EngineRequest e;
    e.engine = engine;
    RenderReport report;
    return ctx.Render(e, frame, report, diags) && !diags.HasErrors();
}

TEST(SectionPlane, CutsASphereThroughItsCentreWithAFlatFaceTowardTheViewer) {
    // Seen from -z (the front view), keeping z >= 0: the near half is cut away and the cut is
    // the disc x² + y² <= 1 of the plane z = 0, its normal toward the viewer (-z).
    const std::string scene = "solid sphere ball =at 0 0 0 =r 1; view front dop 0 0 -1;";
    RenderContext whole, cut;
    Frame a, b;
    ASSERT_TRUE(RenderScene(whole, scene, Sized(101, 101, std::nullopt), "raycast", a));
    ASSERT_TRUE(RenderScene(cut, scene, Sized(101, 101, Plane{0, 0, -1, 0}), "raycast", b));
    // The window is that of the uncut sphere (the section does not change the fit).
    const Mat4& ma = whole.Flat().projection.deviceFromWorld.Matrix();
    const Mat4& mb = cut.Flat().projection.deviceFromWorld.Matrix();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_EQ(ma(i, j), mb(i, j));
    const FlatScene& flat = cut.Flat();
    int section = -1;
    for (std::size_t i = 0; i < flat.halfSpaces.size(); ++i)
        if (flat.halfSpaces[i].name == kSectionName) section = static_cast<int>(i);
    ASSERT_GE(section, 0);
    EXPECT_FALSE(flat.halfSpaces[static_cast<std::size_t>(section)].transparent);
    const Vec3 centre = mb.MapPoint(Vec3{0, 0, 0});
    const double radius = mb.MapPoint(Vec3{1, 0, 0}).x - centre.x;  // pixels
    ASSERT_GT(radius, 40);
    int inside = 0;
    for (int y = 0; y < flat.height; ++y)
        for (int x = 0; x < flat.width; ++x) {
            const double r = std::hypot(x + 0.5 - centre.x, y + 0.5 - centre.y);
            if (std::fabs(r - radius) < 1) continue;  // the rim may go either way
            const std::size_t i = b.Index(x, y);
            EXPECT_EQ(b.Solid(i) != Frame::kNone, r < radius) << x << " " << y;
            EXPECT_EQ(a.Solid(i) != Frame::kNone, r < radius) << x << " " << y;
            if (r >= radius) continue;
            ++inside;
            EXPECT_EQ(b.surface[i], section);
            EXPECT_NEAR(b.depth[i], centre.z, 1e-9 * flat.width);
            EXPECT_NEAR(b.Normal(i).z, -1, 1e-12);
            EXPECT_LT(a.depth[i], b.depth[i]);  // the uncut sphere is nearer
        }
    EXPECT_GT(inside, 5000);
}

TEST(SectionPlane, BadPlanesAreErrors) {
    RenderContext ctx;
    Diagnostics diags;
    InputRequest in;
    in.text = "solid sphere ball =at 0 0 0 =r 1;";
    ASSERT_TRUE(ctx.Read(in, diags));
    EXPECT_FALSE(ctx.Flatten(Sized(16, 16, Plane{0, 0, 0, 1}), diags));
    EXPECT_NE(diags.Items().back().message.find("section plane"), std::string::npos);
    Plane p;
    EXPECT_NE(ParseSectionPlane("1 2 3", p), "");
    EXPECT_NE(ParseSectionPlane("1 2 3 x", p), "");
    EXPECT_NE(ParseSectionPlane("0 0 0 1", p), "");
    ASSERT_EQ(ParseSectionPlane("0.1, -2e-3 3 4", p), "");
    EXPECT_EQ(p, (Plane{0.1, -2e-3, 3, 4}));
    // 17 digits: the text gives the same doubles back.
    const Plane q{1.0 / 3, -std::sqrt(2.0), 1e-300, 12345.678901234567};
    Plane back;
    ASSERT_EQ(ParseSectionPlane(FormatSectionPlane(q), back), "");
    EXPECT_EQ(back, q);
}

struct Cut {
    std::string name, text;
    Plane plane;
};

const std::vector<Cut>& Cuts() {
    // Each plane keeps the side away from the eye, so that the cut faces look at it.
    static const std::vector<Cut> kCuts{
        {"drilled_block_oblique",
         "solid box block =from -1 -1 -1 =to 1 1 1;\n"
         "solid cylinder drill =from 0 -2 0 =to 0 2 0 =r .5;\n"
         "csg drilled (block - drill); view front dop .4 .5 -1;",
         Plane{0.3, 0.2, -1, 0.1}},
        {"union_perspective",
         "solid sphere ball =at 0 0 0 =r 1.2; solid cylinder rod =from -2 0 0 =to 2 0 0 =r .4;\n"
         "csg joined (ball | rod); view eye vrp 0 0 0 cop 3 2.5 -4;",
         Plane{0.5, 0, -1, -0.2}},
        {"machined_part",
         "read \"" + quadrix::testing::SourcePath("examples/machined_part.uq") + "\";",
         Plane{0, 0, -1, 0}},
    };
    return kCuts;
}

struct Case {
    std::string engine, cut;
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.engine << " on " << c.cut; }

std::vector<Case> Cases() {
    std::vector<Case> cases;
    for (const EngineInfo& e : Engines())
        if (!e.hidden)
            for (const Cut& c : Cuts()) cases.push_back({e.name, c.name});
    return cases;
}

class SectionAllEngines : public ::testing::TestWithParam<Case> {};

TEST_P(SectionAllEngines, MatchesRaycast) {
    const Case& c = GetParam();
    const Cut* cut = nullptr;
    for (const Cut& k : Cuts())
        if (k.name == c.cut) cut = &k;
    ASSERT_NE(cut, nullptr);
    RenderContext ctx;
    Frame reference, got;
    ASSERT_TRUE(RenderScene(ctx, cut->text, Sized(120, 90, cut->plane), "raycast", reference));
    ASSERT_TRUE(RenderScene(ctx, cut->text, Sized(120, 90, cut->plane), c.engine, got)) << c.engine;
    // The section shows: some pixels are the plane's.
    int section = -1;
    for (std::size_t i = 0; i < ctx.Flat().halfSpaces.size(); ++i)
        if (ctx.Flat().halfSpaces[i].name == kSectionName) section = static_cast<int>(i);
    std::size_t onPlane = 0;
    for (int s : reference.surface) onPlane += s == section;
    EXPECT_GT(onPlane, 100u) << "the cut face must be visible";
    const FrameComparison cmp = CompareFrames(got, reference, {});
    EXPECT_EQ(cmp.offEdgeDifferences, 0u) << cmp.firstDifference << "\n" << cmp.Summary();
    EXPECT_LE(cmp.maxDepthError, 1e-6 * 120) << cmp.Summary();
}

INSTANTIATE_TEST_SUITE_P(Cuts, SectionAllEngines, ::testing::ValuesIn(Cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                             std::string n = info.param.engine + "_" + info.param.cut;
                             for (char& ch : n)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return n;
                         });

}  // namespace
}  // namespace quadrix
