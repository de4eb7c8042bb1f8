// Hierarchy statements (seed 001 §2.1.3, §2.1.4) with the Quadrix color extension:
//   definition [id];  ...  enddef [id];
//   instance [id] ( defId transforms ) [=c r g b];
//   array    [id] ( defId initTransforms ) count deltaTransforms [=c r g b];
//
// A definition holds half-spaces, bodies, instances, arrays and csg solids with ids local to it.
// Definitions do not nest, and one must be complete (enddef) before it is instanced, which makes
// cyclic hierarchies impossible. An instance is an array of one copy; copy k (0-based) of an
// array is placed by delta^k · init (the Flattener composes them; here each list is composed
// left to right, transforms.h).
//
// Decisions where the paper is silent (docs/language.md): `enddef` may repeat the definition's
// id; a definition must end in the file that opened it; `=c` may follow the closing parenthesis
// or the delta transforms; the count is an integer in [0, 1000000].
#include <fmt/format.h>

#include <cmath>

#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"
#include "quadrix/lang/transforms.h"

namespace quadrix::lang {

namespace {

constexpr double kMaxCopies = 1000000;

// "(" defId transforms ")" shared by instance and array. `definition` is -1 when the id is unknown
// (reported).
bool ParseDefinitionRef(Parser& p, scene::Instance& inst, const char* statement) {
    if (!p.PeekIs(TokenKind::kLParen))
        return p.Expected(fmt::format("'(' after the {} id", statement));
    Token open = p.Take();
    std::string defId;
    SourceLoc defLoc;
    if (!p.ExpectId("the id of a definition", defId, defLoc)) return false;
    ReaderState& s = p.State();
    inst.definition = s.FindDefinition(defId);
    if (inst.definition < 0) {
        if (s.InDefinition() && s.CurrentScope().id == defId)
            p.Error(defLoc, fmt::format("definition '{}' cannot instance itself (a definition "
                                        "must be complete before it is instanced)",
                                        defId));
        else
            p.Error(defLoc, fmt::format("unknown definition '{}' (a definition must be given "
                                        "before it is instanced)",
                                        defId));
    }
    if (!ParseTransforms(p, inst.init)) return false;
    if (p.PeekIs(TokenKind::kOption)) {
        p.Error(p.Peek().loc,
                fmt::format("unknown transform {} (expected =tx =ty =tz =ta =sx =sy =sz =sa =rx "
                            "=ry =rz or a shear =vxy =vxz =vyx =vyz =vzx =vzy)",
                            Describe(p.Peek())),
                kSyntax);
        return false;
    }
    if (!p.PeekIs(TokenKind::kRParen))
        return p.Expected(
            fmt::format("a transform or ')' to close the '(' at {}", open.loc.ToString()));
    p.Take();
    return true;
}

// Appearance options (=c, =finish, =alpha) while the next token is one; false on a syntax error.
bool ParseOptionalColor(Parser& p, scene::Instance& inst) {
    while (p.PeekIs(TokenKind::kOption) && Parser::IsAppearanceOption(p.Peek().text)) {
        Token option = p.Take();
        if (!p.ParseAppearance(option, inst.color, inst.finish)) return false;
    }
    return true;
}

void AddInstance(Parser& p, scene::Instance inst, const SourceLoc& idLoc, const char* prefix) {
    ReaderState& s = p.State();
    if (inst.id.empty()) inst.id = s.GenerateId(prefix, ReaderState::Namespace::kSolid);
    if (std::string dup = s.DuplicateSolidMessage(inst.id); !dup.empty()) {
        p.Error(idLoc, dup);
        return;
    }
    if (inst.definition < 0) return;  // reported
    s.AddInstance(std::move(inst));
}

}  // namespace

bool ParseDefinition(Parser& p, const Token& keyword) {
    ReaderState& s = p.State();
    if (s.InDefinition()) {
        const scene::Scope& open = s.CurrentScope();
        p.Error(keyword.loc, fmt::format("definitions cannot be nested (definition '{}' opened "
                                         "at {} has no enddef yet)",
                                         open.id, open.loc.ToString()));
        return false;
    }
    scene::Scope def;
    def.loc = keyword.loc;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(def.id, idLoc)) return false;
    if (!p.ExpectSemicolon(def.id.empty() ? "'definition'" : "the definition id")) return false;
    if (def.id.empty()) def.id = s.GenerateId("def", ReaderState::Namespace::kDefinition);
    if (int first = s.FindDefinition(def.id); first >= 0)
        p.Error(idLoc, fmt::format("definition '{}' is already defined at {}", def.id,
                                   s.scene.definitions[first].loc.ToString()));
    s.OpenDefinition(std::move(def), &p.GetSource());
    return true;
}

bool ParseEnddef(Parser& p, const Token& keyword) {
    ReaderState& s = p.State();
    std::string id;
    SourceLoc idLoc;
    if (!p.OptionalId(id, idLoc)) return false;
    if (!p.ExpectSemicolon(id.empty() ? "'enddef'" : "the enddef id")) return false;
    if (!s.InDefinition()) {
        p.Error(keyword.loc, "enddef without a definition");
        return true;
    }
    const scene::Scope& def = s.CurrentScope();
    if (s.DefinitionSource() != &p.GetSource()) {
        p.Error(keyword.loc, fmt::format("enddef must be in the file that opened definition "
                                         "'{}' (at {})",
                                         def.id, def.loc.ToString()));
        return true;
    }
    if (!id.empty() && id != def.id)
        p.Error(idLoc, fmt::format("enddef '{}' does not match definition '{}' opened at {}", id,
                                   def.id, def.loc.ToString()));
    if (def.halfSpaces.empty() && def.bodies.empty() && def.instances.empty() && def.csgs.empty() &&
        def.freeforms.empty())
        p.Warning(keyword.loc, fmt::format("definition '{}' is empty", def.id));
    s.CloseDefinition();
    return true;
}

bool ParseInstance(Parser& p, const Token& keyword) {
    scene::Instance inst;
    inst.loc = keyword.loc;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(inst.id, idLoc)) return false;
    if (!ParseDefinitionRef(p, inst, "instance")) return false;
    if (!ParseOptionalColor(p, inst)) return false;
    if (p.PeekIs(TokenKind::kOption)) {
        p.Error(p.Peek().loc,
                fmt::format("unexpected {} after ')': an instance's transforms go inside the "
                            "parentheses, and only =c, =finish and =alpha may follow them",
                            Describe(p.Peek())),
                kSyntax);
        return false;
    }
    if (!p.ExpectSemicolon("the instance")) return false;
    AddInstance(p, std::move(inst), idLoc, "i");
    return true;
}

bool ParseArray(Parser& p, const Token& keyword) {
    scene::Instance inst;
    inst.loc = keyword.loc;
    inst.isArray = true;
    SourceLoc idLoc = keyword.loc;
    if (!p.OptionalId(inst.id, idLoc)) return false;
    if (!ParseDefinitionRef(p, inst, "array")) return false;
    if (!ParseOptionalColor(p, inst)) return false;

    SourceLoc countLoc = p.Peek().loc;
    auto count = p.ExpectNumber("the number of copies after ')'");
    if (!count) return false;
    if (*count < 0 || *count != std::floor(*count) || *count > kMaxCopies) {
        p.Error(countLoc, fmt::format("the number of copies must be a whole number from 0 to {}, "
                                      "not {}",
                                      kMaxCopies, *count));
        inst.count = 0;
    } else {
        inst.count = static_cast<int>(*count);
    }

    bool sawDelta = false;
    while (p.PeekIs(TokenKind::kOption)) {
        if (Parser::IsAppearanceOption(p.Peek().text)) {
            if (!ParseOptionalColor(p, inst)) return false;
            continue;
        }
        if (!IsTransformOption(p.Peek().text)) {
            p.Error(p.Peek().loc,
                    fmt::format("unknown delta transform {} (expected =tx =ty =tz =ta =sx =sy "
                                "=sz =sa =rx =ry =rz =vxy ..., =c, =finish or =alpha)",
                                Describe(p.Peek())),
                    kSyntax);
            return false;
        }
        sawDelta = true;
        if (!ParseTransforms(p, inst.delta)) return false;
    }
    if (!p.ExpectSemicolon("the array's delta transforms")) return false;
    if (inst.count == 0 && *count == 0) p.Warning(countLoc, "an array of 0 copies draws nothing");
    if (inst.count > 1 && !sawDelta)
        p.Warning(countLoc, "array without delta transforms: all copies are at the same place");
    AddInstance(p, std::move(inst), idLoc, "a");
    return true;
}

}  // namespace quadrix::lang
