// --max-memory and --time-limit for every command; see limit_options.h.
#include "limit_options.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>

#include "quadrix/frame/memory_budget.h"
#include "quadrix/io/time_limit.h"

namespace quadrix::cli {

void AddLimitOptions(CLI::App& cmd, LimitArgs& args) {
    cmd.add_option("--max-memory", args.maxMemory,
                   "Memory budget, e.g. 2G or 512M: larger images are refused (docs/output.md)");
    cmd.add_option("--time-limit", args.timeLimit,
                   "Give up after this many seconds (exit 124, no output left)");
}

namespace {

std::string ApplyMaxMemory(const std::string& text) {
    if (text.empty()) return {};
    std::size_t bytes = 0;
    if (!ParseByteSize(text, bytes))
        return fmt::format(
            "--max-memory: expected a size of at least 1M such as 512M or 2G, found '{}'", text);
    SetMemoryBudget(bytes);
    return {};
}

std::string TimeLimitError() { return "--time-limit: expected a positive number of seconds"; }

}  // namespace

std::string ApplyLimits(const LimitArgs& args) {
    if (auto e = ApplyMaxMemory(args.maxMemory); !e.empty()) return e;
    if (args.timeLimit != 0 && !SetTimeLimit(args.timeLimit)) return TimeLimitError();
    return {};
}

std::string ApplyLimits(const std::string& maxMemory, const std::string& timeLimit) {
    if (auto e = ApplyMaxMemory(maxMemory); !e.empty()) return e;
    if (timeLimit.empty()) return {};
    char* end = nullptr;
    errno = 0;
    const double seconds = std::strtod(timeLimit.c_str(), &end);
    if (end == timeLimit.c_str() || *end != '\0' || errno != 0 || !SetTimeLimit(seconds))
        return TimeLimitError() + fmt::format(", found '{}'", timeLimit);
    return {};
}

}  // namespace quadrix::cli
