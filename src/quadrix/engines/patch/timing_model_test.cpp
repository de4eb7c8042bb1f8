// The schedule of seed 000 Table 1.6 and the time per frame.
#include "quadrix/engines/patch/timing_model.h"

#include <gtest/gtest.h>

#include "quadrix/pipeline/stats_report.h"

namespace quadrix::patch {
namespace {

TEST(PatchTiming, ScheduleIsTableOneSix) {
    struct Row {
        int start, end;
        const char* step;
        const char* storage;
    };
    const Row paper[] = {{0, 2, "F2(x,y)", ""},
                         {2, 38, "SRE", ""},
                         {37, 38, "F1(x,y)", ""},
                         {38, 39, "ZF,ZB", ""},
                         {39, 40, "ZP-ZF,ZP-ZB", "ZF,ZB"},
                         {40, 41, "Z',ZOUT", "Z',ZOUT"},
                         {41, 57, "Multiplier", "ZOUT"},
                         {56, 57, "NXBASE,NYBASE,NZBASE", ""},
                         {57, 58, "NXOUT,NYOUT,NZOUT", "ZOUT"}};
    const std::vector<ScheduleStep> s = Schedule(DatapathWidths{});
    ASSERT_EQ(s.size(), std::size(paper));
    for (std::size_t k = 0; k < s.size(); ++k) {
        EXPECT_EQ(s[k].start, paper[k].start) << paper[k].step;
        EXPECT_EQ(s[k].end, paper[k].end) << paper[k].step;
        EXPECT_EQ(s[k].step, paper[k].step);
        EXPECT_EQ(s[k].extraStorage, paper[k].storage);
    }
    EXPECT_EQ(SquareRootCycles(DatapathWidths{}), 36);
    EXPECT_EQ(PipelineLatency(DatapathWidths{}), 58);
    EXPECT_EQ(ExtraRegisters(DatapathWidths{}), 21);  // 2 + 2 + 16 + 1 (§1.5.6)
}

TEST(PatchTiming, LatencyFollowsTheWidths) {
    // 16-bit depths: 8 one-cycle lines and 8 two-cycle lines; 12-bit multiplier.
    const DatapathWidths w{16, 12};
    EXPECT_EQ(SquareRootCycles(w), 24);
    EXPECT_EQ(PipelineLatency(w), 2 + 24 + 3 + 12 + 1);
    EXPECT_EQ(ExtraRegisters(w), 5 + 12);
}

TEST(PatchTiming, FrameTimeAtFiftyMegahertz) {
    FrameTiming t;
    t.AddPatch(1000, 58);
    t.AddPatch(500, 58);
    EXPECT_EQ(t.patches, 2);
    EXPECT_EQ(t.pixels, 1500);
    EXPECT_EQ(t.cycles, 1500 + 2 * 58);
    EXPECT_EQ(t.streamedCycles, 1500 + 58);
    EXPECT_DOUBLE_EQ(t.Seconds(), (1500 + 116) / 50e6);
    const std::string text = FormatStatsTable(ScheduleTable(DatapathWidths{}));
    EXPECT_NE(text.find("41/57"), std::string::npos) << text;
    EXPECT_NE(text.find("start-up 58 cycles"), std::string::npos) << text;
}

}  // namespace
}  // namespace quadrix::patch
