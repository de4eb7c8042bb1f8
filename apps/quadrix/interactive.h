// The UniQuadrix working environment (seed 001 §2.2–2.3, §3.1 "Manager"): one scene read from
// command-line files, -c statements and interactive input; the current view, parallel light and
// device; `show` drawing the scene on the current device; the end-of-session summary.
//
// Interactive mode: statements are read a line at a time after the prompt "uq> " and run as soon
// as their ';' is typed. After an error the reader skips input to the next ';' and no prompt is
// given until then (§2.3). Diagnostics for what was just typed are printed before the next
// prompt. With a terminal on standard input, lines are edited with libedit (history included);
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
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "quadrix/device/device.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/lang/reader.h"
#include "quadrix/lang/reader_state.h"
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
};

// A source of input lines for the interactive mode.
class LineInput {
  public:
    virtual ~LineInput() = default;
    // Shows `prompt` and reads one line (without its newline). False at end of input.
    virtual bool ReadLine(const std::string& prompt, std::string& line) = 0;
    // Why the last ReadLine returned false when it was not the end of input (a line beyond the
    // input bound): an error of the session, so the exit status is not 0. Empty otherwise.
    virtual std::string Error() const { return {}; }
};
// libedit when `in` is a terminal (and libedit was found at build time), plain reading otherwise.
std::unique_ptr<LineInput> MakeLineInput(std::FILE* in, std::FILE* promptOut);

class UqSession : public lang::CommandHandler {
  public:
    UqSession();
    ~UqSession() override;

    UqSettings settings;

    // Where diagnostics and the summary go (-e); the session does not own the stream.
    void SetErrorStream(std::FILE* out) { err_ = out; }
    // Trace stream (-t), nullptr = off.
    void SetTrace(std::FILE* trace) { trace_ = trace; }
    // -v: use this view instead of the last defined one.
    void PinView(const std::string& id);

    // Batch input: a file ("-" = standard input) or statements (-c).
    void ReadFile(const std::string& path);
    void ReadStatements(const std::string& text);
    // The interactive mode, until quit or end of input.
    void Interactive();
    // The picture at the end of a batch command line: drawn unless an input error was noted.
    bool FinalShow();

    // "warnings:N" and error counts by kind (§2.3 session), to the error stream.
    void PrintSummary();
    bool HadErrors() const { return totalErrors_ > 0; }
    bool WasInteractive() const { return wasInteractive_; }

    bool OnCommand(const lang::Command& command, scene::Scene& scene, Diagnostics& diags) override;

  private:
    struct Tracker;
    bool NextLine(Tracker& tracker, std::string& text);
    // Prints diagnostics added since the last flush and counts them; clears the list when
    // `boundary` (no statement is half read, so no parser holds an error count).
    void FlushDiagnostics(bool boundary);
    void SyncCurrent();
    bool Show(const std::string& viewId, bool fast, const SourceLoc& loc);
    // The current device, with a fresh file name when keep is on; nullptr with `error`.
    std::unique_ptr<device::Device> CurrentDevice(std::string& error);
    std::vector<scene::Light> CurrentLights() const;
    // Flattens the scene in the render context for `view` under the current lights; false after
    // errors.
    bool FlattenCurrent(const std::string& view, const device::DeviceInfo& info);
    std::string NextKeptPath(const std::string& path);
    void Trace(const std::string& line);
    void Message(const std::string& line);
    void TraceRead(const std::string& what, double seconds);

    // The render context holds the scene the reader fills (one render path: pipeline/).
    RenderContext ctx_;
    scene::Scene& scene_ = ctx_.Scene();
    Diagnostics diags_;
    std::unique_ptr<lang::ReaderState> state_;
    std::unique_ptr<LineInput> input_;
    std::FILE* err_ = stderr;
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
