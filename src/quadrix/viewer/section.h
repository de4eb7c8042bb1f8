// The viewer's movable section plane (issue 18 §5): a world-space plane that cuts every solid
// (FlattenOptions::section, through the one render path: the cut faces are drawn exactly by the
// engines, as `quadrix render --section` draws them).
//
// State: `normal` (unit, world) and `offset`: the plane normal·p = offset, keeping the part
// normal·p <= offset. Switched on, it passes through the orbit centre facing the viewer
// (normal = the camera's toward): the half nearer the viewer is cut away and the cut faces look
// at the viewer. It stays put in the world while the camera orbits, so the cut can be looked at
// from any side. Move(d) slides it by d world units along its normal (d > 0: toward the viewer
// it was made for, uncovering more); Flip() keeps the other half.
#pragma once

#include <optional>

#include "quadrix/math/quadric.h"
#include "quadrix/math/vec.h"
#include "quadrix/viewer/camera.h"

namespace quadrix::viewer {

struct SectionPlane {
    bool on = false;
    Vec3 normal{0, 0, -1};
    double offset = 0;

    // On through `centre`, facing the camera's viewer; off when it was on.
    void Toggle(const Camera& camera, const Vec3& centre);
    void Move(double distance) { offset += distance; }
    void Flip() {
        normal = -normal;
        offset = -offset;
    }
    // The plane A x + B y + C z + D <= 0 to flatten with, or nullopt when off.
    std::optional<Plane> ToPlane() const;
};

}  // namespace quadrix::viewer
