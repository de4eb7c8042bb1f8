// Extent pieces (extent_piece.h).
#include "quadrix/math/extent_piece.h"

#include <cmath>

namespace quadrix {

bool IsAffine(const Mat4& m) {
    return m.m[3][0] == 0 && m.m[3][1] == 0 && m.m[3][2] == 0 && m.m[3][3] == 1;
}

ExtentPiece MappedPiece(const ExtentPiece& piece, const Mat4& m) {
    return {m.MapPoint(piece.c), m.MapVector(piece.a), m.MapVector(piece.b), m.MapVector(piece.d)};
}

Box3 PieceBox(const ExtentPiece& piece) {
    const Vec3 &c = piece.c, &a = piece.a, &b = piece.b, &d = piece.d;
    Box3 box;
    for (std::size_t i = 0; i < 3; ++i) {
        const double e = std::sqrt(a[i] * a[i] + b[i] * b[i] + d[i] * d[i]);
        box.lo[i] = c[i] - e;
        box.hi[i] = c[i] + e;
    }
    return box;
}

Box3 PieceBox(const ExtentPiece& piece, const Mat4& m) { return PieceBox(MappedPiece(piece, m)); }

}  // namespace quadrix
