// The section plane's text form, shared by `quadrix render --section`, `quadrix draw --section`
// and the viewer's printed view (docs/viewer.md): four numbers "A B C D" (spaces or commas
// between them), the plane A x + B y + C z + D = 0 in world coordinates, keeping the part where
// A x + B y + C z + D <= 0 (the inside of a plane statement; FlattenOptions::section).
// Written with 17 significant digits, so reading the text back gives the same doubles.
#pragma once

#include <string>
#include <string_view>

#include "quadrix/math/quadric.h"

namespace quadrix {

// Error message (for "--section: ...") or empty.
std::string ParseSectionPlane(std::string_view text, Plane& plane);
std::string FormatSectionPlane(const Plane& plane);

}  // namespace quadrix
