// Appearance options of the language (the color and materials extensions, docs/language.md
// §3.6): `=c name` with a CSS/SVG color name, `=finish kd ks shininess` and `=alpha a`. The
// numeric `=c r g b` is Parser::ParseColor in parser.cpp; every statement that takes a color
// takes these options through Parser::ParseAppearance.
#include <fmt/format.h>

#include <cmath>

#include "quadrix/lang/parser.h"
#include "quadrix/scene/css_colors.h"

namespace quadrix::lang {

std::optional<scene::Color> Parser::ParseColorName(const Token& option) {
    Token name = Take();
    auto c = scene::CssColor(name.text);
    if (!c) {
        Error(name.loc,
              fmt::format("unknown color name '{}' after {} (a CSS/SVG color name such as "
                          "steelblue, or three numbers r g b)",
                          name.text, Describe(option)));
        return scene::Color{};  // reported; the statement goes on
    }
    return c;
}

namespace {

// A number in [lo, hi] (hi may be infinite); out-of-range values are reported and clamped.
std::optional<double> Bounded(Parser& p, std::string_view what, double lo, double hi,
                              bool openLow = false) {
    SourceLoc at = p.Peek().loc;
    auto v = p.ExpectNumber(what);
    if (!v) return std::nullopt;
    if (*v < lo || *v > hi || (openLow && *v == lo)) {
        p.Error(at, fmt::format("{} is {}; it must be {} {} and at most {}", what, *v,
                                openLow ? "greater than" : "at least", lo, hi));
        *v = std::clamp(*v, lo, hi);
        if (openLow && *v == lo) *v = 1;
    }
    return v;
}

}  // namespace

bool Parser::ParseAppearance(const Token& option, std::optional<scene::Color>& color,
                             scene::Finish& finish) {
    if (option.text == "c") {
        if (color) Warning(option.loc, "color given twice; the last one is used");
        auto c = ParseColor(option);
        if (!c) return false;
        color = c;
        return true;
    }
    if (option.text == "finish") {
        if (finish.diffuse) Warning(option.loc, "=finish given twice; the last one is used");
        constexpr double kInf = HUGE_VAL;
        auto kd = Bounded(*this, "the diffuse coefficient kd of =finish", 0, kInf);
        if (!kd) return false;
        auto ks = Bounded(*this, "the specular coefficient ks of =finish", 0, kInf);
        if (!ks) return false;
        auto n = Bounded(*this, "the shininess (specular exponent) of =finish", 0, 1e6, true);
        if (!n) return false;
        finish.diffuse = kd;
        finish.specular = ks;
        finish.shininess = n;
        return true;
    }
    if (option.text == "alpha") {
        if (finish.opacity) Warning(option.loc, "=alpha given twice; the last one is used");
        auto a = Bounded(*this, "the opacity of =alpha", 0, 1);
        if (!a) return false;
        finish.opacity = a;
        return true;
    }
    return Expected("=c, =finish or =alpha");
}

}  // namespace quadrix::lang
