// A freeform surface of a model: a B-spline surface, polynomial (control points in R³) or rational
// (homogeneous control points (w x, w y, w z, w)), with a name for diagnostics and statistics.
// Bézier patches are B-spline surfaces with one span in each direction.
//
// Everything the isocurve engine needs from a surface is here: Euclidean evaluation, the direction
// of the normal Su × Sv, the Bézier patches of the surface and of its normal field, conservative
// bounds, and the exact image under a (possibly projective) 4×4 map.
#pragma once

#include <optional>
#include <string>

#include "quadrix/freeform/bspline.h"
#include "quadrix/math/mat4.h"
#include "quadrix/math/vec.h"

namespace quadrix::freeform {

class Surface {
  public:
    Surface() = default;
    // `net` must have dimension 3 (polynomial) or 4 (homogeneous, rational).
    explicit Surface(BSplineSurface net, std::string name = {});
    static Surface FromBezier(const BezierSurface& patch, std::string name = {});

    bool Rational() const { return net_.Dim() == 4; }
    const BSplineSurface& Net() const { return net_; }
    const std::string& Name() const { return name_; }
    void SetName(std::string name) { name_ = std::move(name); }
    double U0() const { return net_.U0(); }
    double U1() const { return net_.U1(); }
    double V0() const { return net_.V0(); }
    double V1() const { return net_.V1(); }

    // The Bézier patches of the surface (same dimension as the net) and of its normal field
    // (bezier_surface.h NormalField, dimension 3).
    const PatchGrid& Patches() const { return patches_; }
    const PatchGrid& NormalPatches() const { return normals_; }

    // Homogeneous point (w = 1 for polynomial surfaces).
    Vec4 HomogeneousPoint(double u, double v) const;
    // Euclidean point; meaningless where the weight function vanishes.
    Vec3 Point(double u, double v) const;
    // The normal field N(u, v): Su × Sv for polynomial surfaces, w³ Su × Sv for rational ones
    // (same direction where w > 0). Zero at degenerate points (collapsed edges, cusps).
    Vec3 NormalField(double u, double v) const;
    // A unit normal, also at degenerate points where N vanishes: there the limit of N from the
    // inside of the domain is taken (N at parameters moved inward by growing steps), which is the
    // surface normal at a collapsed edge such as the pole of the teapot lid. nullopt when no
    // direction can be found (a surface degenerate everywhere nearby).
    std::optional<Vec3> UnitNormal(double u, double v) const;

    // Swaps u and v (the normal field changes sign).
    Surface Transposed() const;
    // Image under x' = M x. Affine maps keep a polynomial surface polynomial; projective ones make
    // it rational. Exact in both cases (homogeneous control points map linearly).
    Surface Transformed(const Mat4& m) const;

    // Conservative Euclidean bounds: the hull of the control points of each patch, after
    // subdividing rational patches until all their weights are positive (weights of zero or of
    // both signs put control points at infinity, Geomview's exact torus does that). Infinite
    // when a patch still has non-positive weights after 6 levels of subdivision.
    Box3 Bounds() const;

    // Smallest weight over the control points of the patches (1 for polynomial surfaces).
    double MinWeight() const;
    // True when the weight function is proven positive on the whole domain (always for
    // polynomial surfaces): the weights of every patch become positive after at most 6 levels of
    // subdivision. False for surfaces that reach infinity (or come too close to it to tell).
    bool WeightPositive() const { return weightPositive_; }

  private:
    BSplineSurface net_;
    PatchGrid patches_;
    PatchGrid normals_;
    double normalScale_ = 0;  // largest |coefficient| of the normal field
    bool weightPositive_ = true;
    std::string name_;
};

}  // namespace quadrix::freeform
