// The raycast engine's Workers kept from render to render (worker_pool.h): one engine object
// rendering scenes of different sizes, depths and settings one after the other gives each the
// frame and counters of a fresh engine, bit for bit; a render that finds the pool held, or whose
// loops run inline, has Workers of its own.
#include "quadrix/engines/raycast/worker_pool.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "quadrix/engines/engine.h"
#include "quadrix/engines/engine_test_util.h"
#include "quadrix/engines/raycast/raycast.h"
#include "quadrix/engines/raycast/scene_tables.h"
#include "quadrix/frame/compare.h"
#include "quadrix/util/parallel.h"

namespace quadrix::raycast {
namespace {

using testing_util::FlatFromText;
using testing_util::IncludeExample;

RenderOptions ThreadsAndSpeed(const std::string& batch, const std::string& kernel) {
    RenderOptions o;
    o.threads = 2;
    o.engineOptions = {{"batch", batch}, {"kernel", kernel}};
    return o;
}

TEST(RaycastWorkers, OneEngineGivesEachRenderTheFrameAndCountersOfAFreshEngine) {
    struct Case {
        std::string text;
        int w, h;
        std::string batch = "on", kernel = "on";
    };
    // Small and deep programs in turn (the Workers' lists grow and are then more than needed),
    // sizes that are not multiples of the tiles, and the speed options switched between renders.
    const std::vector<Case> cases = {
        {IncludeExample("machined_part.uq"), 301, 217},
        {IncludeExample("gallery/clover_knot.uq"), 200, 150},
        {IncludeExample("gallery/hilbert3.uq"), 220, 220},
        {IncludeExample("stack_of_bundles.uq"), 333, 250, "off", "on"},
        {IncludeExample("machined_part.uq") +
             "view close vrp 0 10 0 cop 40 70 -90 =r whh 40 fbp -200 200;\n",
         257, 263, "on", "off"},
        {IncludeExample("gallery/gear.uq"), 240, 180},
        {IncludeExample("machined_part.uq"), 301, 217},
    };
    std::unique_ptr<Engine> kept = MakeRaycastEngine();
    for (int round = 0; round < 2; ++round)
        for (const Case& c : cases) {
            const FlatScene scene = FlatFromText(c.text, c.w, c.h);
            const RenderOptions o = ThreadsAndSpeed(c.batch, c.kernel);
            Frame fresh, again;
            const RenderStats freshStats = MakeRaycastEngine()->Render(scene, o, fresh);
            const RenderStats keptStats = kept->Render(scene, o, again);
            ASSERT_GT(fresh.CoveredCount(), 500u) << c.text;
            EXPECT_EQ(FirstBitDifference(again, fresh), "") << c.text;
            ASSERT_EQ(keptStats.counters.size(), freshStats.counters.size());
            for (std::size_t k = 0; k < freshStats.counters.size(); ++k)
                EXPECT_EQ(keptStats.counters[k], freshStats.counters[k]) << c.text;
        }
}

TEST(RaycastWorkers, ARenderFindingThePoolHeldOrRunningInlineHasWorkersOfItsOwn) {
    const FlatScene scene = FlatFromText(IncludeExample("machined_part.uq"), 64, 48);
    const SceneTables tables(scene);
    WorkerPool pool;
    Worker* pooled = nullptr;
    {
        RenderWorkers first(pool, &tables, 4, Settings{});
        pooled = &first.Local();
        EXPECT_EQ(&first.Local(), pooled);  // one per thread
        pooled->counters.blocks = 7;
        RenderWorkers second(pool, &tables, 4, Settings{});  // the pool is held
        EXPECT_NE(&second.Local(), pooled);
        int used = 0;
        first.ForEach([&](const Worker& w) {
            EXPECT_EQ(&w, pooled);
            ++used;
        });
        EXPECT_EQ(used, 1);
    }
    {
        // The pool again, for a deeper program: this thread's Worker, counting from zero.
        RenderWorkers third(pool, &tables, 40, Settings{});
        EXPECT_EQ(&third.Local(), pooled);
        EXPECT_EQ(pooled->counters.blocks, 0u);
    }
    {
        SerialScope inline_;
        RenderWorkers fourth(pool, &tables, 4, Settings{});
        EXPECT_NE(&fourth.Local(), pooled);
    }
    {
        RenderWorkers fifth(pool, &tables, 4, Settings{});  // released by the ones before
        EXPECT_EQ(&fifth.Local(), pooled);
    }
}

}  // namespace
}  // namespace quadrix::raycast
