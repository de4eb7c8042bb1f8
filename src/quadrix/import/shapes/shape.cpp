// Shapes shared by the importers: containment, exact boxes, placement (shape.h).
#include "quadrix/import/shapes/shape.h"

#include <cmath>

namespace quadrix::import {

bool ShapeContains(const Shape& shape, const Vec3& p, double tol) {
    for (const ShapeBody& body : shape.bodies) {
        bool in = true;
        for (const ShapeHalfSpace& h : body) {
            const double v = h.Evaluate(p);
            if (h.complement ? !(v > -tol) : !(v <= tol)) {
                in = false;
                break;
            }
        }
        if (in) return true;
    }
    return false;
}

Box3 ShapeBox(const Shape& shape, const Mat4& m) {
    Box3 box;
    for (const ExtentPiece& piece : shape.extent) box.Extend(PieceBox(piece, m));
    // A sum's box: the first term placed by m, every later term an offset (its centre a vector).
    for (const auto& sum : shape.extentSums) {
        if (sum.empty()) continue;
        Box3 s = PieceBox(sum[0], m);
        for (std::size_t i = 1; i < sum.size(); ++i) {
            const Box3 b = PieceBox(sum[i], m);
            const Vec3 shift = m.MapVector(sum[i].c) - m.MapPoint(sum[i].c);
            s.lo = s.lo + b.lo + shift;
            s.hi = s.hi + b.hi + shift;
        }
        box.Extend(s);
    }
    return box;
}

Box3 ShapeBox(const Shape& shape, const Mat4& m, const std::vector<ExtentPiece>& bodyExtent) {
    const Box3 box = PiecesBox(bodyExtent);
    return box.Empty() ? ShapeBox(shape, m) : box;
}

std::vector<ExtentPiece> BodyExtent(const Shape& shape, const Mat4& m) {
    std::vector<ExtentPiece> out;
    if (shape.bodies.size() != 1 || !shape.extentExact || !shape.extentSums.empty() ||
        shape.unbounded || !IsAffine(m))
        return out;
    out.reserve(shape.extent.size());
    for (const ExtentPiece& piece : shape.extent) out.push_back(MappedPiece(piece, m));
    return out;
}

void SetSceneSurface(const ShapeHalfSpace& placed, scene::HalfSpace& hs) {
    if (placed.IsQuartic()) {
        hs.kind = scene::HalfSpace::Kind::kQuartic;
        hs.quartic = placed.quartic;
    } else if (placed.isPlane) {
        hs.kind = scene::HalfSpace::Kind::kPlane;
        hs.plane = placed.plane;
    } else {
        hs.kind = scene::HalfSpace::Kind::kQuadric;
        hs.quadric = placed.quadric;
    }
}

ShapeHalfSpace Placed(const ShapeHalfSpace& h, const Transform& t) {
    ShapeHalfSpace out = h;
    if (h.IsQuartic()) {
        out.TransformBy(t);
    } else if (h.isPlane) {
        Plane pl = h.plane.Transformed(t);
        const double n = Length(pl.Normal());
        if (n > 0) pl = Plane{pl.a / n, pl.b / n, pl.c / n, pl.d / n};
        out.plane = pl;
    } else {
        Quadric q = h.quadric.Transformed(t);
        const double s = q.MaxAbs();
        if (s > 0)
            for (double& k : q.k) k /= s;
        out.quadric = q;
    }
    return out;
}

}  // namespace quadrix::import
