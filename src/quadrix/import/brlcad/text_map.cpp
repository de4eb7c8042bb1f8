#include <algorithm>
#include <cctype>
#include <cstdio>

#include "quadrix/import/brlcad/readers.h"

namespace quadrix::import::brlcad {

TextMap::TextMap(std::string_view text, const std::string& file)
    : text_(text), file_(std::make_shared<const std::string>(file)) {
    lineStarts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i)
        if (text[i] == '\n') lineStarts_.push_back(i + 1);
}

SourceLoc TextMap::At(std::size_t offset) const {
    auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
    std::size_t line = static_cast<std::size_t>(it - lineStarts_.begin());  // 1-based
    SourceLoc loc;
    loc.file = file_;
    loc.line = static_cast<int>(line);
    loc.column = static_cast<int>(offset - lineStarts_[line - 1]) + 1;
    return loc;
}

std::string TextMap::LineText(std::size_t offset) const {
    auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
    std::size_t start = *(it - 1);
    std::size_t end = text_.find('\n', start);
    if (end == std::string_view::npos) end = text_.size();
    std::string line(text_.substr(start, end - start));
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // Very long records (v4 lines are ~320 characters) are shown whole: the caret needs them.
    return line;
}

TextFormat DetectFormat(std::string_view text) {
    std::size_t i = 0;
    auto nextLine = [&]() {
        std::size_t e = text.find('\n', i);
        std::string_view l = text.substr(i, e == std::string_view::npos ? text.size() - i : e - i);
        i = e == std::string_view::npos ? text.size() : e + 1;
        return l;
    };
    std::string_view first;
    while (i < text.size()) {
        first = nextLine();
        if (first.find_first_not_of(" \t\r") != std::string_view::npos) break;
    }
    auto startsWith = [](std::string_view s, std::string_view p) {
        s.remove_prefix(std::min(s.find_first_not_of(" \t"), s.size()));
        return s.substr(0, p.size()) == p &&
               (s.size() == p.size() || std::isspace(static_cast<unsigned char>(s[p.size()])));
    };
    if (first.size() > 2 && first[0] == 'I' && first[1] == ' ' &&
        first.find("v4") != std::string_view::npos)
        return TextFormat::kV4;
    for (std::string_view kw : {"title", "units", "put", "attr", "color"})
        if (startsWith(first, kw)) return TextFormat::kV5;
    std::string_view second = nextLine();
    int a = 0, b = 0;
    char extra = 0;
    std::string s(second);
    if (std::sscanf(s.c_str(), "%d %d %c", &a, &b, &extra) == 2 && a > 0 && b >= 0)
        return TextFormat::kComgeom;
    return TextFormat::kUnknown;
}

}  // namespace quadrix::import::brlcad
