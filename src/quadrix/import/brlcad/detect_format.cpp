// Which of the three BRL-CAD text formats a file is, by its content (readers.h).
#include <algorithm>
#include <cctype>
#include <cstdio>

#include "quadrix/import/brlcad/readers.h"

namespace quadrix::import::brlcad {

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
