// Scenes written in the language whose bodies are quadric patches (one quadric, at most four
// transparent planes) render the same with `patch` (float) and `raycast`, through the Reader and
// the Flattener, in a parallel and a perspective view (whose clipping planes the patch
// conversion must absorb: they are transparent and usually redundant).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "quadrix/engines/patch/patch_engine.h"
#include "quadrix/engines/raycast/raycast.h"
#include "quadrix/flatten/flattener.h"
#include "quadrix/frame/compare.h"
#include "quadrix/lang/reader.h"

namespace quadrix {
namespace {

constexpr const char* kPatchScene = R"(
{ A ball cut open by a transparent plane, a hyperboloid waist between two transparent planes,
  a cone cut by a perpendicular-ish plane pair, and an ellipsoid with a complemented plane. }
quadric ball <1 1 1 0 0 0 0 0 0 -4>;
plane cut <1 1 -1 -1> =t;
body cut_ball (ball cut);
quadric waist <1 -1 1 0 0 0 -6 0 0 8>;         { (x-6)^2 - y^2 + z^2 <= 1 }
plane wtop <0 1 0 -2> =t;  plane wbot <0 -1 0 -2> =t;
body hyperboloid (waist wtop wbot);
quadric cone <1 -1 1 0 0 0 6 0 0 9>;           { (x+6)^2 - y^2 + z^2 <= 0 }
plane ctop <0 1 0 -3> =t;  plane cbot <0 1 0 0.5> =t;
body cone_piece (cone ctop !cbot);
quadric egg <0.25 1 1 0 0 0 0 -5 0 24>;        { x^2/4 + (y-5)^2 + z^2 <= 1 }
plane slice <1 0 0 -1> =t;
body egg_piece (egg !slice);
view parallel dop .3 .3 -1;
view persp vrp 0 1 0 cop 4 6 -25;
)";

struct Rendered {
    bool ok = false;
    FlatScene flat;
    Frame patch, ray;
    RenderStats stats;
};

Rendered Render(const std::string& view) {
    Rendered r;
    scene::Scene s;
    Diagnostics diags;
    {
        lang::Reader reader(s, diags);
        reader.ReadText(kPatchScene, "<patch scene>");
    }
    EXPECT_FALSE(diags.HasErrors());
    FlattenOptions fo;
    fo.width = fo.height = 96;
    fo.viewName = view;
    std::optional<FlatScene> flat = Flatten(s, fo, diags);
    if (!flat) return r;
    r.ok = true;
    r.flat = *flat;
    r.stats = MakePatchEngine()->Render(r.flat, RenderOptions{}, r.patch);
    MakeRaycastEngine()->Render(r.flat, RenderOptions{}, r.ray);
    return r;
}

// patch against raycast through the one comparison (frame/compare.h): pixels agree when both
// the surface and the body are the same; there, depths within 1e-6 of raycast's depth range and
// normals within acos(1 - 1e-6) (unit normals whose dot product exceeds 1 - 1e-6).
void ExpectAgreement(const Rendered& r) {
    ASSERT_GT(r.ray.CoveredCount(), 500u);
    const FrameComparison c = CompareFrames(r.patch, r.ray);
    const std::uint64_t differ = c.SurfaceMismatches() + c.sameSurfaceOtherBody;
    const std::uint64_t agree = c.sameSurface - c.sameSurfaceOtherBody;
    EXPECT_LE(c.maxDepthError, 1e-6 * c.referenceDepthRange) << c.Summary();
    EXPECT_LT(c.maxNormalErrorDegrees, std::acos(1 - 1e-6) * 180 / M_PI) << c.Summary();
    double dropped = 0;
    for (const auto& [k, v] : r.stats.counters)
        if (k == "redundant planes dropped") dropped = v;
    std::printf("[patch] scene: %llu pixels agree, %llu differ, %g redundant planes dropped\n",
                static_cast<unsigned long long>(agree), static_cast<unsigned long long>(differ),
                dropped);
    EXPECT_LT(differ, agree / 50);  // silhouette pixels only
}

TEST(PatchScene, LanguageScenesOfPatchesAgreeWithRaycast) {
    for (const std::string view : {"parallel", "persp"}) {
        const Rendered r = Render(view);
        if (!r.ok) GTEST_SKIP() << "the Flattener cannot flatten this scene yet";
        double patches = 0;
        for (const auto& [k, v] : r.stats.counters)
            if (k == "patches") patches = v;
        EXPECT_EQ(patches, 4) << r.stats.report;
        ExpectAgreement(r);
    }
}

}  // namespace
}  // namespace quadrix
