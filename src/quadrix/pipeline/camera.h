// Camera options as OpenSCAD users know them (issue 17, deliverable 6), for every input format:
//   --camera eye_x,eye_y,eye_z,center_x,center_y,center_z   a look-at camera
//   --projection ortho|persp                                 (perspective by default, as OpenSCAD)
//   --fov degrees                                            vertical field of view (22.5)
//   --viewall                                                fit the window to the scene
//   --autocenter                                             centre the scene in the picture
// turned into a scene::View (ViewRequest::view) that the Flattener takes like a `view` statement.
//
// Coordinates. The camera is given in the MODEL's coordinates: Quadrix space for UniQuadrix
// scenes (y up), the Z-up model space of BRL-CAD and OpenSCAD files when the render imports one
// (mapped by QuadrixFromZUp, (x, y, z) → (x, z, y), as rt's views are, FORMAT.md §9.4). Screen up
// is the model's up axis (y, resp. z), or, when the camera looks along it, the depth axis.
//
// The view. vrp = center and vpn = center − eye (the direction into the scene). Perspective puts
// the centre of projection at the eye (cop, absolute); orthographic looks along vpn (dop =
// −vpn). The window's half-height on the view plane through the centre is
//     whh = |center − eye| · tan(fov / 2),
// the image's aspect giving its width (docs/language.md §3.8), so a perspective camera sees the
// centre's plane as OpenSCAD does and an orthographic one keeps the same scale there. --viewall
// leaves the window out: the Flattener's auto-fit then fills the image with the bounded solids,
// centred on their extent (flatten/window_fit.h). --autocenter keeps the camera's direction and
// scale and moves eye and centre together, across the view direction, onto the middle of the
// solids' extent (CentreOnScene: the middle is found by one flatten with an auto-fit window, in
// which every bounded solid is inside the image; under perspective it is the middle of their
// screen-space box, mapped back to the world).
// Without --camera, --viewall and --autocenter apply to the scene's own view; --projection and
// --fov need --camera (an error otherwise: the scene's view has no eye to project from).
#pragma once

#include <optional>
#include <string>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/vec.h"
#include "quadrix/scene/scene.h"

namespace quadrix {

struct CameraRequest {
    std::optional<Vec3> eye, center;  // model coordinates
    bool orthographic = false;
    std::optional<double> fovDegrees;  // default 22.5
    bool viewAll = false, autoCenter = false;
    bool zUp = false;  // the model is Z-up (an imported BRL-CAD or OpenSCAD file)

    bool Any() const { return eye || orthographic || fovDegrees || viewAll || autoCenter; }
};

// Parses "x,y,z,x,y,z" into eye and center; an error message or empty.
std::string ParseCamera(const std::string& text, CameraRequest& request);
// Parses "ortho" / "persp" (also "orthogonal", "perspective"); an error message or empty.
std::string ParseProjection(const std::string& text, CameraRequest& request);

// The view of a camera request: from the camera when one is given, else `sceneView` (the scene's
// own) with --viewall applied. nullopt with an error message in `error`.
std::optional<scene::View> CameraView(const CameraRequest& request, const scene::View& sceneView,
                                      std::string& error);

// --autocenter: `view` moved (vrp, and cop under perspective) across its direction onto the middle
// of `fitted`'s solid extent (`fitted`: the flat scene of the same view with an auto-fit window).
// Unchanged when the scene has no bounded solid.
scene::View CentreOnScene(const scene::View& view, const FlatScene& fitted);

}  // namespace quadrix
