// quadrix-lineedit.so: the line editor of the `uq>` prompt, libedit's readline interface (BSD
// license) behind the table of apps/quadrix/line_edit_module.h.
#include <editline/readline.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "line_edit_module.h"

namespace quadrix::cli {

namespace {

// Tab completion: libedit calls C callbacks, so the completer lives here (one editor per
// process).
LineEditCompleter gComplete = nullptr;
void* gContext = nullptr;
std::vector<std::string> gMatches;

char* NextMatch(const char*, int state) {
    static std::size_t next = 0;
    if (state == 0) next = 0;
    if (next >= gMatches.size()) return nullptr;
    return strdup(gMatches[next++].c_str());
}

char** Complete(const char* text, int start, int) {
    rl_attempted_completion_over = 1;  // no file-name completion instead
    gMatches.clear();
    if (gComplete) {
        const std::string before(rl_line_buffer ? rl_line_buffer : "",
                                 static_cast<std::size_t>(start > 0 ? start : 0));
        gComplete(gContext, text, before, &gMatches);
    }
    return rl_completion_matches(text, NextMatch);
}

void Begin(const char* historyPath) {
    using_history();
    if (historyPath && *historyPath) read_history(historyPath);
}

void End(const char* historyPath) {
    if (historyPath && *historyPath) write_history(historyPath);
}

bool ReadLine(const char* prompt, std::string* line) {
    char* text = readline(prompt);
    if (!text) {
        std::fputc('\n', stdout);
        return false;
    }
    *line = text;
    std::free(text);
    if (line->find_first_not_of(" \t") != std::string::npos) add_history(line->c_str());
    return true;
}

void SetCompleter(LineEditCompleter complete, void* context, const char* breaks) {
    gComplete = complete;
    gContext = context;
    rl_attempted_completion_function = complete ? Complete : nullptr;
    static std::string wordBreaks;  // libedit keeps the pointer
    wordBreaks = breaks ? breaks : " \t\n";
    rl_basic_word_break_characters = wordBreaks.c_str();
}

}  // namespace

}  // namespace quadrix::cli

extern "C" __attribute__((visibility("default"))) const quadrix::cli::LineEditModule*
quadrix_lineedit_module() {
    static const quadrix::cli::LineEditModule table{
        quadrix::cli::kLineEditModuleAbi, &quadrix::cli::Begin, &quadrix::cli::End,
        &quadrix::cli::ReadLine, &quadrix::cli::SetCompleter};
    return &table;
}
