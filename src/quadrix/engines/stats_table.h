// A table of an engine's statistics laid out like one of its paper's: scanline's Tables 7.1–7.3
// (seed 001), Pixel-Powers' Table 1 (seed 004), the patch processor's Tables 1.2–1.7 (seed 000).
//
// Engines fill the cells and never format them: the report (pipeline/stats_report.h) prints
// every engine's tables the same way — aligned columns, text to the left, numbers to the right —
// under --stats, and as {"title", "columns", "rows", "notes"} objects under --stats --json, where
// a number stays a number. A cell is text, an integer or a real with a fixed number of decimals
// (and an optional unit printed after it), so that the text layout and the JSON value come from
// the same cell.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace quadrix {

struct StatsCell {
    enum class Kind { kEmpty, kText, kInteger, kReal };
    Kind kind = Kind::kEmpty;
    std::string text;          // kText
    std::int64_t integer = 0;  // kInteger
    double real = 0;           // kReal
    int decimals = 2;          // kReal: digits after the point in the text layout
    std::string unit;          // printed after the number ("msec"); not part of the JSON value

    static StatsCell Text(std::string s) {
        StatsCell c;
        c.kind = Kind::kText;
        c.text = std::move(s);
        return c;
    }
    template <class Int>
    static StatsCell Integer(Int v) {
        StatsCell c;
        c.kind = Kind::kInteger;
        c.integer = static_cast<std::int64_t>(v);
        return c;
    }
    static StatsCell Real(double v, int decimals, std::string unit = {}) {
        StatsCell c;
        c.kind = Kind::kReal;
        c.real = v;
        c.decimals = decimals;
        c.unit = std::move(unit);
        return c;
    }
    static StatsCell Empty() { return {}; }
};

struct StatsTable {
    std::string title;                         // "Table 7.1 - Resolver statistics"
    std::vector<std::string> columns;          // one header per column; '\n' splits it in lines
    std::vector<std::vector<StatsCell>> rows;  // each row has columns.size() cells
    std::vector<std::string> notes;            // lines printed under the table
};

}  // namespace quadrix
