// The viewer's camera (issue 18): CAD-style navigation whose state is always a real UniQuadrix
// view (seed 001 §2.1.6, docs/language.md §3.8), so that what the window shows can be printed as
// a `view` statement and `quadrix render` reproduces it exactly.
//
// State, in WORLD space:
//   target      the point orbited about and the view reference point (vrp): the window's centre;
//   toward      unit direction from the target toward the viewer (dop of a parallel view; the
//               eye of a perspective view sits at target + distance·toward);
//   up          unit, perpendicular to toward: what appears up on the screen (vup);
//   halfHeight  the window half-height (whh) on the view plane through the target; the width
//               follows from the image's aspect, so resizing keeps the vertical extent;
//   perspective and distance (eye to target).
// The view frame is that of view_setup.h: vpn = -toward (into the scene), screen right
// r = normalize(up × vpn), screen up = up. A pixel of an H-pixel-high image spans
// s = 2·halfHeight/H world units on the view plane.
//
// Navigation (all in pixels of the current window, W×H):
//   Orbit(dx, dy)   a turntable: toward and up turn (right-hand rule) by π·dx/H about worldUp
//                   (the scene's up; its opposite when the camera is upside down) and then by
//                   π·dy/H about the screen's right axis. With the default frame (toward -z,
//                   up +y, right +x) a turn by φ about +y takes right to (cos φ, 0, -sin φ), so
//                   the near point target + toward lands at sin φ > 0 on the screen's x: dragging
//                   right carries the near side of the model to the right; likewise dragging down
//                   carries it down. A drag over the window's height is half a turn. The target
//                   (the orbit centre) stays.
//   Pan(dx, dy)     the target moves by -dx·s·r + dy·s·up: the model follows the cursor.
//   Zoom(c, x, y)   halfHeight (and the perspective distance) scale by f = 0.8^c (c > 0 zooms
//                   in); the target moves toward the view-plane point under the cursor,
//                   o = (x - W/2)·s·r + (H/2 - y)·s·up, by (1 - f)·o. That point then lies under
//                   the cursor again: its window position (o - (1 - f) o) / (f s) = o / s.
//   Axis views, isometric, reset and fit-all set toward/up (and target/halfHeight for fit).
#pragma once

#include <optional>
#include <string>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/vec.h"
#include "quadrix/scene/scene.h"

namespace quadrix::viewer {

// A sphere containing the bounded part of the scene (world space): the orbit centre and the
// fit-all extent.
struct SceneSphere {
    Vec3 centre;
    double radius = 1;
};

enum class StandardView { kFront, kBack, kLeft, kRight, kTop, kBottom, kIso };

struct Camera {
    Vec3 target;
    Vec3 toward{0, 0, -1};
    Vec3 up{0, 1, 0};
    Vec3 worldUp{0, 1, 0};
    double halfHeight = 1;
    bool perspective = false;
    double distance = 1;
    // The point orbited about when set (a double-click's pick), instead of the target: the
    // whole camera turns rigidly about it, so it stays where it is on the screen. Views that
    // re-centre (standard views, fit-all) clear it.
    std::optional<Vec3> pivot;

    // The half-distance ratio used when perspective is switched on: the eye sits at
    // kEyeRatio·halfHeight from the target, a vertical field of view of 2·atan(1/kEyeRatio) ≈ 40°.
    static constexpr double kEyeRatio = 2.75;

    Vec3 Right() const { return Normalize(Cross(up, -toward)); }
    Vec3 Eye() const { return target + toward * distance; }

    void Orbit(double dx, double dy, int height);
    void Pan(double dx, double dy, int height);
    void Zoom(double clicks, double x, double y, int width, int height);
    // Looks at `sphere.centre` from a standard direction, keeping the window size.
    void SetStandardView(StandardView view, const SceneSphere& sphere);
    // Centres on the sphere and sizes the window so that it fits a width×height image with a 5%
    // margin, keeping the direction.
    void FitAll(const SceneSphere& sphere, int width, int height);
    // Switching perspective on puts the eye at max(kEyeRatio·halfHeight, minDistance) from the
    // target (the viewer passes three scene radii, so that the model's near side is not blown
    // up when the window is small next to it).
    void SetPerspective(bool on, double minDistance = 0);
    // Parallel views: slides the target along the view direction to the plane through `p` (the
    // scene's centre), which changes nothing in the picture but makes `p`'s depth the orbit
    // centre's and the perspective eye's reference. Perspective views are left as they are.
    void MoveTargetToDepthOf(const Vec3& p);

    // The scene::View of this camera (id "camera"): vrp, vpn, vup, whh and dop or cop.
    scene::View ToView() const;
};

// The camera as a `view` statement (17 significant digits, so the reader gets the same doubles
// back), preceded by a comment naming the image size it was shown at and `renderOptions` (more
// options of the `quadrix render` that reproduces it, e.g. ` --section "A B C D"`).
std::string FormatViewStatement(const Camera& camera, int width, int height,
                                const std::string& id = "camera",
                                const std::string& renderOptions = {});

// The camera showing (as nearly as a centred window can) what `view` shows on a width×height
// image, from the flattened scene of that view (its projection gives the scale). Parallel views
// are reproduced exactly apart from an oblique dop (replaced by -vpn); a perspective view keeps
// its eye, vrp and scale at the view plane. nullopt when the view does not resolve.
std::optional<Camera> CameraFromView(const scene::View& view, const FlatScene& flat);

// The bounded part of a flattened scene as a world-space sphere (the device-space boxes of the
// bounded solids mapped back through the projection). nullopt when nothing is bounded.
std::optional<SceneSphere> BoundingSphere(const FlatScene& flat);

}  // namespace quadrix::viewer
