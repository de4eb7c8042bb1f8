// Where a piece of user input came from: file, 1-based line and column.
#pragma once

#include <memory>
#include <string>

namespace quadrix {

struct SourceLoc {
    std::shared_ptr<const std::string> file;  // shared: every token of a file points to one name
    int line = 0;                             // 1-based; 0 = unknown
    int column = 0;                           // 1-based; 0 = unknown

    std::string FileName() const { return file ? *file : std::string("<input>"); }
    // "file:line:column" (or "file" when the position is unknown).
    std::string ToString() const;
};

}  // namespace quadrix
