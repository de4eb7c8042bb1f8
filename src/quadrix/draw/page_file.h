// Writing a page to a file by its extension: .svg by the SVG writer (exact arcs, svg_writer.h),
// .pdf, .eps/.ps and .png through Cairo (cairo_writer.h). Used by `quadrix draw` and the
// viewer's drawing key, so both write the same bytes for the same page.
#pragma once

#include <string>

#include "quadrix/draw/page.h"

namespace quadrix::draw {

// Whether the extension is one of those (case-insensitive).
bool IsPageFileName(const std::string& path);
// Error message or empty.
std::string WritePageFile(const std::string& path, const Page& page);

}  // namespace quadrix::draw
