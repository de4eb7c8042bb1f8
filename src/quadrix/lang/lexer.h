// Lexer of the UniQuadrix language (seed 001 §2.1): turns a Source into tokens tagged with
// file:line:column.
//
//  - White space is ' ', tab, CR, LF, FF and VT. Comments are { ... }, nest to any depth and count
//    as white space (§2.1.8); an unterminated comment is an error at its '{'.
//  - Ids: letters, digits, '#', '_', not starting with a digit (§2.1.1). Words found in the keyword
//    table (keywords.h) come back as kKeyword.
//  - Numbers: [+-] digits [. digits] [(e|E) [+-] digits], or [+-] . digits [...]: `.3`, `-4`,
//    `1e-3`. A number that overflows a double is an error; one that underflows becomes 0.
//    A number glued to a letter or another '.' (`1x`, `1.2.3`) is malformed.
//  - Strings: "..." on one line, no escapes (they hold path names, §2.1.7).
//  - Options: '=' followed at once by letters/digits: `=t`, `=0`, `=tx`, `=vxy`, `=c`.
//  - Operators of number expressions (parser.h, NumberExpression): '*', '/', and '+' or '-' when
//    not starting a number.
//
// Lexical errors go to Diagnostics (kind "syntax") and come back as a kError token. A run of
// unexpected bytes (binary garbage) is one error. While the parser is skipping to the next ';'
// after an error it sets quiet mode: malformed tokens are then not reported again, except for
// unterminated comments and strings, which swallow the rest of the input and must be seen.
#pragma once

#include <cstddef>
#include <string>

#include "quadrix/lang/source.h"
#include "quadrix/lang/token.h"
#include "quadrix/scene/diagnostics.h"

namespace quadrix::lang {

class Lexer {
  public:
    Lexer(Source& source, Diagnostics& diags);

    // The next token; kEnd forever once the input is exhausted.
    Token Next();

    // The fast path of number lists (a quadric's ten coefficients): reads `n` plain numbers
    // separated by white space straight from the text held, as n calls of Next() would, and
    // returns true with `lastLine` the line of the last one. Returns false, having read
    // nothing, at anything else (a comment, `clock`, an expression, a malformed or out-of-range
    // number, the end of the text held): Next() then reads, and reports, as always.
    bool TakePlainNumbers(double* out, std::size_t n, int& lastLine);

    void SetQuiet(bool quiet) { quiet_ = quiet; }
    // Skips the text up to byte `end` unread (line and column still counted).
    void SkipTo(std::size_t end) {
        while (pos_ < end && source_.Has(pos_)) Advance();
    }
    Source& GetSource() { return source_; }
    // The offset of the next byte to read.
    std::size_t Offset() const { return pos_; }

    // The source line of `loc` for a diagnostic (see Source::LineForDiagnostic).
    std::string LineOf(const SourceLoc& loc) const;

  private:
    // -1 at end of input.
    int PeekChar(std::size_t ahead = 0) {
        if (!source_.Has(pos_ + ahead)) return -1;
        return static_cast<unsigned char>(source_.At(pos_ + ahead));
    }
    void Advance() {
        if (!source_.Has(pos_)) return;
        if (source_.At(pos_) == '\n') {
            ++line_;
            column_ = 1;
        } else {
            ++column_;
        }
        ++pos_;
    }
    // Advances over `n` bytes already held that contain no newline (a token's characters).
    void AdvanceInLine(std::size_t n) {
        pos_ += n;
        column_ += static_cast<int>(n);
    }
    // The length of the run of id characters from byte pos_ + `from` on, reading more of a
    // growing source when the run reaches the end of what is held.
    std::size_t IdRun(std::size_t from);
    TokenLoc Here() const { return TokenLoc{&source_.Name(), line_, column_}; }
    void SkipSpaceAndComments();
    Token LexNumber(TokenLoc start);
    Token LexWord(TokenLoc start);
    Token LexString(TokenLoc start);
    Token LexOption(TokenLoc start);
    Token LexGarbage(TokenLoc start);
    Token ErrorToken(const TokenLoc& loc, std::string message, bool evenWhenQuiet = false);

    Source& source_;
    Diagnostics& diags_;
    std::size_t pos_ = 0;
    int line_ = 1;
    int column_ = 1;
    bool quiet_ = false;
};

// Character classes shared with the parser (e.g. to explain why a path needs quotes).
inline bool IsIdStart(int c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '#' || c == '_';
}
inline bool IsIdChar(int c) { return IsIdStart(c) || (c >= '0' && c <= '9'); }

}  // namespace quadrix::lang
