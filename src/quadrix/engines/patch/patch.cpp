#include "quadrix/engines/patch/patch.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace quadrix::patch {
namespace {

// First pixel index whose centre i + ½ is >= lo, clamped to [0, size].
int FirstCentreAtOrAbove(double lo, int size) {
    const double i = std::ceil(lo - 0.5);
    return static_cast<int>(std::clamp(i, 0.0, static_cast<double>(size)));
}

// One past the last pixel index whose centre i + ½ is <= hi, clamped to [0, size].
int EndCentreAtOrBelow(double hi, int size) {
    const double i = std::floor(hi - 0.5) + 1;
    return static_cast<int>(std::clamp(i, 0.0, static_cast<double>(size)));
}

// Largest value of the plane's function over the box, with the sum's rounding scale. Infinite
// box sides are fine: a zero coefficient contributes nothing, others contribute ±inf.
struct PlaneMax {
    double max = 0, scale = 0;
};
PlaneMax MaxOverBox(const Plane& p, const Box3& box) {
    PlaneMax r{p.d, std::fabs(p.d)};
    const double coef[3] = {p.a, p.b, p.c};
    for (std::size_t i = 0; i < 3; ++i) {
        if (coef[i] == 0) continue;
        const double v = coef[i] > 0 ? coef[i] * box.hi[i] : coef[i] * box.lo[i];
        r.max += v;
        r.scale += std::fabs(v);
    }
    return r;
}

bool AllFinite(const Plane& p) { return p.AllFinite(); }

}  // namespace

PixelWindow WindowOfBox(const Box3& box, int width, int height) {
    if (box.Empty() || width <= 0 || height <= 0) return {};
    if (std::isnan(box.lo.x) || std::isnan(box.lo.y) || std::isnan(box.hi.x) ||
        std::isnan(box.hi.y))
        return {0, 0, width, height};
    PixelWindow w{FirstCentreAtOrAbove(box.lo.x, width), FirstCentreAtOrAbove(box.lo.y, height),
                  EndCentreAtOrBelow(box.hi.x, width), EndCentreAtOrBelow(box.hi.y, height)};
    if (w.Empty()) return {};
    return w;
}

std::string_view RejectionName(Rejection why) {
    switch (why) {
        case Rejection::kNone:
            return "converted";
        case Rejection::kEmpty:
            return "empty";
        case Rejection::kInvisible:
            return "invisible (transparent quadric)";
        case Rejection::kNoQuadric:
            return "no quadric";
        case Rejection::kSeveralQuadrics:
            return "more than one quadric";
        case Rejection::kTooManyPlanes:
            return "more than four cutting planes";
        case Rejection::kOpaquePlaneFace:
            return "opaque plane face (caps=skip)";
        case Rejection::kViewAlongSurface:
            return "C = 0 (view direction along the quadric)";
        case Rejection::kNotFinite:
            return "non-finite coefficients";
        case Rejection::kMalformed:
            return "literal naming no half-space";
    }
    return "?";
}

Conversion ConvertBody(const FlatScene& scene, int bodyIndex, CapPolicy caps) {
    Conversion out;
    const FlatBody& body = scene.bodies[static_cast<std::size_t>(bodyIndex)];
    if (body.bounds.Empty() || body.literals.empty()) {
        out.why = Rejection::kEmpty;
        return out;
    }

    int quadricLiteral = -1, quadrics = 0;
    struct KeptPlane {
        BoundingPlane bp;
        bool opaque;
    };
    std::vector<KeptPlane> kept;
    for (const FlatLiteral& lit : body.literals) {
        if (lit.halfSpace < 0 || lit.halfSpace >= static_cast<int>(scene.halfSpaces.size())) {
            out.why = Rejection::kMalformed;
            return out;
        }
        const FlatHalfSpace& hs = scene.halfSpaces[static_cast<std::size_t>(lit.halfSpace)];
        if (!hs.isPlane) {
            ++quadrics;
            quadricLiteral = lit.halfSpace;
            if (!hs.quadric.AllFinite()) {
                out.why = Rejection::kNotFinite;
                return out;
            }
            continue;
        }
        if (!AllFinite(hs.plane)) {
            out.why = Rejection::kNotFinite;
            return out;
        }
        Plane p = hs.plane;
        if (lit.complemented) p = Plane::FromVec4(-p.AsVec4());
        if (p.IsZeroNormal()) {  // 0 x + 0 y + 0 z + d <= 0: everywhere or nowhere
            if (p.d <= 0) {
                ++out.planesDropped;
                continue;
            }
            out.why = Rejection::kEmpty;
            return out;
        }
        // Redundant when the plane's function is negative over the whole box: its boundary does
        // not meet the box, which contains the body. The margin covers the rounding of the sum.
        const PlaneMax m = MaxOverBox(p, body.bounds);
        if (m.max < -1e-9 * m.scale) {
            ++out.planesDropped;
            continue;
        }
        // Clipping planes bound but are never drawn, like transparent ones.
        kept.push_back({{p, lit.halfSpace}, !hs.transparent && !hs.isClip});
    }

    if (quadrics == 0) {
        out.why = Rejection::kNoQuadric;
        return out;
    }
    if (quadrics > 1) {
        out.why = Rejection::kSeveralQuadrics;
        return out;
    }
    const bool anyOpaquePlane =
        std::any_of(kept.begin(), kept.end(), [](const KeptPlane& k) { return k.opaque; });
    const FlatHalfSpace& qhs = scene.halfSpaces[static_cast<std::size_t>(quadricLiteral)];
    if (qhs.transparent || qhs.isClip) {
        out.why = anyOpaquePlane && caps == CapPolicy::kSkip ? Rejection::kOpaquePlaneFace
                                                             : Rejection::kInvisible;
        return out;
    }
    if (anyOpaquePlane) {
        if (caps == CapPolicy::kSkip) {
            out.why = Rejection::kOpaquePlaneFace;
            return out;
        }
        out.drawnOpen = true;
    }
    if (static_cast<int>(kept.size()) > kMaxPlanes) {
        out.why = Rejection::kTooManyPlanes;
        out.drawnOpen = false;
        return out;
    }

    QuadricPatch patch;
    patch.quadric = qhs.quadric;
    if (patch.quadric.C() == 0) {
        out.why = Rejection::kViewAlongSurface;
        out.drawnOpen = false;
        return out;
    }
    if (patch.quadric.C() < 0)
        for (double& k : patch.quadric.k) k = -k;  // same surface; C > 0 (see patch.h)
    patch.planeCount = static_cast<int>(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) patch.planes[i] = kept[i].bp;
    patch.box = body.bounds;
    patch.window = WindowOfBox(body.bounds, scene.width, scene.height);
    if (patch.window.Empty()) {
        out.why = Rejection::kEmpty;
        out.drawnOpen = false;
        return out;
    }
    patch.surface = quadricLiteral;
    patch.body = bodyIndex;
    patch.solid = body.solid;
    out.patch = patch;
    return out;
}

Vec3 WorldNormalFromDeviceGradient(const FlatScene& scene, const Vec3& p, const Vec3& g) {
    const Vec4 g4{g, -Dot(p, g)};
    const Mat4& m = scene.projection.deviceFromWorld.Matrix();
    const Vec3 n{m.m[0][0] * g4.x + m.m[1][0] * g4.y + m.m[2][0] * g4.z + m.m[3][0] * g4.w,
                 m.m[0][1] * g4.x + m.m[1][1] * g4.y + m.m[2][1] * g4.z + m.m[3][1] * g4.w,
                 m.m[0][2] * g4.x + m.m[1][2] * g4.y + m.m[2][2] * g4.z + m.m[3][2] * g4.w};
    return Normalize(n);
}

}  // namespace quadrix::patch
