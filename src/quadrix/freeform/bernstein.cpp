#include "quadrix/freeform/bernstein.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "quadrix/freeform/bezier_curve.h"

namespace quadrix::freeform {

namespace {

// Scratch space for de Casteljau; small cases stay on the stack.
class Scratch {
  public:
    explicit Scratch(std::size_t n) {
        if (n > kStack) {
            heap_.resize(n);
            data_ = heap_.data();
        } else {
            data_ = stack_;
        }
    }
    double* data() { return data_; }

  private:
    static constexpr std::size_t kStack = 64;
    double stack_[kStack];
    std::vector<double> heap_;
    double* data_;
};

}  // namespace

void DeCasteljau(const double* c, int n, int dim, double s, double* out) {
    std::size_t size = static_cast<std::size_t>((n + 1) * dim);
    double r = 1 - s;
    if (dim == 1 && n < 64) {
        // Scalar fast path (the Δ² curves): one row of at most 64 values on the stack.
        double w[64];
        for (int i = 0; i <= n; ++i) w[i] = c[i];
        for (int level = n; level > 0; --level)
            for (int i = 0; i < level; ++i) w[i] = r * w[i] + s * w[i + 1];
        out[0] = w[0];
        return;
    }
    Scratch scratch(size);
    double* w = scratch.data();
    for (std::size_t i = 0; i < size; ++i) w[i] = c[i];
    for (int level = n; level > 0; --level) {
        std::size_t len = static_cast<std::size_t>(level * dim);
        for (std::size_t i = 0; i < len; ++i)
            w[i] = r * w[i] + s * w[i + static_cast<std::size_t>(dim)];
    }
    for (int k = 0; k < dim; ++k) out[k] = w[k];
}

void SubdivideInto(const double* c, int n, int dim, double s, double* left, double* right) {
    std::size_t size = static_cast<std::size_t>((n + 1) * dim);
    Scratch scratch(size);
    double* w = scratch.data();
    std::memcpy(w, c, size * sizeof(double));
    double r = 1 - s;
    // The de Casteljau triangle: after row j, the first point is left_j and the last one
    // right_{n-j} (Farin §3.3).
    auto put = [&](double* dst, int index, const double* src) {
        if (dst)
            std::memcpy(dst + index * dim, src, static_cast<std::size_t>(dim) * sizeof(double));
    };
    put(left, 0, w);
    put(right, n, w + n * dim);
    for (int j = 1; j <= n; ++j) {
        for (int i = 0; i <= n - j; ++i)
            for (int k = 0; k < dim; ++k)
                w[i * dim + k] = r * w[i * dim + k] + s * w[(i + 1) * dim + k];
        put(left, j, w);
        put(right, n - j, w + (n - j) * dim);
    }
}

void RestrictInto(const double* c, int n, int dim, double sa, double sb, double* out) {
    std::size_t size = static_cast<std::size_t>((n + 1) * dim);
    if (sa == 0 && sb == 1) {
        std::memcpy(out, c, size * sizeof(double));
        return;
    }
    std::vector<double> tmp(size);
    // First cut at sb, keeping [0, sb]; then cut that at sa / sb, keeping the right part.
    if (sb != 1)
        SubdivideInto(c, n, dim, sb, tmp.data(), nullptr);
    else
        std::memcpy(tmp.data(), c, size * sizeof(double));
    if (sa == 0) {
        std::memcpy(out, tmp.data(), size * sizeof(double));
        return;
    }
    SubdivideInto(tmp.data(), n, dim, sa / sb, nullptr, out);
}

void AccumulateProduct(const double* a, int sa, int m, const double* b, int sb, int n,
                       double factor, double* out, int so) {
    for (int i = 0; i <= m; ++i) {
        double ai = a[i * sa];
        if (ai == 0) continue;
        double ci = Binomial(m, i);
        for (int j = 0; j <= n; ++j)
            out[(i + j) * so] +=
                factor * ci * Binomial(n, j) / Binomial(m + n, i + j) * ai * b[j * sb];
    }
}

}  // namespace quadrix::freeform
