// Helpers shared by the engine tests (test code only): a FlatScene from scene text, render it with
// a named engine and engine options, and read a counter from the RenderStats an engine reports.
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <utility>

#include "quadrix/engines/engine.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/pipeline/pipeline.h"

namespace quadrix::testing_util {

// The flat scene of the scene text `text` at w × h pixels (a test failure when it does not read
// and flatten).
inline FlatScene FlatFromText(const std::string& text, int w, int h) {
    PipelineOptions po;
    po.sceneText = text;
    po.width = w;
    po.height = h;
    PipelineResult pr;
    Diagnostics diags;
    EXPECT_TRUE(ReadAndFlatten(po, pr, diags)) << text;
    return pr.flat;
}

// Scene text that includes examples/`name` of the source tree.
inline std::string IncludeExample(const std::string& name) {
    return "include \"" + std::string(QUADRIX_SOURCE_DIR) + "/examples/" + name + "\";\n";
}

// The Frame of `scene` drawn by the engine named `engine` with options `opts` (which the engine
// must accept); its statistics into `stats` when given.
inline Frame RenderWith(const char* engine, const FlatScene& scene, RenderStats* stats = nullptr,
                        std::map<std::string, std::string> opts = {}) {
    auto e = MakeEngine(engine);
    EXPECT_NE(e, nullptr) << engine;
    Frame f;
    if (!e) return f;
    RenderOptions o;
    o.engineOptions = std::move(opts);
    EXPECT_EQ(e->ValidateOptions(o), "");
    RenderStats s = e->Render(scene, o, f);
    if (stats) *stats = s;
    return f;
}

// The value of the counter `name`, or -1 when the engine reports none of that name (counters
// count, so they are never negative).
inline double Counter(const RenderStats& s, const std::string& name) {
    for (const auto& [k, v] : s.counters)
        if (k == name) return v;
    return -1;
}

// Counter, and a test failure when there is no such counter.
inline double CounterOrFail(const RenderStats& s, const std::string& name) {
    const double v = Counter(s, name);
    if (v < 0) ADD_FAILURE() << "no counter " << name;
    return v;
}

}  // namespace quadrix::testing_util
