// read statement (seed 001 §2.1.7, §2.3):
//   read "pathName";   read pathName;   read -;   read;
// The quotes may be left out when the name is an id (no '.', '/', ...). "-" is standard input.
// `include` is a synonym of `read`. A naked `read;` is the interactive statement that enters
// interactive mode during batch processing (handed to the CommandHandler).
#include <fmt/format.h>

#include "quadrix/lang/input_files.h"
#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

bool ParseRead(Parser& p, const Token& keyword) {
    if (p.PeekIs(TokenKind::kSemicolon)) {
        p.Take();
        if (p.State().InDefinition()) {
            p.Error(keyword.loc, "a naked read is not allowed inside a definition");
            return true;
        }
        Command command;
        command.kind = Command::Kind::kNakedRead;
        command.loc = keyword.loc;
        RunCommand(p, command, false);
        return true;
    }
    std::string path;
    const Token& t = p.Peek();
    // `t` refers to the parser's look-ahead, which Take() destroys: keep its position (a fuzzed
    // `include "";` once reported "empty file name" with no position, issue 7).
    const SourceLoc nameLoc = t.loc;
    if (t.kind == TokenKind::kString || t.kind == TokenKind::kId) {
        path = p.Take().text;
    } else if (t.kind == TokenKind::kMinus) {
        p.Take();
        path = "-";
    } else if (t.kind == TokenKind::kKeyword && t.loc.line > keyword.loc.line &&
               p.AtStatementKeyword()) {
        // `read` alone at the end of a line, then the next statement: a forgotten ';' or name.
        return p.ExpectStatementEnd("a file name or ';' after 'read'");
    } else if (t.kind == TokenKind::kKeyword) {
        p.Error(t.loc,
                fmt::format("'{}' is a reserved word; write the file name in quotes: read \"{}\"",
                            t.text, t.text),
                kSyntax);
        return false;
    } else {
        return p.Expected("a file name (in quotes unless it is an id) or ';' after 'read'");
    }
    if (path.empty()) {
        p.Error(nameLoc, "empty file name");
        return false;
    }
    if (!p.ExpectSemicolon("the file name")) return false;
    ReadIncluded(p.State(), p, path, keyword.loc);
    return true;
}

}  // namespace quadrix::lang
