// body statement (seed 001 §2.1.2) with the Quadrix color extension:
//   body [id] ( [!]hsId ... ) [=c r g b | =c name] [=finish kd ks n] [=alpha a];
// The list may also be written with angle brackets, < ... >, as in the paper's tube example.
// A body is the intersection of the half-spaces it names; '!' takes the complement of one.
// Bodies may name only half-spaces of their own scope (§2.1.3).
#include <fmt/format.h>

#include <unordered_map>
#include <utility>
#include <vector>

#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

namespace {

// Reads one literal and appends it to `body` unless its id is unknown (reported).
// The half-spaces a body has named so far, with where: a short list searched linearly (most
// bodies name a handful), indexed by a hash map once it grows past kLinear entries.
class SeenLiterals {
  public:
    const TokenLoc* Find(int index) const {
        if (map_.empty()) {
            for (std::size_t k = 0; k < size_; ++k)
                if (At(k).first == index) return &At(k).second;
            return nullptr;
        }
        auto it = map_.find(index);
        return it == map_.end() ? nullptr : &At(it->second).second;
    }
    void Add(int index, const TokenLoc& loc) {
        // The first few in place: most bodies name one to six half-spaces, and a vector would
        // allocate for each body.
        if (size_ < kInPlace)
            inPlace_[size_] = {index, loc};
        else
            more_.emplace_back(index, loc);
        ++size_;
        if (size_ == kLinear)
            for (std::size_t k = 0; k < size_; ++k) map_.emplace(At(k).first, k);
        else if (size_ > kLinear)
            map_.emplace(index, size_ - 1);
    }

  private:
    const std::pair<int, TokenLoc>& At(std::size_t k) const {
        return k < kInPlace ? inPlace_[k] : more_[k - kInPlace];
    }
    static constexpr std::size_t kInPlace = 8;
    static constexpr std::size_t kLinear = 16;
    std::pair<int, TokenLoc> inPlace_[kInPlace];
    std::size_t size_ = 0;
    std::vector<std::pair<int, TokenLoc>> more_;
    std::unordered_map<int, std::size_t> map_;
};

bool ParseLiteral(Parser& p, scene::Body& body, SeenLiterals& seen) {
    bool complemented = false;
    if (p.PeekIs(TokenKind::kBang)) {
        p.Take();
        complemented = true;
    }
    std::string id;
    TokenLoc loc;
    if (!p.ExpectId(complemented ? "a half-space id after '!'" : "a half-space id or '!'", id, loc))
        return false;
    ReaderState& s = p.State();
    int index = s.FindHalfSpace(id);
    if (index < 0) {
        std::string where = s.InDefinition() ? fmt::format(
                                                   " in definition '{}' (a body may name only the "
                                                   "half-spaces of its own definition)",
                                                   s.CurrentScope().id)
                                             : std::string();
        p.Error(loc, fmt::format("unknown half-space '{}'{}", id, where));
        return true;
    }
    if (const TokenLoc* first = seen.Find(index))
        p.Warning(loc, fmt::format("half-space '{}' is named twice in this body (first at {})", id,
                                   first->ToString()));
    else
        seen.Add(index, loc);
    body.literals.push_back({index, complemented});
    return true;
}

}  // namespace

bool ParseBody(Parser& p, const Token& keyword) {
    scene::Body body;
    body.loc = keyword.loc;
    TokenLoc idLoc = keyword.loc;
    if (!p.OptionalId(body.id, idLoc)) return false;

    Token open = p.Peek();
    if (!p.PeekIs(TokenKind::kLParen) && !p.PeekIs(TokenKind::kLAngle))
        return p.Expected("'(' or '<' to start the body's list of half-spaces");
    p.Take();
    TokenKind closeKind = open.kind == TokenKind::kLParen ? TokenKind::kRParen : TokenKind::kRAngle;
    const char* closeText = open.kind == TokenKind::kLParen ? "')'" : "'>'";
    SeenLiterals seen;
    bool sawLiteral = false;
    while (!p.PeekIs(closeKind)) {
        if (!p.PeekIs(TokenKind::kId) && !p.PeekIs(TokenKind::kBang) &&
            !p.PeekIs(TokenKind::kKeyword))
            return p.Expected(sawLiteral ? fmt::format("a half-space id or {} to end the list "
                                                       "opened at {}",
                                                       closeText, open.loc.ToString())
                                         : std::string("a half-space id or '!'"));
        if (!ParseLiteral(p, body, seen)) return false;
        sawLiteral = true;
    }
    p.Take();
    if (!sawLiteral) p.Error(open.loc, "a body must name at least one half-space");

    while (p.PeekIs(TokenKind::kOption)) {
        Token option = p.Take();
        if (!Parser::IsAppearanceOption(option.text)) {
            p.Error(option.loc,
                    fmt::format("unknown option {} for a body (expected =c r g b, =finish or "
                                "=alpha)",
                                Describe(option)),
                    kSyntax);
            return false;
        }
        if (!p.ParseAppearance(option, body.color, body.finish)) return false;
    }
    if (!p.TakeIf(TokenKind::kSemicolon) && !p.ExpectSemicolon("body list")) return false;

    ReaderState& s = p.State();
    if (body.id.empty()) body.id = s.GenerateId("b", ReaderState::Namespace::kSolid);
    if (std::string dup = s.DuplicateSolidMessage(body.id); !dup.empty()) {
        p.Error(idLoc, dup);
        return true;
    }
    // A body whose ids were all unknown (reported) is dropped; one with some known ids is kept,
    // so that statements naming it do not report more errors.
    if (body.literals.empty()) return true;
    s.AddBody(std::move(body));
    return true;
}

}  // namespace quadrix::lang
