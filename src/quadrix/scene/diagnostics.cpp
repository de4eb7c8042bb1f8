#include "quadrix/scene/diagnostics.h"

#include <fmt/format.h>

#include <algorithm>

namespace quadrix {

namespace {

// Control bytes (a NUL, an escape sequence) in a message or source line would cut the message
// short or act on the terminal; they are shown as \xHH instead (issue 23). Tabs stay.
bool IsControl(char c) {
    const auto u = static_cast<unsigned char>(c);
    return (u < 0x20 && c != '\t') || u == 0x7f;
}

std::string Visible(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text)
        if (IsControl(c))
            out += fmt::format("\\x{:02X}", static_cast<unsigned char>(c));
        else
            out += c;
    return out;
}

}  // namespace

std::string Diagnostic::Format(bool withSource) const {
    const char* sev = severity == Severity::kError     ? "error"
                      : severity == Severity::kWarning ? "warning"
                                                       : "note";
    std::string s;
    if (loc.file || loc.line > 0)
        s = fmt::format("{}: {}: {}", Visible(loc.ToString()), sev, Visible(message));
    else
        s = fmt::format("quadrix: {}: {}", sev, Visible(message));
    if (withSource && !sourceLine.empty() && loc.column > 0) {
        // Tabs are kept in the caret line so the caret lines up with the source in a terminal;
        // an escaped control byte is four columns wide.
        std::string caret;
        for (int i = 0; i + 1 < loc.column && i < static_cast<int>(sourceLine.size()); ++i)
            caret += sourceLine[i] == '\t' ? "\t" : IsControl(sourceLine[i]) ? "    " : " ";
        s += fmt::format("\n    {}\n    {}^", Visible(sourceLine), caret);
    }
    return s;
}

void Diagnostics::Add(Diagnostic d) {
    // Stored visible too, so that every reader of Items() (the API's and Python's exceptions, the
    // viewer's title, JSON) gets a message without control bytes.
    if (std::find_if(d.message.begin(), d.message.end(), IsControl) != d.message.end())
        d.message = Visible(d.message);
    if (d.severity == Diagnostic::Severity::kError) ++errorCount_;
    if (d.severity == Diagnostic::Severity::kWarning) ++warningCount_;
    if (static_cast<int>(items_.size()) < kMaxStored) items_.push_back(std::move(d));
}

void Diagnostics::Error(const SourceLoc& loc, std::string message, std::string sourceLine,
                        std::string kind) {
    Add({Diagnostic::Severity::kError, loc, std::move(message), std::move(sourceLine),
         std::move(kind)});
}

void Diagnostics::Warning(const SourceLoc& loc, std::string message, std::string sourceLine,
                          std::string kind) {
    Add({Diagnostic::Severity::kWarning, loc, std::move(message), std::move(sourceLine),
         std::move(kind)});
}

void Diagnostics::Note(const SourceLoc& loc, std::string message) {
    Add({Diagnostic::Severity::kNote, loc, std::move(message), {}, "note"});
}

void Diagnostics::Clear() {
    items_.clear();
    errorCount_ = warningCount_ = 0;
}

void Diagnostics::Print(std::FILE* out, bool showWarnings, bool withSource) const {
    for (const Diagnostic& d : items_) {
        if (d.severity == Diagnostic::Severity::kWarning && !showWarnings) continue;
        std::fputs(d.Format(withSource).c_str(), out);
        std::fputc('\n', out);
    }
    int dropped = errorCount_ + warningCount_ - static_cast<int>(items_.size());
    if (dropped > 0) std::fprintf(out, "quadrix: %d more diagnostics not shown\n", dropped);
}

}  // namespace quadrix
