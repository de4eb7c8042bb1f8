// A Bézier curve converted to the power basis in its local parameter, for fast repeated
// evaluation (the isocurve rasterizer evaluates each curve segment once per sample):
//
//     C(s) = Σ_k a_k s^k,   a_k = C(n,k) Σ_{i<=k} (−1)^(k−i) C(k,i) P_i,   s = (t − t0)/(t1 − t0),
//
// evaluated by Horner's rule (n multiply-adds per coordinate instead of de Casteljau's n(n+1)/2).
// The conversion amplifies rounding by at most Σ_k C(n,k) 2^k = 3^n relative to the control
// points: ~1e-13 for the degrees drawn (<= 8), far below a pixel. Geometry decisions (roots,
// bounds) keep using the Bernstein form.
#pragma once

#include <vector>

#include "quadrix/freeform/bezier_curve.h"

namespace quadrix::freeform {

class PowerForm {
  public:
    PowerForm() = default;
    explicit PowerForm(const BezierCurve& c);

    int Dim() const { return dim_; }
    int Degree() const { return degree_; }
    void Evaluate(double t, double* out) const;

  private:
    int dim_ = 0, degree_ = 0;
    double t0_ = 0, scale_ = 1;  // s = (t − t0) · scale
    std::vector<double> a_;      // (degree + 1) · dim, a_k at k · dim
};

}  // namespace quadrix::freeform
