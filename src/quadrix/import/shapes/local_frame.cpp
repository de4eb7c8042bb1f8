// Affine local frames of the shape builders (local_frame.h).
#include "quadrix/import/shapes/local_frame.h"

#include <cmath>

namespace quadrix::import {

LocalFrame::LocalFrame(const Vec3& o, const Vec3& e1, const Vec3& e2, const Vec3& e3) {
    Mat4 w = Mat4::Identity();
    const Vec3 cols[4] = {e1, e2, e3, o};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) w.m[r][c] = cols[c][r];
    if (auto inv = w.Inverse()) {
        local_ = *inv;
        ok_ = inv->AllFinite();
    }
}

ShapeHalfSpace LocalFrame::Quad(const Mat4& q, bool transparent) const {
    ShapeHalfSpace h;
    h.isPlane = false;
    h.quadric = Quadric::FromMatrix(local_.Transposed() * q * local_);
    h.transparent = transparent;
    return h;
}

ShapeHalfSpace LocalFrame::Plane4(double a, double b, double c, double d, bool transparent) const {
    const double p[4] = {a, b, c, d};
    double w[4] = {0, 0, 0, 0};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) w[j] += local_.m[i][j] * p[i];
    ShapeHalfSpace h;
    h.isPlane = true;
    h.plane = Plane{w[0], w[1], w[2], w[3]};
    h.transparent = transparent;
    return h;
}

Mat4 DiagonalQuadric(double a, double b, double c, double d) {
    Mat4 m = Mat4::Zero();
    m.m[0][0] = a;
    m.m[1][1] = b;
    m.m[2][2] = c;
    m.m[3][3] = d;
    return m;
}

Vec3 AnyPerpendicular(const Vec3& h) {
    Vec3 t = std::fabs(h.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    return Normalize(Cross(h, t));
}

}  // namespace quadrix::import
