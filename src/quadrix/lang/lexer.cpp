#include "quadrix/lang/lexer.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace quadrix::lang {

namespace {

bool IsDigit(int c) { return c >= '0' && c <= '9'; }
bool IsSpace(int c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}
// Bytes that may begin a token (or white space / a comment). Anything else is garbage; '.' and
// '+' only begin numbers and are checked there.
bool StartsToken(int c) {
    if (IsSpace(c) || IsIdChar(c)) return true;
    switch (c) {
        case '{':
        case '}':
        case '"':
        case '=':
        case ';':
        case '(':
        case ')':
        case '<':
        case '>':
        case '!':
        case '|':
        case '&':
        case '-':
        case '*':
        case '/':
            return true;
        default:
            return false;
    }
}

std::string ShowByte(int c) {
    if (c >= 0x21 && c <= 0x7e) return fmt::format("'{}'", static_cast<char>(c));
    return fmt::format("byte 0x{:02x}", c);
}

// The decimal order of magnitude of a number written as digits[.digits] with exponent `exp`
// (the power of ten of its leading non-zero digit), used to tell an overflow from an underflow
// when from_chars reports "out of range". Saturates instead of overflowing.
long long DecimalOrder(std::string_view mantissa, long long exp) {
    long long intDigits = 0, leadingFractionZeros = 0;
    bool seenNonZero = false, inFraction = false;
    for (char c : mantissa) {
        if (c == '.') {
            inFraction = true;
            continue;
        }
        if (!inFraction) {
            if (seenNonZero || c != '0') ++intDigits;
            seenNonZero |= c != '0';
        } else if (!seenNonZero) {
            if (c != '0') {
                seenNonZero = true;
                break;
            }
            ++leadingFractionZeros;
        }
    }
    long long order = intDigits > 0 ? intDigits - 1 : -leadingFractionZeros - 1;
    return order + exp;
}

// A number token that starts at `p` (a sign, a digit or '.'), as LexNumber reads it, when it is
// well formed, finite, not an underflow, and followed by a byte that ends it (all within
// [p, end)): its value and length. False for anything LexNumber would report or treat specially.
bool ScanPlainNumber(const char* p, const char* end, double& value, std::size_t& length) {
    auto at = [&](std::size_t i) -> int {
        return p + i < end ? static_cast<unsigned char>(p[i]) : -1;
    };
    std::size_t n = 0;
    const bool negative = at(0) == '-';
    if (at(0) == '+' || at(0) == '-') ++n;
    const std::size_t mantissaStart = n;
    const bool startsNumber = IsDigit(at(n)) || (at(n) == '.' && IsDigit(at(n + 1)));
    if (!startsNumber) return false;
    while (IsDigit(at(n))) ++n;
    if (at(n) == '.') {
        ++n;
        while (IsDigit(at(n))) ++n;
    }
    const int e = at(n), afterE = at(n + 1);
    if ((e == 'e' || e == 'E') &&
        (IsDigit(afterE) || ((afterE == '+' || afterE == '-') && IsDigit(at(n + 2))))) {
        n += 2;
        while (IsDigit(at(n))) ++n;
    }
    const int next = at(n);
    if (next < 0 || IsIdChar(next) || next == '.') return false;  // the end, or malformed
    double v = 0;
    auto [ptr, ec] = std::from_chars(p + mantissaStart, p + n, v, std::chars_format::general);
    if (ec != std::errc() || ptr != p + n || !std::isfinite(v)) return false;
    value = negative ? -v : v;
    length = n;
    return true;
}

}  // namespace

bool Lexer::TakePlainNumbers(double* out, std::size_t n, int& lastLine) {
    const std::string_view text = source_.From(pos_);
    const char* const begin = text.data();
    const char* const end = begin + text.size();
    const char* p = begin;
    int line = line_, column = column_, numberLine = line_;
    for (std::size_t i = 0; i < n; ++i) {
        for (; p < end && IsSpace(static_cast<unsigned char>(*p)); ++p) {
            if (*p == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
        std::size_t length = 0;
        if (!ScanPlainNumber(p, end, out[i], length)) return false;
        numberLine = line;
        p += length;
        column += static_cast<int>(length);
    }
    pos_ += static_cast<std::size_t>(p - begin);
    line_ = line;
    column_ = column;
    lastLine = numberLine;
    return true;
}

Lexer::Lexer(Source& source, Diagnostics& diags) : source_(source), diags_(diags) {
    // A UTF-8 byte order mark, as some editors write, is not part of the scene.
    if (PeekChar(0) == 0xEF && PeekChar(1) == 0xBB && PeekChar(2) == 0xBF) pos_ = 3;
}

std::size_t Lexer::IdRun(std::size_t from) {
    std::size_t n = from;
    while (IsIdChar(PeekChar(n))) ++n;
    return n - from;
}

std::string Lexer::LineOf(const SourceLoc& loc) const {
    return source_.LineForDiagnostic(loc.line, loc.column);
}

Token Lexer::ErrorToken(const TokenLoc& loc, std::string message, bool evenWhenQuiet) {
    if (!quiet_ || evenWhenQuiet) diags_.Error(loc, std::move(message), LineOf(loc), "syntax");
    Token t;
    t.kind = TokenKind::kError;
    t.loc = loc;
    return t;
}

void Lexer::SkipSpaceAndComments() {
    for (;;) {
        int c = PeekChar();
        if (IsSpace(c)) {
            Advance();
            continue;
        }
        if (c != '{') return;
        // Nested comment (§2.1.8): a depth counter, so nesting depth costs no stack.
        TokenLoc start = Here();
        long long depth = 0;
        do {
            c = PeekChar();
            if (c == '{') ++depth;
            if (c == '}') --depth;
            if (c < 0) {
                ErrorToken(start, "unterminated comment (a '{' has no matching '}')", true);
                return;
            }
            Advance();
        } while (depth > 0);
    }
}

Token Lexer::Next() {
    SkipSpaceAndComments();
    TokenLoc start = Here();
    int c = PeekChar();
    Token t;
    t.loc = start;
    if (c < 0) return t;  // kEnd
    auto single = [&](TokenKind kind) {
        t.kind = kind;
        t.text = static_cast<char>(c);
        Advance();
        return std::move(t);
    };
    switch (c) {
        case ';':
            return single(TokenKind::kSemicolon);
        case '(':
            return single(TokenKind::kLParen);
        case ')':
            return single(TokenKind::kRParen);
        case '<':
            return single(TokenKind::kLAngle);
        case '>':
            return single(TokenKind::kRAngle);
        case '!':
            return single(TokenKind::kBang);
        case '|':
            return single(TokenKind::kPipe);
        case '&':
            return single(TokenKind::kAmp);
        case '*':
            return single(TokenKind::kStar);
        case '/':
            return single(TokenKind::kSlash);
        case '"':
            return LexString(start);
        case '=':
            return LexOption(start);
        case '}':
            Advance();
            return ErrorToken(start, "unmatched '}' (no comment is open)");
        default:
            break;
    }
    if (IsDigit(c) || c == '.' || c == '+' || c == '-') {
        int d = PeekChar(1);
        bool number =
            IsDigit(c) || (c == '.' && IsDigit(d)) ||
            ((c == '+' || c == '-') && (IsDigit(d) || (d == '.' && IsDigit(PeekChar(2)))));
        if (number) return LexNumber(start);
        if (c == '-') return single(TokenKind::kMinus);
        if (c == '+') return single(TokenKind::kPlus);
    }
    if (IsIdStart(c)) return LexWord(start);
    return LexGarbage(start);
}

Token Lexer::LexNumber(TokenLoc start) {
    // The token's extent is found by looking ahead (n bytes from pos_), then taken at once: no
    // newline can be inside a number, so the column simply advances by its length.
    std::size_t n = 0;
    bool negative = PeekChar() == '-';
    if (PeekChar() == '+' || PeekChar() == '-') ++n;
    const std::size_t mantissaStart = n;
    while (IsDigit(PeekChar(n))) ++n;
    if (PeekChar(n) == '.') {
        ++n;
        while (IsDigit(PeekChar(n))) ++n;
    }
    const std::size_t mantissaEnd = n;
    long long exponent = 0;
    int e = PeekChar(n);
    int afterE = PeekChar(n + 1);
    if ((e == 'e' || e == 'E') &&
        (IsDigit(afterE) || ((afterE == '+' || afterE == '-') && IsDigit(PeekChar(n + 2))))) {
        ++n;
        bool negExp = false;
        if (PeekChar(n) == '+' || PeekChar(n) == '-') {
            negExp = PeekChar(n) == '-';
            ++n;
        }
        for (int c = PeekChar(n); IsDigit(c); c = PeekChar(++n))
            if (exponent < 1000000) exponent = exponent * 10 + (c - '0');
        if (negExp) exponent = -exponent;
    }
    // A number glued to more id characters or dots ("1x", "1.2.3", "2e") is one malformed token.
    if (IsIdChar(PeekChar(n)) || PeekChar(n) == '.') {
        while (IsIdChar(PeekChar(n)) || PeekChar(n) == '.') ++n;
        std::string text(source_.From(pos_).substr(0, n));
        AdvanceInLine(n);
        std::string shown = text.size() > 40 ? text.substr(0, 40) + "..." : text;
        return ErrorToken(start, fmt::format("malformed number '{}'", shown));
    }
    Token t;
    t.kind = TokenKind::kNumber;
    t.loc = start;
    std::string_view text = source_.From(pos_).substr(0, n);
    AdvanceInLine(n);
    const char* first = text.data() + mantissaStart;
    const char* last = text.data() + text.size();
    double value = 0;
    auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::general);
    if (ec == std::errc::result_out_of_range) {
        std::string_view mantissa(first, mantissaEnd - mantissaStart);
        if (DecimalOrder(mantissa, exponent) > 0) {
            std::string shown =
                text.size() > 40 ? std::string(text.substr(0, 40)) + "..." : std::string(text);
            return ErrorToken(t.loc, fmt::format("number '{}' is too large", shown));
        }
        value = 0;  // underflow: below the smallest double, as good as zero
    } else if (ec != std::errc() || ptr != last || !std::isfinite(value)) {
        return ErrorToken(t.loc, fmt::format("malformed number '{}'", text));
    }
    t.number = negative ? -value : value;
    t.text.assign(text.data(), text.size());
    return t;
}

Token Lexer::LexWord(TokenLoc start) {
    Token t;
    t.loc = start;
    std::size_t n = IdRun(0);
    std::string_view word = source_.From(pos_).substr(0, n);
    t.keyword = LookupKeyword(word);
    t.text.assign(word.data(), word.size());
    AdvanceInLine(n);
    t.kind = t.keyword == Keyword::kNone ? TokenKind::kId : TokenKind::kKeyword;
    return t;
}

Token Lexer::LexString(TokenLoc start) {
    Advance();  // the opening quote
    Token t;
    t.kind = TokenKind::kString;
    t.loc = start;
    for (;;) {
        int c = PeekChar();
        if (c < 0 || c == '\n') {
            return ErrorToken(start, "unterminated string (a '\"' has no closing '\"' on its line)",
                              true);
        }
        Advance();
        if (c == '"') return t;
        t.text += static_cast<char>(c);
    }
}

Token Lexer::LexOption(TokenLoc start) {
    Advance();  // '='
    Token t;
    t.kind = TokenKind::kOption;
    t.loc = start;
    std::size_t n = IdRun(0);
    t.text.assign(source_.From(pos_).substr(0, n));
    AdvanceInLine(n);
    if (t.text.empty())
        return ErrorToken(start, "expected an option name right after '=' (as in =t, =tx, =c)");
    return t;
}

Token Lexer::LexGarbage(TokenLoc start) {
    int first = PeekChar();
    int count = 0;
    do {
        Advance();
        ++count;
    } while (PeekChar() >= 0 && !StartsToken(PeekChar()));
    // A '.' or '/' here is most often an unquoted file name after `read` (seed 001 §2.1.7).
    const char* hint =
        first == '.' || first == '/' ? " (file names with '.' or '/' must be in quotes)" : "";
    if (count == 1)
        return ErrorToken(start, fmt::format("unexpected character {}{}", ShowByte(first), hint));
    return ErrorToken(
        start, fmt::format("unexpected characters (starting with {}){}", ShowByte(first), hint));
}

}  // namespace quadrix::lang
