// Extent pieces (extent_piece.h).
#include "quadrix/math/extent_piece.h"

#include <cmath>

namespace quadrix {

bool IsAffine(const Mat4& m) {
    return m.m[3][0] == 0 && m.m[3][1] == 0 && m.m[3][2] == 0 && m.m[3][3] == 1;
}

namespace {

// m·(p, 1) and m·(v, 0) for an affine m, in Mat4::operator*'s order of operations, so the same
// values (the build keeps products and sums apart: -ffp-contract=off; the last row's w is 1).
Vec3 AffinePoint(const Mat4& m, const Vec3& p) {
    return {m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3],
            m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3],
            m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3]};
}
Vec3 AffineVector(const Mat4& m, const Vec3& v) {
    return {m.m[0][0] * v.x + m.m[0][1] * v.y + m.m[0][2] * v.z,
            m.m[1][0] * v.x + m.m[1][1] * v.y + m.m[1][2] * v.z,
            m.m[2][0] * v.x + m.m[2][1] * v.y + m.m[2][2] * v.z};
}

}  // namespace

ExtentPiece MappedPiece(const ExtentPiece& piece, const Mat4& m) {
    if (!IsAffine(m))
        return {m.MapPoint(piece.c), m.MapVector(piece.a), m.MapVector(piece.b),
                m.MapVector(piece.d)};
    const Vec3 zero{0, 0, 0};
    if (piece.a == zero && piece.b == zero && piece.d == zero)  // a point (a polytope's corner)
        return {AffinePoint(m, piece.c), zero, zero, zero};
    return {AffinePoint(m, piece.c), AffineVector(m, piece.a), AffineVector(m, piece.b),
            AffineVector(m, piece.d)};
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

Box3 PiecesBox(const std::vector<ExtentPiece>& pieces) {
    Box3 box;
    for (const ExtentPiece& piece : pieces) box.Extend(PieceBox(piece));
    return box;
}

Box3 PiecesBox(const std::vector<ExtentPiece>& pieces, const Mat4& m) {
    Box3 box;
    if (!IsAffine(m)) {
        for (const ExtentPiece& piece : pieces) box.Extend(PieceBox(piece, m));
        return box;
    }
    const Vec3 zero{0, 0, 0};
    for (const ExtentPiece& piece : pieces) {
        // PieceBox(MappedPiece(piece, m)), operation for operation.
        const Vec3 c = AffinePoint(m, piece.c);
        double e[3] = {0, 0, 0};
        if (!(piece.a == zero && piece.b == zero && piece.d == zero)) {
            const Vec3 a = AffineVector(m, piece.a), b = AffineVector(m, piece.b),
                       d = AffineVector(m, piece.d);
            for (std::size_t i = 0; i < 3; ++i)
                e[i] = std::sqrt(a[i] * a[i] + b[i] * b[i] + d[i] * d[i]);
        }
        for (std::size_t i = 0; i < 3; ++i) {
            const double lo = c[i] - e[i], hi = c[i] + e[i];
            if (lo < box.lo[i]) box.lo[i] = lo;
            if (hi > box.hi[i]) box.hi[i] = hi;
        }
    }
    return box;
}

}  // namespace quadrix
