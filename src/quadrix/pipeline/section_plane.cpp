#include "quadrix/pipeline/section_plane.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <vector>

namespace quadrix {

std::string ParseSectionPlane(std::string_view text, Plane& plane) {
    std::vector<double> values;
    std::size_t i = 0;
    while (i < text.size()) {
        if (text[i] == ' ' || text[i] == ',' || text[i] == '\t') {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j < text.size() && text[j] != ' ' && text[j] != ',' && text[j] != '\t') ++j;
        double v = 0;
        const char* end = text.data() + j;
        auto [ptr, ec] = std::from_chars(text.data() + i, end, v);
        if (ec != std::errc() || ptr != end || !std::isfinite(v))
            return fmt::format("expected four numbers \"A B C D\", found '{}'",
                               text.substr(i, j - i));
        values.push_back(v);
        i = j;
    }
    if (values.size() != 4)
        return fmt::format(
            "expected four numbers \"A B C D\" (the plane A x + B y + C z + D = 0), "
            "found {}",
            values.size());
    if (values[0] == 0 && values[1] == 0 && values[2] == 0)
        return "the plane's normal (A, B, C) is zero";
    plane = Plane{values[0], values[1], values[2], values[3]};
    return {};
}

std::string FormatSectionPlane(const Plane& p) {
    return fmt::format("{:.17g} {:.17g} {:.17g} {:.17g}", p.a, p.b, p.c, p.d);
}

}  // namespace quadrix
