#include "quadrix/model/solids.h"

#include <cmath>

namespace quadrix::model {

namespace {

SolidSurface PlaneSurface(std::string suffix, const Plane& p, bool isCap = false) {
    SolidSurface s;
    s.suffix = std::move(suffix);
    s.isPlane = true;
    s.plane = p;
    s.isCap = isCap;
    return s;
}

SolidSurface QuadricSurface(const std::array<double, 10>& k) {
    SolidSurface s;
    s.isPlane = false;
    s.quadric = Quadric::FromCoefficients(k);
    return s;
}

// The caps of an axial solid in local coordinates: z >= 0 ("#0", outward normal −w) and
// z <= length ("#1", outward normal +w).
SolidSurface Cap0() { return PlaneSurface("#0", Plane{0, 0, -1, 0}, true); }
SolidSurface Cap1(double length) { return PlaneSurface("#1", Plane{0, 0, 1, -length}, true); }

// A shape built in the frame's local coordinates, mapped to world ones.
SolidShape InFrame(const AxisFrame& frame, SolidShape local) {
    return local.Transformed(frame.WorldFromLocal());
}

}  // namespace

SolidSurface SolidSurface::Transformed(const Transform& t) const {
    SolidSurface r = *this;
    r.TransformBy(t);
    return r;
}

SolidShape SolidShape::Transformed(const Transform& t) const {
    SolidShape r;
    r.surfaces.reserve(surfaces.size());
    for (const SolidSurface& s : surfaces) r.surfaces.push_back(s.Transformed(t));
    return r;
}

bool SolidShape::Contains(const Vec3& p) const {
    for (const SolidSurface& s : surfaces)
        if (s.Evaluate(p) > 0) return false;
    return true;
}

Transform AxisFrame::WorldFromLocal() const {
    // Columns u, v, w, origin; the inverse of a rigid map is its transpose with the translation
    // rotated back: rows uᵀ, vᵀ, wᵀ and −(u·o, v·o, w·o).
    Mat4 m = Mat4::Identity(), inv = Mat4::Identity();
    const Vec3 axes[3] = {u, v, w};
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) {
            m.m[r][c] = axes[c][r];
            inv.m[c][r] = axes[c][r];
        }
        m.m[c][3] = origin[c];
        inv.m[c][3] = -Dot(axes[c], origin);
    }
    return Transform(m, inv);
}

std::optional<AxisFrame> MakeAxisFrame(const Vec3& from, const Vec3& to,
                                       const std::optional<Vec3>& uHint) {
    Vec3 d = to - from;
    double length = Length(d);
    if (!(length > 0) || !std::isfinite(length)) return std::nullopt;
    AxisFrame f;
    f.origin = from;
    f.length = length;
    f.w = d / length;
    Vec3 e;
    if (uHint) {
        e = *uHint;
    } else {
        // The world axis least aligned with w (ties: x before y before z).
        int best = 0;
        for (int i = 1; i < 3; ++i)
            if (std::fabs(f.w[i]) < std::fabs(f.w[best])) best = i;
        e[best] = 1;
    }
    Vec3 across = e - f.w * Dot(e, f.w);
    double len = Length(across);
    // A hint within ~1e-6 rad of the axis gives no usable direction across it.
    if (!(len > 1e-6 * Length(e))) return std::nullopt;
    f.u = across / len;
    f.v = Cross(f.w, f.u);
    return f;
}

SolidShape MakeSphere(const Vec3& c, double r) {
    SolidShape s;
    s.surfaces.push_back(QuadricSurface({1, 1, 1, 0, 0, 0, -c.x, -c.y, -c.z, Dot(c, c) - r * r}));
    return s;
}

SolidShape MakeEllipsoid(double a, double b, double c) {
    SolidShape s;
    s.surfaces.push_back(
        QuadricSurface({1 / (a * a), 1 / (b * b), 1 / (c * c), 0, 0, 0, 0, 0, 0, -1}));
    return s;
}

SolidShape MakeCylinder(const AxisFrame& frame, Section sec) {
    SolidShape local;
    if (sec.Circular())
        local.surfaces.push_back(QuadricSurface({1, 1, 0, 0, 0, 0, 0, 0, 0, -sec.a * sec.a}));
    else
        local.surfaces.push_back(
            QuadricSurface({1 / (sec.a * sec.a), 1 / (sec.b * sec.b), 0, 0, 0, 0, 0, 0, 0, -1}));
    local.surfaces.push_back(Cap0());
    local.surfaces.push_back(Cap1(frame.length));
    return InFrame(frame, std::move(local));
}

SolidShape MakeCone(const AxisFrame& frame, Section s0, Section s1) {
    // Half-axis along u grows linearly: a(z) = a0 + slope·z. The section's shape is fixed, so
    // y is scaled by q = a/b:  x² + q²y² − a(z)² <= 0 (a double cone, or a cylinder if slope 0).
    const double slope = (s1.a - s0.a) / frame.length;
    const double q = s0.a > 0 ? s0.a / s0.b : s1.a / s1.b;
    SolidShape local;
    local.surfaces.push_back(
        QuadricSurface({1, q * q, -slope * slope, 0, 0, 0, 0, 0, -s0.a * slope, -s0.a * s0.a}));
    local.surfaces.push_back(Cap0());
    local.surfaces.push_back(Cap1(frame.length));
    return InFrame(frame, std::move(local));
}

SolidShape MakeBox(const Vec3& c0, const Vec3& c1) {
    static const char* kNames[3][2] = {{"#x0", "#x1"}, {"#y0", "#y1"}, {"#z0", "#z1"}};
    SolidShape s;
    for (int i = 0; i < 3; ++i) {
        double lo = std::fmin(c0[i], c1[i]), hi = std::fmax(c0[i], c1[i]);
        Vec4 low, high;
        low[i] = -1;  // −x + lo <= 0: x >= lo
        low.w = lo;
        high[i] = 1;  // x − hi <= 0
        high.w = -hi;
        s.surfaces.push_back(PlaneSurface(kNames[i][0], Plane::FromVec4(low)));
        s.surfaces.push_back(PlaneSurface(kNames[i][1], Plane::FromVec4(high)));
    }
    return s;
}

SolidShape MakeParaboloid(const AxisFrame& frame, Section sec) {
    // Apex at local z = 0, section sec at z = L:  x²/a² + y²/b² − z/L <= 0, or for a circle of
    // radius r, x² + y² − (r²/L) z <= 0 (linear z coefficient 2J).
    const double L = frame.length;
    SolidShape local;
    if (sec.Circular())
        local.surfaces.push_back(
            QuadricSurface({1, 1, 0, 0, 0, 0, 0, 0, -sec.a * sec.a / (2 * L), 0}));
    else
        local.surfaces.push_back(QuadricSurface(
            {1 / (sec.a * sec.a), 1 / (sec.b * sec.b), 0, 0, 0, 0, 0, 0, -1 / (2 * L), 0}));
    local.surfaces.push_back(Cap1(L));
    return InFrame(frame, std::move(local));
}

namespace {
// x²·α + y²·β − c (z − h)² + k0 <= 0 expanded about local z = 0 (h = L/2, the middle).
std::array<double, 10> AboutMiddle(double alpha, double beta, double c, double h, double k0) {
    return {alpha, beta, -c, 0, 0, 0, 0, 0, c * h, k0 - c * h * h};
}
}  // namespace

SolidShape MakeHyperboloid1(const AxisFrame& frame, Section sec, double waistRatio) {
    // About the middle (z' = z − h): circular x² + y² − w² − (r² − w²) z'²/h² <= 0, with waist
    // w = ρr; elliptic x²/a² + y²/b² − ρ² − (1 − ρ²) z'²/h² <= 0. At z' = ±h the section is sec.
    const double h = frame.length / 2, rho = waistRatio;
    SolidShape local;
    if (sec.Circular()) {
        double r = sec.a, w = rho * r;
        local.surfaces.push_back(
            QuadricSurface(AboutMiddle(1, 1, (r * r - w * w) / (h * h), h, -w * w)));
    } else {
        local.surfaces.push_back(QuadricSurface(AboutMiddle(
            1 / (sec.a * sec.a), 1 / (sec.b * sec.b), (1 - rho * rho) / (h * h), h, -rho * rho)));
    }
    local.surfaces.push_back(Cap0());
    local.surfaces.push_back(Cap1(frame.length));
    return InFrame(frame, std::move(local));
}

SolidShape MakeHyperboloid2(const AxisFrame& frame, Section sec, double gap) {
    // About the middle, vertices at z' = ±g (g = gap/2): the inside of the sheets is
    // x²/a² + y²/b² − (z'² − g²)/(h² − g²) <= 0, which is 1 at the caps z' = ±h; circular
    // sections are scaled by r²: x² + y² − r²(z'² − g²)/(h² − g²) <= 0.
    const double h = frame.length / 2, g = gap / 2;
    const double denom = h * h - g * g;
    SolidShape local;
    if (sec.Circular()) {
        double r2 = sec.a * sec.a, c = r2 / denom;
        local.surfaces.push_back(QuadricSurface(AboutMiddle(1, 1, c, h, c * g * g)));
    } else {
        double c = 1 / denom;
        local.surfaces.push_back(
            QuadricSurface(AboutMiddle(1 / (sec.a * sec.a), 1 / (sec.b * sec.b), c, h, c * g * g)));
    }
    local.surfaces.push_back(Cap0());
    local.surfaces.push_back(Cap1(frame.length));
    return InFrame(frame, std::move(local));
}

SolidShape MakeHalfSpace(const Vec3& point, const Vec3& n) {
    SolidShape s;
    s.surfaces.push_back(PlaneSurface("", Plane{n.x, n.y, n.z, -Dot(n, point)}));
    return s;
}

}  // namespace quadrix::model

namespace quadrix::model {

namespace {

SolidSurface QuarticSolidSurface(const QuarticSurface& q) {
    SolidSurface s;
    s.SetQuartic(q);
    return s;
}

}  // namespace

SolidShape MakeTorus(const QuarticSurface& torus) {
    SolidShape s;
    s.surfaces.push_back(QuarticSolidSurface(torus));
    return s;
}

SolidShape MakeEllipticalTorus(const QuarticSurface& eto) { return MakeTorus(eto); }

SolidShape MakeGeneralCone(const QuarticSurface& cone) {
    SolidShape s;
    s.surfaces.push_back(QuarticSolidSurface(cone));
    const std::array<Vec4, 2> caps = cone.GeneralConeCaps();
    s.surfaces.push_back(PlaneSurface("#0", Plane::FromVec4(caps[0]), true));
    s.surfaces.push_back(PlaneSurface("#1", Plane::FromVec4(caps[1]), true));
    return s;
}

}  // namespace quadrix::model
