// The view transformation of the Flattener (seed 001 §2.1.6, §3.3): a scene::View with its
// defaults applied becomes a map from world space to a PROVISIONAL device space, which is device
// space before the window is fitted to the image:
//
//   x = horizontal view-plane coordinate (world units at the view plane), right,
//   y = vertical view-plane coordinate, DOWN (so the image's row order is already in place),
//   z = depth, growing away from the viewer (world units near the view plane),
//
// with vrp's projection at the origin. Rays are parallel to +z. The Flattener then appends the
// window fit, a uniform scale k (pixels per unit) and a translation in x and y, which is a
// similarity: quadrics keep their conditioning.
//
// View frame (docs/language.md, scene.h): n = unit vpn (from the viewer into the scene),
// u = normalize(vup × n) (screen right), v = n × u (screen up).
//
// Parallel projection. View coordinates relative to vrp: (u_e, v_e, n_e) = ((p - vrp)·u, ...).
// The projection direction is -dop; with r = -dop expressed in (u, v, n), r_n > 0, the oblique
// projection onto the view plane is a shear that makes the rays parallel to n:
//     x = u_e - (r_u/r_n) n_e,   y = -(v_e - (r_v/r_n) n_e),   z = n_e,
// i.e. the matrix [[1 0 -a 0] [0 -1 b 0] [0 0 1 0] [0 0 0 1]] with a = r_u/r_n, b = r_v/r_n,
// whose inverse is [[1 0 a 0] [0 -1 b 0] [0 0 1 0] [0 0 0 1]]. Without obliqueness (dop = -vpn
// direction) it is a rotation and a reflection of y: a similarity, as the device map then is.
//
// Perspective projection. Eye coordinates relative to cop: (u_e, v_e, n_e); the view plane is
// n_e = d with d = (vrp - cop)·n > 0, and vrp sits at (c_u, c_v, d). The projective map
//     X = d u_e - c_u n_e,  Y = -(d v_e - c_v n_e),  Z = d (n_e - d),  W = n_e,
// gives x = d u_e/n_e - c_u, y = -(d v_e/n_e - c_v) (the central projection onto the view plane,
// centred on vrp) and the depth z = d (1 - d/n_e): 0 on the view plane, increasing with n_e,
// dz/dn_e = 1 there (the same scale as x and y), tending to d at n_e = +∞; points behind the eye
// (n_e < 0) map beyond d. Its inverse is
//     [[1/d 0 0 c_u/d] [0 -1/d 0 c_v/d] [0 0 0 1] [0 0 -1/d² 1/d]]
// acting on (X, Y, Z, W) to give (u_e, v_e, n_e, 1) up to scale. Quadrics stay quadrics.
//
// Clipping (seed 001 §3.3: "planar HSBs that represent appropriate sides of the box"):
//   - parallel with fbp d1 d2: z >= front and z <= back (front = min, back = max);
//   - perspective: a near plane at n_e = near, near = max(d + front when that is in front of
//     the eye, 1e-4 d), and a far plane z <= d (the image of n_e = +∞): z <= d holds exactly for
//     n_e > 0, so nothing behind the eye survives; with fbp the back plane z <= d(1 - d/(d+back))
//     replaces it (it excludes n_e < 0 too).
// Objects closer to the eye than 1e-4 d are clipped away (documented limitation).
// fbp has no effect on auto-scaling (§2.1.6): the fit uses `fitClips`, which for perspective are
// the near plane at 1e-4 d and the far plane, and for parallel none.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "quadrix/math/mat4.h"
#include "quadrix/math/quadric.h"
#include "quadrix/scene/diagnostics.h"
#include "quadrix/scene/scene.h"

namespace quadrix {

struct ViewSetup {
    std::string id;
    SourceLoc loc;
    bool perspective = false;
    Transform provFromWorld;  // world → provisional device space (see above)
    Vec3 vrp, eye;            // eye = cop (perspective)
    Vec3 u, v, n;             // the view frame (unit vectors)
    Vec3 towardViewer;        // unit, world: dop (parallel), -n (perspective)
    double d = 0;             // perspective: distance from the eye to the view plane
    std::optional<double> whh, whw;
    double fitNear = -HUGE_VAL;     // perspective: the depth of the fit's near plane (1e-4 d)
    std::vector<Plane> fitClips;    // provisional space; the planes the window fit sees
    std::vector<Plane> finalClips;  // provisional space; appended to every body
};

// Applies the defaults of §2.1.6 and checks the view; nullopt with errors at the view's position
// for zero or non-finite vectors, vup parallel to vpn, dop parallel to the view plane or pointing
// away from the viewer, the eye not in front of the view plane, bad window sizes and clipping
// planes that leave nothing in front of the eye.
std::optional<ViewSetup> ResolveView(const scene::View& view, Diagnostics& diags);

}  // namespace quadrix
