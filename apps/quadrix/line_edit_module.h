// The interface between the `uq>` prompt (interactive.cpp) and its line editor, the module
// quadrix-lineedit.so (modules/lineedit/), which edits lines with libedit's readline interface
// (history with the arrow keys, kept in ~/.quadrix_history; tab completion of keywords and ids).
//
// libedit and the three libraries it brings (libtinfo, libbsd, libmd) cost every quadrix
// process about 0.2 ms of start-up (mapping, relocation, a longer symbol search for every other
// library: docs/performance.md "Small pictures"), for a prompt that only `quadrix -i` on a
// terminal shows. So, like the window of `quadrix view` and the Cairo, OpenEXR and MPI modules
// (src/quadrix/util/module_loader.h), it is loaded when that prompt first reads a line, and a
// quadrix whose module is missing reads plain lines, saying why once.
//
// The module depends on nothing of Quadrix but this header: it is given plain functions and
// strings.
#pragma once

#include <string>
#include <vector>

namespace quadrix::cli {

// Raised whenever LineEditModule changes, so that a module of another build is refused.
inline constexpr int kLineEditModuleAbi = 1;

// The completions of `word` after `before` (the line's text before the word) into `out`;
// `context` is the one given to setCompleter.
using LineEditCompleter = void (*)(void* context, const std::string& word,
                                   const std::string& before, std::vector<std::string>* out);

// The module's table (quadrix_lineedit_module() returns it). One editor per process: the
// functions act on libedit's global state and are called from one thread.
struct LineEditModule {
    int abi = kLineEditModuleAbi;
    // Starts the history, reading `historyPath` when it is not empty (absent: fine).
    void (*begin)(const char* historyPath) = nullptr;
    // Writes the history to `historyPath` when it is not empty.
    void (*end)(const char* historyPath) = nullptr;
    // Shows `prompt` and reads one line, without its newline, into `*line`, adding it to the
    // history unless blank. False at end of input.
    bool (*readLine)(const char* prompt, std::string* line) = nullptr;
    // Tab completion through `complete` (null: none), word breaks at `breaks`.
    void (*setCompleter)(LineEditCompleter complete, void* context, const char* breaks) = nullptr;
};

}  // namespace quadrix::cli

// Defined by modules/lineedit/lineedit_module.cpp, in quadrix-lineedit.so.
extern "C" const quadrix::cli::LineEditModule* quadrix_lineedit_module();
