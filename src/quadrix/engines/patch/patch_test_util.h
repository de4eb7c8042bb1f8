// Test helpers of engines/patch: FlatScenes built by hand (device space = world space) and
// random quadric patches. Header-only, used by the *_test.cpp files of this folder.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/math/mat4.h"
#include "quadrix/math/quadric.h"

namespace quadrix::patch::testing {

// A FlatScene whose device space is world space (identity projection, parallel, viewer toward
// -z), with an ambient and a headlight, to which bodies and CSG solids are added.
class SceneBuilder {
  public:
    SceneBuilder(int width, int height) {
        scene_.width = width;
        scene_.height = height;
        scene_.projection.perspective = false;
        scene_.projection.towardViewer = {0, 0, -1};
        scene::Light ambient;
        ambient.kind = scene::Light::Kind::kAmbient;
        ambient.intensity = 0.1;
        scene::Light head;
        head.kind = scene::Light::Kind::kParallel;
        head.intensity = 0.9;
        head.direction = {0, 0, -1};
        scene_.lights = {ambient, head};
    }

    int AddQuadric(const Quadric& q, bool transparent = false) {
        FlatHalfSpace h;
        h.isPlane = false;
        h.quadric = q;
        h.transparent = transparent;
        h.name = fmt::format("q{}", scene_.halfSpaces.size());
        scene_.halfSpaces.push_back(h);
        return static_cast<int>(scene_.halfSpaces.size()) - 1;
    }
    int AddPlane(const Plane& p, bool transparent = true, bool isClip = false) {
        FlatHalfSpace h;
        h.isPlane = true;
        h.plane = p;
        h.transparent = transparent;
        h.isClip = isClip;
        h.name = fmt::format("p{}", scene_.halfSpaces.size());
        scene_.halfSpaces.push_back(h);
        return static_cast<int>(scene_.halfSpaces.size()) - 1;
    }

    // A body that is its own solid. Returns the body index.
    int AddBody(const std::vector<FlatLiteral>& literals, const Box3& bounds) {
        const int b = AddBodyOnly(literals, bounds);
        FlatCsgNode leaf;
        leaf.isLeaf = true;
        leaf.body = b;
        leaf.bounds = bounds;
        scene_.nodes.push_back(leaf);
        AddSolid(static_cast<int>(scene_.nodes.size()) - 1, bounds);
        scene_.bodies[static_cast<std::size_t>(b)].solid =
            static_cast<int>(scene_.solids.size()) - 1;
        return b;
    }

    // A CSG solid (operator over fresh bodies). Returns the solid index.
    int AddCsg(scene::CsgOp op, const std::vector<std::vector<FlatLiteral>>& bodies,
               const Box3& bounds) {
        FlatCsgNode node;
        node.isLeaf = false;
        node.op = op;
        node.bounds = bounds;
        std::vector<int> bodyIds;
        for (const auto& lits : bodies) {
            const int b = AddBodyOnly(lits, bounds);
            bodyIds.push_back(b);
            FlatCsgNode leaf;
            leaf.body = b;
            leaf.bounds = bounds;
            scene_.nodes.push_back(leaf);
            node.children.push_back(static_cast<int>(scene_.nodes.size()) - 1);
        }
        scene_.nodes.push_back(node);
        AddSolid(static_cast<int>(scene_.nodes.size()) - 1, bounds);
        for (int b : bodyIds)
            scene_.bodies[static_cast<std::size_t>(b)].solid =
                static_cast<int>(scene_.solids.size()) - 1;
        return static_cast<int>(scene_.solids.size()) - 1;
    }

    FlatScene& scene() { return scene_; }

  private:
    int AddBodyOnly(const std::vector<FlatLiteral>& literals, const Box3& bounds) {
        FlatBody body;
        body.literals = literals;
        body.bounds = bounds;
        body.name = fmt::format("b{}", scene_.bodies.size());
        scene_.bodies.push_back(body);
        return static_cast<int>(scene_.bodies.size()) - 1;
    }
    void AddSolid(int root, const Box3& bounds) {
        FlatSolid s;
        s.root = root;
        s.name = fmt::format("s{}", scene_.solids.size());
        s.bounds = bounds.Intersected(
            {{0, 0, -HUGE_VAL},
             {static_cast<double>(scene_.width), static_cast<double>(scene_.height), HUGE_VAL}});
        scene_.solids.push_back(s);
    }

    FlatScene scene_;
};

// x²/rx² + y²/ry² + z²/rz² - 1 at `centre`.
inline Quadric Ellipsoid(const Vec3& centre, const Vec3& radii) {
    Quadric q;
    q.k = {1 / (radii.x * radii.x),
           1 / (radii.y * radii.y),
           1 / (radii.z * radii.z),
           0,
           0,
           0,
           0,
           0,
           0,
           -1};
    return q.Transformed(Transform::Translate(centre));
}

inline Quadric Sphere(const Vec3& centre, double r) { return Ellipsoid(centre, {r, r, r}); }

inline Box3 SphereBox(const Vec3& centre, double r) {
    return {centre - Vec3{r, r, r}, centre + Vec3{r, r, r}};
}

enum class QuadricShape { kEllipsoid, kHyperboloid1, kHyperboloid2, kCone, kCylinder, kParaboloid };

struct RandomBody {
    int body = -1;
    QuadricShape shape = QuadricShape::kEllipsoid;
    int planes = 0;
};

// Adds a random quadric patch body (a rotated quadric of one of the shapes centred in the image at
// depth about 60, with 0..4 random transparent planes, some of them perpendicular to the view,
// some complemented) to `builder`. Ellipsoids get their exact box; other shapes the whole image.
inline RandomBody AddRandomPatch(SceneBuilder& builder, std::mt19937_64& rng, int maxPlanes = 4) {
    FlatScene& scene = builder.scene();
    std::uniform_real_distribution<double> unit(0, 1);
    auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
    const double size = std::min(scene.width, scene.height);
    RandomBody out;
    out.shape = static_cast<QuadricShape>(std::uniform_int_distribution<int>(0, 5)(rng));
    const Vec3 r{uniform(0.15, 0.4) * size, uniform(0.15, 0.4) * size, uniform(0.15, 0.4) * size};
    Quadric q;
    const double ix = 1 / (r.x * r.x), iy = 1 / (r.y * r.y), iz = 1 / (r.z * r.z);
    switch (out.shape) {
        case QuadricShape::kEllipsoid:
            q.k = {ix, iy, iz, 0, 0, 0, 0, 0, 0, -1};
            break;
        case QuadricShape::kHyperboloid1:
            q.k = {ix, iy, -iz, 0, 0, 0, 0, 0, 0, -1};
            break;
        case QuadricShape::kHyperboloid2:
            q.k = {-ix, -iy, iz, 0, 0, 0, 0, 0, 0, -1};
            break;
        case QuadricShape::kCone:
            q.k = {ix, iy, -iz, 0, 0, 0, 0, 0, 0, 0};
            break;
        case QuadricShape::kCylinder:
            q.k = {ix, iy, 0, 0, 0, 0, 0, 0, 0, -1};
            break;
        case QuadricShape::kParaboloid:
            q.k = {ix, iy, 0, 0, 0, 0, 0, 0, -0.5 / r.z, 0};
            break;
    }
    const Vec3 centre{uniform(0.35, 0.65) * scene.width, uniform(0.35, 0.65) * scene.height,
                      uniform(50, 70)};
    const double ax = uniform(0, 360), ay = uniform(0, 360), az = uniform(0, 360);
    const Transform rotation =
        Transform::Rotate(2, az) * Transform::Rotate(1, ay) * Transform::Rotate(0, ax);
    q = q.Transformed(Transform::Translate(centre) * rotation);

    Box3 box = Box3::Everything();
    if (out.shape == QuadricShape::kEllipsoid) {
        // Half-extent along axis i: sqrt(Σ_k R_ik² r_k²) for x = c + R diag(r) u, |u| = 1.
        const Mat4& m = rotation.Matrix();
        Vec3 half;
        for (int i = 0; i < 3; ++i)
            half[static_cast<std::size_t>(i)] =
                std::sqrt(m.m[i][0] * m.m[i][0] * r.x * r.x + m.m[i][1] * m.m[i][1] * r.y * r.y +
                          m.m[i][2] * m.m[i][2] * r.z * r.z);
        box = {centre - half, centre + half};
    }
    std::vector<FlatLiteral> lits{{builder.AddQuadric(q), unit(rng) < 0.3}};
    out.planes = std::uniform_int_distribution<int>(0, maxPlanes)(rng);
    for (int k = 0; k < out.planes; ++k) {
        Vec3 n{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
        if (unit(rng) < 0.2) n.z = 0;  // perpendicular to the view: the CP = 0 branch
        if (Length(n) < 0.2) n = {0.3, 0.5, 0.8};
        n = Normalize(n);
        // n·(p - through) <= 0 keeps the side away from n; `through` lies at -0.3..0.7 of the
        // size along n, so the centre is usually kept and the patch seldom vanishes.
        const double reach = std::fabs(n.x) * r.x + std::fabs(n.y) * r.y + std::fabs(n.z) * r.z;
        const Vec3 through = centre + n * (uniform(-0.3, 0.7) * reach);
        Plane plane{n.x, n.y, n.z, -Dot(n, through)};
        const bool complemented = unit(rng) < 0.5;  // the same half-space written as !(-plane)
        if (complemented) plane = Plane::FromVec4(-plane.AsVec4());
        lits.push_back({builder.AddPlane(plane), complemented});
    }
    out.body = builder.AddBody(lits, box);
    return out;
}

}  // namespace quadrix::patch::testing
