// The UniQuadrix working environment (seed 001 §2.2–2.3, §3.1 "Manager"): one scene read from
// command-line files, -c statements and interactive input; the current view, parallel light and
// device; `show` drawing the scene on the current device; the end-of-session summary.
//
// Interactive mode: statements are read a line at a time after the prompt "uq> " and run as soon
// as their ';' is typed. Lines go through Feed(line), the one entry point the prompt, the tests
// and the viewer share: it runs the statements the line completes and returns their diagnostics.
// The lines are read by the reader's public incremental face (lang/incremental_reader.h:
// statements across lines, errors at the fed line, a misspelt keyword reported at once and the
// input after it skipped to the next ';' with no prompt, §2.3, unless a line starts a statement;
// issue 21: `help` then `solid sphere s =r 1;` used to lose the sphere). `help [WORD]` (with or
// without ';') is the session's own statement (the reader's own-statement hook): keywords,
// syntax, the current view/light/device, the ids.
// Diagnostics for what was just typed are printed before the next prompt. With a terminal on
// standard input, lines are edited with libedit (history, tab completion of keywords and ids);
// otherwise they are read plainly, so scripts can drive a session through a pipe.
//
// Current objects (§2.3: "those that were last defined or redefed"):
//   view  — the last view defined, `redef view`ed, or named by `show id`; -v pins one until the
//           next redef view or show id;
//   light — the last parallel light defined or redefed (or `redef light default`); ambient lights
//           all shine. UniQuadrix shades with one parallel light, so `uq` does too (quadrix render
//           sums all of them);
//   device — set by -d, `device`, else $UQDEV, else the terminal when standard output is one, else
//           png.
#pragma once

#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "quadrix/device/device.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/lang/incremental_reader.h"
#include "quadrix/lang/reader.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix::cli {

// What the paper's options (§2.2) and device statements (§2.3) change.
struct UqSettings {
    std::string device;               // "NAME" or "NAME:PATH"
    bool fast = false;                // -f / -F, show ... fast
    bool keep = false;                // -k / -K, device ... keep / nokeep
    bool warnings = true;             // -n / -N
    double xInches = 0, yInches = 0;  // -sx / -sy, xsize / ysize; 0 = device default
    int deltaMax = 0;                 // -sd; 0 = device default
    std::string engine = "raycast";
    std::map<std::string, std::string> engineOptions;  // --engine-opt KEY=VALUE
    // --allow-missing: the drawing devices (svg:, pdf:, eps:) leave freeform surfaces out with a
    // warning instead of refusing the scene, as quadrix draw --allow-missing does.
    bool allowMissing = false;
};

// A source of input lines for the interactive mode.
class LineInput {
  public:
    virtual ~LineInput() = default;
    // Shows `prompt` and reads one line (without its newline). False at end of input.
    virtual bool ReadLine(const std::string& prompt, std::string& line) = 0;
    // Completions of `word` after `before` (the line's text before it), for tab completion.
    using Completer =
        std::function<std::vector<std::string>(const std::string& word, const std::string& before)>;
    virtual void SetCompleter(Completer) {}
    // Why the last ReadLine returned false when it was not the end of input (a line beyond the
    // input bound): an error of the session, so the exit status is not 0. Empty otherwise.
    virtual std::string Error() const { return {}; }
};
// libedit when `in` is a terminal (and libedit was found at build time), plain reading otherwise.
std::unique_ptr<LineInput> MakeLineInput(std::FILE* in, std::FILE* promptOut);

// `device svg:FILE`, `pdf:FILE`, `eps:FILE` (issue 19): a show writes the exact hidden-line
// drawing of the current view, as `quadrix draw` does (src/quadrix/draw/), instead of a raster.
// True when `spec` names one of them; then `path` (default uq.svg, uq.pdf, uq.eps) and `format`
// are set, and `error` when the path has another extension.
bool IsVectorDeviceSpec(const std::string& spec, std::string& path, std::string& format,
                        std::string& error);

class UqSession : public lang::CommandHandler {
  public:
    UqSession();
    ~UqSession() override;

    UqSettings settings;

    // Where diagnostics and the summary go (-e); the session does not own the stream.
    void SetErrorStream(std::FILE* out) { err_ = out; }
    // Where replies (help, "no user errors", "raster file: ...") go; nullptr = only FeedResult.
    void SetMessageStream(std::FILE* out) { out_ = out; }
    // Trace stream (-t), nullptr = off.
    void SetTrace(std::FILE* trace) { trace_ = trace; }
    // -v: use this view instead of the last defined one.
    void PinView(const std::string& id);

    // Batch input: a file ("-" = standard input) or statements (-c).
    void ReadFile(const std::string& path);
    void ReadStatements(const std::string& text);
    // The interactive mode, until quit or end of input.
    void Interactive();

    // One line of interactive input (without its newline) and what it did.
    struct FeedResult {
        std::vector<std::string> statements;  // statements the line completed, as typed, run
        std::vector<Diagnostic> diagnostics;  // reported while reading and running them
        std::vector<std::string> messages;    // replies: "no user errors", help text, ...
        bool quit = false;                    // `quit;` ended the interactive input
    };
    // Feeds a line to the interactive input (starting it on the first call). Diagnostics and
    // replies are also printed (error stream, standard output) as at the prompt.
    FeedResult Feed(const std::string& line);
    // The prompt for the next line: "uq> " between statements, "...> " inside one, "" while
    // input is skipped after an error.
    std::string Prompt() const;
    // Ends the fed input (end of file): an unfinished statement or definition is reported.
    void EndFeed();
    // Tab completion at the prompt (uq_help.h).
    std::vector<std::string> Completions(const std::string& word, const std::string& before) const;
    // The text of `help [topic]`.
    std::string HelpText(const std::string& topic) const;
    // The picture at the end of a batch command line: drawn unless an input error was noted.
    bool FinalShow();

    // "warnings:N" and error counts by kind (§2.3 session), to the error stream.
    void PrintSummary();
    bool HadErrors() const { return totalErrors_ > 0; }
    bool WasInteractive() const { return wasInteractive_; }

    bool OnCommand(const lang::Command& command, scene::Scene& scene, Diagnostics& diags) override;

  private:
    // Starts an interactive input: an IncrementalReader on the session's Reader.
    void BeginFeed();
    // After each statement read at the prompt: diagnostics printed, current objects updated,
    // the reply to a read statement.
    void AfterStatement(const std::string& statement, int errors);
    // Prints diagnostics added since the last flush and counts them; clears the list when
    // `boundary` (no statement is half read, so no parser holds an error count).
    void FlushDiagnostics(bool boundary);
    void SyncCurrent();
    bool Show(const std::string& viewId, bool fast, const SourceLoc& loc);
    // Show on a vector device: the hidden-line drawing of the current view to `path`.
    bool ShowDrawing(const std::string& view, const std::string& path, const std::string& format,
                     const SourceLoc& loc);
    // The current device, with a fresh file name when keep is on; nullptr with `error`.
    std::unique_ptr<device::Device> CurrentDevice(std::string& error);
    std::vector<scene::Light> CurrentLights() const;
    // Flattens the scene in the render context for `view` under the current lights; false after
    // errors.
    // The view request of a show on the device `info` describes (size, view, current lights).
    ViewRequest CurrentViewRequest(const std::string& view, const device::DeviceInfo& info) const;
    bool FlattenCurrent(const std::string& view, const device::DeviceInfo& info);
    std::string NextKeptPath(const std::string& path);
    void Trace(const std::string& line);
    void Message(const std::string& line);
    void TraceRead(const std::string& what, double seconds);

    // The render context holds the scene the reader fills (one render path: pipeline/).
    RenderContext ctx_;
    scene::Scene& scene_ = ctx_.Scene();
    Diagnostics diags_;
    std::unique_ptr<lang::Reader> reader_;
    std::unique_ptr<LineInput> input_;
    std::vector<std::unique_ptr<lang::IncrementalReader>> levels_;  // innermost last
    FeedResult* collecting_ = nullptr;                              // the Feed in progress
    std::FILE* err_ = stderr;
    std::FILE* out_ = stdout;
    std::FILE* trace_ = nullptr;

    std::size_t printed_ = 0;  // diagnostics of diags_ already printed
    int unstoredErrorsSeen_ = 0, unstoredWarningsSeen_ = 0;  // beyond Diagnostics::kMaxStored
    int totalErrors_ = 0, totalWarnings_ = 0, batchErrors_ = 0;
    std::map<std::string, int> errorsByKind_;
    int interactiveDepth_ = 0;
    bool wasInteractive_ = false;

    std::string currentView_;  // empty = the last defined (or default)
    bool viewPinned_ = false;
    std::string currentLight_;  // empty = the last parallel light (or default)
    std::size_t knownViews_ = 0, knownLights_ = 0;
};

}  // namespace quadrix::cli
