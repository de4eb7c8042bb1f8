// The background statement (extension, docs/language.md §3.8):
//   background color [color] ;      color = r g b (linear, each in [0, 1]) | a CSS/SVG name
// One color fills the background; two make a vertical gradient from the first (top row) to the
// second (bottom row), blended linearly in linear light. A later statement replaces an earlier one.
#include <fmt/format.h>

#include "quadrix/lang/parser.h"
#include "quadrix/lang/statements.h"

namespace quadrix::lang {

bool ParseBackground(Parser& p, const Token& keyword) {
    auto top = p.ParseColor(keyword);
    if (!top) return false;
    std::optional<scene::Color> bottom;
    if (p.PeekIs(TokenKind::kNumber) || p.PeekIs(TokenKind::kId)) {
        bottom = p.ParseColor(keyword);
        if (!bottom) return false;
    }
    if (!p.ExpectSemicolon("the background color")) return false;
    scene::Scene& scene = p.State().scene;
    if (scene.background) p.Warning(keyword.loc, "background given again; the last one is used");
    scene.background = top;
    scene.backgroundBottom = bottom;
    return true;
}

}  // namespace quadrix::lang
