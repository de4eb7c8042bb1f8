// The raycast engine's speed-only options (batch, tile-cull, kernel): every combination gives the
// same frame, bit for bit, on the example and gallery scenes in parallel and perspective views, and
// bad option values are refused.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "quadrix/engines/engine.h"
#include "quadrix/engines/engine_test_util.h"
#include "quadrix/engines/raycast/raycast.h"
#include "quadrix/flatten/test_scene_builder.h"
#include "quadrix/frame/compare.h"

namespace quadrix::raycast {
namespace {

using testing_util::Counter;
using testing_util::FlatFromText;
using testing_util::IncludeExample;
using testing_util::RenderWith;

Frame Render(const FlatScene& scene, const std::string& batch, const std::string& cull,
             RenderStats* stats = nullptr, const std::string& kernel = "on") {
    return RenderWith("raycast", scene, stats,
                      {{"batch", batch}, {"tile-cull", cull}, {"kernel", kernel}});
}

TEST(RaycastOptions, SpeedOptionsChangeNoBit) {
    const std::vector<std::string> scenes = {
        IncludeExample("machined_part.uq"),
        IncludeExample("stack_of_bundles.uq"),
        IncludeExample("cylinder_minus_cylinder.uq"),
        IncludeExample("gallery/gear.uq"),
        IncludeExample("gallery/clover_knot.uq"),
        // The machined part in perspective, close enough for strong foreshortening.
        IncludeExample("machined_part.uq") +
            "view close vrp 0 10 0 cop 40 70 -90 =r whh 40 fbp -200 200;\n",
    };
    double flat = 0, empty = 0, batched = 0, kernel = 0;
    for (const std::string& text : scenes) {
        const FlatScene scene = FlatFromText(text, 301, 217);  // not a multiple of the tile sizes
        RenderStats on;
        const Frame reference = Render(scene, "on", "on", &on);
        ASSERT_GT(reference.CoveredCount(), 1000u) << text;
        flat += Counter(on, "flat_pixels");
        empty += Counter(on, "tile_bodies_empty");
        batched += Counter(on, "batched_body_pixels");
        kernel += Counter(on, "kernel_pixels");
        for (const char* batch : {"on", "off"})
            for (const char* cull : {"on", "off"})
                for (const char* kern : {"on", "off"})
                    EXPECT_EQ(
                        FirstBitDifference(Render(scene, batch, cull, nullptr, kern), reference),
                        "")
                        << text << " batch=" << batch << " tile-cull=" << cull
                        << " kernel=" << kern;
    }
    // The fast paths were taken (else this test would compare a path with itself).
    EXPECT_GT(flat, 3000);
    EXPECT_GT(empty, 100);
    EXPECT_GT(batched, 10000);
    EXPECT_GT(kernel, 10000);
}

TEST(RaycastOptions, BadOptionsAreRefused) {
    auto engine = MakeRaycastEngine();
    RenderOptions bad;
    bad.engineOptions = {{"batch", "maybe"}};
    EXPECT_NE(engine->ValidateOptions(bad).find("on or off"), std::string::npos);
    bad.engineOptions = {{"bacth", "on"}};
    EXPECT_NE(engine->ValidateOptions(bad).find("no option 'bacth'"), std::string::npos);
}

}  // namespace
}  // namespace quadrix::raycast
