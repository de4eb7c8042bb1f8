// User-facing diagnostics (STYLE.md error tier 1): every message about user input carries
// file:line:column and, when the source text is known, the offending line with a caret:
//
//   scene.uq:3:17: error: unknown half-space 'inner'
//       body tube <outer !inner top>;
//                         ^
//
// Readers, the Flattener and the CLI collect what they can into a Diagnostics, then fail with a
// non-zero exit when it holds any error.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "quadrix/scene/source_loc.h"

namespace quadrix {

struct Diagnostic {
    enum class Severity { kNote, kWarning, kError };
    Severity severity = Severity::kError;
    SourceLoc loc;  // line 0 = no position (e.g. a command-line problem)
    std::string message;
    std::string sourceLine;  // the text of the offending line, empty when unknown
    std::string kind;  // category for summaries: "syntax", "input", "parser", "command line", ...

    // "file:line:column: error: message" (one line), optionally followed by the source line and a
    // caret line when withSource is true.
    std::string Format(bool withSource = true) const;
};

class Diagnostics {
  public:
    void Add(Diagnostic d);
    void Error(const SourceLoc& loc, std::string message, std::string sourceLine = {},
               std::string kind = "input");
    void Warning(const SourceLoc& loc, std::string message, std::string sourceLine = {},
                 std::string kind = "input");
    void Note(const SourceLoc& loc, std::string message);

    bool HasErrors() const { return errorCount_ > 0; }
    int ErrorCount() const { return errorCount_; }
    int WarningCount() const { return warningCount_; }
    const std::vector<Diagnostic>& Items() const { return items_; }
    void Clear();

    // Prints every diagnostic (warnings only when showWarnings) to `out`.
    void Print(std::FILE* out, bool showWarnings = true, bool withSource = true) const;

    // Errors beyond this many are counted but not stored (a runaway file cannot flood memory).
    static constexpr int kMaxStored = 100;

  private:
    std::vector<Diagnostic> items_;
    int errorCount_ = 0;
    int warningCount_ = 0;
};

}  // namespace quadrix
