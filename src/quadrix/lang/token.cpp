#include "quadrix/lang/token.h"

#include <fmt/format.h>

namespace quadrix::lang {

namespace {
// Long ids and numbers are shortened so that a message stays one readable line.
std::string Shortened(const std::string& s) {
    constexpr std::size_t kMax = 40;
    if (s.size() <= kMax) return s;
    return s.substr(0, kMax) + "...";
}
}  // namespace

std::string Describe(const Token& token) {
    switch (token.kind) {
        case TokenKind::kEnd:
            return "end of input";
        case TokenKind::kString:
            return fmt::format("\"{}\"", Shortened(token.text));
        case TokenKind::kOption:
            return fmt::format("'={}'", Shortened(token.text));
        case TokenKind::kError:
            return "malformed input";
        default:
            return fmt::format("'{}'", Shortened(token.text));
    }
}

}  // namespace quadrix::lang
