// One bounding surface of a half-space: a plane <A B C D>, a quadric <A … K> (quadric.h) or a
// quartic (quartic_surface.h: torus, elliptical torus, general cone), the inside being where the
// function is <= 0 (seed 001 §2.1.1). The one value type shared by the flat scene
// (FlatHalfSpace), the modeling front end (model::SolidSurface), the BRL-CAD/OpenSCAD primitives
// (import::ShapeHalfSpace) and the scanline Resolver's oriented literals; each adds its own
// attributes by deriving from it.
//
// Quartics. `quartic` is set (and isPlane false) for a quartic surface; `quadric` is then unused
// (zero). Code that tests `isPlane ? plane : quadric` must test IsQuartic() first: only the
// raycast engine, the shading, the bounds and the exporters handle quartics; the render context
// routes every solid with a quartic literal to raycast for the other engines, which never see a
// quartic half-space (pipeline/render_context.cpp). The surface is shared (immutable, copied on
// TransformBy), so a FlatHalfSpace stays small.
#pragma once

#include <memory>

#include "quadrix/math/mat4.h"
#include "quadrix/math/quadric.h"
#include "quadrix/math/quartic_surface.h"
#include "quadrix/math/vec.h"

namespace quadrix {

struct PlaneOrQuadric {
    bool isPlane = true;
    Plane plane;                                    // when isPlane
    Quadric quadric;                                // when !isPlane && !quartic
    std::shared_ptr<const QuarticSurface> quartic;  // when set (then !isPlane)

    bool IsQuartic() const { return quartic != nullptr; }
    bool IsQuadric() const { return !isPlane && quartic == nullptr; }
    void SetQuartic(const QuarticSurface& q) {
        isPlane = false;
        quadric = Quadric{};
        quartic = std::make_shared<const QuarticSurface>(q);
    }

    double Evaluate(const Vec3& p) const {
        if (quartic) return quartic->Evaluate(p);
        return isPlane ? plane.Evaluate(p) : quadric.Evaluate(p);
    }
    // Homogeneous gradient (covector) at a point; its xyz is the normal direction.
    Vec4 HomogeneousGradient(const Vec3& p) const {
        if (quartic) return quartic->HomogeneousGradient(p);
        return isPlane ? plane.AsVec4() : quadric.HomogeneousGradient(p);
    }
    // The same surface after the point map t (p' = M⁻ᵀp, Q' = M⁻ᵀQM⁻¹, with t's stored inverse).
    void TransformBy(const Transform& t) {
        if (quartic) {
            QuarticSurface q = *quartic;
            q.TransformBy(t);
            quartic = std::make_shared<const QuarticSurface>(q);
        } else if (isPlane) {
            plane = plane.Transformed(t);
        } else {
            quadric = quadric.Transformed(t);
        }
    }
};

}  // namespace quadrix
