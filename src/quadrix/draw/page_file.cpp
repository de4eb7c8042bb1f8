#include "quadrix/draw/page_file.h"

#include <cctype>

#include "quadrix/draw/cairo_writer.h"
#include "quadrix/draw/svg_writer.h"

namespace quadrix::draw {

namespace {

bool EndsWith(const std::string& path, const std::string& ext) {
    if (path.size() < ext.size()) return false;
    for (std::size_t i = 0; i < ext.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(path[path.size() - ext.size() + i])) != ext[i])
            return false;
    return true;
}

}  // namespace

bool IsPageFileName(const std::string& path) {
    for (const char* e : {".svg", ".pdf", ".eps", ".ps", ".png"})
        if (EndsWith(path, e)) return true;
    return false;
}

std::string WritePageFile(const std::string& path, const Page& page) {
    if (EndsWith(path, ".svg")) return WriteSvg(path, page);
    if (EndsWith(path, ".pdf")) return WriteCairo(path, page, CairoFormat::kPdf);
    if (EndsWith(path, ".eps") || EndsWith(path, ".ps"))
        return WriteCairo(path, page, CairoFormat::kEps);
    if (EndsWith(path, ".png")) return WriteCairo(path, page, CairoFormat::kPng);
    return path + ": a drawing must end in .svg, .pdf, .eps or .png";
}

}  // namespace quadrix::draw
