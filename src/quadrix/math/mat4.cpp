#include "quadrix/math/mat4.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

namespace quadrix {

Mat4 Mat4::Identity() {
    Mat4 r;
    for (int i = 0; i < 4; ++i) r.m[i][i] = 1.0;
    return r;
}

Mat4 Mat4::operator*(const Mat4& o) const {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += m[i][k] * o.m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

Vec4 Mat4::operator*(const Vec4& v) const {
    Vec4 r;
    for (int i = 0; i < 4; ++i)
        r[i] = m[i][0] * v.x + m[i][1] * v.y + m[i][2] * v.z + m[i][3] * v.w;
    return r;
}

Mat4 Mat4::Transposed() const {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = m[j][i];
    return r;
}

Vec3 Mat4::MapPoint(const Vec3& p) const { return Dehomogenize((*this) * Vec4(p, 1.0)); }

Vec3 Mat4::MapVector(const Vec3& v) const { return ((*this) * Vec4(v, 0.0)).xyz(); }

bool Mat4::AllFinite() const {
    for (const auto& row : m)
        for (double v : row)
            if (!std::isfinite(v)) return false;
    return true;
}

std::optional<Mat4> Mat4::Inverse() const {
    if (!AllFinite()) return std::nullopt;
    Mat4 a = *this;
    Mat4 inv = Identity();
    // Scale-aware singularity test: pivots are compared with the largest entry.
    double scale = 0;
    for (const auto& row : m)
        for (double v : row) scale = std::fmax(scale, std::fabs(v));
    if (scale == 0) return std::nullopt;
    for (int col = 0; col < 4; ++col) {
        int pivot = col;
        for (int r = col + 1; r < 4; ++r)
            if (std::fabs(a.m[r][col]) > std::fabs(a.m[pivot][col])) pivot = r;
        if (std::fabs(a.m[pivot][col]) <= 1e-14 * scale || std::fabs(a.m[pivot][col]) < 1e-300)
            return std::nullopt;
        std::swap(a.m[pivot], a.m[col]);
        std::swap(inv.m[pivot], inv.m[col]);
        double p = a.m[col][col];
        for (int j = 0; j < 4; ++j) {
            a.m[col][j] /= p;
            inv.m[col][j] /= p;
        }
        for (int r = 0; r < 4; ++r) {
            if (r == col) continue;
            double f = a.m[r][col];
            if (f == 0) continue;
            for (int j = 0; j < 4; ++j) {
                a.m[r][j] -= f * a.m[col][j];
                inv.m[r][j] -= f * inv.m[col][j];
            }
        }
    }
    if (!inv.AllFinite()) return std::nullopt;
    return inv;
}

std::string Mat4::ToString() const {
    std::string s;
    for (int i = 0; i < 4; ++i)
        s += fmt::format("[{} {} {} {}]{}", m[i][0], m[i][1], m[i][2], m[i][3], i < 3 ? " " : "");
    return s;
}

std::optional<Transform> Transform::FromMatrix(const Mat4& m) {
    auto inv = m.Inverse();
    if (!inv) return std::nullopt;
    return Transform(m, *inv);
}

Transform Transform::Translate(const Vec3& t) {
    Mat4 m = Mat4::Identity(), inv = Mat4::Identity();
    for (int i = 0; i < 3; ++i) {
        m.m[i][3] = t[i];
        inv.m[i][3] = -t[i];
    }
    return {m, inv};
}

Transform Transform::Scale(const Vec3& s) {
    Mat4 m = Mat4::Identity(), inv = Mat4::Identity();
    for (int i = 0; i < 3; ++i) {
        m.m[i][i] = s[i];
        inv.m[i][i] = 1.0 / s[i];
    }
    return {m, inv};
}

void SinCosDegrees(double degrees, double& s, double& c) {
    // Reduce |degrees| to [0, 360) exactly (fmod is exact), then handle the quadrants so that
    // multiples of 90 degrees give exact 0 and ±1. Working on |degrees| and restoring the sign at
    // the end makes sin(−x) = −sin(x) and cos(−x) = cos(x) bit for bit (reducing a negative angle
    // by adding 360 would round). Non-finite angles give NaN (and must not reach the int cast).
    if (!std::isfinite(degrees)) {
        s = c = std::nan("");
        return;
    }
    double a = std::fmod(std::fabs(degrees), 360.0);
    int quadrant = static_cast<int>(a / 90.0);
    double r = a - 90.0 * quadrant;  // in [0, 90)
    double rs, rc;
    if (r == 0) {
        rs = 0;
        rc = 1;
    } else if (r == 45.0) {
        rs = rc = std::sqrt(0.5);
    } else if (r == 30.0) {
        rs = 0.5;
        rc = std::sqrt(3.0) / 2.0;
    } else if (r == 60.0) {
        rs = std::sqrt(3.0) / 2.0;
        rc = 0.5;
    } else {
        double rad = r * (M_PI / 180.0);
        rs = std::sin(rad);
        rc = std::cos(rad);
    }
    switch (quadrant & 3) {
        case 0:
            s = rs;
            c = rc;
            break;
        case 1:
            s = rc;
            c = -rs;
            break;
        case 2:
            s = -rs;
            c = -rc;
            break;
        default:
            s = -rc;
            c = rs;
            break;
    }
    if (degrees < 0) s = -s;
}

Transform Transform::Rotate(int axis, double degrees) {
    double s, c;
    SinCosDegrees(degrees, s, c);
    int i = (axis + 1) % 3, j = (axis + 2) % 3;  // the rotated plane, cyclic order
    Mat4 m = Mat4::Identity();
    m.m[i][i] = c;
    m.m[i][j] = -s;
    m.m[j][i] = s;
    m.m[j][j] = c;
    return {m, m.Transposed()};
}

Transform Transform::Shear(int to, int from, double factor) {
    Mat4 m = Mat4::Identity(), inv = Mat4::Identity();
    m.m[to][from] = factor;
    inv.m[to][from] = -factor;
    return {m, inv};
}

}  // namespace quadrix
