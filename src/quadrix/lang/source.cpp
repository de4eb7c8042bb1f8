#include "quadrix/lang/source.h"

#include <algorithm>
#include <cstring>

namespace quadrix::lang {

Source::Source(std::string name, std::string text)
    : name_(std::make_shared<const std::string>(std::move(name))), text_(std::move(text)) {}

Source::Source(std::string name, LineReader readLine)
    : name_(std::make_shared<const std::string>(std::move(name))), readLine_(std::move(readLine)) {}

void Source::Append(std::string_view more) { text_ += more; }

bool Source::ReadMore(std::size_t pos) {
    while (pos >= text_.size() && readLine_) {
        if (!readLine_(text_)) {
            readLine_ = nullptr;  // end of input: never ask again
            break;
        }
    }
    return pos < text_.size();
}

void Source::IndexLines() const {
    const char* begin = text_.data();
    const char* end = begin + text_.size();
    for (const char* p = begin + indexedTo_; p < end;) {
        const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
        if (!nl) break;
        p = static_cast<const char*>(nl) + 1;
        lineStarts_.push_back(static_cast<std::size_t>(p - begin));
    }
    indexedTo_ = text_.size();
}

std::string Source::LineForDiagnostic(int line, int column) const {
    if (line >= 1 && line > static_cast<int>(lineStarts_.size())) IndexLines();
    if (line < 1 || line > static_cast<int>(lineStarts_.size()) || column > kMaxShownColumn)
        return {};
    std::size_t start = lineStarts_[line - 1];
    std::size_t end = start;
    while (end < text_.size() && text_[end] != '\n') ++end;
    // Keep at least a little context after the caret, but never print megabytes of one line.
    std::size_t keep = static_cast<std::size_t>(std::max(column + 80, 160));
    bool cut = end - start > keep;
    std::string s = text_.substr(start, std::min(end - start, keep));
    if (!s.empty() && s.back() == '\r') s.pop_back();
    for (char& c : s) {
        unsigned char u = static_cast<unsigned char>(c);
        if ((u < 0x20 && c != '\t') || u == 0x7f) c = '?';
    }
    if (cut) s += " ...";
    return s;
}

}  // namespace quadrix::lang
