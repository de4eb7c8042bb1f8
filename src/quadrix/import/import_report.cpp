// The importers' census and left-out texts (import_report.h).
#include "quadrix/import/import_report.h"

#include <fmt/format.h>

namespace quadrix::import {

std::string ImportReport::CensusText() const {
    std::string s;
    for (const auto& [type, n] : census)
        s += fmt::format("{}{} {}", s.empty() ? "" : ", ", type, n);
    return s.empty() ? "no primitives" : s;
}

std::string ImportReport::SkippedText() const {
    std::string s;
    for (const auto& [type, n] : skipped)
        s += fmt::format("{}{} ×{}", s.empty() ? "" : ", ", type, n);
    return s;
}

}  // namespace quadrix::import
