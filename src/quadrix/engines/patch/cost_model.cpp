#include "quadrix/engines/patch/cost_model.h"

#include <fmt/format.h>

#include "quadrix/engines/patch/timing_model.h"

namespace quadrix::patch {
namespace {

// Table 1.1, transistors per bit.
constexpr std::int64_t kRegisterBit = 26;  // also a D-latch
constexpr std::int64_t kRegisterWithClearBit = 32;
constexpr std::int64_t kAdderBit = 36;
constexpr std::int64_t kMultiplexerBit = 14;
constexpr std::int64_t kTristateBit = 8;
// §1.5.2 and §1.5.5.
constexpr std::int64_t kSreCell = 56;
constexpr std::int64_t kCuttingPlaneLogic = 76;
constexpr std::int64_t kFlagLogic = 46;
// RAM: 1428 transistors for 144 stored bits (Table 1.2), i.e. 119/12 per bit.
std::int64_t RamTransistors(std::int64_t bits) { return (bits * 119 + 6) / 12; }
// The paper's SRE mid-line latches and our structural count at 24 bits (12 cuts × 73 bits).
constexpr std::int64_t kPaperSreExtraLatches = 1271;
constexpr std::int64_t kStructuralMidLineBitsAt24 = 12 * 73;

std::optional<std::int64_t> Paper(bool paperWidths, std::int64_t value) {
    if (!paperWidths) return std::nullopt;
    return value;
}

}  // namespace

std::int64_t CostTable::Total() const {
    std::int64_t t = 0;
    for (const CostLine& l : lines) t += l.Total();
    return t;
}

std::int64_t SreMidLineBits(int rootBits, int adderBits) {
    std::int64_t bits = 0;
    for (int k = 1; k <= rootBits; ++k) {
        const int cycles = (2 * k + adderBits - 1) / adderBits;
        bits += static_cast<std::int64_t>(cycles - 1) * (2 * rootBits + adderBits + 1);
    }
    return bits;
}

std::int64_t SreLatches(int rootBits, int adderBits) {
    const std::int64_t lineRegisters = static_cast<std::int64_t>(rootBits) * 2 * rootBits;
    const std::int64_t mid = SreMidLineBits(rootBits, adderBits);
    const std::int64_t calibrated =
        (mid * kPaperSreExtraLatches + kStructuralMidLineBitsAt24 / 2) / kStructuralMidLineBitsAt24;
    return lineRegisters + calibrated;
}

CostModel ComputeCost(const DatapathWidths& widths, int planes) {
    const std::int64_t d = widths.depthBits;
    const std::int64_t n = widths.normalBits;
    const std::int64_t r = widths.RootBits();
    const std::int64_t p = planes;
    const bool paper = widths == DatapathWidths{} && planes == 4;

    const std::int64_t reg = kRegisterBit * d, regClear = kRegisterWithClearBit * d,
                       adder = kAdderBit * d, mux = kMultiplexerBit * d,
                       tristate = kTristateBit * d;

    CostModel m;
    m.widths = widths;
    m.planes = planes;

    m.basicCells.title = "Table 1.1 Basic cells";
    m.basicCells.lines = {
        {fmt::format("{}-bit register without clear", d), 1, reg, Paper(paper, 624)},
        {fmt::format("{}-bit register with clear", d), 1, regClear, Paper(paper, 768)},
        {fmt::format("{}-bit adder", d), 1, adder, Paper(paper, 864)},
        {fmt::format("{} bit-to-{} bit multiplexer", 2 * d, d), 1, mux, Paper(paper, 336)},
        {fmt::format("{}-bit tristate inverter", d), 1, tristate, Paper(paper, 192)},
    };

    m.ep1.title = "Table 1.2 EP1 cost";
    m.ep1.lines = {
        {fmt::format("{}-bit register with clear", d), 1, regClear, Paper(paper, 768)},
        {fmt::format("{}-bit adder", d), 1, adder, Paper(paper, 864)},
        {"multiplexers", 2, mux, Paper(paper, 672)},
        {"tristate inverters", 2, tristate, Paper(paper, 384)},
        {fmt::format("RAM 2 x 3 words x {} bits", d), 1, RamTransistors(2 * 3 * d),
         Paper(paper, 1428)},
    };
    m.ep1.paperTotal = Paper(paper, 4116);

    m.ep2.title = "Table 1.3 EP2 cost";
    m.ep2.lines = {
        {fmt::format("{}-bit registers with clear", d), 5, regClear, Paper(paper, 3840)},
        {fmt::format("{}-bit adders", d), 4, adder, Paper(paper, 3456)},
        {"multiplexers", 4, mux, Paper(paper, 1344)},
        {"tristate inverters", 4, tristate, Paper(paper, 768)},
        {fmt::format("RAM 2 x 6 words x {} bits", 2 * d), 1, RamTransistors(2 * 6 * 2 * d),
         Paper(paper, 5712)},
    };
    m.ep2.paperTotal = Paper(paper, 15120);

    m.sre.title = "Table 1.4 SRE cost";
    m.sre.lines = {
        {"computation cells", r * (r + 1), kSreCell, Paper(paper, 33600)},
        {"D-latches", SreLatches(static_cast<int>(r), static_cast<int>(d)), kRegisterBit,
         Paper(paper, 62998)},
    };
    m.sre.paperTotal = Paper(paper, 96598);

    m.multiplier.title = "Table 1.5 Multiplier cost";
    m.multiplier.lines = {
        {fmt::format("{}x{} adders", n, n), n * n, kAdderBit, Paper(paper, 9216)},
        {fmt::format("{}x{} D-latches", n, n), n * n, kRegisterBit, Paper(paper, 6656)},
    };
    m.multiplier.paperTotal = Paper(paper, 15872);

    const std::int64_t adderRegisters = 2 + 2 * p + 3;
    const std::int64_t logic = kCuttingPlaneLogic * p + kFlagLogic + 2 * mux;
    const std::int64_t pipelining = ExtraRegisters(widths) * reg;
    m.processor.title = "Table 1.7 Processor cost";
    m.processor.lines = {
        {"EP1", p + 4, m.ep1.Total(), Paper(paper, 32928)},
        {"EP2", 1, m.ep2.Total(), Paper(paper, 15120)},
        {"SRE", 1, m.sre.Total(), Paper(paper, 96598)},
        {"multipliers", 3, m.multiplier.Total(), Paper(paper, 47616)},
        {"adder-registers", adderRegisters, adder + reg, Paper(paper, 19344)},
        {"Bounding-plane logic", 1, logic, Paper(paper, 1022)},
        {"Pipelining registers", 1, pipelining, Paper(paper, 13104)},
    };
    m.processor.paperTotal = Paper(paper, kPaperTotalTransistors);
    return m;
}

namespace {

StatsTable Table(const CostTable& t) {
    using C = StatsCell;
    StatsTable out;
    out.title = t.title;
    out.columns = {"Cell", "Count", "Each", "Total", "Paper"};
    for (const CostLine& l : t.lines)
        out.rows.push_back({C::Text(l.cell), C::Integer(l.count), C::Integer(l.unit),
                            C::Integer(l.Total()), l.paper ? C::Integer(*l.paper) : C::Empty()});
    out.rows.push_back({C::Text("TOTAL"), C::Empty(), C::Empty(), C::Integer(t.Total()),
                        t.paperTotal ? C::Integer(*t.paperTotal) : C::Empty()});
    return out;
}

}  // namespace

std::vector<StatsTable> CostTables(const CostModel& m) {
    std::vector<StatsTable> out;
    for (const CostTable* t : {&m.basicCells, &m.ep1, &m.ep2, &m.sre, &m.multiplier, &m.processor})
        out.push_back(Table(*t));
    out.back().notes = {fmt::format("transistors; depth {} bits, normals {} bits, {} planes",
                                    m.widths.depthBits, m.widths.normalBits, m.planes)};
    return out;
}

}  // namespace quadrix::patch
