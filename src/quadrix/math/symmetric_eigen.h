// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations (Golub & Van Loan,
// §8.5): the one solver shared by the bounds (flatten/bounds_math.cpp: eigenvalue bounds of a
// quadric's quadratic part) and the scanline Resolver (definite quadrics, seed 001 §3.4).
//
// Each rotation annihilates one off-diagonal entry; sweeps stop when the off-diagonal mass is
// below 1e-17 of the Frobenius norm (quadratic convergence: 3 to 6 sweeps in practice, 12 at
// most). Jacobi is backward stable: the values are exact for a matrix within a few ulps of ‖A‖.
//
// SymmetricEigenLanes decomposes up to kEigenLanes matrices at once, for callers with many (the
// flattener's literal cache: one per quadric of a model). A rotation is a chain of a division,
// two square roots and another division, whose latency bounds a lone decomposition; in vector
// lanes one chain serves four matrices. Each lane does SymmetricEigen's IEEE operations in its
// order, a lane whose matrix would skip a rotation or stop sweeping keeping its entries, so each
// result is SymmetricEigen's bit for bit.
#pragma once

namespace quadrix {

// Eigenvalues in ascending order and unit eigenvectors (columns of vecs) of the symmetric `a`
// (only read). `offDiagonal` receives the largest Gershgorin radius left: a bound on the distance
// of each returned value from the spectrum, before rounding.
void SymmetricEigen(const double a[3][3], double vals[3], double vecs[3][3], double& offDiagonal);

inline constexpr int kEigenLanes = 4;

struct SymmetricEigenResult {
    double vals[3];
    double vecs[3][3];
    double offDiagonal;
};

// out[i] = SymmetricEigen(*a[i]) for i < n (n <= kEigenLanes), bit for bit: in AVX2 lanes where
// the processor has them, else one after another.
void SymmetricEigenLanes(int n, const double (*const a[])[3], SymmetricEigenResult out[]);

}  // namespace quadrix
