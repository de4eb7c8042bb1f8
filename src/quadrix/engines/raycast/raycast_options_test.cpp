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
#include "quadrix/pipeline/pipeline.h"

namespace quadrix::raycast {
namespace {

using testing_util::Counter;
using testing_util::RenderWith;

FlatScene Load(const std::string& text, int w, int h) {
    PipelineOptions po;
    po.sceneText = text;
    po.width = w;
    po.height = h;
    PipelineResult pr;
    Diagnostics diags;
    EXPECT_TRUE(ReadAndFlatten(po, pr, diags));
    return pr.flat;
}

std::string Include(const std::string& example) {
    return "include \"" + std::string(QUADRIX_SOURCE_DIR) + "/examples/" + example + "\";\n";
}

Frame Render(const FlatScene& scene, const std::string& batch, const std::string& cull,
             RenderStats* stats = nullptr, const std::string& kernel = "on") {
    return RenderWith("raycast", scene, stats,
                      {{"batch", batch}, {"tile-cull", cull}, {"kernel", kernel}});
}

TEST(RaycastOptions, SpeedOptionsChangeNoBit) {
    const std::vector<std::string> scenes = {
        Include("machined_part.uq"),
        Include("stack_of_bundles.uq"),
        Include("cylinder_minus_cylinder.uq"),
        Include("gallery/gear.uq"),
        Include("gallery/clover_knot.uq"),
        // The machined part in perspective, close enough for strong foreshortening.
        Include("machined_part.uq") +
            "view close vrp 0 10 0 cop 40 70 -90 =r whh 40 fbp -200 200;\n",
    };
    double flat = 0, empty = 0, batched = 0, kernel = 0;
    for (const std::string& text : scenes) {
        const FlatScene scene = Load(text, 301, 217);  // not a multiple of the tile sizes
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
