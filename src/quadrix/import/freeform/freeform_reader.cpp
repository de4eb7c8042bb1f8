#include "quadrix/import/freeform/freeform_reader.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>

#include "quadrix/import/freeform/readers_internal.h"
#include "quadrix/io/bounded_read.h"

namespace quadrix::import {

std::string_view FreeformFormatName(FreeformFormat format) {
    switch (format) {
        case FreeformFormat::kAuto:
            return "auto";
        case FreeformFormat::kNewell:
            return "newell";
        case FreeformFormat::kBpt:
            return "bpt";
        case FreeformFormat::kGeomview:
            return "geomview";
        case FreeformFormat::kObj:
            return "obj";
    }
    return "?";
}

namespace {

std::string Lower(std::string_view s) {
    std::string r(s);
    for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return r;
}

bool EndsWith(const std::string& s, std::string_view suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The file name without directories and extension: the base of surface names.
std::string Stem(const std::string& path) {
    std::size_t slash = path.find_last_of("/\\");
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    std::size_t dot = name.find_last_of('.');
    if (dot != std::string::npos && dot > 0) name = name.substr(0, dot);
    return name.empty() ? std::string("surface") : name;
}

}  // namespace

namespace detail {

std::string SurfaceName(const std::string& baseName, std::size_t index) {
    return baseName + "[" + std::to_string(index) + "]";
}

}  // namespace detail

FreeformFormat DetectFreeformFormat(std::string_view fileName, std::string_view text) {
    std::string name = Lower(fileName);
    if (EndsWith(name, ".obj")) return FreeformFormat::kObj;
    if (EndsWith(name, ".bpt")) return FreeformFormat::kBpt;
    if (EndsWith(name, ".bez") || EndsWith(name, ".bbp")) return FreeformFormat::kGeomview;
    // Look at the first words that are not comments.
    std::istringstream in{std::string(text.substr(0, 4096))};
    std::string line;
    while (std::getline(in, line)) {
        std::size_t hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        std::string w;
        if (!(words >> w)) continue;
        if (w.find("BBP") != std::string::npos || w.find("BEZ") != std::string::npos ||
            w == "appearance" || w == "{")
            return FreeformFormat::kGeomview;
        if (w == "v" || w == "cstype" || w == "deg" || w == "surf" || w == "o" || w == "g" ||
            w == "mtllib")
            return FreeformFormat::kObj;
        break;
    }
    if (text.substr(0, 4096).find(',') != std::string_view::npos) return FreeformFormat::kNewell;
    return FreeformFormat::kBpt;
}

std::optional<FreeformModel> ReadFreeformText(std::string_view text, const std::string& fileName,
                                              FreeformFormat format, Diagnostics& diagnostics) {
    if (format == FreeformFormat::kAuto) format = DetectFreeformFormat(fileName, text);
    int errorsBefore = diagnostics.ErrorCount();
    TextScanner scanner(text, fileName, diagnostics, format == FreeformFormat::kNewell);
    std::string base = Stem(fileName);
    FreeformModel model;
    model.format = format;
    switch (format) {
        case FreeformFormat::kNewell:
            model.surfaces = detail::ReadNewell(scanner, base);
            break;
        case FreeformFormat::kBpt:
            model.surfaces = detail::ReadBpt(scanner, base);
            break;
        case FreeformFormat::kGeomview:
            model.surfaces = detail::ReadGeomview(scanner, base);
            break;
        case FreeformFormat::kObj:
            model.surfaces = detail::ReadObj(scanner, base);
            break;
        case FreeformFormat::kAuto:
            break;
    }
    if (diagnostics.ErrorCount() > errorsBefore) return std::nullopt;
    if (model.surfaces.empty()) {
        diagnostics.Error(
            SourceLoc{std::make_shared<const std::string>(fileName), 0, 0},
            "no freeform surface found (read as " + std::string(FreeformFormatName(format)) + ")");
        return std::nullopt;
    }
    return model;
}

std::optional<FreeformModel> ReadFreeformFile(const std::string& path, Diagnostics& diagnostics,
                                              FreeformFormat format) {
    std::string text;
    if (std::string why = ReadBoundedFile(path, text); !why.empty()) {
        diagnostics.Error(SourceLoc{std::make_shared<const std::string>(path), 0, 0},
                          "cannot read freeform model file: " + why);
        return std::nullopt;
    }
    return ReadFreeformText(text, path, format, diagnostics);
}

}  // namespace quadrix::import
