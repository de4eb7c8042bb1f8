// Timing model of the quadric patch processor: the schedule of seed 000 Table 1.6, computed for
// any word widths, and the time per patch and per frame at the paper's 50 MHz clock.
//
// The clock period is that of one depthBits-wide ripple adder (§1.5.2: a square-root cell "is
// roughly a full adder and a multiplexer ... its computation time is the same as that of an
// adder"). Hence:
//   F2            2 cycles   the EP2's two pipelined half adders
//   SRE           Σ_k ceil(2k / depthBits) for k = 1..rootBits: line k has 2k cells, so the lines
//                 of the second half (more cells than one adder) take two cycles. For 24 bits:
//                 12·1 + 12·2 = 36 cycles, Table 1.6's 2/38.
//   F1            1 cycle, ending with the SRE (37/38)
//   ZF, ZB        1        (38/39)
//   ZP-ZF, ZP-ZB  1        (39/40), holding ZF, ZB
//   Z', ZOUT      1        (40/41), holding Z', ZOUT
//   Multiplier    normalBits cycles, one array row per cycle (41/57), holding ZOUT each cycle
//   NXBASE...     1 cycle, ending with the multiplier (56/57)
//   NXOUT...      1        (57/58), holding ZOUT
// The pipeline latency is 2 + SRE + 3 + normalBits + 1 = 58 cycles for the paper's widths, and
// the extra storage 2 + 2 + normalBits + 1 = 21 depth registers (§1.5.6).
//
// Per patch: the window is scanned at one pixel per clock after the pipeline fills, so a patch
// costs latency + pixels cycles. The RAMs are double-buffered (§1.5.1: one is loaded by the host
// while the other computes), so per frame we give two figures: `cycles` charges the latency to
// every patch (the pipeline drains between patches, the conservative reading), `streamedCycles`
// charges it once (patches follow each other through a full pipeline). The paper gives no
// per-line overhead; the EP line steps are done in the RAMs while the pipeline flows.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "quadrix/engines/patch/fixed_point.h"
#include "quadrix/engines/stats_table.h"

namespace quadrix::patch {

inline constexpr double kPaperClockHz = 50e6;  // seed 000 (the chip "was designed for 50MHz")

struct ScheduleStep {
    int start = 0, end = 0;    // cycles, as in Table 1.6's "Timing" column
    std::string step;          // the step's name as in the paper
    std::string extraStorage;  // what is held while it runs
    int extraRegisters = 0;    // depth registers that holding takes
};

// Table 1.6 for the given widths.
std::vector<ScheduleStep> Schedule(const DatapathWidths& widths);
int SquareRootCycles(const DatapathWidths& widths);
int PipelineLatency(const DatapathWidths& widths);  // 58 for the paper's widths
int ExtraRegisters(const DatapathWidths& widths);   // 21 for the paper's widths

struct FrameTiming {
    std::int64_t patches = 0;
    std::int64_t pixels = 0;          // window pixels scanned, one per clock
    std::int64_t cycles = 0;          // Σ (latency + pixels) over patches
    std::int64_t streamedCycles = 0;  // latency once + Σ pixels
    double clockHz = kPaperClockHz;

    void AddPatch(std::int64_t windowPixels, int latency);
    double Seconds() const { return static_cast<double>(cycles) / clockHz; }
    double StreamedSeconds() const { return static_cast<double>(streamedCycles) / clockHz; }
};

// Table 1.6 for the report (engines/stats_table.h), the latency in its notes.
StatsTable ScheduleTable(const DatapathWidths& widths);

}  // namespace quadrix::patch
