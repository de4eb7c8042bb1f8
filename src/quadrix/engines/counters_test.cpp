#include "quadrix/engines/counters.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "quadrix/engines/patch/counters.h"
#include "quadrix/engines/patch/patch.h"
#include "quadrix/engines/registry.h"
#include "quadrix/engines/scanline/counters.h"
#include "quadrix/engines/scanline/resolver.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix {
namespace {

TEST(EngineCounters, EveryEngineDeclaresUniqueNamedCountersWithMeanings) {
    for (const EngineInfo& e : Engines()) {
        if (e.hidden) continue;
        EXPECT_FALSE(e.counters.empty()) << e.name;
        std::set<std::string> names;
        for (const CounterDecl& c : e.counters) {
            EXPECT_TRUE(names.insert(c.name).second)
                << e.name << " declares " << c.name << " twice";
            EXPECT_GT(std::string(c.meaning).size(), 5u) << e.name << ": " << c.name;
            // Never a composition counter: the report puts those first, once.
            EXPECT_FALSE(IsDeclared(kCompositionCounters, c.name)) << e.name << ": " << c.name;
        }
    }
}

TEST(EngineCounters, ValuesAreReportedInTheDeclaredOrderAndOnlyWhenSet) {
    static constexpr CounterDecl kDecls[] = {
        {"a", "first one"}, {"b", "second one"}, {"c", "third one"}};
    CounterValues values(kDecls);
    values.Set(2, 7u);
    values.Set(0, 1.5);
    std::vector<std::pair<std::string, double>> out;
    values.AppendTo(out);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].first, "a");
    EXPECT_EQ(out[0].second, 1.5);
    EXPECT_EQ(out[1].first, "c");
    EXPECT_EQ(out[1].second, 7.0);
    EXPECT_TRUE(IsDeclared(kDecls, "b"));
    EXPECT_FALSE(IsDeclared(kDecls, "d"));
}

// The rows the engines index by type carry the names the types print.
TEST(EngineCounters, IndexedRowsMatchTheirTypeNames) {
    for (std::size_t t = 0; t < 6; ++t) {
        EXPECT_EQ(std::string(scanline::kScanlineCounters[scanline::kIlinesNoexist + t].name),
                  std::string("ilines_") + scanline::ToString(static_cast<scanline::ILineType>(t)));
    }
    for (std::size_t t = 0; t < 4; ++t) {
        EXPECT_EQ(
            std::string(scanline::kScanlineCounters[scanline::kIverticesHextrm + t].name),
            std::string("ivertices_") + scanline::ToString(static_cast<scanline::IVertexType>(t)));
    }
    const auto first = static_cast<std::size_t>(patch::Rejection::kEmpty);
    for (std::size_t r = first; r <= static_cast<std::size_t>(patch::Rejection::kMalformed); ++r) {
        EXPECT_EQ(std::string(patch::kPatchCounters[patch::kSkippedEmpty + (r - first)].name),
                  "bodies skipped: " +
                      std::string(patch::RejectionName(static_cast<patch::Rejection>(r))));
    }
}

}  // namespace
}  // namespace quadrix
