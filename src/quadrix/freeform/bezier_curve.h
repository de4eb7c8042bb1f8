// Polynomial Bézier curves of any degree and any dimension, in Bernstein form.
//
// Notation (used by every file of freeform/): a curve of degree n and dimension d over the
// parameter interval [t0, t1] is
//
//     C(t) = Σ_{i=0..n} P_i B_i^n(s),   s = (t - t0) / (t1 - t0),   B_i^n(s) = C(n,i) sᶦ (1-s)ⁿ⁻ᶦ.
//
// The dimension is a run-time value so that one type serves the scalar curves of the isocurve
// algorithm (the squared iso-distance Δ²(u), d = 1), Euclidean curves (d = 3) and homogeneous
// rational curves (d = 4, control points (w x, w y, w z, w)). A rational curve is handled as the
// polynomial curve of its homogeneous coordinates; dividing by w is left to the caller.
//
// The symbolic operations (sum, difference, product, dot and cross products) are exact in the
// Bernstein basis (seed 002 §2 "difference, sum, and product of curves, all computable and
// representable in the polynomial ... domains"); the product uses
//
//     B_i^m B_j^n = C(m,i) C(n,j) / C(m+n,i+j) · B_{i+j}^{m+n}.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "quadrix/math/vec.h"

namespace quadrix::freeform {

// C(n, k) as a double; exact for the degrees used here (n <= 60).
double Binomial(int n, int k);

class BezierCurve {
  public:
    BezierCurve() = default;
    // `coefficients` holds (degree + 1) * dim values, point after point.
    BezierCurve(int dim, int degree, std::vector<double> coefficients, double t0 = 0,
                double t1 = 1);
    static BezierCurve Scalar(std::vector<double> coefficients, double t0 = 0, double t1 = 1);
    static BezierCurve FromPoints(std::span<const Vec3> points, double t0 = 0, double t1 = 1);
    // Homogeneous (w x, w y, w z, w) control points from Euclidean points and weights.
    static BezierCurve FromWeightedPoints(std::span<const Vec3> points,
                                          std::span<const double> weights, double t0 = 0,
                                          double t1 = 1);

    int Dim() const { return dim_; }
    int Degree() const { return degree_; }
    int Size() const { return degree_ + 1; }
    double T0() const { return t0_; }
    double T1() const { return t1_; }
    bool Empty() const { return dim_ == 0; }

    const double* Point(int i) const { return c_.data() + static_cast<std::size_t>(i) * dim_; }
    double* Point(int i) { return c_.data() + static_cast<std::size_t>(i) * dim_; }
    double Coefficient(int i, int k = 0) const { return Point(i)[k]; }
    const std::vector<double>& Coefficients() const { return c_; }
    std::vector<double>& Coefficients() { return c_; }

    // de Casteljau at the global parameter t; `out` receives Dim() values.
    void Evaluate(double t, double* out) const;
    std::vector<double> Evaluate(double t) const;
    double EvaluateScalar(double t) const;
    Vec3 EvaluateVec3(double t) const;  // first three components
    Vec4 EvaluateVec4(double t) const;  // first four components (dim must be >= 4)

    // dC/dt, a curve of degree n-1 (a constant zero curve of degree 0 when n = 0).
    BezierCurve Derivative() const;
    // The two halves at global parameter t (t0 < t < t1), each on its own sub-interval.
    std::pair<BezierCurve, BezierCurve> Split(double t) const;
    // The same curve restricted to [a, b] ⊆ [t0, t1] (by two de Casteljau subdivisions).
    BezierCurve Restricted(double a, double b) const;
    // Degree elevation by `times` (Farin, "Curves and Surfaces for CAGD", §5.1).
    BezierCurve Elevated(int times = 1) const;
    BezierCurve ElevatedTo(int degree) const;
    // Same control points on a new parameter interval.
    BezierCurve Reparametrized(double t0, double t1) const;
    // One coordinate as a scalar curve.
    BezierCurve Component(int k) const;
    // Adds `value` to every control point of a scalar curve: since Σ B_i = 1, C(t) + value.
    BezierCurve PlusConstant(double value) const;
    BezierCurve Scaled(double factor) const;

    // Componentwise min / max of the control points (convex-hull bounds of a polynomial curve).
    double MinCoefficient(int k = 0) const;
    double MaxCoefficient(int k = 0) const;

  private:
    int dim_ = 0;
    int degree_ = 0;
    double t0_ = 0, t1_ = 1;
    std::vector<double> c_;
};

// Symbolic operations on curves over the same parameter interval (checked by the caller; the
// result takes a's interval). Sum and difference elevate the lower degree first.
BezierCurve Add(const BezierCurve& a, const BezierCurve& b);
BezierCurve Subtract(const BezierCurve& a, const BezierCurve& b);
// Product of a scalar curve `s` with a curve of any dimension `c`.
BezierCurve Multiply(const BezierCurve& s, const BezierCurve& c);
// Σ_k a_k(t) b_k(t), a scalar curve of degree m + n.
BezierCurve Dot(const BezierCurve& a, const BezierCurve& b);
// a(t) × b(t) for three-dimensional curves.
BezierCurve Cross(const BezierCurve& a, const BezierCurve& b);

}  // namespace quadrix::freeform
