#include "quadrix/math/symmetric_eigen.h"

#include <algorithm>
#include <cmath>

namespace quadrix {

void SymmetricEigen(const double a[3][3], double vals[3], double vecs[3][3], double& offDiagonal) {
    double m[3][3], v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    double frob = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            m[i][j] = a[i][j];
            frob += m[i][j] * m[i][j];
        }
    for (int sweep = 0; sweep < 12 && frob > 0; ++sweep) {
        double off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
        if (off <= 1e-34 * frob) break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (m[p][q] == 0) continue;
                // Jacobi rotation annihilating m[p][q] (Golub & Van Loan, §8.5).
                double theta = (m[q][q] - m[p][p]) / (2 * m[p][q]);
                double t =
                    (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
                double c = 1 / std::sqrt(t * t + 1), s = t * c;
                for (int r = 0; r < 3; ++r) {
                    double mrp = m[r][p], mrq = m[r][q];
                    m[r][p] = c * mrp - s * mrq;
                    m[r][q] = s * mrp + c * mrq;
                }
                for (int r = 0; r < 3; ++r) {
                    double mpr = m[p][r], mqr = m[q][r];
                    m[p][r] = c * mpr - s * mqr;
                    m[q][r] = s * mpr + c * mqr;
                }
                for (int r = 0; r < 3; ++r) {
                    double vrp = v[r][p], vrq = v[r][q];
                    v[r][p] = c * vrp - s * vrq;
                    v[r][q] = s * vrp + c * vrq;
                }
            }
    }
    offDiagonal = 0;
    for (int i = 0; i < 3; ++i) {
        double radius = 0;
        for (int j = 0; j < 3; ++j)
            if (j != i) radius += std::fabs(m[i][j]);
        offDiagonal = std::fmax(offDiagonal, radius);
    }
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int x, int y) { return m[x][x] < m[y][y]; });
    for (int i = 0; i < 3; ++i) {
        vals[i] = m[order[i]][order[i]];
        for (int r = 0; r < 3; ++r) vecs[r][i] = v[r][order[i]];
    }
}

}  // namespace quadrix
