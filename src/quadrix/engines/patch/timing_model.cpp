#include "quadrix/engines/patch/timing_model.h"

#include <fmt/format.h>

namespace quadrix::patch {

int SquareRootCycles(const DatapathWidths& widths) {
    // Line k has 2k cells and one clock covers one adder of depthBits cells (§1.5.2).
    int cycles = 0;
    for (int k = 1; k <= widths.RootBits(); ++k)
        cycles += (2 * k + widths.depthBits - 1) / widths.depthBits;
    return cycles;
}

std::vector<ScheduleStep> Schedule(const DatapathWidths& widths) {
    const int sre = SquareRootCycles(widths);
    const int mul = widths.MultiplierBits();  // one array row per cycle
    std::vector<ScheduleStep> s;
    int t = 0;
    s.push_back({t, t + 2, "F2(x,y)", "", 0});  // two pipelined half adders
    t += 2;
    s.push_back({t, t + sre, "SRE", "", 0});
    t += sre;
    s.push_back({t - 1, t, "F1(x,y)", "", 0});  // ends with the SRE
    s.push_back({t, t + 1, "ZF,ZB", "", 0});
    t += 1;
    s.push_back({t, t + 1, "ZP-ZF,ZP-ZB", "ZF,ZB", 2});
    t += 1;
    s.push_back({t, t + 1, "Z',ZOUT", "Z',ZOUT", 2});
    t += 1;
    s.push_back({t, t + mul, "Multiplier", "ZOUT", mul});  // ZOUT waits one register per cycle
    t += mul;
    s.push_back({t - 1, t, "NXBASE,NYBASE,NZBASE", "", 0});  // ends with the multiplier
    s.push_back({t, t + 1, "NXOUT,NYOUT,NZOUT", "ZOUT", 1});
    return s;
}

int PipelineLatency(const DatapathWidths& widths) { return Schedule(widths).back().end; }

int ExtraRegisters(const DatapathWidths& widths) {
    int n = 0;
    for (const ScheduleStep& step : Schedule(widths)) n += step.extraRegisters;
    return n;
}

void FrameTiming::AddPatch(std::int64_t windowPixels, int latency) {
    if (patches == 0) streamedCycles = latency;
    ++patches;
    pixels += windowPixels;
    cycles += latency + windowPixels;
    streamedCycles += windowPixels;
}

StatsTable ScheduleTable(const DatapathWidths& widths) {
    StatsTable t;
    t.title = fmt::format("Table 1.6 Scheduling (depth {} bits, normals {} bits)", widths.depthBits,
                          widths.normalBits);
    t.columns = {"Timing", "Step", "Extra storage"};
    for (const ScheduleStep& step : Schedule(widths))
        t.rows.push_back({StatsCell::Text(fmt::format("{}/{}", step.start, step.end)),
                          StatsCell::Text(step.step), StatsCell::Text(step.extraStorage)});
    t.notes = {fmt::format("pipeline start-up {} cycles; {} extra registers",
                           PipelineLatency(widths), ExtraRegisters(widths))};
    return t;
}

}  // namespace quadrix::patch
