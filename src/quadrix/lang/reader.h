// Reader for the UniQuadrix scene language (seed 001 §2.1, §2.3) with the Quadrix extensions
// (CSG and colors), documented in docs/language.md.
//
// Pipeline inside the reader: Lexer (tokens tagged with file:line:column, nested { } comments)
// → Parser (one small function per statement keyword, dispatched by a table; synonyms resolved
// by the lexer's keyword table) → Scene (plain data, no transform applied except composing each
// statement's own transform list into a Transform).
//
// Errors are collected in a Diagnostics with the offending line and a caret; after an error the
// parser skips to the next ';' and goes on, so one run reports several errors.
//
// Interactive statements (`redef`, `device`, `show`, `quit`, naked `read;`) are parsed here and
// handed to a CommandHandler; without one they are accepted with a warning that they have no
// effect in batch rendering.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix::lang {

class ReaderState;

// An interactive-mode statement (seed 001 §2.3).
struct Command {
    enum class Kind { kRedefLight, kRedefView, kDevice, kShow, kQuit, kNakedRead };
    Kind kind = Kind::kShow;
    std::string id;                           // light/view id for redef and show
    bool fast = false;                        // show ... fast
    std::string device;                       // device name
    bool keep = false, nokeep = false;        // device options
    double xsizeInches = 0, ysizeInches = 0;  // device options, 0 = not given
    SourceLoc loc;
};

class CommandHandler {
  public:
    virtual ~CommandHandler() = default;
    // Returns false to stop reading the current input (quit).
    virtual bool OnCommand(const Command& command, scene::Scene& scene, Diagnostics& diags) = 0;
};

// A view or redef view statement as written: where it starts and its text from its first keyword
// to its ';'. A scene whose `clock` is only in its views re-reads just these at another clock
// (an animated camera: RenderContext::ReadAtClock), in order, on the views.
struct ViewStatement {
    std::shared_ptr<const std::string> file;  // its name in diagnostics
    int line = 0, column = 0;                 // of the first keyword, 1-based
    std::string text;
};

struct ReadOptions {
    int maxIncludeDepth = 16;  // seed 001 §2.1.7: reads nest to depth 16
    CommandHandler* commands = nullptr;
    // The value of `clock` in numbers (an animation's frame time, docs/language.md §3.14).
    double clock = 0;
};

class Reader {
  public:
    Reader(scene::Scene& scene, Diagnostics& diags, ReadOptions options = {});
    ~Reader();

    // Reads a file ("-" = standard input) into the scene. Returns false when errors were added.
    bool ReadFile(const std::string& path);
    // Reads text; `name` is used in diagnostics and to resolve relative `read` paths.
    bool ReadText(std::string_view text, const std::string& name);
    // Whether some number read so far was written with `clock` (docs/language.md §3.14): the
    // scene then depends on ReadOptions::clock, and an animation reads it again per frame.
    bool UsesClock() const;
    // Whether `clock` was used outside view statements (the scene's geometry, lights or
    // background depend on it); false when the clock only moves the camera.
    bool UsesClockOutsideViews() const;
    // The view and redef view statements read so far, in order.
    const std::vector<ViewStatement>& ViewStatements() const;
    // Reading stops everywhere after too many errors or statements; a session that reports and
    // clears its diagnostics between inputs resumes reading with the next one by calling this.
    void Resume();
    // Lines typed at a prompt are read by an IncrementalReader on this Reader
    // (incremental_reader.h).

  private:
    friend class IncrementalReader;
    ReaderState& State();

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Convenience: a fresh scene from one or more files; errors in diags.
bool ReadSceneFiles(const std::vector<std::string>& paths, scene::Scene& scene, Diagnostics& diags,
                    ReadOptions options = {});

}  // namespace quadrix::lang
