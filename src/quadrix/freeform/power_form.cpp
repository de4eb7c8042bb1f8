#include "quadrix/freeform/power_form.h"

namespace quadrix::freeform {

PowerForm::PowerForm(const BezierCurve& c)
    : dim_(c.Dim()),
      degree_(c.Degree()),
      t0_(c.T0()),
      scale_(1 / (c.T1() - c.T0())),
      a_(c.Coefficients().size(), 0.0) {
    int n = degree_;
    for (int k = 0; k <= n; ++k) {
        double outer = Binomial(n, k);
        for (int i = 0; i <= k; ++i) {
            double f = outer * Binomial(k, i) * ((k - i) % 2 ? -1.0 : 1.0);
            for (int d = 0; d < dim_; ++d)
                a_[static_cast<std::size_t>(k * dim_ + d)] += f * c.Point(i)[d];
        }
    }
}

void PowerForm::Evaluate(double t, double* out) const {
    double s = (t - t0_) * scale_;
    for (int d = 0; d < dim_; ++d) out[d] = a_[static_cast<std::size_t>(degree_ * dim_ + d)];
    for (int k = degree_ - 1; k >= 0; --k)
        for (int d = 0; d < dim_; ++d)
            out[d] = out[d] * s + a_[static_cast<std::size_t>(k * dim_ + d)];
}

}  // namespace quadrix::freeform
