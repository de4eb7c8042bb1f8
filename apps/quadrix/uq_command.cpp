// `quadrix uq [options] [files]` and `quadrix -i`: the UniQuadrix command line (seed 001 §2.2).
//
// Files and options are processed in order from left to right; an option changes what follows
// it (-f before a file that shows, -d before -c "show;", ...). Option values may be glued to the
// option, as in the paper (-dpng, -sx4, -vtop_down), or given as the next word (-d png). Two
// options take an optional value, which must then be glued: -tPATH (bare -t traces to standard
// error) and -cSTMTS (bare -c enters interactive mode); `-c 'stmts'` with a separate word is
// accepted when the word contains a ';', since a file name would not.
//
// Every option is checked before anything is read or drawn, so a bad option gives an error and
// the usage with exit status 2 and writes nothing. The option table and its mapping to
// `quadrix render` are in docs/uq-compat.md.
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "commands.h"
#include "interactive.h"
#include "quadrix/device/device.h"
#include "quadrix/engines/engine.h"
#include "quadrix/io/output_file.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix::cli {

namespace {

constexpr const char* kUsage =
    "usage: quadrix uq [options] [files]      (UniQuadrix batch and interactive modes)\n"
    "       quadrix -i [options] [files]      (the same as quadrix uq -i ...)\n"
    "Files and options are processed from left to right; '-' reads standard input. With no\n"
    "file, -c or -i, standard input is read. Values may be glued (-dpng) or separate (-d png).\n"
    "  -c STMTS    execute the statements STMTS; a bare -c enters interactive mode, and on quit\n"
    "              the rest of the command line is processed\n"
    "  -d DEVICE   draw on DEVICE or DEVICE:PATH (default $UQDEV, else the terminal when\n"
    "              standard output is one, else png); devices: {devices}; svg, pdf, eps\n"
    "              (svg:FILE ...) write the hidden-line drawing of quadrix draw\n"
    "  -e PATH     write error messages to PATH\n"
    "  -f / -F     fast constant shading on / off\n"
    "  -i          interactive mode (uq> prompt) after the options and files\n"
    "  -k / -K     keep raster files on / off: each picture gets a new file, reported\n"
    "  -n / -N     warnings off / on\n"
    "  -sx INCHES  drawing width in inches      -sy INCHES  drawing height in inches\n"
    "  -sd COUNT   smooth shading every COUNT pixels (shading interval, seed 001 §6.5.1)\n"
    "  -t[PATH]    trace each stage to PATH (glued; standard error if missing); -T: trace off\n"
    "  -v VIEW     use view VIEW instead of the last defined\n"
    "  -x          do not draw a picture after the last file\n"
    "  --engine NAME       rendering engine (default raycast), as quadrix render's\n"
    "  --engine-opt K=V    engine-specific setting (repeatable), as quadrix render's\n"
    "  --allow-missing     the svg, pdf and eps devices draw without the freeform surfaces\n"
    "                      (a warning instead of an error), as quadrix draw --allow-missing\n"
    "  --max-memory SIZE   memory budget (512M, 2G): larger pictures are refused, as quadrix\n"
    "                      render's\n"
    "  --time-limit SECS   give up after SECS seconds (exit 124, no output left)\n"
    "  --version   print the version\n"
    "  -h, --help  this text\n"
    "See docs/uq-compat.md for the matching quadrix render options.\n";

void PrintUsage(std::FILE* out) { PrintUqUsage(out); }

struct Action {
    enum class Kind {
        kFile,
        kStatements,
        kInteractive,
        kDevice,
        kErrors,
        kFast,
        kNoFast,
        kKeep,
        kNoKeep,
        kNoWarnings,
        kWarnings,
        kSizeX,
        kSizeY,
        kDelta,
        kTrace,
        kNoTrace,
        kView,
        kEngine,
        kEngineOpt,
        kAllowMissing
    };
    Kind kind;
    std::string text;
    double number = 0;
};

struct Plan {
    std::vector<Action> actions;
    bool interactiveAtEnd = false;  // -i
    bool noRender = false;          // -x
    bool help = false;
    bool version = false;
    EngineRequest engine;  // the last --engine and every --engine-opt, checked before any work
    std::string maxMemory, timeLimit;  // --max-memory, --time-limit (limit_options.h)
};

// Parses the arguments into a plan; returns an error message or empty.
std::string ParseArgs(const std::vector<std::string>& args, Plan& plan) {
    using Kind = Action::Kind;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto add = [&](Kind k, std::string text = {}, double number = 0) {
            plan.actions.push_back({k, std::move(text), number});
        };
        if (a == "-") {
            add(Kind::kFile, "-");
            continue;
        }
        if (a.size() < 2 || a[0] != '-') {
            add(Kind::kFile, a);
            continue;
        }
        if (a == "-h" || a == "--help") {
            plan.help = true;
            continue;
        }
        if (a == "--version") {
            plan.version = true;
            continue;
        }
        if (a == "--allow-missing") {
            add(Kind::kAllowMissing);
            continue;
        }
        // --max-memory SIZE and --time-limit SECONDS (or =VALUE), as quadrix render's.
        if (a == "--max-memory" || a.rfind("--max-memory=", 0) == 0 || a == "--time-limit" ||
            a.rfind("--time-limit=", 0) == 0) {
            const bool memory = a.rfind("--max-memory", 0) == 0;
            const std::string option = memory ? "--max-memory" : "--time-limit";
            std::string v;
            if (a.size() > option.size()) {
                v = a.substr(option.size() + 1);
            } else if (i + 1 < args.size()) {
                v = args[++i];
            } else {
                return fmt::format("option {} needs {}", option,
                                   memory ? "a size such as 512M" : "a number of seconds");
            }
            (memory ? plan.maxMemory : plan.timeLimit) = v;
            continue;
        }
        // --engine NAME / --engine=NAME and --engine-opt KEY=VALUE, as quadrix render's.
        if (a == "--engine" || a.rfind("--engine=", 0) == 0 || a == "--engine-opt" ||
            a.rfind("--engine-opt=", 0) == 0) {
            const bool isOpt = a.rfind("--engine-opt", 0) == 0;
            const std::string option = isOpt ? "--engine-opt" : "--engine";
            std::string v;
            if (a.size() > option.size()) {
                v = a.substr(option.size() + 1);
            } else if (i + 1 < args.size()) {
                v = args[++i];
            } else {
                return fmt::format("option {} needs {}", option,
                                   isOpt ? "KEY=VALUE" : "an engine name");
            }
            if (isOpt) {
                auto eq = v.find('=');
                if (eq == std::string::npos || eq == 0)
                    return fmt::format("--engine-opt: expected KEY=VALUE, found '{}'", v);
                add(Kind::kEngineOpt, v);
                plan.engine.options[v.substr(0, eq)] = v.substr(eq + 1);
            } else {
                add(Kind::kEngine, v);
                plan.engine.engine = v;
            }
            continue;
        }
        // The option letter(s) and a glued value.
        std::string opt, glued;
        if (a.rfind("-s", 0) == 0) {
            opt = a.substr(0, 3);
            glued = a.size() > 3 ? a.substr(3) : "";
            if (opt != "-sx" && opt != "-sy" && opt != "-sd")
                return fmt::format("unknown option '{}' (size options are -sx, -sy and -sd)", a);
        } else {
            opt = a.substr(0, 2);
            glued = a.substr(2);
        }
        // A required value: glued, else the next word.
        auto value = [&](const char* what, std::string& out) -> std::string {
            if (!glued.empty()) {
                out = glued;
                return {};
            }
            if (i + 1 >= args.size()) return fmt::format("option {} needs {}", opt, what);
            out = args[++i];
            return {};
        };
        auto flag = [&](Kind k) -> std::string {
            if (!glued.empty())
                return fmt::format("unknown option '{}' (option {} takes no value)", a, opt);
            add(k);
            return {};
        };
        auto inches = [&](Kind k) -> std::string {
            std::string v;
            if (auto e = value("a size in inches", v); !e.empty()) return e;
            char* end = nullptr;
            double d = std::strtod(v.c_str(), &end);
            if (end == v.c_str() || *end != '\0' || !std::isfinite(d) || d <= 0)
                return fmt::format("option {}: '{}' is not a positive number of inches", opt, v);
            add(k, {}, d);
            return {};
        };
        std::string e, v;
        const char c = opt[1];
        if (opt == "-sx")
            e = inches(Kind::kSizeX);
        else if (opt == "-sy")
            e = inches(Kind::kSizeY);
        else if (opt == "-sd") {
            if (e = value("a pixel count", v); e.empty()) {
                char* end = nullptr;
                long n = std::strtol(v.c_str(), &end, 10);
                if (end == v.c_str() || *end != '\0' || n < 1 || n > 1000000)
                    e = fmt::format("option -sd: '{}' is not a positive pixel count", v);
                else
                    add(Kind::kDelta, {}, static_cast<double>(n));
            }
        } else if (c == 'c') {
            if (!glued.empty())
                add(Kind::kStatements, glued);
            else if (i + 1 < args.size() && args[i + 1].find(';') != std::string::npos)
                add(Kind::kStatements, args[++i]);
            else
                add(Kind::kInteractive);
        } else if (c == 'd') {
            if (e = value("a device name", v); e.empty()) add(Kind::kDevice, v);
        } else if (c == 'e') {
            if (e = value("a file name", v); e.empty()) add(Kind::kErrors, v);
        } else if (c == 'v') {
            if (e = value("a view id", v); e.empty()) add(Kind::kView, v);
        } else if (c == 't') {
            add(Kind::kTrace, glued);
        } else if (c == 'f')
            e = flag(Kind::kFast);
        else if (c == 'F')
            e = flag(Kind::kNoFast);
        else if (c == 'k')
            e = flag(Kind::kKeep);
        else if (c == 'K')
            e = flag(Kind::kNoKeep);
        else if (c == 'n')
            e = flag(Kind::kNoWarnings);
        else if (c == 'N')
            e = flag(Kind::kWarnings);
        else if (c == 'T')
            e = flag(Kind::kNoTrace);
        else if (c == 'x' && glued.empty())
            plan.noRender = true;
        else if (c == 'i' && glued.empty())
            plan.interactiveAtEnd = true;
        else
            e = fmt::format("unknown option '{}'", a);
        if (!e.empty()) return e;
    }
    return {};
}

// The device used when no -d is given (§2.2: "UniQuadrix checks for device names in environment
// variable UQDEV, then TERM").
std::string DefaultDevice() {
    if (const char* d = std::getenv("UQDEV"); d && *d) return d;
    const char* term = std::getenv("TERM");
    if (term && *term && std::strcmp(term, "dumb") != 0 && isatty(fileno(stdout)))
        return "terminal";
    return "png";
}

// Replays the device-changing options left to right, so a bad device, path or size is an error
// before anything is read or drawn.
std::string CheckDevices(const Plan& plan, const std::string& initial, const char* source) {
    using Kind = Action::Kind;
    std::string spec = initial;
    device::DeviceSettings ds;
    std::string error;
    // No output (a device's file, -e, -t) may be one of the scene files (io/output_file.h).
    std::vector<std::string> inputs;
    for (const Action& a : plan.actions)
        if (a.kind == Kind::kFile) inputs.push_back(a.text);
    for (const Action& a : plan.actions)
        if ((a.kind == Kind::kErrors || a.kind == Kind::kTrace) && !a.text.empty())
            for (const std::string& in : inputs)
                if (IsSameFile(a.text, in))
                    return fmt::format("cannot write '{}': it is the input file '{}'", a.text, in);
    auto checkOutput = [&](const std::unique_ptr<device::Device>& d) {
        if (!d) return false;
        if (d->Info().path.empty()) return true;  // a window
        if (auto e = CheckOutputPaths({d->Info().path}, inputs); !e.empty()) error = e;
        return error.empty();
    };
    // svg:FILE, pdf:FILE, eps:FILE: the hidden-line drawing (interactive.h).
    auto check = [&]() {
        std::string path, format;
        if (!IsVectorDeviceSpec(spec, path, format, error))
            return checkOutput(device::MakeDevice(spec, ds, error));
        if (!error.empty()) return false;
        if (auto e = CheckOutputPaths({path}, inputs); !e.empty()) error = e;
        return error.empty();
    };
    if (!check()) return fmt::format("{} (device from {})", error, source);
    for (const Action& a : plan.actions) {
        if (a.kind == Kind::kDevice)
            spec = a.text;
        else if (a.kind == Kind::kSizeX)
            ds.xInches = a.number;
        else if (a.kind == Kind::kSizeY)
            ds.yInches = a.number;
        else if (a.kind == Kind::kDelta)
            ds.deltaMax = static_cast<int>(a.number);
        else
            continue;
        if (!check()) return error;
    }
    return {};
}

int UsageError(const std::string& message) {
    std::fprintf(stderr, "quadrix uq: error: %s\n", message.c_str());
    PrintUsage(stderr);
    return 2;
}

}  // namespace

void PrintUqUsage(std::FILE* out) {
    std::string usage = kUsage;
    std::string::size_type at = usage.find("{devices}");
    usage.replace(at, 9, device::KnownDevicesText());
    std::fputs(usage.c_str(), out);
}

int RunUq(const std::vector<std::string>& args) {
    Plan plan;
    if (auto e = ParseArgs(args, plan); !e.empty()) return UsageError(e);
    if (plan.help) {
        PrintUsage(stdout);
        return 0;
    }
    if (plan.version) {
        std::printf("quadrix %s\n", QUADRIX_VERSION);
        return 0;
    }
    // An unknown engine or a bad engine option is a usage error (docs/cli.md), as in render.
    if (auto e = RenderContext::CheckEngine(plan.engine); !e.empty()) return UsageError(e);
    if (auto e = ApplyLimits(plan.maxMemory, plan.timeLimit); !e.empty()) return UsageError(e);
    // "If no -d option is given, UniQuadrix checks for device names in environment variable
    // UQDEV": with a -d anywhere on the line, its first device is the device from the start.
    std::string initialDevice;
    for (const Action& a : plan.actions)
        if (a.kind == Action::Kind::kDevice && initialDevice.empty()) initialDevice = a.text;
    const char* deviceSource = "-d";
    if (initialDevice.empty()) {
        initialDevice = DefaultDevice();
        deviceSource = std::getenv("UQDEV") && *std::getenv("UQDEV") ? "$UQDEV" : "the default";
    }
    if (auto e = CheckDevices(plan, initialDevice, deviceSource); !e.empty()) return UsageError(e);

    UqSession session;
    session.settings.device = initialDevice;
    std::FILE* errors = nullptr;  // -e
    std::FILE* trace = nullptr;   // -tPATH
    auto closeFile = [](std::FILE*& f) {
        if (f) std::fclose(f);
        f = nullptr;
    };
    bool anyInput = false;
    bool tracing = false;
    using Kind = Action::Kind;
    for (const Action& a : plan.actions) {
        switch (a.kind) {
            case Kind::kFile:
                session.ReadFile(a.text);
                anyInput = true;
                break;
            case Kind::kStatements:
                session.ReadStatements(a.text);
                anyInput = true;
                break;
            case Kind::kInteractive:
                session.Interactive();
                anyInput = true;
                break;
            case Kind::kDevice:
                session.settings.device = a.text;
                break;
            case Kind::kErrors: {
                std::FILE* f = std::fopen(a.text.c_str(), "w");
                if (!f) {
                    std::fprintf(stderr, "quadrix uq: error: cannot write '%s': %s\n",
                                 a.text.c_str(), std::strerror(errno));
                    closeFile(errors);
                    closeFile(trace);
                    return 2;
                }
                closeFile(errors);
                errors = f;
                session.SetErrorStream(errors);
                break;
            }
            case Kind::kFast:
                session.settings.fast = true;
                break;
            case Kind::kNoFast:
                session.settings.fast = false;
                break;
            case Kind::kKeep:
                session.settings.keep = true;
                break;
            case Kind::kNoKeep:
                session.settings.keep = false;
                break;
            case Kind::kNoWarnings:
                session.settings.warnings = false;
                break;
            case Kind::kWarnings:
                session.settings.warnings = true;
                break;
            case Kind::kSizeX:
                session.settings.xInches = a.number;
                break;
            case Kind::kSizeY:
                session.settings.yInches = a.number;
                break;
            case Kind::kDelta:
                session.settings.deltaMax = static_cast<int>(a.number);
                break;
            case Kind::kTrace:
                closeFile(trace);
                if (!a.text.empty()) {
                    trace = std::fopen(a.text.c_str(), "w");
                    if (!trace) {
                        std::fprintf(stderr, "quadrix uq: error: cannot write '%s': %s\n",
                                     a.text.c_str(), std::strerror(errno));
                        closeFile(errors);
                        return 2;
                    }
                }
                session.SetTrace(trace ? trace : stderr);
                tracing = true;
                break;
            case Kind::kNoTrace:
                session.SetTrace(nullptr);
                tracing = false;
                break;
            case Kind::kView:
                session.PinView(a.text);
                break;
            case Kind::kEngine:
                session.settings.engine = a.text;
                break;
            case Kind::kAllowMissing:
                session.settings.allowMissing = true;
                break;
            case Kind::kEngineOpt: {
                const auto eq = a.text.find('=');
                session.settings.engineOptions[a.text.substr(0, eq)] = a.text.substr(eq + 1);
                break;
            }
        }
    }
    if (!anyInput && !plan.interactiveAtEnd) session.ReadFile("-");
    if (plan.interactiveAtEnd)
        session.Interactive();
    else if (!plan.noRender)
        session.FinalShow();
    if (session.WasInteractive() || tracing) session.PrintSummary();
    int code = session.HadErrors() ? 1 : 0;
    session.SetTrace(nullptr);
    session.SetErrorStream(stderr);
    closeFile(trace);
    closeFile(errors);
    return code;
}

void AddUqCommand(CLI::App& app) {
    // Registered for `quadrix --help` only: MaybeRunUq runs it before CLI11 sees the arguments,
    // because UniQuadrix options glue their values (-dpng, -sx4) in a way CLI11 does not parse.
    app.add_subcommand("uq",
                       "UniQuadrix batch and interactive modes with the paper's options "
                       "(quadrix uq --help; quadrix -i for the uq> prompt)")
        ->allow_extras();
}

bool MaybeRunUq(int argc, char** argv, int& exitCode) {
    if (argc < 2) return false;
    std::string first = argv[1];
    if (first != "uq" && first != "-i") return false;
    std::vector<std::string> args;
    if (first == "-i") args.push_back("-i");
    for (int i = 2; i < argc; ++i) args.emplace_back(argv[i]);
    exitCode = RunUq(args);
    return true;
}

}  // namespace quadrix::cli
