// An affine frame in which a shape builder writes its quadrics and planes in their textbook form,
// and the map that carries them into the shape's own coordinates (shape.h).
//
// Maths. The frame is P = O + u1 e1 + u2 e2 + u3 e3, e1, e2, e3 any independent vectors (not
// necessarily orthogonal or of unit length). With W = [e1 e2 e3 O; 0 0 0 1] (the point map from
// local to shape coordinates, columns e1, e2, e3, O) and L = W⁻¹ (localFromShape), a point P has
// local coordinates u = L P. A local quadric uᵀ Q_loc u <= 0 (u = (u1 u2 u3 1)ᵀ, the symmetric
// matrix of DESIGN.md "Coefficients") is then the quadric Q = Lᵀ Q_loc L of shape space, and a
// local plane p_loc·u <= 0 the plane p = Lᵀ p_loc: DESIGN.md's rules Q' = M⁻ᵀ Q M⁻¹, p' = M⁻ᵀ p
// with M = W. So the unit ball diag(1, 1, 1, −1) in the frame (V; A, B, C) is the ellipsoid of
// semi-axes A, B, C, the unit circular cylinder u1² + u2² <= 1 in the frame (V; A, B, H) the
// elliptic cylinder along H, and so on (ellipsoid.h, truncated_cone.h; BRL-CAD's rpc, rhc, epa,
// ehy and hyp in brlcad/primitives.cpp).
//
// A frame whose vectors are dependent (or whose inverse is not finite) is not ok(); its shapes are
// then meaningless and the builders refuse them.
#pragma once

#include "quadrix/import/shapes/shape.h"
#include "quadrix/math/mat4.h"
#include "quadrix/math/vec.h"

namespace quadrix::import {

class LocalFrame {
  public:
    LocalFrame(const Vec3& o, const Vec3& e1, const Vec3& e2, const Vec3& e3);
    bool ok() const { return ok_; }

    // The local quadric matrix q (symmetric 4×4, uᵀ q u <= 0 inside) in shape space: Lᵀ q L.
    ShapeHalfSpace Quad(const Mat4& q, bool transparent = false) const;
    // The local plane a u1 + b u2 + c u3 + d <= 0 in shape space: Lᵀ (a b c d)ᵀ.
    ShapeHalfSpace Plane4(double a, double b, double c, double d, bool transparent = false) const;

  private:
    Mat4 local_ = Mat4::Identity();  // L = localFromShape
    bool ok_ = false;
};

// diag(a, b, c, d): the local quadric a u1² + b u2² + c u3² + d <= 0.
Mat4 DiagonalQuadric(double a, double b, double c, double d);

// A unit vector perpendicular to the unit vector h (for frames that only fix one axis: a torus's
// ring, a cone about a segment). The choice is fixed (it depends on h alone), so that a shape is
// always built with the same frame.
Vec3 AnyPerpendicular(const Vec3& h);

}  // namespace quadrix::import
