#include "quadrix/lang/statements.h"

#include <array>

namespace quadrix::lang {

namespace {
constexpr std::array kStatements = {
    StatementEntry{Keyword::kPlane, ParsePlane, true},
    StatementEntry{Keyword::kQuadric, ParseQuadric, true},
    StatementEntry{Keyword::kBody, ParseBody, true},
    StatementEntry{Keyword::kCsg, ParseCsg, true},
    StatementEntry{Keyword::kSolid, ParseSolid, true},
    StatementEntry{Keyword::kPatch, ParsePatch, true},
    StatementEntry{Keyword::kBezier, ParseBezier, true},
    StatementEntry{Keyword::kBspline, ParseBspline, true},
    StatementEntry{Keyword::kPatches, ParsePatches, true},
    StatementEntry{Keyword::kDefinition, ParseDefinition, true},  // reports nesting itself
    StatementEntry{Keyword::kEnddef, ParseEnddef, true},
    StatementEntry{Keyword::kInstance, ParseInstance, true},
    StatementEntry{Keyword::kArray, ParseArray, true},
    StatementEntry{Keyword::kRead, ParseRead, true},
    StatementEntry{Keyword::kLight, ParseLight, false},
    StatementEntry{Keyword::kBackground, ParseBackground, false},
    StatementEntry{Keyword::kView, ParseView, false},
    StatementEntry{Keyword::kRedef, ParseRedef, false},
    StatementEntry{Keyword::kDevice, ParseDevice, false},
    StatementEntry{Keyword::kShow, ParseShow, false},
    StatementEntry{Keyword::kQuit, ParseQuit, false},
};
}  // namespace

const StatementEntry* FindStatement(Keyword keyword) {
    for (const StatementEntry& e : kStatements)
        if (e.keyword == keyword) return &e;
    return nullptr;
}

}  // namespace quadrix::lang
