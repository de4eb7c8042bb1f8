// What the hidden-line drawer cannot draw (docs/drawings.md, "What is not drawn"), checked before
// drawing so that a drawing is never silently incomplete:
//   - quartic half-spaces (torus, elliptical torus, general cone): an error at the statement
//     that defined the first one (file:line:column), naming it and its kind;
//   - freeform surfaces (Bézier/NURBS): an error naming the first surface and where it was
//     defined (file:line:column);
// unless `allowMissing` (--allow-missing, as `quadrix render` and `quadrix export` take it for
// imported primitives): then a warning for each kind with the count, and the drawing shows the
// other solids only (DrawableSubset). What is left out hides nothing in the drawing.
// Every front end that writes a drawing calls it through pipeline/drawing_output.h, on the flat
// scene of the (first) view: `quadrix draw` (--allow-missing), uq's `device svg:FILE`, `pdf:`,
// `eps:` (quadrix uq --allow-missing) and the viewer's D key (quadrix view --allow-missing; the
// message also appears in the window's overlay).
#pragma once

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/scene/diagnostics.h"

namespace quadrix::draw {

// false when the scene holds something the drawer would leave out and !allowMissing (errors in
// diags); true otherwise, with warnings in diags for what is left out under allowMissing.
// `source`, the scene that was flattened, gives the position of a quartic half-space's statement
// (a flat half-space's name ends in its id in the scope that defined it).
bool CheckDrawable(const FlatScene& scene, bool allowMissing, Diagnostics& diags,
                   const scene::Scene* source = nullptr);

// The scene the drawer draws: without freeform surfaces and without the solids that use a
// quartic half-space (their bodies keep no literals; every quartic half-space becomes a
// transparent plane that holds nowhere, so indices are unchanged). A copy of the scene (cheap
// beside drawing it).
FlatScene DrawableSubset(const FlatScene& scene);

}  // namespace quadrix::draw
