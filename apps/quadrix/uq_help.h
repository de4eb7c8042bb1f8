// What the uq> prompt tells about itself (issue 21): the `help` statement's text and the words
// offered by tab completion. Both read the statement keywords from the language's own tables
// (lang/keywords.h, lang/statements.h), so a new statement appears here without an edit, and
// the ids from the scene being read.
#pragma once

#include <string>
#include <vector>

#include "quadrix/scene/scene.h"

namespace quadrix::cli {

// What `help` reports about the session besides the statements.
struct UqHelpState {
    std::string view;    // current view id ("" = the last defined, or the default)
    std::string light;   // current parallel light id ("" = the last defined, or the default)
    std::string device;  // "NAME" or "NAME:PATH"
    std::string engine;
};

// `help;` (topic empty): the statements, the current view/light/device/engine and the scene's
// ids by kind. `help WORD;`: the syntax of that statement (a keyword or synonym), or of the
// view parameters, devices or ids.
std::string UqHelpText(const std::string& topic, const scene::Scene& scene,
                       const UqHelpState& state);

// Completions of `word` (the partial word under the cursor) after `before` (the text of the
// line before it): statement keywords (and help) at the start of a statement; device names
// after device; keywords and the scene's ids elsewhere. Sorted, without duplicates.
std::vector<std::string> UqCompletions(const std::string& word, const std::string& before,
                                       const scene::Scene& scene);

// True when `word` starts a statement (a statement keyword or synonym; not help).
bool IsStatementWord(const std::string& word);
// True for the words of the session's own help statement ("help", "?").
bool IsHelpWord(const std::string& word);

}  // namespace quadrix::cli
