// A small scanner for the line-oriented numeric formats of freeform models (Newell tea set, BPT,
// Geomview BEZ/BBP, Wavefront OBJ): tokens with 1-based line and column, '#' comments, optional
// comma separators, numbers parsed strictly (the whole token, finite), and errors reported through
// Diagnostics with the offending line (STYLE.md error tier 1).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/source_loc.h"

namespace quadrix::import {

struct ScanToken {
    std::string_view text;
    int line = 0;    // 1-based
    int column = 0;  // 1-based
};

class TextScanner {
  public:
    // `commasSeparate`: commas count as white space (the Newell format).
    TextScanner(std::string_view text, std::string fileName, Diagnostics& diagnostics,
                bool commasSeparate);

    // The next token of the whole text (across lines); false at the end.
    bool Next(ScanToken& token);
    bool Peek(ScanToken& token);
    // The tokens of the next logical line (a trailing '\' joins the following line, as in OBJ);
    // false at the end of the text. Empty and comment-only lines are skipped.
    bool NextLine(std::vector<ScanToken>& tokens);

    // Strict conversions; on failure they report "expected <what>" at the token and return nullopt.
    std::optional<double> Number(const ScanToken& token, std::string_view what);
    std::optional<long long> Integer(const ScanToken& token, std::string_view what);
    // Reads the next token as a number / integer; reports a missing token at the end of input.
    std::optional<double> NextNumber(std::string_view what);
    std::optional<long long> NextInteger(std::string_view what);

    void Error(const ScanToken& at, std::string message);
    void Warning(const ScanToken& at, std::string message);
    // An error at the end of the input ("unexpected end of file, expected ...").
    void ErrorAtEnd(std::string message);

    SourceLoc Loc(const ScanToken& at) const;
    std::string LineText(int line) const;
    Diagnostics& Diags() { return diagnostics_; }
    // The last token returned (for messages about what follows it).
    const ScanToken& Last() const { return last_; }

  private:
    void SkipSpaceAndComments(bool acrossLines);
    bool IsSeparator(char c) const;

    std::string_view text_;
    std::shared_ptr<const std::string> file_;
    Diagnostics& diagnostics_;
    bool commasSeparate_;
    std::size_t pos_ = 0;
    int line_ = 1;
    std::size_t lineStart_ = 0;
    std::vector<std::size_t> lineStarts_;
    ScanToken last_;
};

}  // namespace quadrix::import
