// Reading inputs: top-level files and texts, `read` statements (seed 001 §2.1.7) and standard
// input.
//
//  - A relative path in a read statement is resolved against the directory of the file that
//    contains the statement (standard input and unnamed texts: the working directory).
//  - "-" is standard input, read a line at a time (so interactive input runs statement by
//    statement).
//  - Reads nest to ReadOptions::maxIncludeDepth (16) below the top-level input; one more is an
//    error at the read statement. A file that is already being read (a cycle) is an error naming
//    the chain.
//  - A file that cannot be read is an error at the read statement, or with no position for a
//    top-level file.
#pragma once

#include <string>
#include <string_view>

#include "quadrix/lang/reader_state.h"
#include "quadrix/scene/source_loc.h"

namespace quadrix::lang {

class Parser;

// Reads a top-level file ("-" = standard input).
void ReadTopLevelFile(ReaderState& state, const std::string& path);
// Reads a top-level text; `name` names it in diagnostics and anchors relative reads.
void ReadTopLevelText(ReaderState& state, std::string_view text, const std::string& name);
// `path` as a file named in a statement of `includer`'s source: relative paths are taken
// relative to that file's directory (standard input and unnamed texts: the working directory).
std::string ResolveAgainstIncluder(Parser& includer, const std::string& path);
// Executes `read path;` found by `includer` at `at`.
void ReadIncluded(ReaderState& state, Parser& includer, const std::string& path,
                  const SourceLoc& at);

}  // namespace quadrix::lang
