// Geomview BBP / BEZ files (freeform_reader.h; Geomview manual, "BBP and BEZ").
#include <cctype>
#include <string>

#include "quadrix/freeform/bezier_surface.h"
#include "quadrix/import/freeform/freeform_reader.h"
#include "quadrix/import/freeform/readers_internal.h"

namespace quadrix::import::detail {

namespace {

struct Header {
    int degreeU = 3, degreeV = 3;
    int coords = 3;       // 3, or 4 for homogeneous x y z w
    bool st = false;      // 4 (s, t) pairs follow each patch
    bool colors = false;  // 4 RGBA colours follow each patch
};

bool IsDigit16(char c) { return c >= '1' && c <= '6'; }

// Parses "[ST]BBP" or "[C]BEZ<Nu><Nv><Nd>[_ST]"; nullopt for any other word.
std::optional<Header> ParseHeader(std::string_view w) {
    Header h;
    if (w == "BBP") return h;
    if (w == "STBBP") {
        h.st = true;
        return h;
    }
    if (w.starts_with("C")) {
        h.colors = true;
        w.remove_prefix(1);
    }
    if (!w.starts_with("BEZ") || w.size() < 6) return std::nullopt;
    if (!IsDigit16(w[3]) || !IsDigit16(w[4]) || (w[5] != '3' && w[5] != '4')) return std::nullopt;
    h.degreeU = w[3] - '0';
    h.degreeV = w[4] - '0';
    h.coords = w[5] - '0';
    std::string_view rest = w.substr(6);
    if (rest == "_ST") {
        h.st = true;
    } else if (!rest.empty()) {
        return std::nullopt;
    }
    return h;
}

bool LooksNumeric(std::string_view w) {
    return !w.empty() && (std::isdigit(static_cast<unsigned char>(w[0])) || w[0] == '-' ||
                          w[0] == '+' || w[0] == '.');
}

// Skips "{ ... }" with nesting; the opening brace is the next token.
bool SkipBlock(TextScanner& s) {
    ScanToken t;
    if (!s.Next(t) || t.text != "{") {
        if (t.text.empty())
            s.ErrorAtEnd("unexpected end of file, expected '{'");
        else
            s.Error(t, "expected '{' after 'appearance'");
        return false;
    }
    int depth = 1;
    while (depth > 0) {
        if (!s.Next(t)) {
            s.ErrorAtEnd("unexpected end of file inside an appearance block");
            return false;
        }
        if (t.text == "{") ++depth;
        if (t.text == "}") --depth;
    }
    return true;
}

bool SkipNumbers(TextScanner& s, int count, std::string_view what) {
    for (int i = 0; i < count; ++i)
        if (!s.NextNumber(what)) return false;
    return true;
}

}  // namespace

std::vector<freeform::Surface> ReadGeomview(TextScanner& s, const std::string& baseName) {
    std::vector<freeform::Surface> out;
    std::optional<Header> header;
    ScanToken t;
    while (s.Peek(t)) {
        if (t.text == "appearance") {
            s.Next(t);
            if (!SkipBlock(s)) return out;
            continue;
        }
        if (t.text == "{" || t.text == "}" || t.text == "=") {
            s.Next(t);  // object braces around the data carry no geometry
            continue;
        }
        if (!LooksNumeric(t.text)) {
            s.Next(t);
            std::optional<Header> h = ParseHeader(t.text);
            if (!h) {
                s.Error(t,
                        "expected a Geomview patch header ([ST]BBP or [C]BEZ<u><v><3|4>[_ST]) "
                        "or patch data, found '" +
                            std::string(t.text) + "'");
                return out;
            }
            header = h;
            continue;
        }
        if (!header) {
            s.Error(t, "patch data before the BBP/BEZ header");
            return out;
        }
        int count = (header->degreeU + 1) * (header->degreeV + 1);
        std::vector<double> c;
        for (int k = 0; k < count; ++k) {
            double p[4] = {0, 0, 0, 1};
            for (int d = 0; d < header->coords; ++d) {
                std::optional<double> x = s.NextNumber("a control point coordinate");
                if (!x) return out;
                p[d] = *x;
            }
            // Homogeneous points are stored as they are: (x, y, z, w) already means (x/w, y/w,
            // z/w), and w = 0 (a point at infinity) is legal.
            if (header->coords == 4)
                c.insert(c.end(), {p[0], p[1], p[2], p[3]});
            else
                c.insert(c.end(), {p[0], p[1], p[2]});
        }
        ScanToken first = s.Last();
        if (header->st && !SkipNumbers(s, 8, "a texture coordinate")) return out;
        if (header->colors && !SkipNumbers(s, 16, "a colour component")) return out;
        freeform::BezierSurface patch(header->coords == 4 ? 4 : 3, header->degreeU, header->degreeV,
                                      std::move(c));
        if (header->coords == 4) {
            bool allZero = true;
            for (std::size_t k = 3; k < patch.Coefficients().size(); k += 4)
                allZero = allZero && patch.Coefficients()[k] == 0;
            if (allZero) {
                s.Error(first, "every weight of this homogeneous patch is zero");
                return out;
            }
        }
        out.push_back(freeform::Surface::FromBezier(patch, SurfaceName(baseName, out.size())));
    }
    if (!header) s.ErrorAtEnd("no BBP/BEZ header found");
    return out;
}

}  // namespace quadrix::import::detail
