// The isocurves of one surface in one direction, as Bézier segments (seed 002 §2).
//
// Notation of the isocurve engine: an isocurve keeps one parameter constant (the "fixed"
// parameter, a dyadic value of its domain) and runs along the other (the "running" parameter t).
// IsoFamily always works on iso-v curves, C(t) = S(t, v): for curves of constant u it holds the
// transposed surface, so that Algorithm 1 ("iso-v curves are assumed") is written once.
//
// An isocurve of a B-spline surface is a B-spline curve with the u knots of the surface. The
// surface is split once at its u knots into strips that are single Bézier spans in u (Bézier
// extraction), so an isocurve comes out directly as one Bézier segment per u span: for strip k,
// de Boor in v on its rows gives the segment's control points. Segments of the normal field
// N = Su × Sv (w³ Su × Sv for rational surfaces, bezier_surface.h) come from its patches alike.
#pragma once

#include <map>
#include <vector>

#include "quadrix/freeform/bspline.h"
#include "quadrix/freeform/surface.h"

namespace quadrix::isocurve {

// Which parameter of the surface an isocurve keeps constant.
enum class Constant { kV, kU };

class IsoFamily {
  public:
    IsoFamily(const freeform::Surface& surface, Constant constant);

    Constant Which() const { return constant_; }
    // The surface with the fixed parameter in the v role (the transpose for Constant::kU).
    const freeform::Surface& Oriented() const { return oriented_; }
    bool Rational() const { return oriented_.Rational(); }
    double Run0() const { return breaks_.front(); }
    double Run1() const { return breaks_.back(); }
    double Fixed0() const { return oriented_.V0(); }
    double Fixed1() const { return oriented_.V1(); }
    // Breakpoints of the running parameter (the distinct u knots of the oriented surface).
    const std::vector<double>& Breaks() const { return breaks_; }

    // The isocurve at `fixed`, one Bézier segment per running span (homogeneous when rational).
    // Cached: the adaptive algorithm asks for each curve several times.
    const std::vector<freeform::BezierCurve>& Curve(double fixed);
    // The pieces of that curve on [a, b]: one per span that [a, b] overlaps, restricted to it.
    std::vector<freeform::BezierCurve> Pieces(double fixed, double a, double b);
    // The normal field along the isocurve on [a, b] (dimension 3, world frame of the surface).
    std::vector<freeform::BezierCurve> NormalPieces(double fixed, double a, double b) const;

    // Point and unit normal of the oriented surface (for degenerate normals, Surface::UnitNormal).
    Vec3 Point(double t, double fixed) const { return oriented_.Point(t, fixed); }

    // Drops cached curves (the cache grows with the number of distinct fixed values).
    void ClearCache() { cache_.clear(); }

  private:
    Constant constant_;
    freeform::Surface oriented_;
    std::vector<double> breaks_;
    std::vector<freeform::BSplineCurve> stripRows_;  // per running span: rows as a curve in v
    std::map<double, std::vector<freeform::BezierCurve>> cache_;
};

// Restricts consecutive segments (covering [breaks]) to [a, b].
std::vector<freeform::BezierCurve> RestrictSegments(const std::vector<freeform::BezierCurve>& segs,
                                                    double a, double b);

// Arc length of a (possibly homogeneous) Bézier segment, by composite Gauss–Legendre quadrature
// (accurate to ~1e-8 relative for the smooth, low-degree segments of isocurves).
double ArcLength(const freeform::BezierCurve& segment);

}  // namespace quadrix::isocurve
