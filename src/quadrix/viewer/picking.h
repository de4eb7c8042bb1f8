// Picking (issue 18 §5): what a pixel of the viewer's picture shows, from the Frame that was drawn
// (its solid, body and surface ids, depth and world normal, frame/frame.h) and the flattened scene
// it was drawn from (names and the projection).
//
// The world point is the device point (x + ½, y + ½, depth) mapped back through the projection:
// p_world = worldFromDevice (x+½, y+½, z, 1), divided by w (perspective is a projective map,
// view_setup.h). The source position is that of the scene body whose id is the last component of
// the flattened body's path ("part/holes[2]/bore" → bore), looked up in the top scope, then in the
// definitions: a body path says which definition a copy came from, not which copy. A freeform
// surface (no body) gives its own statement's position, which the flat scene keeps.
#pragma once

#include <string>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"
#include "quadrix/math/vec.h"
#include "quadrix/scene/scene.h"

namespace quadrix::viewer {

struct PickResult {
    bool hit = false;
    int x = 0, y = 0;  // pixel of the frame
    int solid = Frame::kNone, body = Frame::kNone, surface = Frame::kNone;
    std::string solidName, bodyName, surfaceName;
    std::string where;  // file:line:column of the body's statement, or empty
    bool freeform = false;
    double depth = 0;
    Vec3 point, normal;  // world space
};

// The pixel (x, y) of `frame`, drawn from `flat`; `scene` (may be null) gives source positions.
// Out-of-frame pixels are misses.
PickResult Pick(const Frame& frame, const FlatScene& flat, const scene::Scene* scene, int x, int y);

// One line: "pick 120 80: solid part body part/bore half-space bore (file:3:1) point ... normal
// ...", or "pick 120 80: background".
std::string FormatPick(const PickResult& pick);
// The same for the window's overlay, a line per item: what was hit (solid, body, half-space, or
// the freeform surface), "at file:line:col", the point and the normal.
std::vector<std::string> PickOverlayLines(const PickResult& pick);

}  // namespace quadrix::viewer
