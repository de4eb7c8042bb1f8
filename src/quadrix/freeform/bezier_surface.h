// Tensor-product Bézier surfaces of any degrees and any dimension (bezier_curve.h has the
// notation).
//
//     S(u, v) = Σ_i Σ_j P_ij B_i^m(s) B_j^n(r),  s, r the local parameters of [u0,u1] × [v0,v1].
//
// Control point P_ij (i = 0..m along u, j = 0..n along v) is stored at index j (m + 1) + i: u
// varies fastest, the order of the OBJ and Geomview formats. Because the rows are contiguous, a
// surface is also a Bézier curve in v whose "points" are whole rows (dimension (m + 1) d); every v
// operation (evaluation of an isocurve, subdivision, elevation, derivative) is done that way, and u
// operations on the transpose.
//
// A rational surface is the polynomial surface of its homogeneous coordinates (d = 4, control
// points (w x, w y, w z, w)); NormalField gives a polynomial normal field for both kinds.
#pragma once

#include <utility>
#include <vector>

#include "quadrix/freeform/bezier_curve.h"
#include "quadrix/math/vec.h"

namespace quadrix::freeform {

class BezierSurface {
  public:
    BezierSurface() = default;
    BezierSurface(int dim, int degreeU, int degreeV, std::vector<double> coefficients,
                  double u0 = 0, double u1 = 1, double v0 = 0, double v1 = 1);
    // (m+1)(n+1) Euclidean points, u fastest.
    static BezierSurface FromPoints(int degreeU, int degreeV, const std::vector<Vec3>& points);
    // Homogeneous (w x, w y, w z, w) control points from Euclidean points and weights.
    static BezierSurface FromWeightedPoints(int degreeU, int degreeV,
                                            const std::vector<Vec3>& points,
                                            const std::vector<double>& weights);

    int Dim() const { return dim_; }
    int DegreeU() const { return degreeU_; }
    int DegreeV() const { return degreeV_; }
    int SizeU() const { return degreeU_ + 1; }
    int SizeV() const { return degreeV_ + 1; }
    double U0() const { return u0_; }
    double U1() const { return u1_; }
    double V0() const { return v0_; }
    double V1() const { return v1_; }
    bool Empty() const { return dim_ == 0; }

    const double* Point(int i, int j) const {
        return c_.data() + static_cast<std::size_t>((j * (degreeU_ + 1) + i) * dim_);
    }
    double* Point(int i, int j) {
        return c_.data() + static_cast<std::size_t>((j * (degreeU_ + 1) + i) * dim_);
    }
    const std::vector<double>& Coefficients() const { return c_; }
    std::vector<double>& Coefficients() { return c_; }

    void Evaluate(double u, double v, double* out) const;
    std::vector<double> Evaluate(double u, double v) const;
    Vec3 EvaluateVec3(double u, double v) const;
    Vec4 EvaluateVec4(double u, double v) const;

    // The isocurve v = const as a curve in u over [u0, u1], and u = const as a curve in v.
    BezierCurve IsoCurveAtV(double v) const;
    BezierCurve IsoCurveAtU(double u) const;

    BezierSurface DerivativeU() const;
    BezierSurface DerivativeV() const;
    std::pair<BezierSurface, BezierSurface> SplitU(double u) const;
    std::pair<BezierSurface, BezierSurface> SplitV(double v) const;
    BezierSurface Restricted(double ua, double ub, double va, double vb) const;
    BezierSurface ElevatedU(int times = 1) const;
    BezierSurface ElevatedV(int times = 1) const;
    BezierSurface ElevatedTo(int degreeU, int degreeV) const;
    BezierSurface Reparametrized(double u0, double u1, double v0, double v1) const;
    // Swaps the roles of u and v: P'_ji = P_ij.
    BezierSurface Transposed() const;
    // Coordinates [first, first + count) as a surface of dimension count.
    BezierSurface Components(int first, int count) const;

    // The surface seen as a Bézier curve in v whose points are rows (see the file comment).
    BezierCurve RowsAsCurveInV() const;
    static BezierSurface FromRowsCurve(const BezierCurve& rows, int dim, int degreeU, double u0,
                                       double u1);

  private:
    int dim_ = 0;
    int degreeU_ = 0, degreeV_ = 0;
    double u0_ = 0, u1_ = 1, v0_ = 0, v1_ = 1;
    std::vector<double> c_;
};

// Symbolic operations on surfaces over the same domain (the result takes a's domain).
BezierSurface Add(const BezierSurface& a, const BezierSurface& b);
BezierSurface Subtract(const BezierSurface& a, const BezierSurface& b);
BezierSurface Multiply(const BezierSurface& scalar, const BezierSurface& s);
BezierSurface Dot(const BezierSurface& a, const BezierSurface& b);
BezierSurface Cross(const BezierSurface& a, const BezierSurface& b);

// The unnormalised normal field as a polynomial surface (seed 002 §3.1: n(u,v) = ∂S/∂u × ∂S/∂v,
// "computed symbolically").
//  - Polynomial S (dim 3): N = Su × Sv, degrees (2m-1, 2n-1).
//  - Rational S = P / w (dim 4, homogeneous): Su × Sv = [w Pu×Pv − wv Pu×P − wu P×Pv] / w³
//    (expand Su = (Pu w − P wu)/w², Sv likewise, and use P×P = 0); N is the bracket, degrees
//    (3m-1, 3n-1), which has the direction of Su × Sv wherever w > 0.
BezierSurface NormalField(const BezierSurface& s);

}  // namespace quadrix::freeform
