// Silicon cost model of the quadric patch processor: seed 000 Tables 1.1-1.7 computed as
// cells × transistors for any word widths. At the paper's widths it reproduces every published
// figure and the total of 225,732 transistors.
//
// Basic cells (Table 1.1, ES2 ECPD15 library), per bit of a w-bit word:
//   register without clear 26, register with clear 32, adder 36, 2-to-1 word multiplexer 14,
//   tristate inverter 8 (a D-latch is the register bit without clear, 26).
// Blocks (d = depthBits, n = normalBits, r = rootBits = d, p = planes = 4):
//   EP1 (Table 1.2)  1 register with clear, 1 adder, 2 multiplexers, 2 tristate inverters (d bits)
//                    + RAM: two buffers of 3 words × d bits.
//   EP2 (Table 1.3)  5 registers with clear, 4 adders, 4 multiplexers, 4 tristate inverters, all
//                    d bits (the 2d-bit words are two pipelined halves: 2 cells × 2 halves of
//                    accumulator and adder, plus the synchronisation register)
//                    + RAM: two buffers of 6 words × 2d bits.
//   RAM              the paper gives 1428 for the EP1's two buffers of 3 × 24 bits (144 bits) and
//                    5712 = 4 × 1428 for the EP2's two buffers of 6 × 48 bits (576 bits): the same
//                    119/12 transistors per stored bit, which confirms the word counts; we keep
//                    that rate for other widths (rounded to the nearest transistor).
//   SRE (Table 1.4)  r(r + 1) cells of 56 (line k has 2k cells) + D-latches: one 2r-bit register
//                    per line (r · 2r) plus the mid-line registers of the lines longer than one
//                    adder (the lines k with 2k > d). The paper gives 1271 for the latter without
//                    derivation ("the pipelining is quite complex"); we count the bits crossing
//                    each mid-line cut (3r + 1: the 2r bits a line passes on, the r low bits of
//                    both the difference and the previous remainder, which the restoring selection
//                    needs until the line's final borrow is known, and that borrow) and scale by
//                    the paper's ratio 1271 / (12 × 73), so the model is exact at 24 bits and
//                    grows with the same structure elsewhere. This is the one calibrated figure.
//   Multiplier       n × n adder cells (36) + n × n D-latches (26) (Table 1.5)
//   Adder-registers  2 (ZF, ZB) + 2p (ZP - ZF, ZP - ZB) + 3 (NXOUT, NYOUT, NZOUT), each a d-bit
//                    adder and a d-bit register without clear
//   Bounding-plane   76 per cutting-plane logic, 46 for the two p-input ANDs and the ZOUT control,
//   logic            and the Z' and ZOUT multiplexers (2 × d-bit multiplexer)
//   Pipelining       (5 + n) extra d-bit registers without clear (timing_model.h)
//   Processor        (p + 4) EP1 (p planes, F1, NXBASE, NYBASE, NZBASE), 1 EP2, 1 SRE,
//   (Table 1.7)      3 multipliers, the adder-registers, the logic, the pipelining registers.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "quadrix/engines/patch/fixed_point.h"
#include "quadrix/engines/stats_table.h"

namespace quadrix::patch {

struct CostLine {
    std::string cell;        // "24-bit adder", "4 multiplexers", ...
    std::int64_t count = 1;  // how many
    std::int64_t unit = 0;   // transistors each
    std::int64_t Total() const { return count * unit; }
    std::optional<std::int64_t> paper;  // the published figure for this line, at the paper's widths
};

struct CostTable {
    std::string title;  // "Table 1.2 EP1 cost"
    std::vector<CostLine> lines;
    std::int64_t Total() const;
    std::optional<std::int64_t> paperTotal;
};

struct CostModel {
    DatapathWidths widths;
    int planes = 4;
    CostTable basicCells;  // 1.1
    CostTable ep1;         // 1.2
    CostTable ep2;         // 1.3
    CostTable sre;         // 1.4
    CostTable multiplier;  // 1.5
    CostTable processor;   // 1.7
    std::int64_t Total() const { return processor.Total(); }
};

inline constexpr std::int64_t kPaperTotalTransistors = 225732;

// Paper figures are attached when widths are the paper's (24/16) and planes == 4.
CostModel ComputeCost(const DatapathWidths& widths, int planes = 4);

// Unrounded structural count of the SRE's mid-line latch bits (before the calibration).
std::int64_t SreMidLineBits(int rootBits, int adderBits);
// The SRE's D-latches: 2r per line plus the calibrated mid-line registers.
std::int64_t SreLatches(int rootBits, int adderBits);

// The tables for the report (engines/stats_table.h), with a "Paper" column where the paper
// gives a figure; the widths in the last table's notes.
std::vector<StatsTable> CostTables(const CostModel& model);

}  // namespace quadrix::patch
