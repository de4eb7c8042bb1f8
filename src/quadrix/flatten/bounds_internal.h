// Internals of the bounds (bounds.h): the literals' inside functions, their evaluation with
// rounding allowances, the analytic boxes of stage (a), the convex relaxation of stage (b1) and
// the branch-and-bound of stage (b2). Not part of the library's interface.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "quadrix/flatten/bounds.h"
#include "quadrix/math/symmetric_eigen.h"

namespace quadrix::bounds_detail {

inline constexpr double kEps = std::numeric_limits<double>::epsilon();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The inside function of one literal (f <= 0 inside) as f(p) = pᵀAp + 2b·p + k; a plane has
// A = 0 and b = n/2. Normalised so that the largest coefficient has magnitude 1 (the scale does
// not change the set and keeps magnitudes in range). A complemented literal is -f.
struct InsideFn {
    bool isPlane = true;
    double a[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    double b[3] = {0, 0, 0}, k = 0;
    // Bounds on the eigenvalues of A (lamMin <= λ <= lamMax), widened by a rounding allowance.
    double lamMin = 0, lamMax = 0;
};

// The eigen-decomposition MakeInsideFn made of a quadric's normalised A (its eigenvalue bounds
// come from it), for the callers that need more of it (HalfSpaceScale): values ascending, unit
// vectors as columns. Not `ok` for a plane or an A whose norm is 0 or not finite.
struct InsideEigen {
    bool ok = false;
    double vals[3] = {0, 0, 0};
    double vecs[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

InsideFn MakeInsideFn(const FlatHalfSpace& hs, bool complemented, InsideEigen* eigen = nullptr);

// MakeInsideFn in steps, for a caller that decomposes several quadrics' A at once
// (SymmetricEigenLanes: the literal cache). Unbounded is the function without its eigenvalue
// bounds; when NeedsEigen, Bound takes SymmetricEigen's results for its A (else null). The result
// is MakeInsideFn's bit for bit.
InsideFn MakeInsideFnUnbounded(const FlatHalfSpace& hs, bool complemented);
bool NeedsEigen(const InsideFn& f);
void Bound(InsideFn& f, const SymmetricEigenResult* decomposition, InsideEigen* eigen);

// The extent of the uncomplemented quadric's set about the origin when its normalised A is
// positive definite beyond rounding (eigenvalues above 1e-14 of the largest): |c| + sqrt(R/λmin)
// with c = -A⁻¹b and R = bᵀA⁻¹b - k, from f and the eigen-decomposition of its A (scale free:
// the same for f and any positive multiple of it); 0 otherwise.
double QuadricExtent(const InsideFn& f, const InsideEigen& eigen);

double EvaluateAt(const InsideFn& f, const double p[3]);

// Value, gradient and the magnitude of the summed terms (for rounding allowances) at a point.
struct Local {
    double v;
    double g[3];
    double mag;
};
Local EvaluateLocal(const InsideFn& f, const double c[3]);

struct Range {
    double lo, hi, margin;
};
// The centred form over |d_i| <= h_i (bounds.h). `slack` (optional) receives each axis' smear
// (max |∂f/∂x_i| over the box times h_i), which says where to split.
Range RangeFromLocal(const Local& l, const double a[3][3], double lamMin, double lamMax,
                     const double h[3], double* slack);

inline constexpr double kMaxCondition = 1e10;
// Cholesky of the m×m submatrix A[idx][idx]; false unless positive definite with a pivot ratio
// below maxCondition.
bool Cholesky(const InsideFn& f, const int* idx, int m, double l[3][3], double& condition,
              double maxCondition = kMaxCondition);
void CholeskySolve(const double l[3][3], int m, const double* rhs, double* x);

// Stage (a) for one inside function. `centre` receives the ellipsoid's centre when there is one.
Box3 AnalyticBox(const InsideFn& f, Vec3* centre, bool* hasCentre);

// Non-negative multipliers (at most 3 non-zero) minimising |Σ λ_i g_i - t|; false when no
// support of at least minSupport members has positive multipliers.
inline constexpr int kMaxSurrogate = 4;
bool NonNegativeCombination(int n, const double g[][3], const double t[3], double lambda[],
                            int minSupport = 2);

// A quadric literal whose set {f <= 0} has convex connected components: A with exactly one
// negative eigenvalue and R = -f(apex) <= 0 (rounding allowed), i.e. the two nappes of a cone or
// the insides of the two sheets of a hyperboloid. The components lie on either side of the plane
// through the apex perpendicular to `axis` (the eigenvector of the negative eigenvalue).
struct Nappe {
    bool ok = false;
    Vec3 apex, axis;   // axis: unit
    double rPlus = 0;  // max(R, 0): a rounding-level positive R (a one-sheet hyperboloid's neck)
    double beta = 0;   // |negative eigenvalue|
    double vals[3] = {0, 0, 0};  // eigenvalues of A, ascending (vals[0] < 0)
    Vec3 vecs[3];                // unit eigenvectors
};
Nappe DetectNappe(const InsideFn& f);

// Stage (b1), see bounds_relaxation.cpp. The constraints are planes, positive semidefinite
// quadrics and nappes (nappes[i].ok for those), for the set intersected with `region`.
struct RelaxationOutcome {
    bool solved = false;      // an interior point was found and the sides were attempted
    bool empty = false;       // the certified box came out empty
    bool usedNappes = false;  // false when the nappes had to be left out
    Vec3 extremes[6];         // the relaxation's extreme points, per side (2·axis + (sign > 0))
    bool haveExtreme[6] = {false, false, false, false, false, false};
};
RelaxationOutcome BoundByConvexRelaxation(const std::vector<const InsideFn*>& fns,
                                          const std::vector<Nappe>& nappes, const Box3& region,
                                          Box3& work, BoundsStats* stats);
// The same over a working set of the literals grown by cutting planes (bounds_working_set.cpp),
// for bodies of more than kWorkingSetThreshold literals: near-linear in their number.
inline constexpr std::size_t kWorkingSetThreshold = 128;
RelaxationOutcome BoundByWorkingSetRelaxation(const std::vector<const InsideFn*>& fns,
                                              const std::vector<Nappe>& nappes, const Box3& region,
                                              Box3& work, BoundsStats* stats);

// Stage (a''), see bounds_critical.cpp: the certified box of a body of one convex quadric (or a
// nappe) and planes from the critical points of the coordinates; nullopt when the stage does not
// apply or cannot certify a tight box (then the relaxation decides). `neckWide`, when given, is
// set when some side is tight only within a nappe's neck allowance (more than kTightNappe from
// its candidate): such a box is as loose as the relaxation's, not within 1e-5 of the true one.
std::optional<Box3> CriticalPointBox(const std::vector<InsideFn>& shaping, const Box3& b0,
                                     const BoundsOptions& options, bool* neckWide = nullptr);

// A candidate extreme point of one side and its Lagrange multipliers, indexed like the
// constraints of a relaxation over `fns` and a region: the literals, then the region's faces
// x_i >= lo_i, x_i <= hi_i for i = 0, 1, 2 (in that order).
struct CandidateExtreme {
    Vec3 x;
    std::vector<double> lambda;
};
// The weak-duality certificate of the relaxation (bounds_relaxation.cpp) applied to given
// extreme points of the six sides: shrinks `work` to the certified box, or returns false (work
// unchanged) when a side could not be certified or a nappe is not separated from its twin by a
// plane. `interior` is a point of the body (it orients the nappes). `neck`, when given, receives
// per side the part of its certified bound that allows for a nappe's rounding-level neck
// (0 without nappes): the bound lies that much beyond the candidate by construction.
bool CertifyExtremes(const std::vector<const InsideFn*>& fns, const std::vector<Nappe>& nappes,
                     const Box3& region, const Vec3& interior, const CandidateExtreme extremes[6],
                     Box3& work, double neck[6] = nullptr);

// Stage (b2), see bounds_search.cpp: refines the sides selected by sides[2·axis + (sign > 0)];
// false when the set is proven empty.
bool RefineByBranchAndBound(std::vector<InsideFn> fns, const std::vector<Vec3>& seeds,
                            const bool sides[6], const BoundsOptions& options, BoundsStats* stats,
                            Box3& work);

}  // namespace quadrix::bounds_detail
