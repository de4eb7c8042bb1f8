#include "quadrix/draw/undrawable.h"

#include <fmt/format.h>

namespace quadrix::draw {

bool CheckDrawable(const FlatScene& scene, bool allowMissing, Diagnostics& diags) {
    for (const FlatHalfSpace& h : scene.halfSpaces)
        if (h.IsQuartic()) {
            diags.Error({},
                        fmt::format("half-space '{}' is a {} (a quartic surface); drawings handle "
                                    "planes and quadrics only (render it with quadrix render)",
                                    h.name, h.quartic->KindName()),
                        {}, "draw");
            return false;
        }
    const std::size_t n = scene.freeforms.size();
    if (n == 0) return true;
    const FlatFreeform& first = scene.freeforms.front();
    const std::string others =
        n > 1 ? fmt::format(" (and {} more freeform surface{})", n - 1, n > 2 ? "s" : "") : "";
    if (!allowMissing) {
        diags.Error(first.loc,
                    fmt::format("freeform surface '{}'{} cannot be drawn: hidden-line drawings "
                                "handle planes and quadrics only (--allow-missing draws the "
                                "drawing without them)",
                                first.name, others),
                    {}, "draw");
        return false;
    }
    diags.Warning(first.loc,
                  fmt::format("freeform surface '{}'{} left out of the drawing (--allow-missing)",
                              first.name, others),
                  {}, "draw");
    return true;
}

}  // namespace quadrix::draw
