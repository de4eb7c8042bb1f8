// The CSG extension statement (docs/language.md; decided in the project's design notes):
//   csg [id] ( expr ) [=c r g b | =c name] [=finish kd ks n] [=alpha a];
//   expr   := term { '|' term }                  union, lowest precedence
//   term   := factor { ('&' | '-') factor }      intersection / difference, left-associative
//   factor := id | '(' expr ')'
// Operands are bodies, instances/arrays or csg solids of the same scope that already exist, so a
// csg cannot name itself or a later one (no cycles). Operands are marked usedAsOperand: they are
// drawn only as part of the csg. Parentheses nest at most kMaxNesting deep, which also bounds the
// recursion of this recursive-descent parser.
#include <fmt/format.h>

#include <algorithm>

#include "quadrix/lang/big_arrays.h"
#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

namespace {

constexpr int kMaxNesting = 256;
constexpr int kInvalid = -1;  // a subtree with an unknown operand (reported)

class CsgBuilder {
  public:
    CsgBuilder(Parser& p, scene::Csg& csg) : p_(p), csg_(csg) {}

    // Each returns the node index, kInvalid for a subtree with a reported meaning error, or
    // nullopt after a syntax error.
    std::optional<int> Expr() {
        auto left = Term();
        while (left && p_.PeekIs(TokenKind::kPipe)) {
            Token op = p_.Take();
            auto right = Term();
            if (!right) return std::nullopt;
            left = Combine(scene::CsgOp::kUnion, *left, *right, op.loc);
        }
        return left;
    }

    // The statement's own parentheses count as the first level.
    std::optional<int> Parenthesised() {
        Token open = p_.Take();  // '('
        if (++depth_ > kMaxNesting) {
            p_.Error(open.loc,
                     fmt::format("csg expression nested deeper than {} parentheses", kMaxNesting),
                     kParser);
            return std::nullopt;
        }
        auto inner = Expr();
        if (!inner) return std::nullopt;
        if (!p_.PeekIs(TokenKind::kRParen)) {
            p_.Expected(
                fmt::format("'|', '&', '-' or ')' to close the '(' at {}", open.loc.ToString()));
            return std::nullopt;
        }
        p_.Take();
        --depth_;
        return inner;
    }

  private:
    std::optional<int> Term() {
        auto left = Factor();
        while (left && (p_.PeekIs(TokenKind::kAmp) || p_.PeekIs(TokenKind::kMinus))) {
            Token op = p_.Take();
            auto right = Factor();
            if (!right) return std::nullopt;
            left = Combine(op.kind == TokenKind::kAmp ? scene::CsgOp::kIntersection
                                                      : scene::CsgOp::kDifference,
                           *left, *right, op.loc);
        }
        return left;
    }

    std::optional<int> Factor() {
        if (p_.PeekIs(TokenKind::kLParen)) return Parenthesised();
        std::string id;
        TokenLoc loc;
        if (!p_.ExpectId("a body, instance, array or csg id, or '('", id, loc)) return std::nullopt;
        return Leaf(id, loc);
    }

    int Leaf(const std::string& id, const TokenLoc& loc) {
        ReaderState& s = p_.State();
        auto ref = s.FindSolid(id);
        if (!ref) {
            if (id == csg_.id)
                p_.Error(loc, fmt::format("csg solid '{}' cannot be an operand of itself", id));
            else if (s.FindHalfSpace(id) >= 0)
                p_.Error(loc, fmt::format("'{}' is a half-space; csg operands are bodies, "
                                          "instances, arrays or csg solids",
                                          id));
            else
                p_.Error(loc, fmt::format("unknown csg operand '{}' (operands must be defined "
                                          "before the csg, in the same scope)",
                                          id));
            return kInvalid;
        }
        scene::CsgNode node;
        node.isLeaf = true;
        node.ref = *ref;
        node.loc = loc;
        PrepareAppend(csg_.nodes);
        csg_.nodes.push_back(std::move(node));
        return static_cast<int>(csg_.nodes.size()) - 1;
    }

    int Combine(scene::CsgOp op, int left, int right, const TokenLoc& loc) {
        if (left == kInvalid || right == kInvalid) return kInvalid;
        scene::CsgNode node;
        node.isLeaf = false;
        node.op = op;
        node.left = left;
        node.right = right;
        node.loc = loc;
        PrepareAppend(csg_.nodes);
        csg_.nodes.push_back(std::move(node));
        return static_cast<int>(csg_.nodes.size()) - 1;
    }

    Parser& p_;
    scene::Csg& csg_;
    int depth_ = 0;
};

}  // namespace

bool ParseCsg(Parser& p, const Token& keyword) {
    scene::Csg csg;
    csg.loc = keyword.loc;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(csg.id, idLoc)) return false;
    if (!p.PeekIs(TokenKind::kLParen)) return p.Expected("'(' to start the csg expression");
    // A big expression gets its node array at once (big_arrays.h): a node per operand and per
    // operator, at most 2 per operator character ahead ('-' may also start a number).
    if (std::string_view ahead = p.TextToSemicolon(); ahead.size() >= 16384) {
        const auto ops = std::count_if(ahead.begin(), ahead.end(),
                                       [](char c) { return c == '|' || c == '&' || c == '-'; });
        ReserveAdvised(csg.nodes, 2 * static_cast<std::size_t>(ops) + 1);
    }
    CsgBuilder builder(p, csg);
    auto root = builder.Parenthesised();
    if (!root) return false;
    while (p.PeekIs(TokenKind::kOption)) {
        Token option = p.Take();
        if (!Parser::IsAppearanceOption(option.text)) {
            p.Error(option.loc,
                    fmt::format("unknown option {} for a csg (expected =c r g b, =finish or "
                                "=alpha)",
                                Describe(option)),
                    kSyntax);
            return false;
        }
        if (!p.ParseAppearance(option, csg.color, csg.finish)) return false;
    }
    if (!p.ExpectSemicolon("the csg expression")) return false;

    ReaderState& s = p.State();
    if (csg.id.empty()) csg.id = s.GenerateId("c", ReaderState::Namespace::kSolid);
    if (std::string dup = s.DuplicateSolidMessage(csg.id); !dup.empty()) {
        p.Error(idLoc, dup);
        return true;
    }
    if (*root == kInvalid) return true;  // reported
    csg.root = *root;
    for (const scene::CsgNode& node : csg.nodes)
        if (node.isLeaf) s.MarkOperand(node.ref);
    s.AddCsg(std::move(csg));
    return true;
}

}  // namespace quadrix::lang
