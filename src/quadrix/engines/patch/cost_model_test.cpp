// The cost model reproduces seed 000 Tables 1.1-1.5 and 1.7 at the paper's widths.
#include "quadrix/engines/patch/cost_model.h"

#include <gtest/gtest.h>

#include "quadrix/pipeline/stats_report.h"

namespace quadrix::patch {
namespace {

void ExpectMatchesPaper(const CostTable& t) {
    for (const CostLine& l : t.lines) {
        ASSERT_TRUE(l.paper.has_value()) << t.title << ": " << l.cell;
        EXPECT_EQ(l.Total(), *l.paper) << t.title << ": " << l.cell;
    }
    if (t.paperTotal) {
        EXPECT_EQ(t.Total(), *t.paperTotal) << t.title;
    }
}

TEST(PatchCost, EveryTableMatchesThePaperAtItsWidths) {
    const CostModel m = ComputeCost(DatapathWidths{});
    for (const CostTable* t : {&m.basicCells, &m.ep1, &m.ep2, &m.sre, &m.multiplier, &m.processor})
        ExpectMatchesPaper(*t);
    EXPECT_EQ(m.ep1.Total(), 4116);
    EXPECT_EQ(m.ep2.Total(), 15120);
    EXPECT_EQ(m.sre.Total(), 96598);
    EXPECT_EQ(m.multiplier.Total(), 15872);
    EXPECT_EQ(m.Total(), kPaperTotalTransistors);
    EXPECT_EQ(m.Total(), 225732);
}

TEST(PatchCost, SquareRootArrayCounts) {
    // n(n + 1) cells (line k has 2k cells): 600 at 24 bits; 2423 D-latches.
    const CostModel m = ComputeCost(DatapathWidths{});
    EXPECT_EQ(m.sre.lines[0].count, 600);
    EXPECT_EQ(SreLatches(24, 24), 2423);
    EXPECT_EQ(SreMidLineBits(24, 24), 12 * 73);
    // No line longer than one adder for a 1-bit root... and the count grows with the width.
    EXPECT_EQ(SreMidLineBits(1, 24), 0);
    EXPECT_LT(SreLatches(16, 16), SreLatches(24, 24));
    EXPECT_LT(SreLatches(24, 24), SreLatches(30, 30));
}

TEST(PatchCost, OtherWidthsScaleAndCarryNoPaperFigures) {
    const CostModel narrow = ComputeCost({16, 12});
    const CostModel wide = ComputeCost({30, 20});
    EXPECT_LT(narrow.Total(), kPaperTotalTransistors);
    EXPECT_GT(wide.Total(), kPaperTotalTransistors);
    EXPECT_FALSE(narrow.processor.paperTotal.has_value());
    for (const CostLine& l : narrow.processor.lines) EXPECT_FALSE(l.paper.has_value());
    // Per-bit cells are linear in the width: a 16-bit adder is 16 × 36.
    EXPECT_EQ(narrow.basicCells.lines[2].Total(), 16 * 36);
    // Multipliers are quadratic in the normal width.
    EXPECT_EQ(narrow.multiplier.Total(), 12 * 12 * (36 + 26));
    // The EP1 RAM rate is the paper's (119/12 per bit): 2 × 3 × 16 bits = 952.
    EXPECT_EQ(narrow.ep1.lines.back().Total(), 952);
    // Fewer planes, fewer EP1s, adder-registers and logic.
    EXPECT_LT(ComputeCost(DatapathWidths{}, 2).Total(), kPaperTotalTransistors);
}

TEST(PatchCost, FormattedTablesShowTheTotalNextToThePaper) {
    const std::vector<StatsTable> tables = CostTables(ComputeCost(DatapathWidths{}));
    ASSERT_EQ(tables.size(), 6u);
    const StatsTable& t = tables.back();
    EXPECT_NE(t.title.find("Table 1.7"), std::string::npos);
    // The TOTAL row: our total next to the paper's.
    const std::vector<StatsCell>& total = t.rows.back();
    EXPECT_EQ(total[0].text, "TOTAL");
    EXPECT_EQ(total[3].integer, 225732);
    EXPECT_EQ(total[4].integer, kPaperTotalTransistors);
    const std::string text = FormatStatsTable(t);
    EXPECT_NE(text.find("225732  225732"), std::string::npos) << text;
}

}  // namespace
}  // namespace quadrix::patch
