// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations (Golub & Van Loan,
// §8.5): the one solver shared by the bounds (flatten/bounds_math.cpp: eigenvalue bounds of a
// quadric's quadratic part) and the scanline Resolver (definite quadrics, seed 001 §3.4).
//
// Each rotation annihilates one off-diagonal entry; sweeps stop when the off-diagonal mass is
// below 1e-17 of the Frobenius norm (quadratic convergence: 3 to 6 sweeps in practice, 12 at
// most). Jacobi is backward stable: the values are exact for a matrix within a few ulps of ‖A‖.
#pragma once

namespace quadrix {

// Eigenvalues in ascending order and unit eigenvectors (columns of vecs) of the symmetric `a`
// (only read). `offDiagonal` receives the largest Gershgorin radius left: a bound on the distance
// of each returned value from the spectrum, before rounding.
void SymmetricEigen(const double a[3][3], double vals[3], double vecs[3][3], double& offDiagonal);

}  // namespace quadrix
