// The UniQuadrix Manager and interactive mode (seed 001 §2.3, §3.1); see interactive.h.
#include "interactive.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <utility>

#include "quadrix/engines/engine.h"
#include "quadrix/flatten/flattener.h"
#include "quadrix/io/bounded_read.h"
#include "quadrix/io/output_file.h"
#include "quadrix/pipeline/drawing_output.h"
#include "quadrix/shade/shader.h"
#include "quadrix/util/module_loader.h"
#include "uq_help.h"
#ifdef QUADRIX_HAVE_LIBEDIT
#include "line_edit_module.h"
#endif

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
// Line editing and history through the module quadrix-lineedit.so (line_edit_module.h). The
// history is kept across sessions in ~/.quadrix_history.
class EditLineInput : public LineInput {
  public:
    explicit EditLineInput(const LineEditModule& m) : m_(m) {
        if (const char* home = std::getenv("HOME"); home && *home)
            historyPath_ = std::string(home) + "/.quadrix_history";
        m_.begin(historyPath_.c_str());  // a history absent on the first session: fine
    }
    ~EditLineInput() override {
        m_.setCompleter(nullptr, nullptr, nullptr);
        m_.end(historyPath_.c_str());
    }
    void SetCompleter(Completer completer) override {
        completer_ = std::move(completer);
        m_.setCompleter(&EditLineInput::Complete, this, " \t\n;()<>!|&-=\"");
    }
    bool ReadLine(const std::string& prompt, std::string& line) override {
        return m_.readLine(prompt.c_str(), &line);
    }

  private:
    static void Complete(void* self, const std::string& word, const std::string& before,
                         std::vector<std::string>* out) {
        const Completer& c = static_cast<EditLineInput*>(self)->completer_;
        if (c) *out = c(word, before);
    }
    const LineEditModule& m_;
    std::string historyPath_;
    Completer completer_;
};

// The line editor module, loaded on first use; null, with `*error` set, when it cannot be.
const LineEditModule* LineEditor(std::string* error) {
    const auto entry = reinterpret_cast<const LineEditModule* (*)()>(
        LoadModuleSymbol("quadrix-lineedit.so", "quadrix_lineedit_module", error));
    if (!entry) return nullptr;
    const LineEditModule* m = entry();
    if (m->abi != kLineEditModuleAbi || !m->begin || !m->end || !m->readLine || !m->setCompleter) {
        *error = "quadrix-lineedit.so is from another build of Quadrix (interface " +
                 std::to_string(m->abi) + ", this program's " + std::to_string(kLineEditModuleAbi) +
                 ")";
        return nullptr;
    }
    return m;
}
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
    if (terminal && in == stdin && promptOut == stdout) {
        std::string error;
        if (const LineEditModule* m = LineEditor(&error))
            return std::make_unique<EditLineInput>(*m);
        std::fprintf(stderr, "quadrix: no line editing at this prompt: %s; reading plain lines\n",
                     error.c_str());
    }
#endif
    return std::make_unique<PlainLineInput>(in, promptOut, !terminal);
}

bool IsVectorDeviceSpec(const std::string& spec, std::string& path, std::string& format,
                        std::string& error) {
    const std::size_t colon = spec.find(':');
    const std::string name = Lower(spec.substr(0, colon));
    if (name != "svg" && name != "pdf" && name != "eps") return false;
    format = name;
    path = colon == std::string::npos || colon + 1 == spec.size() ? "uq." + name
                                                                  : spec.substr(colon + 1);
    const std::string ext = Lower(std::filesystem::path(path).extension().string());
    error.clear();
    if (ext != "." + name)
        error =
            fmt::format("device {} writes .{} files; '{}' has another extension", name, name, path);
    return true;
}

UqSession::UqSession() {
    lang::ReadOptions options;
    options.commands = this;
    reader_ = std::make_unique<lang::Reader>(scene_, diags_, options);
}

UqSession::~UqSession() = default;

void UqSession::PinView(const std::string& id) {
    currentView_ = id;
    viewPinned_ = true;
}

void UqSession::Message(const std::string& line) {
    if (collecting_) collecting_->messages.push_back(line);
    if (!out_) return;
    std::fputs(line.c_str(), out_);
    std::fputc('\n', out_);
    std::fflush(out_);
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
        if (collecting_) collecting_->diagnostics.push_back(d);
        if (err_) {
            std::fputs(text.c_str(), err_);
            std::fputc('\n', err_);
        }
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
    if (err_) std::fflush(err_);
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
    reader_->Resume();
    reader_->ReadFile(path);
    FlushDiagnostics(true);
    SyncCurrent();
    TraceRead(path == "-" ? "standard input" : path, SecondsSince(t0));
}

void UqSession::ReadStatements(const std::string& text) {
    auto t0 = std::chrono::steady_clock::now();
    reader_->Resume();
    reader_->ReadText(text, "<-c>");
    FlushDiagnostics(true);
    SyncCurrent();
    TraceRead("-c statements", SecondsSince(t0));
}

void UqSession::BeginFeed() {
    FlushDiagnostics(false);
    SyncCurrent();
    ++interactiveDepth_;
    wasInteractive_ = true;
    lang::IncrementalReader::Hooks hooks;
    hooks.ownWord = [](const std::string& word) { return IsHelpWord(word); };
    hooks.runOwn = [this](const std::string&, const std::string& afterWord) {
        std::string topic = afterWord;
        if (auto semi = topic.find(';'); semi != std::string::npos) topic.erase(semi);
        Message(HelpText(FirstWord(topic)));
    };
    hooks.afterStatement = [this](const std::string& statement, int errors) {
        AfterStatement(statement, errors);
    };
    levels_.push_back(
        std::make_unique<lang::IncrementalReader>(*reader_, std::move(hooks), kInteractiveName));
    FlushDiagnostics(false);
}

void UqSession::AfterStatement(const std::string& statement, int errors) {
    FlushDiagnostics(levels_.size() == 1);
    SyncCurrent();
    // The reply to a read statement (§2.3 session: "uq> read scenefile;" → "no user errors").
    std::string rest;
    const std::string word = FirstWord(statement, &rest);
    if ((word == "read" || word == "include") && !Blank(rest.substr(0, rest.find(';'))))
        Message(errors == 0 ? "no user errors" : fmt::format("user errors: {}", errors));
}

void UqSession::EndFeed() {
    if (levels_.empty()) return;
    levels_.back()->Finish();
    FlushDiagnostics(false);
    levels_.pop_back();
    SyncCurrent();
    --interactiveDepth_;
}

std::string UqSession::Prompt() const {
    if (levels_.empty()) return "uq> ";
    switch (levels_.back()->Where()) {
        case lang::IncrementalReader::Position::kSkipping:
            return {};  // skipping to the next ';' after an error (§2.3)
        case lang::IncrementalReader::Position::kInsideStatement:
            return "...> ";
        case lang::IncrementalReader::Position::kBetweenStatements:
            break;
    }
    return "uq> ";
}

UqSession::FeedResult UqSession::Feed(const std::string& line) {
    FeedResult result;
    if (levels_.empty()) BeginFeed();
    lang::IncrementalReader& level = *levels_.back();
    if (level.Ended()) {
        result.quit = true;
        return result;
    }
    FeedResult* outer = collecting_;
    collecting_ = &result;
    result.statements = level.Feed(line);
    FlushDiagnostics(false);
    SyncCurrent();
    result.quit = level.Ended();
    collecting_ = outer;
    return result;
}

std::vector<std::string> UqSession::Completions(const std::string& word,
                                                const std::string& before) const {
    return UqCompletions(word, before, scene_);
}

std::string UqSession::HelpText(const std::string& topic) const {
    UqHelpState state{currentView_, currentLight_, settings.device, settings.engine};
    std::string text = UqHelpText(topic, scene_, state);
    if (!text.empty() && text.back() == '\n') text.pop_back();
    return text;
}

void UqSession::Interactive() {
    if (!input_) {
        input_ = MakeLineInput(stdin, stdout);
        input_->SetCompleter([this](const std::string& word, const std::string& before) {
            return Completions(word, before);
        });
    }
    BeginFeed();
    for (;;) {
        std::string line;
        if (!input_->ReadLine(Prompt(), line)) {
            // `quadrix -i < /dev/zero` once exited 0 (issue 23): a line past the input bound is
            // an error of the session.
            if (std::string e = input_->Error(); !e.empty()) diags_.Error({}, e, {}, "input");
            break;
        }
        if (Feed(line).quit) break;
    }
    EndFeed();
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
            std::string error, vectorPath, vectorFormat;
            if (IsVectorDeviceSpec(command.device, vectorPath, vectorFormat, error)) {
                if (error.empty()) error = CheckOutputPath(vectorPath);
                if (!error.empty()) {
                    diags.Error(command.loc, error, {}, "input");
                    return true;
                }
            } else if (!device::MakeDevice(command.device, ds, error)) {
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

ViewRequest UqSession::CurrentViewRequest(const std::string& view,
                                          const device::DeviceInfo& info) const {
    ViewRequest request;
    request.width = info.width;
    request.height = info.height;
    request.viewName = view;
    // Passed in, never swapped into the scene; none declared: the Flattener's default rig.
    if (std::vector<scene::Light> lights = CurrentLights(); !lights.empty())
        request.lights = std::move(lights);
    return request;
}

bool UqSession::FlattenCurrent(const std::string& view, const device::DeviceInfo& info) {
    auto t0 = std::chrono::steady_clock::now();
    ctx_.SceneChanged();  // the reader may have added statements since
    if (!ctx_.Flatten(CurrentViewRequest(view, info), diags_)) return false;
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
    std::string error, vectorPath, vectorFormat;
    if (IsVectorDeviceSpec(settings.device, vectorPath, vectorFormat, error)) {
        if (!error.empty()) return fail(error, "device");
        return ShowDrawing(viewId.empty() ? currentView_ : viewId, vectorPath, vectorFormat, loc);
    }
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
    request.options = settings.engineOptions;
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

bool UqSession::ShowDrawing(const std::string& view, const std::string& path,
                            const std::string& format, const SourceLoc& loc) {
    // The size of the png device under the current -sx/-sy: the drawing's view fits as a
    // picture on it would.
    device::DeviceSettings ds;
    ds.xInches = settings.xInches;
    ds.yInches = settings.yInches;
    std::string error;
    auto raster = device::MakeDevice("png:uq.png", ds, error);
    if (!raster) {
        diags_.Error(loc, error, {}, "device");
        FlushDiagnostics(false);
        return false;
    }
    const std::string target = settings.keep ? NextKeptPath(path) : path;
    auto t0 = std::chrono::steady_clock::now();
    if (!FlattenCurrent(view, raster->Info())) {
        FlushDiagnostics(false);
        return false;
    }
    // The path quadrix draw and the viewer take (pipeline/drawing_output.h): what cannot be
    // drawn is refused (freeform surfaces unless --allow-missing), nothing half written.
    DrawingRequest request;
    request.view = CurrentViewRequest(view, raster->Info());
    request.allowMissing = settings.allowMissing;
    request.title = ctx_.Flat().viewName;
    request.loc = loc;
    DrawingReport report;
    if (!WriteDrawingFile(ctx_, request, target, diags_, &report)) {
        FlushDiagnostics(false);
        return false;
    }
    FlushDiagnostics(false);  // a warning: freeform surfaces left out
    Trace(fmt::format("device {}: hidden-line drawing, {} strokes; wrote {}; {:.4f} s", format,
                      report.strokes, target, SecondsSince(t0)));
    if (settings.keep) Message("drawing file: " + target);
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
