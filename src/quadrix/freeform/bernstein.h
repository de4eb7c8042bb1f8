// Low-level Bernstein-form kernels shared by curves and surfaces (see bezier_curve.h for the
// notation). Coefficient arrays are strided: point i of a d-dimensional array starts at c[i * d].
#pragma once

#include <cstddef>

namespace quadrix::freeform {

// Largest dimension evaluated into stack arrays by the convenience evaluators.
inline constexpr int kMaxStackDim = 8;

// Value at local parameter s ∈ [0, 1] of the degree-n, d-dimensional Bézier polynomial with
// control points c (de Casteljau; stable for s outside [0, 1] too, as an extrapolation).
void DeCasteljau(const double* c, int n, int dim, double s, double* out);

// Splits at local parameter s: `left` gets the control points of [0, s], `right` those of [s, 1]
// (both arrays hold (n + 1) * dim values; either may be null).
void SubdivideInto(const double* c, int n, int dim, double s, double* left, double* right);

// Control points of the same polynomial on the local interval [sa, sb].
void RestrictInto(const double* c, int n, int dim, double sa, double sb, double* out);

// out_k += factor · Σ_{i+j=k} C(m,i) C(n,j) / C(m+n,k) · a_i b_j  for k = 0..m+n: the Bernstein
// coefficients of the product of two scalar polynomials, a read with stride sa, b with stride sb,
// out written with stride so.
void AccumulateProduct(const double* a, int sa, int m, const double* b, int sb, int n,
                       double factor, double* out, int so);

}  // namespace quadrix::freeform
