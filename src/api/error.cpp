// quadrix::Message and quadrix::Error (include/quadrix/quadrix.h): the API's error model, one
// exception type that carries the diagnostics of the scene readers (file:line:column) as values.
#include <utility>

#include "api_internal.h"

namespace quadrix {

const char* VersionString() { return QUADRIX_VERSION; }

namespace {

Diagnostic ToDiagnostic(const Message& m) {
    Diagnostic d;
    d.severity = m.severity == Message::Severity::kError     ? Diagnostic::Severity::kError
                 : m.severity == Message::Severity::kWarning ? Diagnostic::Severity::kWarning
                                                             : Diagnostic::Severity::kNote;
    if (!m.file.empty()) d.loc.file = std::make_shared<const std::string>(m.file);
    d.loc.line = m.line;
    d.loc.column = m.column;
    d.message = m.text;
    d.sourceLine = m.sourceLine;
    return d;
}

std::string JoinErrors(const std::vector<Message>& messages) {
    std::string s;
    for (const Message& m : messages) {
        if (m.severity != Message::Severity::kError) continue;
        if (!s.empty()) s += '\n';
        s += m.Format(false);
    }
    return s.empty() ? std::string("quadrix: error") : s;
}

}  // namespace

std::string Message::Format(bool withSource) const {
    return ToDiagnostic(*this).Format(withSource);
}

Error::Error(std::vector<Message> messages)
    : std::runtime_error(JoinErrors(messages)), messages_(std::move(messages)) {
    first_ = messages_.size();
    for (std::size_t i = 0; i < messages_.size(); ++i)
        if (messages_[i].severity == Message::Severity::kError) {
            first_ = i;
            break;
        }
}

Error::Error(const std::string& text)
    : Error(std::vector<Message>{Message{Message::Severity::kError, {}, 0, 0, text, {}}}) {}

const std::string& Error::File() const noexcept {
    static const std::string kEmpty;
    return first_ < messages_.size() ? messages_[first_].file : kEmpty;
}
int Error::Line() const noexcept { return first_ < messages_.size() ? messages_[first_].line : 0; }
int Error::Column() const noexcept {
    return first_ < messages_.size() ? messages_[first_].column : 0;
}

namespace api {

Message ToMessage(const Diagnostic& d) {
    Message m;
    m.severity = d.severity == Diagnostic::Severity::kError     ? Message::Severity::kError
                 : d.severity == Diagnostic::Severity::kWarning ? Message::Severity::kWarning
                                                                : Message::Severity::kNote;
    if (d.loc.file) m.file = *d.loc.file;
    m.line = d.loc.line;
    m.column = d.loc.column;
    m.text = d.message;
    m.sourceLine = d.sourceLine;
    return m;
}

std::vector<Message> ToMessages(const Diagnostics& diags) {
    std::vector<Message> out;
    for (const Diagnostic& d : diags.Items()) out.push_back(ToMessage(d));
    return out;
}

std::vector<Message> WarningsOf(const Diagnostics& diags) {
    std::vector<Message> out;
    for (const Diagnostic& d : diags.Items())
        if (d.severity == Diagnostic::Severity::kWarning) out.push_back(ToMessage(d));
    return out;
}

void ThrowDiagnostics(const Diagnostics& diags, const std::string& fallback) {
    std::vector<Message> messages = ToMessages(diags);
    bool anyError = false;
    for (const Message& m : messages) anyError |= m.severity == Message::Severity::kError;
    if (!anyError) messages.push_back(Message{Message::Severity::kError, {}, 0, 0, fallback, {}});
    throw Error(std::move(messages));
}

}  // namespace api
}  // namespace quadrix
