// One bounding surface of a half-space: a plane <A B C D> or a quadric <A … K> (quadric.h), the
// inside being where the function is <= 0 (seed 001 §2.1.1). The one value type shared by the
// flat scene (FlatHalfSpace), the modeling front end (model::SolidSurface), the BRL-CAD/OpenSCAD
// primitives (import::brlcad::ShapeHalfSpace) and the scanline Resolver's oriented literals;
// each adds its own attributes by deriving from it.
#pragma once

#include "quadrix/math/mat4.h"
#include "quadrix/math/quadric.h"
#include "quadrix/math/vec.h"

namespace quadrix {

struct PlaneOrQuadric {
    bool isPlane = true;
    Plane plane;      // when isPlane
    Quadric quadric;  // when !isPlane

    double Evaluate(const Vec3& p) const {
        return isPlane ? plane.Evaluate(p) : quadric.Evaluate(p);
    }
    // Homogeneous gradient (covector) at a point; its xyz is the normal direction.
    Vec4 HomogeneousGradient(const Vec3& p) const {
        return isPlane ? plane.AsVec4() : quadric.HomogeneousGradient(p);
    }
    // The same surface after the point map t (p' = M⁻ᵀp, Q' = M⁻ᵀQM⁻¹, with t's stored inverse).
    void TransformBy(const Transform& t) {
        if (isPlane)
            plane = plane.Transformed(t);
        else
            quadric = quadric.Transformed(t);
    }
};

}  // namespace quadrix
