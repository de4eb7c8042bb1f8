// Tokens of the UniQuadrix language, each tagged with its file:line:column.
#pragma once

#include <memory>
#include <string>

#include "quadrix/lang/keywords.h"
#include "quadrix/scene/source_loc.h"

namespace quadrix::lang {

enum class TokenKind {
    kEnd,        // end of the current input
    kId,         // letters, digits, '#', '_', not starting with a digit; not a keyword
    kKeyword,    // a reserved word or synonym (Token::keyword says which)
    kNumber,     // decimal number with optional sign, fraction and exponent (Token::number)
    kString,     // "..." (Token::text holds the contents without quotes)
    kOption,     // '=' immediately followed by letters/digits: =t =0 =tx =c ... (text without '=')
    kSemicolon,  // ;
    kLParen,     // (
    kRParen,     // )
    kLAngle,     // <
    kRAngle,     // >
    kBang,       // !
    kPipe,       // |  CSG union
    kAmp,        // &  CSG intersection
    kMinus,      // -  CSG difference (a '-' not starting a number); also `read -;`
    kPlus,       // +  (a '+' not starting a number) in a clock expression
    kStar,       // *  in a clock expression
    kSlash,      // /  in a clock expression
    kError,      // malformed input; the lexer has already reported it
};

// Where a token starts. A SourceLoc holds the file name by shared pointer, whose atomic
// reference count would be touched twice for every token read; a token instead points at the
// Source's own pointer and becomes a SourceLoc only when something keeps its position (a
// diagnostic, an object of the scene). Valid while the Source it came from exists, which outlives
// the parsing of its statements.
struct TokenLoc {
    const std::shared_ptr<const std::string>* file = nullptr;
    int line = 0;    // 1-based
    int column = 0;  // 1-based

    operator SourceLoc() const { return SourceLoc{file ? *file : nullptr, line, column}; }
    std::string ToString() const { return SourceLoc(*this).ToString(); }
};

struct Token {
    TokenKind kind = TokenKind::kEnd;
    Keyword keyword = Keyword::kNone;
    std::string text;   // the spelling as written (strings: the contents)
    double number = 0;  // kNumber only; always finite
    TokenLoc loc;
};

// How a token is named in "expected X, found Y" messages: 'quadric', '1.5', "path", end of input.
std::string Describe(const Token& token);

}  // namespace quadrix::lang
