// B-spline (and, through homogeneous coordinates, NURBS) curves and tensor-product surfaces.
//
// A curve of degree p with control points P_0..P_{n-1} (any dimension d) has a knot vector
// t_0 <= ... <= t_{n+p}; its domain is [t_p, t_n] (clamped or not). On the knot span
// [t_k, t_{k+1}] it is a polynomial whose Bézier points are blossom values (Ramshaw):
//
//     b_i = f(t_k, ..., t_k [p-i times], t_{k+1}, ..., t_{k+1} [i times]),
//
// computed by the de Boor triangle with one argument per level. Evaluation is de Boor, knot
// insertion is Boehm's algorithm, the derivative is the usual B-spline of degree p-1
//
//     Q_i = p (P_{i+1} - P_i) / (t_{i+p+1} - t_{i+1}),   knots t_1..t_{n+p-1},
//
// (Piegl & Tiller, The NURBS Book, eq. 3.8 / §5.2). Degree elevation and the symbolic operations go
// through Bézier extraction: the result is a piecewise Bézier curve written back as a B-spline with
// interior knots of multiplicity p (p + 1 where the pieces do not meet), which is exact but does
// not try to remove knots again.
//
// Surfaces store control point (i, j) (i along u, j along v) at index j nu + i (u fastest, as in
// OBJ). As for BezierSurface, v operations treat the rows as the points of a curve in v.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "quadrix/freeform/bezier_curve.h"
#include "quadrix/freeform/bezier_surface.h"

namespace quadrix::freeform {

// Checks a knot vector for `count` control points of degree `degree`: length, order, and a
// non-empty domain. Returns an empty string or an explanation.
std::string CheckKnots(const std::vector<double>& knots, int degree, int count);

class BSplineCurve {
  public:
    BSplineCurve() = default;
    BSplineCurve(int dim, int degree, std::vector<double> knots, std::vector<double> coefficients);
    static BSplineCurve FromBezier(const BezierCurve& c);
    // Joins consecutive Bézier segments (each segment's interval gives the knots; the segments are
    // elevated to a common degree). Interior knots get multiplicity p where consecutive segments
    // share their end point exactly, p + 1 otherwise.
    static BSplineCurve FromBezierSegments(const std::vector<BezierCurve>& segments);

    int Dim() const { return dim_; }
    int Degree() const { return degree_; }
    int Count() const { return static_cast<int>(c_.size()) / dim_; }
    const std::vector<double>& Knots() const { return knots_; }
    const std::vector<double>& Coefficients() const { return c_; }
    const double* Point(int i) const { return c_.data() + static_cast<std::size_t>(i) * dim_; }
    double T0() const { return knots_[static_cast<std::size_t>(degree_)]; }
    double T1() const { return knots_[static_cast<std::size_t>(Count())]; }

    // The span index k with t_k <= t < t_{k+1} and t_k < t_{k+1}, clamped to the domain (the
    // last non-empty span for t = T1()).
    int FindSpan(double t) const;
    void Evaluate(double t, double* out) const;
    std::vector<double> Evaluate(double t) const;
    // de Boor with argument args[r-1] at level r on span k: the blossom of that span's polynomial.
    void Blossom(int span, const double* args, double* out) const;

    BSplineCurve Derivative() const;
    BSplineCurve WithKnotInserted(double t, int times = 1) const;
    // Distinct knot values inside [T0, T1], both ends included.
    std::vector<double> Breakpoints() const;
    // One Bézier curve per non-empty knot span of the domain, in order.
    std::vector<BezierCurve> ToBezier() const;
    BSplineCurve Elevated(int times = 1) const;
    // The curve on [a, b] ⊆ [T0, T1] (as Bézier pieces joined again; clamped ends).
    BSplineCurve Restricted(double a, double b) const;

  private:
    int dim_ = 0;
    int degree_ = 0;
    std::vector<double> knots_;
    std::vector<double> c_;
};

// Symbolic operations on B-spline curves with the same domain: computed per Bézier piece on the
// union of both sets of breakpoints.
BSplineCurve Add(const BSplineCurve& a, const BSplineCurve& b);
BSplineCurve Subtract(const BSplineCurve& a, const BSplineCurve& b);
BSplineCurve Multiply(const BSplineCurve& scalar, const BSplineCurve& c);
BSplineCurve Dot(const BSplineCurve& a, const BSplineCurve& b);
BSplineCurve Cross(const BSplineCurve& a, const BSplineCurve& b);

// The polynomial pieces of a curve on a given sorted list of breakpoints inside its domain.
std::vector<BezierCurve> BezierPiecesOn(const BSplineCurve& c, const std::vector<double>& breaks);

class PatchGrid;

class BSplineSurface {
  public:
    BSplineSurface() = default;
    BSplineSurface(int dim, int degreeU, int degreeV, std::vector<double> knotsU,
                   std::vector<double> knotsV, std::vector<double> coefficients);
    static BSplineSurface FromBezier(const BezierSurface& s);

    int Dim() const { return dim_; }
    int DegreeU() const { return degreeU_; }
    int DegreeV() const { return degreeV_; }
    int CountU() const { return static_cast<int>(knotsU_.size()) - degreeU_ - 1; }
    int CountV() const { return static_cast<int>(knotsV_.size()) - degreeV_ - 1; }
    const std::vector<double>& KnotsU() const { return knotsU_; }
    const std::vector<double>& KnotsV() const { return knotsV_; }
    const std::vector<double>& Coefficients() const { return c_; }
    std::vector<double>& Coefficients() { return c_; }
    const double* Point(int i, int j) const {
        return c_.data() + static_cast<std::size_t>((j * CountU() + i) * dim_);
    }
    double U0() const { return knotsU_[static_cast<std::size_t>(degreeU_)]; }
    double U1() const { return knotsU_[static_cast<std::size_t>(CountU())]; }
    double V0() const { return knotsV_[static_cast<std::size_t>(degreeV_)]; }
    double V1() const { return knotsV_[static_cast<std::size_t>(CountV())]; }

    void Evaluate(double u, double v, double* out) const;
    std::vector<double> Evaluate(double u, double v) const;
    BSplineCurve IsoCurveAtV(double v) const;  // a curve in u
    BSplineCurve IsoCurveAtU(double u) const;  // a curve in v

    BSplineSurface DerivativeU() const;
    BSplineSurface DerivativeV() const;
    BSplineSurface WithKnotInsertedU(double u, int times = 1) const;
    BSplineSurface WithKnotInsertedV(double v, int times = 1) const;
    BSplineSurface ElevatedU(int times = 1) const;
    BSplineSurface ElevatedV(int times = 1) const;
    BSplineSurface Transposed() const;
    // The surface on [ua, ub] × [va, vb] inside its domain.
    BSplineSurface Restricted(double ua, double ub, double va, double vb) const;
    // Bézier extraction in both directions.
    PatchGrid ToPatches() const;
    // Bézier extraction in u only: one surface per non-empty u span, a single Bézier span in u
    // (clamped knots) and unchanged in v, so that an isocurve v = const of a strip is directly a
    // Bézier segment (used by the isocurve engine).
    std::vector<BSplineSurface> SplitIntoUSpans() const;

    // The rows seen as the points of a curve in v (dimension CountU() · Dim()).
    BSplineCurve RowsAsCurveInV() const;
    static BSplineSurface FromRowsCurve(const BSplineCurve& rows, int dim, int degreeU,
                                        std::vector<double> knotsU);

  private:
    int dim_ = 0;
    int degreeU_ = 0, degreeV_ = 0;
    std::vector<double> knotsU_, knotsV_;
    std::vector<double> c_;
};

// A piecewise Bézier surface: patch (a, b) covers [breaksU[a], breaksU[a+1]] × [breaksV[b],
// breaksV[b+1]]. The result of Bézier extraction, and the form of symbolic products of surfaces
// (e.g. the normal field), which need not be as smooth as their factors.
class PatchGrid {
  public:
    PatchGrid() = default;
    PatchGrid(std::vector<double> breaksU, std::vector<double> breaksV,
              std::vector<BezierSurface> patches);

    int SpansU() const { return static_cast<int>(breaksU_.size()) - 1; }
    int SpansV() const { return static_cast<int>(breaksV_.size()) - 1; }
    const std::vector<double>& BreaksU() const { return breaksU_; }
    const std::vector<double>& BreaksV() const { return breaksV_; }
    const BezierSurface& Patch(int a, int b) const {
        return patches_[static_cast<std::size_t>(b * SpansU() + a)];
    }
    const std::vector<BezierSurface>& Patches() const { return patches_; }
    int Dim() const { return patches_.empty() ? 0 : patches_.front().Dim(); }

    int SpanU(double u) const;
    int SpanV(double v) const;
    void Evaluate(double u, double v, double* out) const;
    std::vector<double> Evaluate(double u, double v) const;
    // The isocurve v = const, one Bézier segment per u span.
    std::vector<BezierCurve> IsoCurveAtV(double v) const;
    PatchGrid Transposed() const;
    // Back to a B-spline surface (multiplicity p at interior breaks where all patches meet
    // exactly, p + 1 elsewhere).
    BSplineSurface ToBSpline() const;

  private:
    std::vector<double> breaksU_, breaksV_;
    std::vector<BezierSurface> patches_;
};

// The normal field of a B-spline or NURBS surface (bezier_surface.h NormalField per patch).
PatchGrid NormalField(const BSplineSurface& s);

}  // namespace quadrix::freeform
