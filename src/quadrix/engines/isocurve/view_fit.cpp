#include "quadrix/engines/isocurve/view_fit.h"

#include <algorithm>
#include <cmath>

namespace quadrix::isocurve {

namespace {

struct Frame3 {
    Vec3 right, up, vpn;
};

Frame3 ViewFrame(const Vec3& towardViewer, const Vec3& up) {
    Vec3 vpn = Normalize(-towardViewer);
    Vec3 r = Normalize(Cross(up, vpn));
    return {r, Cross(vpn, r), vpn};
}

Mat4 Rows(const Vec4& a, const Vec4& b, const Vec4& c, const Vec4& d) {
    Mat4 m;
    const Vec4* rows[4] = {&a, &b, &c, &d};
    for (int r = 0; r < 4; ++r)
        for (int k = 0; k < 4; ++k) m(r, k) = (*rows[r])[static_cast<std::size_t>(k)];
    return m;
}

}  // namespace

Projection FitParallel(const Box3& bounds, const Vec3& towardViewer, const Vec3& up, int width,
                       int height, double margin) {
    Frame3 f = ViewFrame(towardViewer, up);
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int k = 0; k < 8; ++k) {
        Vec3 p{k & 1 ? bounds.hi.x : bounds.lo.x, k & 2 ? bounds.hi.y : bounds.lo.y,
               k & 4 ? bounds.hi.z : bounds.lo.z};
        double c[3] = {Dot(p, f.right), Dot(p, f.up), Dot(p, f.vpn)};
        for (int i = 0; i < 3; ++i) {
            lo[i] = std::min(lo[i], c[i]);
            hi[i] = std::max(hi[i], c[i]);
        }
    }
    double usable = std::min(width, height) * (1 - 2 * margin);
    double s = usable / std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-300});
    double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    // x = s (p·right − cx) + W/2,  y = −s (p·up − cy) + H/2,  z = s (p·vpn − lo) + 1.
    Mat4 m = Rows(Vec4(f.right * s, -s * cx + 0.5 * width), Vec4(f.up * -s, s * cy + 0.5 * height),
                  Vec4(f.vpn * s, -s * lo[2] + 1), Vec4(0, 0, 0, 1));
    Projection p;
    p.perspective = false;
    p.deviceFromWorld = Transform::FromMatrix(m).value();
    p.towardViewer = Normalize(towardViewer);
    return p;
}

Projection FitPerspective(const Box3& bounds, const Vec3& towardViewer, const Vec3& up, int width,
                          int height, double distance) {
    Frame3 f = ViewFrame(towardViewer, up);
    Vec3 centre = bounds.Center();
    double radius = 0.5 * Length(bounds.Size());
    Vec3 eye = centre + Normalize(towardViewer) * (distance * 2 * radius);
    double d = Length(centre - eye);
    // Focal length in pixels so that the bounding sphere (half-angle asin(r/d)) fits.
    double half = std::asin(std::min(radius / d, 0.99));
    double focal = 0.5 * std::min(width, height) * 0.95 / std::tan(half);
    double nearPlane = 0.5 * (d - radius);
    // Homogeneous rows: x_h = f (p−e)·right + W/2 · w_h, y_h = −f (p−e)·up + H/2 · w_h,
    // z_h = w_h − near, w_h = (p−e)·vpn, so z = 1 − near / depth grows with the depth.
    Vec4 w(f.vpn, -Dot(f.vpn, eye));
    Vec4 x = Vec4(f.right * focal, -focal * Dot(f.right, eye)) + w * (0.5 * width);
    Vec4 y = Vec4(f.up * -focal, focal * Dot(f.up, eye)) + w * (0.5 * height);
    Vec4 z = w + Vec4(0, 0, 0, -nearPlane);
    Projection p;
    p.perspective = true;
    p.deviceFromWorld = Transform::FromMatrix(Rows(x, y, z, w)).value();
    p.eye = eye;
    p.towardViewer = Normalize(towardViewer);
    return p;
}

}  // namespace quadrix::isocurve
