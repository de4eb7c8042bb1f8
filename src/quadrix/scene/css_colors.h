// The CSS Color Module Level 4 named colors (the 148 names of SVG 1.1 and CSS, including the
// grey/gray spellings and rebeccapurple). OpenSCAD's color("name") accepts the same list, and so
// does the language's `=c name` (docs/language.md §3.6). The table is in sRGB bytes, as the
// standard gives it; lookups return linear-light colors (math/srgb.h), the space Quadrix shades in.
#pragma once

#include <optional>
#include <string_view>

#include "quadrix/scene/scene.h"

namespace quadrix::scene {

// Case-insensitive; nullopt for an unknown name.
std::optional<Color> CssColor(std::string_view name);
// The number of names in the table (for tests).
int CssColorCount();

}  // namespace quadrix::scene
