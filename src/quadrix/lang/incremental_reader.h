// Interactive input for the reader (seed 001 §2.3): text fed a line at a time into the scene of a
// Reader, the public face through which the uq> prompt, its tests and the viewer read what is
// typed (apps/quadrix/interactive.h). The contract:
//
//  - Statements complete across lines. A line is held until a ';' (outside { comments } and
//    "strings") ends the statement it belongs to; each statement is read as soon as it is
//    complete, and one line may complete several. The parser only ever sees complete
//    statements, so an error inside one never reaches past its ';'.
//  - Errors are positioned at the fed line: the text fed is one growing source (named `name`,
//    "<stdin>" by default) whose lines are the lines fed, blank lines and comments included, so
//    a diagnostic says "<stdin>:LINE:COLUMN" with the line typed and a caret.
//  - A line that does not start a statement (a misspelt keyword) is read at once, so that its
//    error is reported now and not at some later ';'. The input after it is skipped up to the
//    next ';' (§2.3), except that a line starting with a statement keyword ends the skip: the
//    next valid statement is never lost.
//  - The scene is extended in place: ids, the open definition and the CommandHandler (show,
//    device, quit, ...) are the Reader's, shared with the files it reads before and after. `quit`
//    (the handler returning false) or an abort (too many errors) ends the input: Feed then reads
//    nothing more.
//  - The caller's own statements (uq's `help`): a statement whose first word Hooks::ownWord
//    accepts ends at its ';' or at the end of its line; it is not parsed (its text only counts
//    for positions) but given to Hooks::runOwn.
//  - Interactive inputs nest like files (a `read;` met while reading starts another one on the
//    same Reader), to ReadOptions::maxIncludeDepth; one more is an error, and that input reads
//    nothing. An IncrementalReader must end (Finish or destruction) before an outer one goes on.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/lang/reader.h"

namespace quadrix::lang {

class IncrementalReader {
  public:
    struct Hooks {
        // True when `word` (lower case) starts one of the caller's own statements.
        std::function<bool(const std::string& word)> ownWord;
        // Runs an own statement: its text as typed and the text after its first word.
        std::function<void(const std::string& statement, const std::string& afterWord)> runOwn;
        // Called after each statement the parser read (complete, or the text of a line that does
        // not start a statement, or what is held at the end of input), with the number of errors
        // reported while reading and running it.
        std::function<void(const std::string& statement, int errors)> afterStatement;
    };

    // Where the fed input stands: between statements, inside one (a continuation line is
    // expected), or skipping to the next ';' after an error.
    enum class Position { kBetweenStatements, kInsideStatement, kSkipping };

    IncrementalReader(Reader& reader, Hooks hooks = {}, std::string name = "<stdin>");
    // Leaves the input without reading what is held and without calling the hooks (Finish is
    // the end of input); the Reader must still exist.
    ~IncrementalReader();
    IncrementalReader(const IncrementalReader&) = delete;
    IncrementalReader& operator=(const IncrementalReader&) = delete;

    // Feeds one line (without its newline) and reads the statements it completes. Returns those
    // statements as typed, in order (own statements included); nothing once Ended().
    std::vector<std::string> Feed(std::string_view line);
    Position Where() const;
    // True after quit, an abort, Finish, or when nested too deep: no more input is read.
    bool Ended() const;
    // The end of the input: an unfinished statement is read as it is (its error reported), then
    // an open definition is reported. Further calls do nothing.
    void Finish();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace quadrix::lang
