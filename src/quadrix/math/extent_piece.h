// Extent pieces: ellipsoids whose convex hull has a set's bounding box, under every affine map.
//
// A piece is the ellipsoid c + a·α + b·β + d·γ with α² + β² + γ² <= 1 (an ellipse when d = 0, a
// segment when b = d = 0, a point when a = b = d = 0). An affine map x -> Lx + t sends it to the
// piece (Lc + t, La, Lb, Ld), and the extreme of coordinate i over it is c_i ± sqrt(a_i² + b_i² +
// d_i²). So a set given with pieces whose convex hull has the set's box (a cylinder: its two end
// discs; a box: its eight corners; an ellipsoid: itself) has an exact box under every placement
// and view that is affine, for the cost of mapping a few vectors. The importers' shapes list
// their pieces (import/shapes/shape.h); the scene keeps them with a body (scene::Body::extent)
// and the Flattener bounds such bodies from them (flattener.h).
#pragma once

#include <vector>

#include "quadrix/math/mat4.h"
#include "quadrix/math/vec.h"

namespace quadrix {

struct ExtentPiece {
    Vec3 c, a, b, d;
};

// True when m is affine: its last row is exactly 0 0 0 1.
bool IsAffine(const Mat4& m);

// The piece under the map m: its image when m is affine (otherwise each point and vector is
// mapped by Mat4::MapPoint and MapVector, which is not the image of the ellipsoid). For an affine
// m the same values as MapPoint and MapVector, in fewer operations.
ExtentPiece MappedPiece(const ExtentPiece& piece, const Mat4& m);

// The piece's box (not rounded outward), and its box after the affine map m.
Box3 PieceBox(const ExtentPiece& piece);
Box3 PieceBox(const ExtentPiece& piece, const Mat4& m);

// The box of the pieces' hull: their boxes' union (empty for no pieces); with m, of their
// images under m, the values of PieceBox(piece, m) without making the mapped pieces.
Box3 PiecesBox(const std::vector<ExtentPiece>& pieces);
Box3 PiecesBox(const std::vector<ExtentPiece>& pieces, const Mat4& m);

}  // namespace quadrix
