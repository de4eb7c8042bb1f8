// Parser of the UniQuadrix language (seed 001 §2.1, §2.3): reads the statements of one Source
// into the scene held by a ReaderState.
//
// The statement loop looks at the first token of each statement and calls the small function
// registered for that keyword in the statement table (statements.h); each such function parses
// one statement up to and including its ';'. This class gives those functions a token cursor,
// error reporting, and the grammar pieces they share (numbers, ids, colors, the final ';').
//
// Error recovery (seed 001 §2.3: "If an error is noted, all input is ignored ... until the next
// semi-colon"): a statement function returns false after a syntax error it has reported; the loop
// then skips to the next ';' and goes on (except for a ';' missing before the next statement's
// keyword: that statement is kept and reading resumes at the keyword). Errors about meaning
// (unknown ids, bad values) are reported where they are found and the statement goes on, so one
// statement may report several.
//
// The cursor lexes lazily: after a statement's ';' nothing more is read until the next statement
// is wanted, so statements typed on standard input run as soon as they are complete.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "quadrix/lang/lexer.h"
#include "quadrix/lang/reader_state.h"
#include "quadrix/lang/source.h"

namespace quadrix::lang {

// Diagnostic kinds used by the reader (the end-of-session summary counts them, seed 001 §2.3):
inline constexpr const char* kSyntax = "syntax";  // malformed tokens, unexpected tokens
inline constexpr const char* kInput = "input";    // well-formed statements that mean nothing valid
inline constexpr const char* kParser = "parser";  // files, nesting limits, too many errors

class Parser {
  public:
    Parser(ReaderState& state, Source& source);

    // Reads statements to the end of the source, a `quit`, or until reading is aborted.
    void Run();
    // For a source that grows by Source::Append (an interactive session's Feed): reads the
    // statements available now, and leaves the parser ready to go on when more text is appended;
    // false after `quit` or an abort. Finish() ends the input (an open definition is reported).
    bool RunAvailable();
    void Finish();
    // Skips the source's text up to byte `end` without reading it (input skipped after an
    // error, a statement the session handled itself).
    void SkipInput(std::size_t end);
    bool Stopped() const { return stopped_ || state_.aborted; }

    ReaderState& State() { return state_; }
    Source& GetSource() { return source_; }
    // Stops reading this source after the current statement (quit).
    void Stop() { stopped_ = true; }
    // Records the view statement that `keyword` started and whose ';' was just taken
    // (ReaderState::viewStatements).
    void RecordViewStatement(const Token& keyword);

    // --- token cursor -----------------------------------------------------------------------
    const Token& Peek();
    Token Take();
    bool PeekIs(TokenKind kind) { return Peek().kind == kind; }
    // Takes the next token when it is of `kind`. With TakeNumber, the fast paths in front of the
    // Expect... calls below, whose messages are then formatted only when something is wrong:
    //   p.TakeIf(TokenKind::kSemicolon) || p.ExpectSemicolon(fmt::format(...))
    bool TakeIf(TokenKind kind) {
        if (!PeekIs(kind)) return false;
        lastLine_ = next_->loc.line;
        next_.reset();
        return true;
    }
    // Takes a plain NUMBER token into `value`; false (nothing taken) for anything else, including
    // `clock` and parenthesised expressions, which ExpectNumber reads.
    bool TakeNumber(double& value) {
        if (!PeekIs(TokenKind::kNumber)) return false;
        value = next_->number;
        lastLine_ = next_->loc.line;
        next_.reset();
        return true;
    }
    // Takes `n` plain numbers at once (Lexer::TakePlainNumbers) when nothing has been looked at
    // ahead; false (nothing taken) otherwise: the caller then takes them one by one.
    bool TakePlainNumbers(double* out, std::size_t n) {
        return !next_ && lexer_.TakePlainNumbers(out, n, lastLine_);
    }
    // For capacity hints (a csg expression of 100,000 operands): the text held from the next
    // byte to read up to the next ';'. Empty when there is no ';' in the text held, or when that
    // text was already handed out (so that no byte is looked at twice, even when ';' are missing).
    std::string_view TextToSemicolon();
    bool PeekIsKeyword(Keyword keyword) {
        return Peek().kind == TokenKind::kKeyword && Peek().keyword == keyword;
    }
    bool PeekIsOption(std::string_view name) {
        return Peek().kind == TokenKind::kOption && Peek().text == name;
    }

    // --- diagnostics ------------------------------------------------------------------------
    void Error(const SourceLoc& loc, std::string message, const char* kind = kInput);
    void Warning(const SourceLoc& loc, std::string message, const char* kind = kInput);
    // "expected <what>, found <next token>" at the next token (kind syntax); returns false so that
    // statement functions can `return Expected(...)`. Silent when the next token is a lexical
    // error, which the lexer has already reported.
    bool Expected(std::string_view what);

    // --- shared grammar pieces --------------------------------------------------------------
    // A number; `what` names it in the error message ("coefficient B of the plane"). Also
    // `clock` or a parenthesised expression (number_expression.cpp, docs/language.md §3.14).
    std::optional<double> ExpectNumber(std::string_view what);
    // True when the next token starts a number (a NUMBER, `clock` or '(').
    bool PeekIsNumber();
    // The ';' that ends a statement; `after` completes "expected ';' after ...". When it is
    // missing but a statement keyword follows, the error is reported and true is returned: the
    // statement is kept and reading resumes at that keyword.
    bool ExpectSemicolon(std::string_view after);
    // The same with the whole expectation spelled out: "expected <expected>, found ...".
    bool ExpectStatementEnd(std::string_view expected);
    // True when the next token starts a statement.
    bool AtStatementKeyword();
    // The optional id after a statement keyword. Returns false on a reserved word (reported);
    // leaves `id` empty when the next token is not an id. Keywords for which
    // `keywordMayFollow(keyword)` is true are not ids but the start of what follows.
    bool OptionalId(std::string& id, SourceLoc& loc, bool (*keywordMayFollow)(Keyword) = nullptr);
    // The same with the position as a TokenLoc (token.h), for the statements read by the
    // hundred thousand: no file-name reference count is touched unless the position is kept.
    bool OptionalId(std::string& id, TokenLoc& loc, bool (*keywordMayFollow)(Keyword) = nullptr);
    // A required id (`what` names it: "definition id").
    bool ExpectId(std::string_view what, std::string& id, SourceLoc& loc);
    bool ExpectId(std::string_view what, std::string& id, TokenLoc& loc);
    // `=c r g b` after its option token has been taken: three numbers in [0, 1] (linear light),
    // or `=c name` with one of the CSS/SVG color names (sRGB, converted to linear; appearance.cpp).
    std::optional<scene::Color> ParseColor(const Token& option);
    // The appearance options of solids (the color and materials extensions, docs/language.md
    // §3.6), after the option token has been taken:
    //   =c r g b | =c name          the color
    //   =finish kd ks shininess     diffuse and specular coefficients, specular exponent
    //   =alpha a                    opacity in [0, 1]
    // A repeated option warns and the last one is used. False on a syntax error (reported).
    static bool IsAppearanceOption(std::string_view name) {
        return name == "c" || name == "finish" || name == "alpha";
    }
    bool ParseAppearance(const Token& option, std::optional<scene::Color>& color,
                         scene::Finish& finish);

  private:
    // Number expressions (number_expression.cpp).
    std::optional<double> ClockValue();
    std::optional<double> Parenthesised(std::string_view what, int depth);
    std::optional<double> Sum(std::string_view what, int depth);
    std::optional<double> Product(std::string_view what, int depth);
    std::optional<double> Factor(std::string_view what, int depth);
    std::optional<scene::Color> ParseColorName(const Token& option);
    bool RunStatement();
    void SkipToSemicolon();
    void RunStatements();
    void CheckUnclosedDefinition();
    // Stops reading everywhere once Diagnostics::kMaxStored errors have been reported.
    void CheckErrorLimit();
    bool ReservedWord(const Token& token);
    template <class Loc>
    bool OptionalIdAt(std::string& id, Loc& loc, bool (*keywordMayFollow)(Keyword));
    template <class Loc>
    bool ExpectIdAt(std::string_view what, std::string& id, Loc& loc);

    ReaderState& state_;
    Source& source_;
    Lexer lexer_;
    std::optional<Token> next_;
    int lastLine_ = 0;               // line of the last token taken
    std::size_t keywordEnd_ = 0;     // byte offset after the keyword of the current statement
    std::size_t lookedAheadTo_ = 0;  // TextToSemicolon: the end of the last text handed out
    bool stopped_ = false;
};

}  // namespace quadrix::lang
