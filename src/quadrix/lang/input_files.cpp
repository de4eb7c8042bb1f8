#include "quadrix/lang/input_files.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "quadrix/io/bounded_read.h"
#include "quadrix/lang/parser.h"
#include "quadrix/lang/source.h"

namespace quadrix::lang {

namespace {

namespace fs = std::filesystem;

constexpr const char* kStdinName = "<stdin>";
constexpr const char* kStdinKey = "-";

// The key that identifies a file on the include stack: its canonical path when it can be
// computed, else the normalised absolute path.
std::string CanonicalKey(const std::string& path) {
    if (path == "-") return kStdinKey;
    std::error_code ec;
    fs::path p = fs::weakly_canonical(fs::path(path), ec);
    if (ec) p = fs::absolute(fs::path(path), ec).lexically_normal();
    return p.string();
}

// Loads a whole file through the bounded reader (io/bounded_read.h: at most 256 MiB, so `read
// "/dev/zero";` or an endless pipe ends in an error, issue 7 fuzzing); false with a reason.
bool LoadFile(const std::string& path, std::string& text, std::string& reason) {
    reason = ReadBoundedFile(path, text);
    return reason.empty();
}

bool ReadStdinLine(std::string& text) { return ReadBoundedStdinLine(text); }

// Why `frame` may not be read now (a cycle, or nesting too deep), or empty when it may.
std::string CheckCanRead(const ReaderState& state, const IncludeFrame& frame) {
    for (std::size_t i = 0; i < state.includeStack.size(); ++i) {
        if (state.includeStack[i].key != frame.key) continue;
        std::string chain;
        for (std::size_t j = i; j < state.includeStack.size(); ++j)
            chain += state.includeStack[j].displayName + " -> ";
        return fmt::format("read cycle: {}{}", chain, frame.displayName);
    }
    // The top-level input is depth 0; each read goes one deeper.
    if (static_cast<int>(state.includeStack.size()) > state.options.maxIncludeDepth)
        return fmt::format("reads nested deeper than {} levels (reading {})",
                           state.options.maxIncludeDepth, frame.displayName);
    return {};
}

// Pushes `frame` and runs a parser over `source`, unless CheckCanRead objects (then returns its
// message without reading).
std::string RunSource(ReaderState& state, Source& source, IncludeFrame frame) {
    if (std::string why = CheckCanRead(state, frame); !why.empty()) return why;
    state.includeStack.push_back(std::move(frame));
    state.ReserveForText(source.From(0));  // empty for standard input, which grows
    Parser parser(state, source);
    parser.Run();
    state.includeStack.pop_back();
    return {};
}

void TopLevelError(ReaderState& state, const std::string& name, std::string message) {
    state.diags.Error(SourceLoc{std::make_shared<const std::string>(name), 0, 0},
                      std::move(message), {}, kParser);
}

}  // namespace

void ReadTopLevelFile(ReaderState& state, const std::string& path) {
    if (state.aborted) return;
    if (path == "-") {
        Source source(kStdinName, Source::LineReader(ReadStdinLine));
        std::string error = RunSource(state, source, {kStdinKey, kStdinName});
        if (!error.empty()) TopLevelError(state, kStdinName, error);
        if (std::string e = StdinError(); error.empty() && !e.empty())
            TopLevelError(state, kStdinName, "cannot read standard input: " + e);
        return;
    }
    std::string text, reason;
    if (!LoadFile(path, text, reason)) {
        TopLevelError(state, path, fmt::format("cannot read {}: {}", path, reason));
        return;
    }
    Source source(path, std::move(text));
    std::string error = RunSource(state, source, {CanonicalKey(path), path});
    if (!error.empty()) TopLevelError(state, path, error);
}

void ReadTopLevelText(ReaderState& state, std::string_view text, const std::string& name) {
    if (state.aborted) return;
    std::string shown = name.empty() ? "<input>" : name;
    Source source(shown, std::string(text));
    std::string key = name.empty() ? "<input>" : CanonicalKey(name);
    std::string error = RunSource(state, source, {key, shown});
    if (!error.empty()) TopLevelError(state, shown, error);
}

std::string ResolveAgainstIncluder(Parser& includer, const std::string& path) {
    // Relative paths are relative to the including file (not to the working directory), so a
    // scene and the files it reads can move together.
    fs::path resolved(path);
    const std::string& includerName = *includer.GetSource().Name();
    bool includerIsFile = includerName != kStdinName && includerName != "<input>";
    if (resolved.is_relative() && includerIsFile)
        resolved = (fs::path(includerName).parent_path() / resolved).lexically_normal();
    return resolved.string();
}

void ReadIncluded(ReaderState& state, Parser& includer, const std::string& path,
                  const SourceLoc& at) {
    if (path == "-") {
        Source source(kStdinName, Source::LineReader(ReadStdinLine));
        std::string error = RunSource(state, source, {kStdinKey, kStdinName});
        if (!error.empty()) includer.Error(at, error, kParser);
        if (std::string e = StdinError(); error.empty() && !e.empty())
            includer.Error(at, "cannot read standard input: " + e, kParser);
        return;
    }
    std::string shown = ResolveAgainstIncluder(includer, path);
    // Check nesting and cycles before touching the file, so a cycle is reported as a cycle.
    IncludeFrame frame{CanonicalKey(shown), shown};
    if (std::string why = CheckCanRead(state, frame); !why.empty()) {
        includer.Error(at, why, kParser);
        return;
    }
    if (++state.filesRead > ReaderState::kMaxFilesRead) {
        includer.Error(at,
                       fmt::format("more than {} files read by read statements (a read fan-out: "
                                   "files that read other files many times); reading stopped",
                                   ReaderState::kMaxFilesRead),
                       kParser);
        state.aborted = true;
        return;
    }
    std::string text, reason;
    if (!LoadFile(shown, text, reason)) {
        includer.Error(at, fmt::format("cannot read {}: {}", shown, reason), kParser);
        return;
    }
    state.bytesRead += static_cast<long long>(text.size());
    if (state.bytesRead > ReaderState::kMaxBytesRead) {
        includer.Error(at,
                       fmt::format("read statements have read more than {} MiB in all (reading "
                                   "{}); reading stopped",
                                   ReaderState::kMaxBytesRead >> 20, shown),
                       kParser);
        state.aborted = true;
        return;
    }
    Source source(shown, std::move(text));
    std::string error = RunSource(state, source, std::move(frame));
    if (!error.empty()) includer.Error(at, error, kParser);
}

}  // namespace quadrix::lang
