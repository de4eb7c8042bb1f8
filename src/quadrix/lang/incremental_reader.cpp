// Interactive input fed a line at a time (incremental_reader.h): the held text is cut into
// statements by a light scan (comments, strings, the first word, the ';'), and each complete
// statement is appended to one growing Source that a Parser kept across lines reads
// (Parser::RunAvailable), so positions count the lines fed and definitions span statements.
#include "quadrix/lang/incremental_reader.h"

#include <fmt/format.h>

#include <cctype>
#include <utility>

#include "quadrix/lang/keywords.h"
#include "quadrix/lang/parser.h"
#include "quadrix/lang/reader_state.h"
#include "quadrix/lang/source.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

namespace {

bool Blank(std::string_view s) { return s.find_first_not_of(" \t\r\n") == std::string::npos; }

std::string Lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// True when `word` starts a statement of the language (a keyword or synonym with a statement).
bool IsStatementWord(const std::string& word) {
    const Keyword k = LookupKeyword(word);
    return k != Keyword::kNone && FindStatement(k) != nullptr;
}

// Where the held text stops: the first word (outside comments), the end of the first statement
// (after its ';', outside comments and "strings"; npos if none), and whether the text ends
// inside a comment.
struct Scan {
    std::string firstWord;
    std::size_t wordEnd = std::string::npos;
    std::size_t end = std::string::npos;
    bool openComment = false;
};

Scan ScanStatement(std::string_view text) {
    Scan scan;
    int depth = 0;
    bool inString = false, wordDone = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '"' || c == '\n') inString = false;
            continue;
        }
        if (depth > 0) {
            depth += c == '{' ? 1 : c == '}' ? -1 : 0;
            continue;
        }
        if (c == '{') {
            ++depth;
            wordDone = wordDone || !scan.firstWord.empty();
            continue;
        }
        if (c == ';') {
            scan.end = i + 1;
            if (!scan.firstWord.empty() && scan.wordEnd == std::string::npos) scan.wordEnd = i;
            return scan;
        }
        if (c == '"') inString = true;
        const bool wordChar = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '#' ||
                              c == '?' || c == '.';
        if (!wordDone && wordChar) {
            scan.firstWord += c;
        } else if (!scan.firstWord.empty() && !wordDone) {
            wordDone = true;
            scan.wordEnd = i;
        } else if (!wordDone && !std::isspace(static_cast<unsigned char>(c))) {
            wordDone = true;  // the statement starts with punctuation
            scan.firstWord = std::string(1, c);
            scan.wordEnd = i + 1;
        }
    }
    scan.openComment = depth > 0;
    if (!scan.firstWord.empty() && scan.wordEnd == std::string::npos) scan.wordEnd = text.size();
    return scan;
}

}  // namespace

struct IncrementalReader::Impl {
    ReaderState& state;
    Hooks hooks;
    Source source;
    std::unique_ptr<Parser> parser;  // null when nested too deep
    std::string held;                // an unfinished statement
    bool skipping = false;           // after an error, up to the next ';'
    bool stopped = false;            // quit or abort
    bool finished = false;

    Impl(ReaderState& s, Hooks h, std::string name)
        : state(s), hooks(std::move(h)), source(std::move(name), std::string()) {}

    bool OwnWord(const std::string& word) const { return hooks.ownWord && hooks.ownWord(word); }

    // Appends `text` to the source and reads the statements in it.
    void Run(const std::string& text) {
        const int errorsBefore = state.diags.ErrorCount();
        source.Append(text);
        if (!parser->RunAvailable()) stopped = true;
        if (hooks.afterStatement)
            hooks.afterStatement(text, state.diags.ErrorCount() - errorsBefore);
    }

    // Text the parser must not read (skipped input, own statements): positions still count it.
    void Skip(std::string_view text) {
        source.Append(text);
        parser->SkipInput(source.Size());
    }

    // Gives the complete statements (and skipped text) of the held text to the parser.
    void ProcessHeld(std::vector<std::string>& statements) {
        while (!stopped) {
            const Scan scan = ScanStatement(held);
            if (scan.firstWord.empty() && scan.end == std::string::npos) {
                // Only blanks and whole comments: handed over so that positions keep counting.
                if (!scan.openComment) {
                    Skip(held);
                    held.clear();
                }
                return;
            }
            if (OwnWord(Lower(scan.firstWord))) {
                // The caller's own statement; its ';' may be left out at the end of the line.
                const std::size_t end = scan.end == std::string::npos ? held.size() : scan.end;
                const std::string statement = held.substr(0, end);
                Skip(statement);
                held.erase(0, end);
                statements.push_back(statement);
                if (hooks.runOwn) hooks.runOwn(statement, statement.substr(scan.wordEnd));
                continue;
            }
            if (scan.end != std::string::npos) {
                const std::string statement = held.substr(0, scan.end);
                held.erase(0, scan.end);
                statements.push_back(statement);
                Run(statement);
                continue;
            }
            if (scan.openComment || IsStatementWord(scan.firstWord)) return;  // continues
            // Not a statement: the parser reports it now (not at some later ';'), and the rest
            // of it is skipped up to the next ';' or the next line that starts a statement.
            const std::string text = std::move(held);
            held.clear();
            Run(text);
            skipping = true;
            return;
        }
    }
};

IncrementalReader::IncrementalReader(Reader& reader, Hooks hooks, std::string name) {
    ReaderState& state = reader.State();
    impl_ = std::make_unique<Impl>(state, std::move(hooks), name);  // a copy: the stack needs it
    state.aborted = false;
    if (static_cast<int>(state.includeStack.size()) > state.options.maxIncludeDepth) {
        state.diags.Error({}, "interactive mode nested too deep", {}, kParser);
        impl_->stopped = impl_->finished = true;
        return;
    }
    // The key only has to differ from every file's (cycle detection) and from the other
    // interactive inputs on the stack.
    state.includeStack.push_back(
        {fmt::format("<interactive {}>", state.includeStack.size()), std::move(name)});
    impl_->parser = std::make_unique<Parser>(state, impl_->source);
}

IncrementalReader::~IncrementalReader() {
    if (!impl_->finished) impl_->state.includeStack.pop_back();
}

std::vector<std::string> IncrementalReader::Feed(std::string_view line) {
    std::vector<std::string> statements;
    Impl& m = *impl_;
    if (Ended()) return statements;
    std::string text = std::string(line) + "\n";
    if (m.skipping) {
        const Scan scan = ScanStatement(text);
        if (!IsStatementWord(scan.firstWord) && !m.OwnWord(Lower(scan.firstWord))) {
            const std::size_t end = scan.end == std::string::npos ? text.size() : scan.end;
            m.Skip(std::string_view(text).substr(0, end));
            text.erase(0, end);
            m.skipping = scan.end == std::string::npos;
        } else {
            m.skipping = false;
        }
    }
    if (!m.skipping) {
        m.held += text;
        m.ProcessHeld(statements);
    }
    return statements;
}

IncrementalReader::Position IncrementalReader::Where() const {
    if (impl_->skipping) return Position::kSkipping;
    return Blank(impl_->held) ? Position::kBetweenStatements : Position::kInsideStatement;
}

bool IncrementalReader::Ended() const { return impl_->stopped || impl_->finished; }

void IncrementalReader::Finish() {
    Impl& m = *impl_;
    if (m.finished) return;
    m.finished = true;
    // An unfinished statement at the end of input is read as it is (its error reported).
    if (!m.stopped && !m.skipping && !Blank(m.held)) m.Run(m.held);
    m.parser->Finish();
    m.state.includeStack.pop_back();
}

}  // namespace quadrix::lang
