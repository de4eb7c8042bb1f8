// Quartic half-spaces (quartic_surface.h): constructors, evaluation, lines.
#include "quadrix/math/quartic_surface.h"

#include <algorithm>
#include <cmath>

#include "quadrix/math/quartic_roots.h"

namespace quadrix {
namespace {

// Quadratic and quartic polynomials in the line parameter s (coefficients of s^0, s^1, ...).
using Q2 = std::array<double, 3>;
using Q4 = std::array<double, 5>;

Q2 Mul(double a0, double a1, double b0, double b1) { return {a0 * b0, a0 * b1 + a1 * b0, a1 * b1}; }
Q2 Add(const Q2& a, const Q2& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Q2 Scale(double k, const Q2& a) { return {k * a[0], k * a[1], k * a[2]}; }
Q4 Mul(const Q2& a, const Q2& b) {
    return {a[0] * b[0], a[0] * b[1] + a[1] * b[0], a[0] * b[2] + a[1] * b[1] + a[2] * b[0],
            a[1] * b[2] + a[2] * b[1], a[2] * b[2]};
}

// The box a little larger (by `m` of its largest half-extent), so that its faces never bound the
// inside of a torus (which it contains) and the caps of a cone win over its slab ends.
Box3 Grown(const Box3& b, double m) {
    const Vec3 s = b.Size();
    const double g = m * std::max({s.x, s.y, s.z});
    return {b.lo - Vec3{g, g, g}, b.hi + Vec3{g, g, g}};
}

// A unit vector perpendicular to unit w: the world axis least aligned with w, made perpendicular.
Vec3 Perpendicular(const Vec3& w) {
    const Vec3 ax = std::fabs(w.x) <= std::fabs(w.y) && std::fabs(w.x) <= std::fabs(w.z)
                        ? Vec3{1, 0, 0}
                        : (std::fabs(w.y) <= std::fabs(w.z) ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    return Normalize(ax - w * Dot(ax, w));
}

// spaceFromLocal with columns u·s, v·s, w·s, origin (orthonormal u, v, w): the inverse is exact
// in form (rows u/s, v/s, w/s).
Transform OrthoFrame(const Vec3& origin, const Vec3& u, const Vec3& v, const Vec3& w, double s) {
    Mat4 m = Mat4::Identity(), inv = Mat4::Identity();
    const Vec3 axes[3] = {u, v, w};
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r) {
            m(r, c) = axes[c][static_cast<std::size_t>(r)] * s;
            inv(c, r) = axes[c][static_cast<std::size_t>(r)] / s;
        }
        m(c, 3) = origin[static_cast<std::size_t>(c)];
        inv(c, 3) = -Dot(axes[c], origin) / s;
    }
    return Transform(inv, m);  // localFromSpace
}

bool Fail(std::string* why, const char* text) {
    if (why) *why = text;
    return false;
}

bool Finite(double v) { return std::isfinite(v); }

}  // namespace

std::optional<QuarticSurface> QuarticSurface::EllipticalTorus(const Vec3& V, const Vec3& N,
                                                              double r, const Vec3& C, double d,
                                                              std::string* why) {
    if (!IsFinite(V) || !IsFinite(N) || !IsFinite(C) || !Finite(r) || !Finite(d)) {
        Fail(why, "non-finite parameter");
        return std::nullopt;
    }
    const double nl = Length(N);
    if (!(nl > 0)) {
        Fail(why, "the axis is the zero vector");
        return std::nullopt;
    }
    const Vec3 w = N / nl;
    const double c = Length(C);
    if (!(c > 0) || !(d > 0) || !(r > 0)) {
        Fail(why, "the radius and both semi-axes must be > 0");
        return std::nullopt;
    }
    const double cz = Dot(C, w);
    const Vec3 cr = C - w * cz;
    const double crl = Length(cr);
    const Vec3 u = crl > 1e-12 * c ? cr / crl : Perpendicular(w);
    const Vec3 v = Cross(w, u);
    // The ellipse's half-extents along ρ and z (support of the ellipse in those directions).
    const double wr = std::sqrt(crl * crl + d * d * cz * cz / (c * c));
    const double wz = std::sqrt(cz * cz + d * d * crl * crl / (c * c));
    if (!(r > wr)) {
        Fail(why,
             "the ellipse reaches the axis (the radius of revolution must exceed the "
             "ellipse's extent across it)");
        return std::nullopt;
    }
    QuarticSurface q;
    q.kind = Kind::kEllipticalTorus;
    q.p = {r, c, d, crl, cz};
    const double s = r + wr;  // local unit: the solid's outer radius
    q.localFromSpace = OrthoFrame(V, u, v, w, s);
    // g = qᵀ M q − 1 with q = (ρ − r, z) in local units, M = e1e1ᵀ/c² + e2e2ᵀ/d², scaled by
    // min(c, d)² so that its coefficients are ~1.
    const double rl = r / s, cl = c / s, dl = d / s;
    const double e1r = crl / c, e1z = cz / c, e2r = -e1z, e2z = e1r;
    const double k2 = std::min(cl, dl) * std::min(cl, dl);
    const double m00 = k2 * (e1r * e1r / (cl * cl) + e2r * e2r / (dl * dl));
    const double m01 = k2 * (e1r * e1z / (cl * cl) + e2r * e2z / (dl * dl));
    const double m11 = k2 * (e1z * e1z / (cl * cl) + e2z * e2z / (dl * dl));
    q.k = {m00, m01, m11, -2 * m00 * rl, -2 * m01 * rl, m00 * rl * rl - k2};
    const double zl = wz / s;
    q.localBox = Grown({{-1, -1, -zl}, {1, 1, zl}}, 1e-6);
    return q;
}

std::optional<QuarticSurface> QuarticSurface::Torus(const Vec3& center, const Vec3& axis, double R,
                                                    double r, std::string* why) {
    if (!Finite(R) || !Finite(r) || !(r > 0) || !(R > r)) {
        Fail(why, "a torus needs radii 0 < r < R");
        return std::nullopt;
    }
    const Vec3 w = Length(axis) > 0 ? Normalize(axis) : axis;
    std::optional<QuarticSurface> q = EllipticalTorus(
        center, axis, R, Perpendicular(Length(w) > 0 ? w : Vec3{0, 0, 1}) * r, r, why);
    if (!q) return q;
    q->kind = Kind::kTorus;
    q->p = {R, r, 0, 0, 0};
    return q;
}

std::optional<QuarticSurface> QuarticSurface::GeneralCone(const Vec3& V, const Vec3& H,
                                                          const Vec3& A, const Vec3& B, double c,
                                                          double d, std::string* why) {
    if (!IsFinite(V) || !IsFinite(H) || !IsFinite(A) || !IsFinite(B) || !Finite(c) || !Finite(d)) {
        Fail(why, "non-finite parameter");
        return std::nullopt;
    }
    const double a0 = Length(A), b0 = Length(B);
    if (!(a0 > 0) || !(b0 > 0)) {
        Fail(why, "the base semi-axes A and B must be non-zero");
        return std::nullopt;
    }
    if (!(c >= 0) || !(d >= 0)) {
        Fail(why, "the top semi-axes must be >= 0");
        return std::nullopt;
    }
    const Vec3 ua = A / a0, ub = B / b0;
    if (std::fabs(Dot(ua, ub)) > 1e-6) {
        Fail(why, "the semi-axes A and B must be perpendicular");
        return std::nullopt;
    }
    const double hl = Length(H);
    if (!(hl > 0) || std::fabs(Dot(Cross(ua, ub), H)) <= 1e-9 * hl) {
        Fail(why, "the height vector is zero or lies in the plane of A and B");
        return std::nullopt;
    }
    const double s = std::max({a0, b0, c, d});
    Mat4 m = Mat4::Identity();
    for (int r = 0; r < 3; ++r) {
        const std::size_t i = static_cast<std::size_t>(r);
        m(r, 0) = ua[i] * s;
        m(r, 1) = ub[i] * s;
        m(r, 2) = H[i];
        m(r, 3) = V[i];
    }
    const std::optional<Mat4> inv = m.Inverse();
    if (!inv) {
        Fail(why, "the cone's frame is singular");
        return std::nullopt;
    }
    QuarticSurface q;
    q.kind = Kind::kGeneralCone;
    q.p = {a0, b0, c, d, 0};
    q.localFromSpace = Transform(*inv, m);
    q.k = {a0 / s, (c - a0) / s, b0 / s, (d - b0) / s, 0, 0};
    const double mt = kConeSlabMargin;
    auto maxAbs = [&](double k0, double k1) {
        return std::max(std::fabs(k0 - mt * k1), std::fabs(k0 + (1 + mt) * k1));
    };
    const double xa = maxAbs(q.k[0], q.k[1]), yb = maxAbs(q.k[2], q.k[3]);
    q.localBox = {{-xa, -yb, -mt}, {xa, yb, 1 + mt}};
    q.localBox = Grown(q.localBox, 1e-9);
    q.localBox.lo.z = -mt;  // the slab ends stay where documented
    q.localBox.hi.z = 1 + mt;
    return q;
}

std::array<Vec4, 2> QuarticSurface::GeneralConeCaps() const {
    const Mat4& m = localFromSpace.Matrix();
    const Vec4 rowT{m(2, 0), m(2, 1), m(2, 2), m(2, 3)};
    const Vec4 rowW{m(3, 0), m(3, 1), m(3, 2), m(3, 3)};
    Vec4 base{-rowT.x, -rowT.y, -rowT.z, -rowT.w};
    Vec4 top{rowT.x - rowW.x, rowT.y - rowW.y, rowT.z - rowW.z, rowT.w - rowW.w};
    // Unit normals, as the other solids' caps.
    for (Vec4* p : {&base, &top}) {
        const double n = Length(Vec3{p->x, p->y, p->z});
        if (n > 0) *p = Vec4{p->x / n, p->y / n, p->z / n, p->w / n};
    }
    return {base, top};
}

double QuarticSurface::LocalF(const Vec4& L) const {
    if (kind == Kind::kGeneralCone) {
        const double al = k[0] * L.w + k[1] * L.z, be = k[2] * L.w + k[3] * L.z;
        const double a2 = al * al, b2 = be * be;
        return L.x * L.x * b2 + L.y * L.y * a2 - a2 * b2;
    }
    const double r2 = L.x * L.x + L.y * L.y;
    const double E = k[0] * r2 + k[2] * L.z * L.z + k[4] * L.z * L.w + k[5] * L.w * L.w;
    const double O = 2 * k[1] * L.z + k[3] * L.w;
    return E * E - r2 * O * O;
}

double QuarticSurface::Evaluate(const Vec3& p) const {
    const Vec4 L = localFromSpace.Matrix() * Vec4(p, 1);
    const double f = LocalF(L);
    bool inBox = L.w > 0;
    if (inBox) {
        const Vec3 l{L.x / L.w, L.y / L.w, L.z / L.w};
        for (std::size_t i = 0; i < 3; ++i)
            if (l[i] < localBox.lo[i] || l[i] > localBox.hi[i]) inBox = false;
    }
    if (inBox || f > 0) return f;
    return 1;  // outside the clip box: outside
}

Vec4 QuarticSurface::HomogeneousGradient(const Vec3& p) const {
    const Mat4& m = localFromSpace.Matrix();
    const Vec4 L = m * Vec4(p, 1);
    Vec4 g;
    if (kind == Kind::kGeneralCone) {
        const double al = k[0] * L.w + k[1] * L.z, be = k[2] * L.w + k[3] * L.z;
        const double da = 2 * L.y * L.y * al - 2 * al * be * be;
        const double db = 2 * L.x * L.x * be - 2 * al * al * be;
        g = {2 * L.x * be * be, 2 * L.y * al * al, da * k[1] + db * k[3], da * k[0] + db * k[2]};
    } else {
        const double r2 = L.x * L.x + L.y * L.y;
        const double E = k[0] * r2 + k[2] * L.z * L.z + k[4] * L.z * L.w + k[5] * L.w * L.w;
        const double O = 2 * k[1] * L.z + k[3] * L.w;
        const double gx = 2 * (2 * k[0] * E - O * O);
        g = {gx * L.x, gx * L.y, 2 * E * (2 * k[2] * L.z + k[4] * L.w) - 4 * r2 * O * k[1],
             2 * E * (k[4] * L.z + 2 * k[5] * L.w) - 2 * r2 * O * k[3]};
    }
    // Covector pulled back: gᵀ M.
    Vec4 out;
    for (int c = 0; c < 4; ++c)
        out[static_cast<std::size_t>(c)] =
            g.x * m(0, c) + g.y * m(1, c) + g.z * m(2, c) + g.w * m(3, c);
    return out;
}

void QuarticSurface::TransformBy(const Transform& t) {
    localFromSpace = localFromSpace * t.Inverted();
}

bool QuarticSurface::AllFinite() const {
    for (double v : k)
        if (!std::isfinite(v)) return false;
    return localFromSpace.Matrix().AllFinite() && localFromSpace.Inverse().AllFinite();
}

std::array<double, 5> QuarticSurface::LocalLinePolynomial(const Vec4& L0, const Vec4& L1) const {
    const Q2 xx = Mul(L0.x, L1.x, L0.x, L1.x), yy = Mul(L0.y, L1.y, L0.y, L1.y);
    if (kind == Kind::kGeneralCone) {
        const double a0 = k[0] * L0.w + k[1] * L0.z, a1 = k[0] * L1.w + k[1] * L1.z;
        const double b0 = k[2] * L0.w + k[3] * L0.z, b1 = k[2] * L1.w + k[3] * L1.z;
        const Q2 aa = Mul(a0, a1, a0, a1), bb = Mul(b0, b1, b0, b1);
        const Q4 t1 = Mul(xx, bb), t2 = Mul(yy, aa), t3 = Mul(aa, bb);
        return {t1[0] + t2[0] - t3[0], t1[1] + t2[1] - t3[1], t1[2] + t2[2] - t3[2],
                t1[3] + t2[3] - t3[3], t1[4] + t2[4] - t3[4]};
    }
    const Q2 r2 = Add(xx, yy);
    const Q2 zz = Mul(L0.z, L1.z, L0.z, L1.z), zw = Mul(L0.z, L1.z, L0.w, L1.w),
             ww = Mul(L0.w, L1.w, L0.w, L1.w);
    const Q2 E = Add(Add(Scale(k[0], r2), Scale(k[2], zz)), Add(Scale(k[4], zw), Scale(k[5], ww)));
    const double o0 = 2 * k[1] * L0.z + k[3] * L0.w, o1 = 2 * k[1] * L1.z + k[3] * L1.w;
    const Q4 ee = Mul(E, E), ro = Mul(r2, Mul(o0, o1, o0, o1));
    return {ee[0] - ro[0], ee[1] - ro[1], ee[2] - ro[2], ee[3] - ro[3], ee[4] - ro[4]};
}

QuarticLineSet QuarticSurface::OnLine(const Vec4& P0, const Vec4& P1) const {
    QuarticLineSet out;
    const Mat4& m = localFromSpace.Matrix();
    const Vec4 L0 = m * P0, L1 = m * P1;
    // Clip to the box: each face n·L(t) <= 0 is linear in t, and W(t) >= 0.
    double tlo = -HUGE_VAL, thi = HUGE_VAL;
    auto clip = [&](double a, double b) {  // a + b t <= 0
        if (b == 0) {
            if (!(a <= 0)) tlo = HUGE_VAL;  // also for NaN
            return;
        }
        const double r = -a / b;
        if (b > 0)
            thi = std::min(thi, r);
        else
            tlo = std::max(tlo, r);
    };
    clip(-L0.w, -L1.w);
    for (std::size_t i = 0; i < 3; ++i) {
        clip(L0[i] - localBox.hi[i] * L0.w, L1[i] - localBox.hi[i] * L1.w);
        clip(localBox.lo[i] * L0.w - L0[i], localBox.lo[i] * L1.w - L1[i]);
    }
    if (!(tlo < thi)) return out;
    // An unbounded chord (the line's point at infinity maps into the box: only near a
    // perspective eye, which the flattener's near plane removes): bounded conservatively.
    constexpr double kFar = 1e12;
    if (std::isinf(tlo)) tlo = std::min(-kFar, thi - kFar);
    if (std::isinf(thi)) thi = std::max(kFar, tlo + kFar);
    const double tm = 0.5 * (tlo + thi), h = 0.5 * (thi - tlo);
    if (!(h > 0) || !std::isfinite(tm)) return out;
    const Vec4 A{L0.x + tm * L1.x, L0.y + tm * L1.y, L0.z + tm * L1.z, L0.w + tm * L1.w};
    const Vec4 B{h * L1.x, h * L1.y, h * L1.z, h * L1.w};
    const std::array<double, 5> poly = LocalLinePolynomial(A, B);
    std::array<double, 3> slo{}, shi{};
    const int n = NonPositiveSet(poly, -1, 1, slo, shi);
    auto toT = [&](double s) { return s == -1 ? tlo : (s == 1 ? thi : tm + h * s); };
    for (int i = 0; i < n && out.count < 2; ++i) {
        const double a = toT(slo[static_cast<std::size_t>(i)]);
        const double b = toT(shi[static_cast<std::size_t>(i)]);
        if (!(a < b)) continue;
        out.lo[static_cast<std::size_t>(out.count)] = a;
        out.hi[static_cast<std::size_t>(out.count)] = b;
        ++out.count;
    }
    if (n > 2 && out.count == 2) out.hi[1] = toT(shi[static_cast<std::size_t>(n - 1)]);
    return out;
}

Box3 QuarticSurface::SpaceBounds() const {
    const Mat4& inv = localFromSpace.Inverse();
    Box3 b;
    for (int c = 0; c < 8; ++c) {
        const Vec4 l{(c & 1) ? localBox.hi.x : localBox.lo.x,
                     (c & 2) ? localBox.hi.y : localBox.lo.y,
                     (c & 4) ? localBox.hi.z : localBox.lo.z, 1};
        const Vec4 s = inv * l;
        if (!(s.w > 0) || !std::isfinite(s.x + s.y + s.z)) return Box3::Everything();
        b.Extend(Vec3{s.x / s.w, s.y / s.w, s.z / s.w});
    }
    return b;
}

std::vector<Vec4> QuarticSurface::SpaceBoxPlanes() const {
    const Mat4& m = localFromSpace.Matrix();
    auto pull = [&](const Vec4& g) {
        Vec4 out;
        for (int c = 0; c < 4; ++c)
            out[static_cast<std::size_t>(c)] =
                g.x * m(0, c) + g.y * m(1, c) + g.z * m(2, c) + g.w * m(3, c);
        return out;
    };
    std::vector<Vec4> planes;
    for (std::size_t i = 0; i < 3; ++i) {
        Vec4 hi, lo;
        hi[i] = 1;
        hi.w = -localBox.hi[i];
        lo[i] = -1;
        lo.w = localBox.lo[i];
        planes.push_back(pull(hi));
        planes.push_back(pull(lo));
    }
    if (m(3, 0) != 0 || m(3, 1) != 0 || m(3, 2) != 0) planes.push_back(pull({0, 0, 0, -1}));
    return planes;
}

std::string_view QuarticSurface::KindName() const {
    switch (kind) {
        case Kind::kTorus:
            return "torus";
        case Kind::kEllipticalTorus:
            return "elliptical torus";
        case Kind::kGeneralCone:
            return "general cone";
    }
    return "quartic";
}

}  // namespace quadrix
