// Line/column bookkeeping of imported texts (text_map.h).
#include "quadrix/import/text_map.h"

#include <algorithm>

namespace quadrix::import {

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

}  // namespace quadrix::import
