// How a solid's tree is written does not change its picture or its cost (issue 24): the same
// drilled cluster written as ∪ᵢ (ballᵢ − drill) and as (∪ᵢ ballᵢ) − drill flattens to the same
// tree (the walk groups differences that subtract the same body, flatten/hierarchy.h), so every
// engine draws the two with the same bits at every pixel: depth, normal and solid, and surfaces
// and bodies that correspond one to one (the walk numbers them in the order it meets them, which
// differs between the two forms).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "quadrix/engines/registry.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix {
namespace {

// Twelve balls on a ring, each cut by the drill along the ring's axis and by a slot plane.
std::string Cluster(bool distributed) {
    std::string t;
    for (int i = 0; i < 12; ++i) {
        const double a = i * 0.5236;
        t += fmt::format("solid sphere b{} =at {:.6f} {:.6f} 0 =r .9;\n", i, 2 * std::cos(a),
                         2 * std::sin(a));
    }
    t += "solid cylinder drill =from 0 0 -3 =to 0 0 3 =r 1.6;\n";
    t += distributed ? "csg cluster (" : "csg cluster ((";
    for (int i = 0; i < 12; ++i)
        t += distributed ? fmt::format("{}(b{} - drill)", i ? " | " : "", i)
                         : fmt::format("{}b{}", i ? " | " : "", i);
    t += distributed ? ") =c .8 .6 .3;\n" : ") - drill) =c .8 .6 .3;\n";
    t += "view v dop .3 .5 -1;\n";
    return t;
}

struct Rendered {
    Frame frame;
    std::size_t bodies = 0;
};

Rendered Render(const std::string& engine, bool distributed) {
    RenderContext ctx;
    Diagnostics diags;
    InputRequest in;
    in.text = Cluster(distributed);
    in.textName = distributed ? "distributed.uq" : "nested.uq";
    ViewRequest view;
    view.width = 160;
    view.height = 120;
    Rendered r;
    EXPECT_TRUE(ctx.Read(in, diags) && ctx.Flatten(view, diags)) << in.text;
    if (diags.HasErrors()) return r;
    EngineRequest request;
    request.engine = engine;
    RenderReport report;
    EXPECT_TRUE(ctx.Render(request, r.frame, report, diags)) << engine;
    r.bodies = ctx.Flat().bodies.size();
    return r;
}

TEST(TreeForm, DistributedAndNestedDifferencesDrawTheSameBitsWithEveryEngine) {
    for (const EngineInfo& e : Engines()) {
        if (e.hidden) continue;
        SCOPED_TRACE(e.name);
        const Rendered d = Render(e.name, true);
        const Rendered n = Render(e.name, false);
        EXPECT_EQ(d.bodies, 13u);  // twelve balls and one drill
        EXPECT_EQ(n.bodies, 13u);
        ASSERT_EQ(d.frame.width, n.frame.width);
        ASSERT_EQ(d.frame.height, n.frame.height);
        std::size_t covered = 0, drillFaces = 0, differences = 0;
        std::map<int, int> bodyOf, surfaceOf;  // distributed → nested
        for (std::size_t i = 0; i < d.frame.depth.size(); ++i) {
            const bool same = d.frame.depth[i] == n.frame.depth[i] &&
                              d.frame.normal[i] == n.frame.normal[i] &&
                              d.frame.Solid(i) == n.frame.Solid(i);
            if (!same) ++differences;
            if (d.frame.body[i] == Frame::kNone) {
                EXPECT_EQ(n.frame.body[i], Frame::kNone);
                EXPECT_EQ(n.frame.surface[i], d.frame.surface[i]);
                continue;
            }
            ++covered;
            const auto b = bodyOf.emplace(d.frame.body[i], n.frame.body[i]).first;
            const auto s = surfaceOf.emplace(d.frame.surface[i], n.frame.surface[i]).first;
            if (b->second != n.frame.body[i] || s->second != n.frame.surface[i]) ++differences;
            if (n.frame.body[i] == 12) ++drillFaces;  // the nested form's last body
        }
        EXPECT_EQ(differences, 0u);
        // One to one: no two bodies or surfaces of one form are one of the other.
        std::map<int, int> inverse;
        for (const auto& [from, to] : bodyOf) EXPECT_TRUE(inverse.emplace(to, from).second);
        inverse.clear();
        for (const auto& [from, to] : surfaceOf) EXPECT_TRUE(inverse.emplace(to, from).second);
        EXPECT_GT(covered, 2000u);
        EXPECT_GT(drillFaces, 100u) << "the drill's faces are seen inside the ring";
    }
}

}  // namespace
}  // namespace quadrix
