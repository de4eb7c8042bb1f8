// Line and column of a byte offset in an imported text, for file:line:column diagnostics; shared
// by the BRL-CAD readers and the OpenSCAD reader.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "quadrix/scene/diagnostics.h"

namespace quadrix::import {

class TextMap {
  public:
    TextMap(std::string_view text, const std::string& file);
    SourceLoc At(std::size_t offset) const;
    std::string LineText(std::size_t offset) const;
    std::string_view text() const { return text_; }

  private:
    std::string_view text_;
    std::shared_ptr<const std::string> file_;
    std::vector<std::size_t> lineStarts_;
};

}  // namespace quadrix::import
