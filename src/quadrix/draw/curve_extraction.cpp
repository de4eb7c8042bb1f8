#include "quadrix/draw/curve_extraction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "quadrix/draw/conic_section.h"
#include "quadrix/draw/quartic_trace.h"

namespace quadrix::draw {

namespace {

// Coefficients of a half-space normalised so that its largest coefficient (the first of the
// largest, within rounding) is +1: equal arrays mean the same surface.
std::array<double, 10> Normalised(const FlatHalfSpace& h, bool& ok) {
    std::array<double, 10> k{};
    if (h.isPlane) {
        k = {h.plane.a, h.plane.b, h.plane.c, h.plane.d, 0, 0, 0, 0, 0, 0};
    } else {
        k = h.quadric.k;
    }
    double mx = 0;
    for (double v : k) mx = std::fmax(mx, std::fabs(v));
    ok = mx > 0 && std::isfinite(mx);
    if (!ok) return k;
    double pivot = 0;
    for (double v : k)
        if (std::fabs(v) >= mx * (1 - 1e-12)) {
            pivot = v;
            break;
        }
    for (double& v : k) v /= pivot;
    return k;
}

}  // namespace

bool LimbPlaneOf(const Quadric& q, Plane& out) {
    // ∂Q/∂z / 2 = F x + E y + C z + J.
    out = Plane{q.F(), q.E(), q.C(), q.J()};
    const double s = std::fabs(q.A()) + std::fabs(q.B()) + std::fabs(q.C()) + std::fabs(q.D()) +
                     std::fabs(q.E()) + std::fabs(q.F());
    const double zs = std::fabs(q.C()) + std::fabs(q.E()) + std::fabs(q.F());
    return s > 0 && zs > 1e-12 * s;
}

Box3 SceneBox(const FlatScene& scene) {
    Box3 box;
    const double L = std::max(scene.width, scene.height);
    const Box3 limit{{-4 * L, -4 * L, -1e3 * L}, {5 * L, 5 * L, 1e3 * L}};
    for (const FlatSolid& s : scene.solids) box.Extend(s.bounds.Intersected(limit));
    // Solid bounds are clipped to the image in x and y; widen by a pixel so edges on the image
    // border stay inside.
    if (!box.Empty()) {
        box.lo -= Vec3{1, 1, 1};
        box.hi += Vec3{1, 1, 1};
    }
    return box;
}

Surfaces ClassifySurfaces(const FlatScene& scene, const Box3& sceneBox) {
    Surfaces s;
    const std::size_t n = scene.halfSpaces.size();
    s.rep.assign(n, -1);
    s.box.assign(n, Box3{});
    s.opaque.assign(n, false);
    // Representatives by a cell of the sum of their normalised coefficients (planes and
    // quadrics apart); a half-space is matched against the representatives of its cell and the
    // two neighbouring ones, coefficient by coefficient within kSame. (Rounding the
    // coefficients to a grid would split equal surfaces whose values straddle a grid line.)
    constexpr double kSame = 1e-9, kCell = 1e-6;
    std::map<std::pair<bool, long long>, std::vector<int>> byCell;
    std::vector<std::array<double, 10>> keys(n);
    std::vector<Box3> own(n);
    for (const FlatBody& b : scene.bodies)
        for (const FlatLiteral& l : b.literals)
            if (l.halfSpace >= 0 && static_cast<std::size_t>(l.halfSpace) < n)
                own[static_cast<std::size_t>(l.halfSpace)].Extend(b.bounds.Intersected(sceneBox));
    for (std::size_t i = 0; i < n; ++i) {
        const FlatHalfSpace& h = scene.halfSpaces[i];
        bool ok = false;
        auto key = Normalised(h, ok);
        if (!ok || own[i].Empty()) continue;
        if (!h.isPlane && h.quadric.IsDegenerateToLinear()) continue;  // rare; not drawn
        keys[i] = key;
        double sum = 0;
        for (double v : key) sum += v;
        const long long cell = static_cast<long long>(std::floor(sum / kCell));
        int r = -1;
        for (long long c = cell - 1; c <= cell + 1 && r < 0; ++c) {
            auto it = byCell.find({h.isPlane, c});
            if (it == byCell.end()) continue;
            for (int cand : it->second) {
                bool same = true;
                for (std::size_t k = 0; k < key.size() && same; ++k)
                    same = std::fabs(keys[static_cast<std::size_t>(cand)][k] - key[k]) <= kSame;
                if (same) {
                    r = cand;
                    break;
                }
            }
        }
        if (r < 0) {
            r = static_cast<int>(i);
            byCell[{h.isPlane, cell}].push_back(r);
            s.reps.push_back(r);
        }
        s.rep[i] = r;
        s.box[static_cast<std::size_t>(r)].Extend(own[i]);
        if (!h.transparent && !h.isClip) s.opaque[static_cast<std::size_t>(r)] = true;
    }
    return s;
}

std::vector<Curve3> ExtractCurves(const FlatScene& scene, const Surfaces& surfaces,
                                  const Box3& /*sceneBox*/, ExtractionCounters& counters) {
    std::vector<Curve3> out;
    const auto& hs = scene.halfSpaces;
    for (std::size_t ia = 0; ia < surfaces.reps.size(); ++ia) {
        const int a = surfaces.reps[ia];
        const FlatHalfSpace& A = hs[static_cast<std::size_t>(a)];
        const Box3& boxA = surfaces.box[static_cast<std::size_t>(a)];
        // Silhouette.
        if (!A.isPlane && surfaces.opaque[static_cast<std::size_t>(a)]) {
            Plane limb;
            if (LimbPlaneOf(A.quadric, limb)) {
                for (Curve3& c : PlaneQuadricCurves(limb, A.quadric, boxA)) {
                    c.role = CurveRole::kSilhouette;
                    c.surfaceA = a;
                    out.push_back(std::move(c));
                    ++counters.silhouettes;
                }
            }
        }
        for (std::size_t ib = ia + 1; ib < surfaces.reps.size(); ++ib) {
            const int b = surfaces.reps[ib];
            if (!surfaces.opaque[static_cast<std::size_t>(a)] &&
                !surfaces.opaque[static_cast<std::size_t>(b)])
                continue;
            const Box3& boxB = surfaces.box[static_cast<std::size_t>(b)];
            if (!boxA.Overlaps(boxB)) continue;
            const Box3 both = boxA.Intersected(boxB);
            const FlatHalfSpace& B = hs[static_cast<std::size_t>(b)];
            std::vector<Curve3> found;
            if (A.isPlane && B.isPlane) {
                Curve3 line;
                if (PlanePlaneLine(A.plane, B.plane, both, line)) {
                    found.push_back(line);
                    ++counters.lines;
                }
            } else if (A.isPlane || B.isPlane) {
                const Plane& p = A.isPlane ? A.plane : B.plane;
                const Quadric& q = A.isPlane ? B.quadric : A.quadric;
                bool tangent = false;
                found = PlaneQuadricCurves(p, q, both, &tangent);
                // A double line: kept as a candidate tangent edge (trim.h decides).
                if (tangent)
                    ++counters.tangentPairs;
                else
                    counters.conics += static_cast<int>(found.size());
            } else {
                found = TraceQuadricQuadric(A.quadric, B.quadric, both);
                counters.quartics += static_cast<int>(found.size());
            }
            for (Curve3& c : found) {
                c.role = CurveRole::kEdge;
                c.surfaceA = a;
                c.surfaceB = b;
                out.push_back(std::move(c));
            }
        }
    }
    return out;
}

}  // namespace quadrix::draw
