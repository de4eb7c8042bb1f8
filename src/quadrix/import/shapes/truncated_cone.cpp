// Truncated general cones: the quadric with similar ends, the quartic otherwise (truncated_cone.h).
#include "quadrix/import/shapes/truncated_cone.h"

#include <cmath>
#include <string>
#include <utility>

#include "quadrix/import/shapes/local_frame.h"
#include "quadrix/math/quartic_surface.h"

namespace quadrix::import {

namespace {

ConeShape Refused(std::string why, bool quartic = false) {
    ConeShape r;
    r.problem = std::move(why);
    r.quartic = quartic;
    return r;
}

// Ends that are not similar: the quartic general cone capped by the planes of its end ellipses.
ConeShape GeneralCone(const Vec3& v, const Vec3& h, const Vec3& a, const Vec3& b, const Vec3& c,
                      const Vec3& d) {
    std::string why;
    auto q = QuarticSurface::GeneralCone(v, h, a, b, Length(c), Length(d), &why);
    if (!q) return Refused(why, true);
    ConeShape r;
    r.ok = true;
    r.quartic = true;
    ShapeHalfSpace cone;
    cone.SetQuartic(*q);
    ShapeBody body{cone};
    for (const Vec4& cap : q->GeneralConeCaps()) {
        ShapeHalfSpace p;
        p.plane = Plane::FromVec4(cap);
        body.push_back(p);
    }
    r.shape.bodies.push_back(std::move(body));
    auto unit = [](const Vec3& u) { return Length(u) > 0 ? Normalize(u) : Vec3{}; };
    r.shape.extent.push_back({v, a, b, {}});
    r.shape.extent.push_back({v + h, unit(a) * Length(c), unit(b) * Length(d), {}});
    r.shape.extentExact = true;  // on each ruling a coordinate is linear: its ends decide
    return r;
}

}  // namespace

std::optional<ShapeBody> SimilarConeBody(const Vec3& v, const Vec3& a, const Vec3& b, const Vec3& h,
                                         double k) {
    LocalFrame f(v, a, b, h);
    if (!f.ok()) return std::nullopt;
    // α² + β² - (1 + (k-1)s)² <= 0 in (u1, u2, u3) = (α, β, s).
    double km = k - 1;
    Mat4 q = DiagonalQuadric(1, 1, -km * km, -1);
    q.m[2][3] = q.m[3][2] = -km;
    return ShapeBody{f.Quad(q), f.Plane4(0, 0, -1, 0), f.Plane4(0, 0, 1, -1)};
}

ConeShape TruncatedConeShape(const Vec3& v0, const Vec3& h0, const Vec3& a0, const Vec3& b0,
                             const Vec3& c0, const Vec3& d0) {
    Vec3 v = v0, h = h0, a = a0, b = b0, c = c0, d = d0;
    double la = Length(a), lb = Length(b), lc = Length(c), ld = Length(d);
    if (Length(h) == 0) return Refused("the height vector H is zero");
    if ((la == 0 || lb == 0) && (lc == 0 || ld == 0))
        return Refused("both end ellipses are degenerate");
    // C must be parallel to A and D to B, in the same sense (librt's tgc); a zero C or D is a
    // degenerate end.
    auto parallel = [](const Vec3& u, const Vec3& w) {
        const double lu = Length(u), lw = Length(w);
        return lu == 0 || lw == 0 || Length(u / lu - w / lw) <= 1e-4;
    };
    if (!parallel(a, c) || !parallel(b, d)) return Refused("C must be parallel to A and D to B");
    double ad = la * ld, bc = lb * lc;
    if (std::fabs(ad - bc) > kSimilarEndsTol * std::fmax(ad, bc))
        return GeneralCone(v0, h0, a0, b0, c0, d0);
    if (la == 0 || lb == 0) {  // apex at the base: describe it from the top end
        v = v + h;
        h = -h;
        std::swap(a, c);
        std::swap(b, d);
        std::swap(la, lc);
        std::swap(lb, ld);
    }
    const double k = lc / la;
    auto body = SimilarConeBody(v, a, b, h, k);
    if (!body) return Refused("A, B and H are coplanar");
    ConeShape r;
    r.ok = true;
    r.shape.bodies.push_back(std::move(*body));
    r.shape.extent.push_back({v, a, b, {}});
    r.shape.extent.push_back({v + h, a * k, b * k, {}});
    r.shape.extentExact = true;
    return r;
}

}  // namespace quadrix::import
