// The statement table: one small function per statement keyword (seed 001 §2.1 and §2.3, plus the
// CSG extension). Each function is called after its keyword has been taken and parses the rest
// of the statement up to and including the ';'. It returns false after a syntax error it has
// reported (the parser then skips to the next ';').
//
// The functions live in files by concept:
//   stmt_half_space.cpp  plane, quadric                       (§2.1.1)
//   stmt_body.cpp        body                                 (§2.1.2)
//   stmt_csg.cpp         csg                                  (extension)
//   stmt_definition.cpp  definition, enddef, instance, array  (§2.1.3, §2.1.4)
//   stmt_light.cpp       light                                (§2.1.5)
//   stmt_view.cpp        view                                 (§2.1.6)
//   stmt_read.cpp        read / include, naked read           (§2.1.7, §2.3)
//   stmt_interactive.cpp redef, device, show, quit            (§2.3)
#pragma once

#include "quadrix/lang/keywords.h"
#include "quadrix/lang/token.h"

namespace quadrix::lang {

class Parser;
struct Command;

using StatementFn = bool (*)(Parser& parser, const Token& keyword);

struct StatementEntry {
    Keyword keyword;
    StatementFn parse;
    bool allowedInDefinition;  // definitions hold geometry only (§2.1.3), plus read and enddef
};

// The entry for a statement keyword; nullptr when `keyword` does not start a statement.
const StatementEntry* FindStatement(Keyword keyword);

bool ParsePlane(Parser& p, const Token& keyword);
bool ParseQuadric(Parser& p, const Token& keyword);
bool ParseBody(Parser& p, const Token& keyword);
bool ParseCsg(Parser& p, const Token& keyword);
bool ParsePatch(Parser& p, const Token& keyword);      // stmt_patch.cpp
bool ParseBezier(Parser& p, const Token& keyword);     // stmt_freeform.cpp
bool ParseBspline(Parser& p, const Token& keyword);    // stmt_freeform.cpp
bool ParsePatches(Parser& p, const Token& keyword);    // stmt_freeform.cpp
bool ParseSolid(Parser& p, const Token& keyword);      // stmt_solids.cpp: solids by dimensions
bool ParsePipeSolid(Parser& p, const Token& keyword);  // stmt_pipe.cpp: after `solid pipe`
bool ParseDefinition(Parser& p, const Token& keyword);
bool ParseEnddef(Parser& p, const Token& keyword);
bool ParseInstance(Parser& p, const Token& keyword);
bool ParseArray(Parser& p, const Token& keyword);
bool ParseLight(Parser& p, const Token& keyword);
bool ParseBackground(Parser& p, const Token& keyword);  // stmt_background.cpp
bool ParseView(Parser& p, const Token& keyword);
bool ParseRead(Parser& p, const Token& keyword);
bool ParseRedef(Parser& p, const Token& keyword);
bool ParseDevice(Parser& p, const Token& keyword);
bool ParseShow(Parser& p, const Token& keyword);
bool ParseQuit(Parser& p, const Token& keyword);

// The two forms of `redef` (§2.3), called by ParseRedef after `redef light` / `redef view`.
bool ParseRedefLight(Parser& p, const Token& keyword);
bool ParseRedefView(Parser& p, const Token& keyword);

// Hands an interactive statement to ReadOptions::commands (stopping this input when it returns
// false). Without a handler, warns that the statement has no effect in batch rendering unless
// `changedScene` (a redef that gave new values has changed the scene); `quit` still stops
// reading the current input.
void RunCommand(Parser& p, const Command& command, bool changedScene);

}  // namespace quadrix::lang
