// Interactive statements (seed 001 §2.3), also valid in batch files:
//   redef light id [intensity [x y z]];      (stmt_light.cpp)
//   redef view id [params];                  (stmt_view.cpp)
//   device name [keep] [nokeep] [xsize inches] [ysize inches];
//   show [viewId] [fast];
//   quit;
// The reader parses them into a Command for ReadOptions::commands. Without a handler (batch
// rendering) they are accepted with a warning that they have no effect; quit still stops reading
// the current input ("quit returns control to the batch file").
#include <fmt/format.h>

#include <cmath>

#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

namespace {

const char* CommandName(Command::Kind kind) {
    switch (kind) {
        case Command::Kind::kRedefLight:
            return "redef light";
        case Command::Kind::kRedefView:
            return "redef view";
        case Command::Kind::kDevice:
            return "device";
        case Command::Kind::kShow:
            return "show";
        case Command::Kind::kQuit:
            return "quit";
        case Command::Kind::kNakedRead:
            return "read;";
    }
    return "?";
}

bool IsShowWord(Keyword k) { return k == Keyword::kFast; }

bool IsDeviceOption(Keyword k) {
    return k == Keyword::kKeep || k == Keyword::kNokeep || k == Keyword::kXsize ||
           k == Keyword::kYsize;
}

}  // namespace

void RunCommand(Parser& p, const Command& command, bool changedScene) {
    ReaderState& s = p.State();
    if (s.options.commands) {
        if (!s.options.commands->OnCommand(command, s.scene, s.diags)) p.Stop();
        return;
    }
    if (command.kind == Command::Kind::kQuit) {
        p.Warning(command.loc,
                  fmt::format("quit: the rest of {} is not read", *p.GetSource().Name()));
        p.Stop();
        return;
    }
    if (!changedScene)
        p.Warning(command.loc,
                  fmt::format("'{}' has no effect in batch rendering", CommandName(command.kind)));
}

bool ParseRedef(Parser& p, const Token& keyword) {
    if (p.PeekIsKeyword(Keyword::kLight)) {
        p.Take();
        return ParseRedefLight(p, keyword);
    }
    if (p.PeekIsKeyword(Keyword::kView)) {
        p.Take();
        return ParseRedefView(p, keyword);
    }
    return p.Expected("'light' or 'view' after 'redef'");
}

bool ParseDevice(Parser& p, const Token& keyword) {
    Command command;
    command.kind = Command::Kind::kDevice;
    command.loc = keyword.loc;
    // Device names are free words: some of the paper's short names ("a" for ascii) are also
    // synonyms of statement keywords, so keywords are accepted here, except the options.
    const Token& name = p.Peek();
    bool isName = name.kind == TokenKind::kId || name.kind == TokenKind::kString ||
                  (name.kind == TokenKind::kKeyword && !IsDeviceOption(name.keyword));
    if (!isName) return p.Expected("a device name after 'device'");
    command.device = p.Take().text;
    for (;;) {
        if (p.PeekIsKeyword(Keyword::kKeep)) {
            p.Take();
            command.keep = true;
            command.nokeep = false;
        } else if (p.PeekIsKeyword(Keyword::kNokeep)) {
            p.Take();
            command.nokeep = true;
            command.keep = false;
        } else if (p.PeekIsKeyword(Keyword::kXsize) || p.PeekIsKeyword(Keyword::kYsize)) {
            Token option = p.Take();
            SourceLoc at = p.Peek().loc;
            auto inches = p.ExpectNumber(fmt::format("a size in inches after {}", option.text));
            if (!inches) return false;
            if (*inches <= 0) {
                p.Error(at, fmt::format("{} must be greater than 0, not {}", option.text, *inches));
                continue;
            }
            (option.keyword == Keyword::kXsize ? command.xsizeInches : command.ysizeInches) =
                *inches;
        } else {
            break;
        }
    }
    if (!p.ExpectStatementEnd("keep, nokeep, xsize, ysize or ';' in the device statement"))
        return false;
    RunCommand(p, command, false);
    return true;
}

bool ParseShow(Parser& p, const Token& keyword) {
    Command command;
    command.kind = Command::Kind::kShow;
    command.loc = keyword.loc;
    SourceLoc idLoc;
    if (!p.OptionalId(command.id, idLoc, IsShowWord)) return false;
    if (p.PeekIsKeyword(Keyword::kFast)) {
        p.Take();
        command.fast = true;
    }
    if (!p.ExpectStatementEnd(command.fast ? "';' after 'fast'"
                                           : "a view id, 'fast' or ';' after 'show'"))
        return false;
    if (!command.id.empty() && command.id != "default" && p.State().FindView(command.id) < 0) {
        p.Error(idLoc, fmt::format("unknown view '{}'", command.id));
        return true;
    }
    RunCommand(p, command, false);
    return true;
}

bool ParseQuit(Parser& p, const Token& keyword) {
    if (!p.ExpectSemicolon("'quit'")) return false;
    Command command;
    command.kind = Command::Kind::kQuit;
    command.loc = keyword.loc;
    RunCommand(p, command, false);
    return true;
}

}  // namespace quadrix::lang
