// The resource limits every command that reads a scene shares (docs/output.md "Memory" and
// "Time"; issue 23): --max-memory SIZE caps the memory budget (frame/memory_budget.h) that big
// allocations are checked against, and --time-limit SECONDS ends the command after that much
// wall-clock time (io/time_limit.h, exit 124, no output left). One table and one parser for
// render, batch, view, draw, export and uq (uq parses its own words and calls ApplyLimits).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace quadrix::cli {

struct LimitArgs {
    std::string maxMemory;  // e.g. "2G"; empty = the machine's budget only
    double timeLimit = 0;   // seconds of wall-clock time; 0 = none
};

// Adds --max-memory and --time-limit to `cmd`.
void AddLimitOptions(CLI::App& cmd, LimitArgs& args);

// Sets the budget and arms the time limit. Returns empty, or a usage error message (without
// "quadrix: error: ") for a malformed value; the caller exits with status 2.
std::string ApplyLimits(const LimitArgs& args);
// The same for text values (uq's own parser): an empty string leaves that limit unset.
std::string ApplyLimits(const std::string& maxMemory, const std::string& timeLimit);

}  // namespace quadrix::cli
