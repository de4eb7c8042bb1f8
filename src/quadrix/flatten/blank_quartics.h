// Quartic half-spaces blanked out of a flat scene, for the stages that cannot handle them (an
// engine without the `quartics` capability, hidden-line drawings): each one becomes a
// transparent plane that holds nowhere, so indices (and Frame ids) keep their meaning. Callers
// first drop the solids and bodies that name a quartic; nothing may name a blanked half-space.
#pragma once

#include "quadrix/flatten/flat_scene.h"

namespace quadrix {

inline void BlankQuarticHalfSpaces(FlatScene& flat) {
    for (FlatHalfSpace& h : flat.halfSpaces) {
        if (!h.IsQuartic()) continue;
        h.quartic.reset();
        h.isPlane = true;
        h.plane = Plane{0, 0, 0, 1};
        h.transparent = true;
    }
}

}  // namespace quadrix
