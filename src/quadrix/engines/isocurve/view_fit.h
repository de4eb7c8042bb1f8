// Projections that frame a bounding box in an image, for the isocurve tests and benchmarks (until
// scene files carry freeform surfaces through the Flattener, which then supplies the projection).
// Conventions of DESIGN.md: device x = column, y = row (down), z grows away from the viewer;
// screen right = normalize(up × vpn), screen up = vpn × right, vpn = −towardViewer.
#pragma once

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/vec.h"

namespace quadrix::isocurve {

// Parallel projection along −towardViewer that fits `bounds` into width × height with a margin
// (fraction of the smaller side on each border).
Projection FitParallel(const Box3& bounds, const Vec3& towardViewer, const Vec3& up, int width,
                       int height, double margin = 0.05);

// Perspective from an eye placed `distance` box diagonals from the box centre along
// towardViewer, fitting the box's bounding sphere.
Projection FitPerspective(const Box3& bounds, const Vec3& towardViewer, const Vec3& up, int width,
                          int height, double distance = 2.5);

}  // namespace quadrix::isocurve
