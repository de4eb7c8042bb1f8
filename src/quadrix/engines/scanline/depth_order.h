// Depth order of show-faces, seed 001 §5.5.1 ("Depth comparisons"): which of two faces is in
// front at a point of the current scan line, with the seed's tie-breaks for faces that meet
// there. Used by the face stacks (face_stack.h: insertion at a crossing) and by the span stacks of
// the bodies evaluated exactly (span_shader.h).
#pragma once

#include "quadrix/flatten/flat_scene.h"

namespace quadrix::scanline {

// Depth ordering of two show-faces at (x, y) with the tie-breaks of §5.5.1: depth at (x, y);
// equal within `tolerance` → depth at (x + 1, y) ("Q on the next scan line" turned to the span
// direction); equal again → slope dz/dx; equal → rate d²z/dx² (smaller is in front). Faces are
// (half-space, sheet) with sheet 0 = front root, 1 = back root (planes: 0). Returns −1 when F is
// in front, +1 when G is, 0 when they are indistinguishable (coincident).
struct FaceRef {
    int halfSpace = -1;
    int sheet = 0;
};
int CompareFaces(const FlatScene& scene, const FaceRef& f, const FaceRef& g, double x, double y,
                 double tolerance);
// z, dz/dx and d²z/dx² of a face at (x, y) by implicit differentiation of F(x, y, z) = 0:
//   z' = −F_x/F_z,  z'' = −(F_xx + 2 F_xz z' + F_zz z'²)/F_z
// (the seed's (5.2) lost the last two terms to the OCR; this is the full chain rule).
// False when the face has no point there.
bool FaceDerivatives(const FlatScene& scene, const FaceRef& f, double x, double y, double& z,
                     double& dz, double& d2z);

}  // namespace quadrix::scanline
