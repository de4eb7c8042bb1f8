#include "quadrix/import/freeform/text_scanner.h"

#include <charconv>
#include <cmath>

namespace quadrix::import {

TextScanner::TextScanner(std::string_view text, std::string fileName, Diagnostics& diagnostics,
                         bool commasSeparate)
    : text_(text),
      file_(std::make_shared<const std::string>(std::move(fileName))),
      diagnostics_(diagnostics),
      commasSeparate_(commasSeparate) {
    lineStarts_.push_back(0);
    for (std::size_t i = 0; i < text_.size(); ++i)
        if (text_[i] == '\n') lineStarts_.push_back(i + 1);
    last_ = {{}, 1, 1};
}

bool TextScanner::IsSeparator(char c) const {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v' ||
           (commasSeparate_ && c == ',');
}

void TextScanner::SkipSpaceAndComments(bool acrossLines) {
    while (pos_ < text_.size()) {
        char c = text_[pos_];
        if (IsSeparator(c)) {
            ++pos_;
        } else if (c == '#') {
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        } else if (c == '\n' && acrossLines) {
            ++pos_;
            ++line_;
            lineStart_ = pos_;
        } else {
            break;
        }
    }
}

bool TextScanner::Next(ScanToken& token) {
    SkipSpaceAndComments(true);
    if (pos_ >= text_.size()) return false;
    std::size_t start = pos_;
    while (pos_ < text_.size() && !IsSeparator(text_[pos_]) && text_[pos_] != '\n' &&
           text_[pos_] != '#')
        ++pos_;
    token = {text_.substr(start, pos_ - start), line_, static_cast<int>(start - lineStart_) + 1};
    last_ = token;
    return true;
}

bool TextScanner::Peek(ScanToken& token) {
    std::size_t pos = pos_, lineStart = lineStart_;
    int line = line_;
    ScanToken last = last_;
    bool ok = Next(token);
    pos_ = pos;
    lineStart_ = lineStart;
    line_ = line;
    last_ = last;
    return ok;
}

bool TextScanner::NextLine(std::vector<ScanToken>& tokens) {
    tokens.clear();
    for (;;) {
        SkipSpaceAndComments(false);
        if (pos_ >= text_.size()) return !tokens.empty();
        char c = text_[pos_];
        if (c == '\n') {
            ++pos_;
            ++line_;
            lineStart_ = pos_;
            if (!tokens.empty()) return true;
            continue;
        }
        if (c == '\\') {
            // A backslash at the end of a line continues the statement on the next line.
            std::size_t p = pos_ + 1;
            while (p < text_.size() && IsSeparator(text_[p])) ++p;
            if (p >= text_.size() || text_[p] == '\n') {
                pos_ = p;
                if (pos_ < text_.size()) {
                    ++pos_;
                    ++line_;
                    lineStart_ = pos_;
                }
                continue;
            }
        }
        std::size_t start = pos_;
        while (pos_ < text_.size() && !IsSeparator(text_[pos_]) && text_[pos_] != '\n' &&
               text_[pos_] != '#')
            ++pos_;
        tokens.push_back(
            {text_.substr(start, pos_ - start), line_, static_cast<int>(start - lineStart_) + 1});
        last_ = tokens.back();
    }
}

std::optional<double> TextScanner::Number(const ScanToken& token, std::string_view what) {
    const char* first = token.text.data();
    const char* last = first + token.text.size();
    if (first != last && *first == '+') ++first;  // from_chars rejects a leading '+'
    double value = 0;
    auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || ptr != last || first == last) {
        Error(token, "expected " + std::string(what) + ", found '" + std::string(token.text) + "'");
        return std::nullopt;
    }
    if (!std::isfinite(value)) {
        Error(token, std::string(what) + " is not finite: '" + std::string(token.text) + "'");
        return std::nullopt;
    }
    return value;
}

std::optional<long long> TextScanner::Integer(const ScanToken& token, std::string_view what) {
    const char* first = token.text.data();
    const char* last = first + token.text.size();
    if (first != last && *first == '+') ++first;
    long long value = 0;
    auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || ptr != last || first == last) {
        Error(token, "expected " + std::string(what) + ", found '" + std::string(token.text) + "'");
        return std::nullopt;
    }
    return value;
}

std::optional<double> TextScanner::NextNumber(std::string_view what) {
    ScanToken t;
    if (!Next(t)) {
        ErrorAtEnd("unexpected end of file, expected " + std::string(what));
        return std::nullopt;
    }
    return Number(t, what);
}

std::optional<long long> TextScanner::NextInteger(std::string_view what) {
    ScanToken t;
    if (!Next(t)) {
        ErrorAtEnd("unexpected end of file, expected " + std::string(what));
        return std::nullopt;
    }
    return Integer(t, what);
}

SourceLoc TextScanner::Loc(const ScanToken& at) const { return {file_, at.line, at.column}; }

std::string TextScanner::LineText(int line) const {
    if (line < 1 || static_cast<std::size_t>(line) > lineStarts_.size()) return {};
    std::size_t start = lineStarts_[static_cast<std::size_t>(line - 1)];
    std::size_t end = text_.find('\n', start);
    if (end == std::string_view::npos) end = text_.size();
    std::string s(text_.substr(start, end - start));
    if (!s.empty() && s.back() == '\r') s.pop_back();
    return s;
}

void TextScanner::Error(const ScanToken& at, std::string message) {
    diagnostics_.Error(Loc(at), std::move(message), LineText(at.line), "input");
}

void TextScanner::Warning(const ScanToken& at, std::string message) {
    diagnostics_.Warning(Loc(at), std::move(message), LineText(at.line), "input");
}

void TextScanner::ErrorAtEnd(std::string message) {
    // Point just after the last token read.
    ScanToken at = last_;
    at.column += static_cast<int>(at.text.size());
    diagnostics_.Error(Loc(at), std::move(message), LineText(at.line), "input");
}

}  // namespace quadrix::import
