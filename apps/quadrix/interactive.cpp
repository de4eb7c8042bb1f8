// The UniQuadrix Manager and interactive mode (seed 001 §2.3, §3.1); see interactive.h.
#include "interactive.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <utility>

#ifdef QUADRIX_HAVE_LIBEDIT
#include <editline/readline.h>
#endif

#include "quadrix/engines/engine.h"
#include "quadrix/flatten/flattener.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/lang/input_files.h"
#include "quadrix/lang/parser.h"
#include "quadrix/lang/source.h"
#include "quadrix/shade/shader.h"

namespace quadrix::cli {

namespace {

// The name of interactive input in diagnostics (as the reader names standard input).
constexpr const char* kInteractiveName = "<stdin>";

double SecondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Reads lines with stdio; echoes them after the prompt when the input is not a terminal, so a
// transcript of a scripted session reads like the paper's (prompt, statement, reply).
class PlainLineInput : public LineInput {
  public:
    PlainLineInput(std::FILE* in, std::FILE* out, bool echo) : in_(in), out_(out), echo_(echo) {}
    bool ReadLine(const std::string& prompt, std::string& line) override {
        std::fputs(prompt.c_str(), out_);
        std::fflush(out_);
        line.clear();
        int c;
        bool any = false;
        while ((c = std::fgetc(in_)) != EOF) {
            any = true;
            if (c == '\n') break;
            // One line is bounded like every input (io/bounded_read.h): `quadrix -i < /dev/zero`.
            if (line.size() >= kMaxInputBytes) {
                error_ = "cannot read standard input: a line is longer than " +
                         ByteSizeText(kMaxInputBytes);
                return false;
            }
            line += static_cast<char>(c);
        }
        if (!any) {
            if (!prompt.empty()) std::fputc('\n', out_);  // end the prompt line at end of input
            std::fflush(out_);
            return false;
        }
        if (echo_) {
            std::fputs(line.c_str(), out_);
            std::fputc('\n', out_);
            std::fflush(out_);
        }
        return true;
    }
    std::string Error() const override { return error_; }

  private:
    std::FILE* in_;
    std::FILE* out_;
    bool echo_;
    std::string error_;
};

#ifdef QUADRIX_HAVE_LIBEDIT
// Line editing and history with libedit's readline interface (BSD license). The history is kept
// across sessions in ~/.quadrix_history.
class EditLineInput : public LineInput {
  public:
    EditLineInput() {
        using_history();
        if (const char* home = std::getenv("HOME"); home && *home) {
            historyPath_ = std::string(home) + "/.quadrix_history";
            read_history(historyPath_.c_str());  // absent on the first session: fine
        }
    }
    ~EditLineInput() override {
        if (!historyPath_.empty()) write_history(historyPath_.c_str());
    }
    bool ReadLine(const std::string& prompt, std::string& line) override {
        char* text = readline(prompt.c_str());
        if (!text) {
            std::fputc('\n', stdout);
            return false;
        }
        line = text;
        std::free(text);
        if (line.find_first_not_of(" \t") != std::string::npos) add_history(line.c_str());
        return true;
    }

  private:
    std::string historyPath_;
};
#endif

std::string Lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// First word of a statement, lower case.
std::string FirstWord(const std::string& s, std::string* rest = nullptr) {
    std::size_t b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return {};
    std::size_t e = s.find_first_of(" \t\r\n", b);
    if (rest) *rest = e == std::string::npos ? std::string() : s.substr(e);
    return Lower(s.substr(b, e == std::string::npos ? std::string::npos : e - b));
}

bool Blank(const std::string& s) { return s.find_first_not_of(" \t\r\n") == std::string::npos; }

}  // namespace

std::unique_ptr<LineInput> MakeLineInput(std::FILE* in, std::FILE* promptOut) {
    bool terminal = isatty(fileno(in)) != 0;
#ifdef QUADRIX_HAVE_LIBEDIT
    if (terminal && in == stdin && promptOut == stdout) return std::make_unique<EditLineInput>();
#endif
    return std::make_unique<PlainLineInput>(in, promptOut, !terminal);
}

// Follows the statements typed so far just enough to tell whether input stops between two
// statements (then the prompt is shown) or inside one: nested { } comments and "strings" are
// skipped, ';' ends a statement.
struct UqSession::Tracker {
    int commentDepth = 0;
    bool inString = false;
    std::string pending;                 // the statement being typed
    std::vector<std::string> completed;  // statements completed since the last prompt
    int errorsAtBoundary = 0;            // error count when the last statement ended
    int errorsAtPrompt = 0;

    bool AtBoundary() const { return commentDepth == 0 && !inString && Blank(pending); }
    void Feed(const std::string& text) {
        for (char c : text) {
            if (inString) {
                if (c == '"' || c == '\n') inString = false;
                pending += c;
            } else if (commentDepth > 0) {
                if (c == '{') ++commentDepth;
                if (c == '}') --commentDepth;
            } else if (c == '{') {
                ++commentDepth;
                pending += ' ';
            } else if (c == ';') {
                completed.push_back(pending);
                pending.clear();
            } else {
                if (c == '"') inString = true;
                pending += c;
            }
        }
    }
};

UqSession::UqSession() {
    lang::ReadOptions options;
    options.commands = this;
    state_ = std::make_unique<lang::ReaderState>(scene_, diags_, options);
}

UqSession::~UqSession() = default;

void UqSession::PinView(const std::string& id) {
    currentView_ = id;
    viewPinned_ = true;
}

void UqSession::Message(const std::string& line) {
    std::fputs(line.c_str(), stdout);
    std::fputc('\n', stdout);
    std::fflush(stdout);
}

void UqSession::Trace(const std::string& line) {
    if (!trace_) return;
    std::fprintf(trace_, "trace: %s\n", line.c_str());
    std::fflush(trace_);
}

void UqSession::TraceRead(const std::string& what, double seconds) {
    if (!trace_) return;
    const scene::Scope& top = scene_.top;
    Trace(
        fmt::format("reader: {} in {:.4f} s; scene: {} half-spaces, {} bodies, {} instances/"
                    "arrays, {} csg solids, {} definitions, {} lights, {} views; {} errors, {} "
                    "warnings so far",
                    what, seconds, top.halfSpaces.size(), top.bodies.size(), top.instances.size(),
                    top.csgs.size(), scene_.definitions.size(), scene_.lights.size(),
                    scene_.views.size(), totalErrors_, totalWarnings_));
}

void UqSession::FlushDiagnostics(bool boundary) {
    const auto& items = diags_.Items();
    int storedErrors = 0, storedWarnings = 0;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const Diagnostic& d = items[i];
        bool isError = d.severity == Diagnostic::Severity::kError;
        bool isWarning = d.severity == Diagnostic::Severity::kWarning;
        storedErrors += isError;
        storedWarnings += isWarning;
        if (i < printed_) continue;
        if (isError) {
            ++totalErrors_;
            ++errorsByKind_[d.kind.empty() ? "input" : d.kind];
            if (interactiveDepth_ == 0) ++batchErrors_;
        }
        if (isWarning) ++totalWarnings_;
        if (isWarning && !settings.warnings) continue;
        // What was just typed needs no file name: "warning: id l#1 created", as in §2.3; only
        // errors repeat the line with a caret.
        const bool typed = interactiveDepth_ > 0 && d.loc.file && *d.loc.file == kInteractiveName;
        std::string text = d.Format(!(typed && isWarning));
        if (typed) {
            std::string prefix = d.loc.ToString() + ": ";
            if (text.rfind(prefix, 0) == 0) text.erase(0, prefix.size());
        }
        std::fputs(text.c_str(), err_);
        std::fputc('\n', err_);
    }
    printed_ = items.size();
    // Diagnostics beyond Diagnostics::kMaxStored are counted but not kept: count them too.
    int unstoredErrors = diags_.ErrorCount() - storedErrors - unstoredErrorsSeen_;
    int unstoredWarnings = diags_.WarningCount() - storedWarnings - unstoredWarningsSeen_;
    if (unstoredErrors > 0) {
        totalErrors_ += unstoredErrors;
        errorsByKind_["input"] += unstoredErrors;
        if (interactiveDepth_ == 0) batchErrors_ += unstoredErrors;
        unstoredErrorsSeen_ += unstoredErrors;
    }
    if (unstoredWarnings > 0) {
        totalWarnings_ += unstoredWarnings;
        unstoredWarningsSeen_ += unstoredWarnings;
    }
    std::fflush(err_);
    if (boundary) {
        diags_.Clear();
        printed_ = 0;
        unstoredErrorsSeen_ = unstoredWarningsSeen_ = 0;
    }
}

void UqSession::SyncCurrent() {
    for (std::size_t i = knownLights_; i < scene_.lights.size(); ++i)
        if (scene_.lights[i].kind == scene::Light::Kind::kParallel)
            currentLight_ = scene_.lights[i].id;
    knownLights_ = scene_.lights.size();
    for (std::size_t i = knownViews_; i < scene_.views.size(); ++i)
        if (!viewPinned_) currentView_ = scene_.views[i].id;
    knownViews_ = scene_.views.size();
}

void UqSession::ReadFile(const std::string& path) {
    auto t0 = std::chrono::steady_clock::now();
    state_->aborted = false;
    lang::ReadTopLevelFile(*state_, path);
    FlushDiagnostics(true);
    SyncCurrent();
    TraceRead(path == "-" ? "standard input" : path, SecondsSince(t0));
}

void UqSession::ReadStatements(const std::string& text) {
    auto t0 = std::chrono::steady_clock::now();
    state_->aborted = false;
    lang::ReadTopLevelText(*state_, text, "<-c>");
    FlushDiagnostics(true);
    SyncCurrent();
    TraceRead("-c statements", SecondsSince(t0));
}

bool UqSession::NextLine(Tracker& tracker, std::string& text) {
    const bool boundary = tracker.AtBoundary();
    FlushDiagnostics(boundary);
    SyncCurrent();
    // The reply to a read statement (§2.3 session: "uq> read scenefile;" → "no user errors").
    int newErrors = totalErrors_ - tracker.errorsAtPrompt;
    for (const std::string& s : tracker.completed) {
        std::string rest;
        std::string word = FirstWord(s, &rest);
        if ((word == "read" || word == "include") && !Blank(rest))
            Message(newErrors == 0 ? "no user errors" : fmt::format("user errors: {}", newErrors));
    }
    tracker.completed.clear();
    std::string prompt;
    if (boundary) {
        prompt = "uq> ";
        tracker.errorsAtBoundary = totalErrors_;
    } else if (totalErrors_ == tracker.errorsAtBoundary) {
        prompt = "...> ";  // a statement continues on the next line
    }                      // else: skipping to the next ';' after an error, no prompt (§2.3)
    tracker.errorsAtPrompt = totalErrors_;
    std::string line;
    if (!input_->ReadLine(prompt, line)) {
        // `quadrix -i < /dev/zero` once exited 0 after this error (issue 23).
        if (std::string e = input_->Error(); !e.empty()) diags_.Error({}, e, {}, "input");
        return false;
    }
    line += '\n';
    tracker.Feed(line);
    text += line;
    return true;
}

void UqSession::Interactive() {
    if (!input_) input_ = MakeLineInput(stdin, stdout);
    FlushDiagnostics(false);
    SyncCurrent();
    ++interactiveDepth_;
    wasInteractive_ = true;
    state_->aborted = false;
    Tracker tracker;
    tracker.errorsAtBoundary = tracker.errorsAtPrompt = totalErrors_;
    lang::Source source(kInteractiveName,
                        [this, &tracker](std::string& text) { return NextLine(tracker, text); });
    if (static_cast<int>(state_->includeStack.size()) > state_->options.maxIncludeDepth) {
        diags_.Error({}, "interactive mode nested too deep", {}, "parser");
    } else {
        state_->includeStack.push_back(
            {fmt::format("<interactive {}>", interactiveDepth_), kInteractiveName});
        {
            lang::Parser parser(*state_, source);
            parser.Run();
        }
        state_->includeStack.pop_back();
    }
    FlushDiagnostics(false);
    SyncCurrent();
    --interactiveDepth_;
}

bool UqSession::OnCommand(const lang::Command& command, scene::Scene& scene, Diagnostics& diags) {
    using Kind = lang::Command::Kind;
    SyncCurrent();
    switch (command.kind) {
        case Kind::kRedefLight: {
            int i = scene.FindLight(command.id);
            if (i < 0 && command.id == "default")
                currentLight_ = "default";
            else if (i >= 0 && scene.lights[i].kind == scene::Light::Kind::kParallel)
                currentLight_ = command.id;
            return true;
        }
        case Kind::kRedefView:
            currentView_ = command.id;
            viewPinned_ = false;
            return true;
        case Kind::kDevice: {
            // Check the device now, so a misspelt name is reported at the statement.
            device::DeviceSettings ds;
            ds.xInches = command.xsizeInches ? command.xsizeInches : settings.xInches;
            ds.yInches = command.ysizeInches ? command.ysizeInches : settings.yInches;
            ds.deltaMax = settings.deltaMax;
            std::string error;
            if (!device::MakeDevice(command.device, ds, error)) {
                diags.Error(command.loc, error, {}, "input");
                return true;
            }
            settings.device = command.device;
            if (command.keep) settings.keep = true;
            if (command.nokeep) settings.keep = false;
            settings.xInches = ds.xInches;
            settings.yInches = ds.yInches;
            return true;
        }
        case Kind::kShow:
            if (!command.id.empty()) {
                currentView_ = command.id;  // "show ViewId" = "redef view ViewId; show;"
                viewPinned_ = false;
            }
            Show(std::string(), command.fast || settings.fast, command.loc);
            return true;
        case Kind::kQuit:
            return false;
        case Kind::kNakedRead:
            if (interactiveDepth_ > 0 && command.loc.file &&
                *command.loc.file == kInteractiveName) {
                diags.Warning(command.loc, "already in interactive mode; 'read;' ignored", {},
                              "input");
                return true;
            }
            Interactive();
            return true;
    }
    return true;
}

std::string UqSession::NextKeptPath(const std::string& path) {
    namespace fs = std::filesystem;
    fs::path p(path);
    std::string stem = (p.parent_path() / p.stem()).string();
    std::string ext = p.extension().string();
    for (int n = 1;; ++n) {
        std::string candidate = fmt::format("{}-{}{}", stem, n, ext);
        std::error_code ec;
        if (!fs::exists(candidate, ec)) return candidate;
    }
}

std::unique_ptr<device::Device> UqSession::CurrentDevice(std::string& error) {
    device::DeviceSettings ds;
    ds.xInches = settings.xInches;
    ds.yInches = settings.yInches;
    ds.deltaMax = settings.deltaMax;
    auto dev = device::MakeDevice(settings.device, ds, error);
    if (dev && settings.keep && dev->Info().hard)
        dev =
            device::MakeDevice(dev->Info().name + ":" + NextKeptPath(dev->Info().path), ds, error);
    return dev;
}

std::vector<scene::Light> UqSession::CurrentLights() const {
    // Every ambient, point and spot light and the current parallel light (interactive.h), in
    // the scene's order (the shader's sums then match `quadrix render` bit for bit); the default
    // light when none of them is directed. Empty when the scene declares no light: the Flattener
    // then lights it with the default rig, as `quadrix render` does (docs/language.md §3.7).
    const scene::Light* parallel = nullptr;
    for (const scene::Light& l : scene_.lights)
        if (l.kind == scene::Light::Kind::kParallel &&
            (currentLight_.empty() || l.id == currentLight_))
            parallel = &l;
    std::vector<scene::Light> lights;
    bool directed = false;
    for (const scene::Light& l : scene_.lights) {
        if (l.kind == scene::Light::Kind::kParallel && &l != parallel) continue;
        directed |= l.kind != scene::Light::Kind::kAmbient;
        lights.push_back(l);
    }
    if (!scene_.lights.empty() && !directed) lights.push_back(scene::DefaultLight());
    return lights;
}

bool UqSession::FlattenCurrent(const std::string& view, const device::DeviceInfo& info) {
    auto t0 = std::chrono::steady_clock::now();
    ViewRequest request;
    request.width = info.width;
    request.height = info.height;
    request.viewName = view;
    // Passed in, never swapped into the scene; none declared: the Flattener's default rig.
    if (std::vector<scene::Light> lights = CurrentLights(); !lights.empty())
        request.lights = std::move(lights);
    ctx_.SceneChanged();               // the reader may have added statements since
    if (!ctx_.Flatten(request, diags_)) return false;
    const FlatScene& flat = ctx_.Flat();
    Trace(
        fmt::format("flattener: {} solids, {} bodies, {} half-spaces in device space, {} "
                    "lights; {:.4f} s",
                    flat.solids.size(), flat.bodies.size(), flat.halfSpaces.size(),
                    flat.lights.size(), SecondsSince(t0)));
    return true;
}

bool UqSession::Show(const std::string& viewId, bool fast, const SourceLoc& loc) {
    FlushDiagnostics(false);
    SyncCurrent();
    if (interactiveDepth_ == 0 && batchErrors_ > 0) {
        // §2.2: "Any error more severe than a warning noted during input processing aborts
        // rendering."
        std::fprintf(err_, "quadrix: %d input error%s; nothing drawn\n", batchErrors_,
                     batchErrors_ == 1 ? "" : "s");
        std::fflush(err_);
        return false;
    }
    auto fail = [&](const std::string& message, const char* kind) {
        if (!message.empty()) diags_.Error(loc, message, {}, kind);
        FlushDiagnostics(false);
        return false;
    };
    std::string error;
    auto dev = CurrentDevice(error);
    if (!dev) return fail(error, "device");
    const device::DeviceInfo& info = dev->Info();
    const std::string view = viewId.empty() ? currentView_ : viewId;
    Trace(
        fmt::format("show: view {}, device {} {}x{} ({} levels, aspect {}, delta max {}), "
                    "{} shading, engine {}",
                    view.empty() ? "(last defined)" : "'" + view + "'", info.name, info.width,
                    info.height, info.levels, info.aspect, info.deltaMax,
                    fast ? "fast constant" : "smooth", settings.engine));
    if (!FlattenCurrent(view, info)) return fail({}, "input");  // the Flattener reported why

    EngineRequest request;
    request.engine = settings.engine;
    auto t0 = std::chrono::steady_clock::now();
    Frame frame;
    RenderReport report;
    if (!ctx_.Render(request, frame, report, diags_)) return fail({}, "command line");
    for (const std::string& w : report.stats.warnings)
        std::fprintf(err_, "quadrix: warning: engine %s: %s\n", settings.engine.c_str(), w.c_str());
    for (const std::string& n : report.notes) std::fprintf(err_, "quadrix: note: %s\n", n.c_str());
    if (trace_) {
        std::string counters;
        for (const auto& [name, value] : report.Counters())
            counters += fmt::format(", {} {}", name, value);
        Trace(fmt::format("engine {}: {} of {} pixels covered{}; {:.4f} s", settings.engine,
                          frame.CoveredCount(), frame.depth.size(), counters, SecondsSince(t0)));
    }

    t0 = std::chrono::steady_clock::now();
    ShadeOptions so;
    so.fast = fast;
    Image image = ctx_.Shade(frame, so);
    Trace(fmt::format("shader: {} pixels, {}; {:.4f} s", frame.depth.size(),
                      image.channels == 3 ? "RGB" : "gray", SecondsSince(t0)));

    t0 = std::chrono::steady_clock::now();
    if (auto e = dev->Open(image.channels == 3); !e.empty()) return fail(e, "device");
    device::DrawStats drawn = device::DrawImage(*dev, image, &frame, info.deltaMax);
    if (auto e = dev->Close(); !e.empty()) return fail(e, "device");
    Trace(fmt::format("device {}: {} spans, {} intensity evaluations; {}; {:.4f} s", info.name,
                      drawn.spans, drawn.evaluations,
                      info.hard ? "wrote " + info.path : std::string("drawn on the screen"),
                      SecondsSince(t0)));
    if (settings.keep && info.hard) Message("raster file: " + info.path);
    return true;
}

bool UqSession::FinalShow() {
    FlushDiagnostics(true);
    if (batchErrors_ > 0) {
        std::fprintf(err_, "quadrix: %d input error%s; nothing drawn\n", batchErrors_,
                     batchErrors_ == 1 ? "" : "s");
        std::fflush(err_);
        return false;
    }
    return Show(std::string(), settings.fast, {});
}

void UqSession::PrintSummary() {
    FlushDiagnostics(false);
    std::fprintf(err_, "warnings:%d\n", totalWarnings_);
    // The paper's four kinds first, in its order, then any other kind that occurred.
    static const char* const kKinds[] = {"parser", "syntax", "input", "command line"};
    std::string line;
    for (const char* k : kKinds) {
        auto it = errorsByKind_.find(k);
        line += fmt::format("{}{}:{}", line.empty() ? "" : " ", k,
                            it == errorsByKind_.end() ? 0 : it->second);
    }
    for (const auto& [kind, count] : errorsByKind_)
        if (std::find(std::begin(kKinds), std::end(kKinds), kind) == std::end(kKinds))
            line += fmt::format(" {}:{}", kind, count);
    std::fprintf(err_, "%s\n", line.c_str());
    std::fflush(err_);
}

}  // namespace quadrix::cli
