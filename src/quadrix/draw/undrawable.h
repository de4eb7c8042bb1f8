// What the hidden-line drawer cannot draw (docs/drawings.md, "What is not drawn"), checked before
// drawing so that a drawing is never silently incomplete:
//   - quartic half-spaces (torus, elliptical torus, general truncated cone): always an error;
//   - freeform surfaces (Bézier/NURBS): an error naming the first surface and where it was
//     defined (file:line:column), unless `allowMissing` (--allow-missing, as `quadrix render`
//     and `quadrix export` take it for imported primitives): then a warning with the count, and
//     the drawing shows the quadric solids only.
// Every front end that writes a drawing calls it through pipeline/drawing_output.h, on the flat
// scene of the (first) view: `quadrix draw` (--allow-missing), uq's `device svg:FILE`, `pdf:`,
// `eps:` (quadrix uq --allow-missing) and the viewer's D key (quadrix view --allow-missing; the
// message also appears in the window's overlay).
#pragma once

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/scene/diagnostics.h"

namespace quadrix::draw {

// false when the scene holds something the drawer would leave out (errors in diags); true
// otherwise, with a warning in diags for freeform surfaces left out under allowMissing.
bool CheckDrawable(const FlatScene& scene, bool allowMissing, Diagnostics& diags);

}  // namespace quadrix::draw
