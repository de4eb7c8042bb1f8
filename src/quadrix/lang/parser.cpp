#include "quadrix/lang/parser.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "quadrix/lang/statements.h"

namespace quadrix::lang {

Parser::Parser(ReaderState& state, Source& source)
    : state_(state), source_(source), lexer_(source, state.diags) {}

const Token& Parser::Peek() {
    if (!next_) next_ = lexer_.Next();
    return *next_;
}

Token Parser::Take() {
    Peek();
    lastLine_ = next_->loc.line;
    Token t = std::move(*next_);
    next_.reset();
    return t;
}

std::string_view Parser::TextToSemicolon() {
    const std::size_t from = lexer_.Offset();
    if (from < lookedAheadTo_) return {};
    const std::string_view text = source_.From(from);
    const std::size_t semicolon = text.find(';');
    lookedAheadTo_ = semicolon == std::string_view::npos ? source_.Size() : from + semicolon;
    return semicolon == std::string_view::npos ? std::string_view() : text.substr(0, semicolon);
}

void Parser::Error(const SourceLoc& loc, std::string message, const char* kind) {
    if (state_.aborted) return;
    // Only positions in this source have their line at hand.
    std::string line = loc.file == source_.Name() ? lexer_.LineOf(loc) : std::string();
    state_.diags.Error(loc, std::move(message), std::move(line), kind);
    CheckErrorLimit();
}

void Parser::CheckErrorLimit() {
    if (state_.aborted || state_.diags.ErrorCount() < Diagnostics::kMaxStored) return;
    state_.aborted = true;
    state_.diags.Note(SourceLoc{source_.Name(), 0, 0}, "too many errors; reading stopped");
}

void Parser::Warning(const SourceLoc& loc, std::string message, const char* kind) {
    if (state_.aborted) return;
    std::string line = loc.file == source_.Name() ? lexer_.LineOf(loc) : std::string();
    state_.diags.Warning(loc, std::move(message), std::move(line), kind);
}

bool Parser::Expected(std::string_view what) {
    const Token& t = Peek();
    if (t.kind != TokenKind::kError)
        Error(t.loc, fmt::format("expected {}, found {}", what, Describe(t)), kSyntax);
    return false;
}

std::optional<double> Parser::ExpectNumber(std::string_view what) {
    const Token& t = Peek();
    if (t.kind == TokenKind::kNumber) return Take().number;
    // `clock` and parenthesised expressions (number_expression.cpp).
    if (t.kind == TokenKind::kId && t.text == "clock") {
        Take();
        return ClockValue();
    }
    if (t.kind == TokenKind::kLParen) return Parenthesised(what, 0);
    if (t.kind == TokenKind::kId) {
        std::string lower = t.text;
        std::transform(lower.begin(), lower.end(), lower.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (lower == "nan" || lower == "inf" || lower == "infinity") {
            Error(t.loc,
                  fmt::format("expected {}, found '{}': numbers must be finite", what, t.text),
                  kSyntax);
            return std::nullopt;
        }
    }
    Expected(what);
    return std::nullopt;
}

bool Parser::ExpectSemicolon(std::string_view after) {
    return ExpectStatementEnd(fmt::format("';' after {}", after));
}

bool Parser::ExpectStatementEnd(std::string_view expected) {
    if (PeekIs(TokenKind::kSemicolon)) {
        Take();
        return true;
    }
    Expected(expected);
    // The most common slip is a forgotten ';' at the end of a line. When a statement keyword
    // follows, the statement is complete: keep it and read on from that keyword, instead of
    // skipping (and losing) the next statement too.
    return AtStatementKeyword();
}

bool Parser::AtStatementKeyword() {
    return Peek().kind == TokenKind::kKeyword && FindStatement(Peek().keyword) != nullptr;
}

bool Parser::ReservedWord(const Token& token) {
    std::string_view canonical = KeywordName(token.keyword);
    if (canonical == token.text)
        Error(token.loc,
              fmt::format("'{}' is a reserved word and cannot be used as an id", token.text),
              kSyntax);
    else
        Error(token.loc,
              fmt::format("'{}' is a reserved word (synonym of '{}') and cannot be used as an id",
                          token.text, canonical),
              kSyntax);
    return false;
}

bool Parser::OptionalId(std::string& id, SourceLoc& loc, bool (*keywordMayFollow)(Keyword)) {
    return OptionalIdAt(id, loc, keywordMayFollow);
}
bool Parser::OptionalId(std::string& id, TokenLoc& loc, bool (*keywordMayFollow)(Keyword)) {
    return OptionalIdAt(id, loc, keywordMayFollow);
}
bool Parser::ExpectId(std::string_view what, std::string& id, SourceLoc& loc) {
    return ExpectIdAt(what, id, loc);
}
bool Parser::ExpectId(std::string_view what, std::string& id, TokenLoc& loc) {
    return ExpectIdAt(what, id, loc);
}

template <class Loc>
bool Parser::OptionalIdAt(std::string& id, Loc& loc, bool (*keywordMayFollow)(Keyword)) {
    const Token& t = Peek();
    if (t.kind == TokenKind::kId) {
        id = std::move(next_->text);
        loc = t.loc;
        Take();
        return true;
    }
    if (t.kind != TokenKind::kKeyword || (keywordMayFollow && keywordMayFollow(t.keyword)))
        return true;
    // A statement keyword on a later line is the next statement after a forgotten ';' (which
    // the caller reports), not an attempt to use a reserved word as an id.
    if (t.loc.line > lastLine_ && AtStatementKeyword()) return true;
    return ReservedWord(t);
}

template <class Loc>
bool Parser::ExpectIdAt(std::string_view what, std::string& id, Loc& loc) {
    const Token& t = Peek();
    if (t.kind == TokenKind::kId) {
        id = std::move(next_->text);
        loc = t.loc;
        Take();
        return true;
    }
    if (t.kind == TokenKind::kKeyword) return ReservedWord(t);
    return Expected(what);
}

std::optional<scene::Color> Parser::ParseColor(const Token& option) {
    if (PeekIs(TokenKind::kId) || PeekIs(TokenKind::kKeyword)) return ParseColorName(option);
    static constexpr const char* kNames[3] = {"red", "green", "blue"};
    double rgb[3];
    for (int i = 0; i < 3; ++i) {
        SourceLoc at = Peek().loc;
        std::optional<double> v;
        if (double x; TakeNumber(x))
            v = x;
        else
            v = ExpectNumber(fmt::format("the {} component after {}", kNames[i], Describe(option)));
        if (!v) return std::nullopt;
        if (*v < 0 || *v > 1) {
            Error(at, fmt::format("color component {} is outside [0, 1]", *v));
            *v = std::clamp(*v, 0.0, 1.0);
        }
        rgb[i] = *v;
    }
    return scene::Color{rgb[0], rgb[1], rgb[2]};
}

bool Parser::RunStatement() {
    const Token& t = Peek();
    switch (t.kind) {
        case TokenKind::kSemicolon:
            Take();
            return true;  // an empty statement
        case TokenKind::kError:
            return false;  // already reported
        case TokenKind::kKeyword:
            break;
        case TokenKind::kId:
            Error(t.loc,
                  fmt::format("expected a statement (plane, quadric, body, definition, instance, "
                              "array, csg, light, view, read, ...), found unknown word '{}'",
                              t.text),
                  kSyntax);
            return false;
        default:
            return Expected("a statement");
    }
    const StatementEntry* entry = FindStatement(t.keyword);
    if (!entry) {
        if (IsViewParameter(t.keyword))
            Error(t.loc,
                  fmt::format("'{}' is a view parameter; it may only follow 'view' or 'redef view'",
                              t.text),
                  kSyntax);
        else
            Error(t.loc, fmt::format("'{}' cannot start a statement", t.text), kSyntax);
        return false;
    }
    Token keyword = Take();
    keywordEnd_ = lexer_.Offset();
    if (state_.InDefinition() && !entry->allowedInDefinition) {
        Error(keyword.loc,
              fmt::format("a '{}' statement is not allowed inside a definition (definition '{}' "
                          "has no enddef yet)",
                          KeywordName(keyword.keyword), state_.CurrentScope().id));
        return false;
    }
    return entry->parse(*this, keyword);
}

void Parser::RecordViewStatement(const Token& keyword) {
    const std::size_t end = lexer_.Offset();
    if (next_ || end < keywordEnd_) return;  // no ';' (an error was reported)
    state_.viewStatements.push_back(
        {keyword.loc.file ? *keyword.loc.file : nullptr, keyword.loc.line, keyword.loc.column,
         keyword.text + std::string(source_.From(keywordEnd_).substr(0, end - keywordEnd_))});
}

void Parser::SkipToSemicolon() {
    lexer_.SetQuiet(true);
    while (!PeekIs(TokenKind::kEnd) && !PeekIs(TokenKind::kSemicolon)) Take();
    if (PeekIs(TokenKind::kSemicolon)) Take();
    lexer_.SetQuiet(false);
}

void Parser::CheckUnclosedDefinition() {
    if (!state_.InDefinition() || state_.DefinitionSource() != &source_) return;
    const scene::Scope& def = state_.CurrentScope();
    Error(def.loc, fmt::format("definition '{}' has no enddef (end of {} reached)", def.id,
                               *source_.Name()));
    // Keep it, so that later statements naming it do not report more errors.
    state_.CloseDefinition();
}

// The statement loop shared by Run() and RunAvailable(): statements until the end of the input
// seen so far, `quit`, or an abort (the statement limit).
void Parser::RunStatements() {
    while (!stopped_ && !state_.aborted) {
        if (PeekIs(TokenKind::kEnd)) break;
        if (++state_.statementCount > ReaderState::kMaxStatements) {
            Error(Peek().loc,
                  fmt::format("more than {} statements; reading stopped",
                              ReaderState::kMaxStatements),
                  kParser);
            state_.aborted = true;
            break;
        }
        if (!RunStatement()) SkipToSemicolon();
        CheckErrorLimit();  // lexical errors go to Diagnostics directly
    }
}

bool Parser::RunAvailable() {
    // Run() minus the end-of-input checks: the kEnd token seen now only means "nothing more
    // yet", so it is dropped for the lexer to look again next time.
    RunStatements();
    if (next_ && next_->kind == TokenKind::kEnd) next_.reset();
    return !Stopped();
}

void Parser::Finish() {
    if (!state_.aborted) CheckUnclosedDefinition();
}

void Parser::SkipInput(std::size_t end) {
    next_.reset();
    lexer_.SkipTo(end);
}

void Parser::Run() {
    RunStatements();
    if (!state_.aborted) CheckUnclosedDefinition();
}

}  // namespace quadrix::lang
