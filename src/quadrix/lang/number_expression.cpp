// Numbers of the language with the animation clock (docs/language.md §3.14, issue 22).
//
// Wherever the grammar takes a number it also takes `clock` (the frame's time, 0 → 1 over an
// animation; 0 outside one) or a parenthesised expression over numbers and `clock`:
//
//   number  := NUMBER | 'clock' | '(' sum ')'
//   sum     := product { ('+' | '-') product }      a signed NUMBER after an operand is added:
//   product := factor { ('*' | '/') factor }        (clock -1) = (clock - 1)
//   factor  := NUMBER | 'clock' | '(' sum ')' | ('+' | '-') factor
//
// Expressions are evaluated as they are read, in double precision, left to right: the scene holds
// their values, and a scene that names `clock` is marked (Reader::UsesClock) so that a frame loop
// reads it again for every frame instead of only flattening it again. Outside parentheses numbers
// stay space-separated lists (`<1 0 -1 2>` is four numbers). Division by zero and results that
// are not finite are errors at the operator; nesting is limited (kMaxDepth) so that hostile input
// cannot exhaust the stack.
#include <fmt/format.h>

#include <cmath>

#include "quadrix/lang/parser.h"

namespace quadrix::lang {

namespace {
constexpr int kMaxDepth = 64;
}  // namespace

bool Parser::PeekIsNumber() {
    const Token& t = Peek();
    return t.kind == TokenKind::kNumber || t.kind == TokenKind::kLParen ||
           (t.kind == TokenKind::kId && t.text == "clock");
}

std::optional<double> Parser::ClockValue() {
    state_.usesClock = true;
    if (state_.viewDepth == 0) state_.usesClockOutsideViews = true;
    return state_.options.clock;
}

std::optional<double> Parser::Parenthesised(std::string_view what, int depth) {
    const Token open = Take();  // '('
    if (depth > kMaxDepth) {
        Error(open.loc, fmt::format("expression nested deeper than {} parentheses", kMaxDepth),
              kSyntax);
        return std::nullopt;
    }
    auto value = Sum(what, depth + 1);
    if (!value) return std::nullopt;
    if (!PeekIs(TokenKind::kRParen)) {
        Expected(fmt::format("')' to close the expression of {} opened at column {}", what,
                             open.loc.column));
        return std::nullopt;
    }
    Take();
    return value;
}

std::optional<double> Parser::Factor(std::string_view what, int depth) {
    const Token& t = Peek();
    if (t.kind == TokenKind::kNumber) return Take().number;
    if (t.kind == TokenKind::kId && t.text == "clock") {
        Take();
        return ClockValue();
    }
    if (t.kind == TokenKind::kLParen) return Parenthesised(what, depth);
    if (t.kind == TokenKind::kMinus || t.kind == TokenKind::kPlus) {
        const bool negate = t.kind == TokenKind::kMinus;
        Take();
        if (depth > kMaxDepth) {
            Error(Peek().loc, "expression nested too deeply", kSyntax);
            return std::nullopt;
        }
        auto v = Factor(what, depth + 1);
        if (!v) return std::nullopt;
        return negate ? -*v : *v;
    }
    Expected(fmt::format("a number, 'clock' or '(' in the expression of {}", what));
    return std::nullopt;
}

std::optional<double> Parser::Product(std::string_view what, int depth) {
    auto value = Factor(what, depth);
    while (value && (PeekIs(TokenKind::kStar) || PeekIs(TokenKind::kSlash))) {
        const Token op = Take();
        auto rhs = Factor(what, depth);
        if (!rhs) return std::nullopt;
        if (op.kind == TokenKind::kSlash && *rhs == 0) {
            Error(op.loc, fmt::format("division by zero in the expression of {}", what));
            return std::nullopt;
        }
        value = op.kind == TokenKind::kStar ? *value * *rhs : *value / *rhs;
        if (!std::isfinite(*value)) {
            Error(op.loc, fmt::format("the expression of {} is not a finite number", what));
            return std::nullopt;
        }
    }
    return value;
}

std::optional<double> Parser::Sum(std::string_view what, int depth) {
    auto value = Product(what, depth);
    while (value) {
        const Token& t = Peek();
        const SourceLoc loc = t.loc;
        std::optional<double> rhs;
        if (t.kind == TokenKind::kPlus || t.kind == TokenKind::kMinus) {
            const bool minus = t.kind == TokenKind::kMinus;
            Take();
            rhs = Product(what, depth);
            if (rhs && minus) rhs = -*rhs;
        } else if (t.kind == TokenKind::kNumber &&
                   (t.text.front() == '+' || t.text.front() == '-')) {
            // `(clock -1)`: the lexer saw a signed number; it is the right operand of a sum.
            rhs = Product(what, depth);
        } else {
            break;
        }
        if (!rhs) return std::nullopt;
        value = *value + *rhs;
        if (!std::isfinite(*value)) {
            Error(loc, fmt::format("the expression of {} is not a finite number", what));
            return std::nullopt;
        }
    }
    return value;
}

}  // namespace quadrix::lang
