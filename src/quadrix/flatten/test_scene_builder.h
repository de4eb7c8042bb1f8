// Builds FlatScenes by hand for engine tests, directly in device space with
// projection.deviceFromWorld = identity (so world normals equal device normals).
//
// Device space (DESIGN.md): x = column, y = row, pixel centres (i+½, j+½), rays along +z, z grows
// away from the viewer. Bounds default to Box3::Everything() (always correct, never culls); pass
// real bounds to exercise the engine's culling.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"

namespace quadrix::testing_util {

class TestSceneBuilder {
  public:
    TestSceneBuilder(int width, int height) {
        scene_.width = width;
        scene_.height = height;
    }

    // Half-spaces; each returns its index.
    int AddPlane(double a, double b, double c, double d, bool transparent = false) {
        FlatHalfSpace h;
        h.isPlane = true;
        h.plane = {a, b, c, d};
        h.transparent = transparent;
        return Add(std::move(h));
    }
    int AddQuadric(const std::array<double, 10>& k, bool transparent = false) {
        FlatHalfSpace h;
        h.isPlane = false;
        h.quadric = quadrix::Quadric::FromCoefficients(k);
        h.transparent = transparent;
        return Add(std::move(h));
    }
    // |x − c|² − r² <= 0.
    int AddSphere(const Vec3& c, double r) {
        return AddQuadric({1, 1, 1, 0, 0, 0, -c.x, -c.y, -c.z, Dot(c, c) - r * r});
    }
    // A clipping plane (transparent, drawn never) as the Flattener adds them.
    int AddClipPlane(double a, double b, double c, double d) {
        int i = AddPlane(a, b, c, d, true);
        scene_.halfSpaces[static_cast<std::size_t>(i)].isClip = true;
        return i;
    }

    // A body: the intersection of literals (half-space index, complemented).
    int AddBody(const std::vector<std::pair<int, bool>>& literals,
                const Box3& bounds = Box3::Everything()) {
        FlatBody b;
        for (auto [hs, complemented] : literals) b.literals.push_back({hs, complemented});
        b.bounds = bounds;
        scene_.bodies.push_back(std::move(b));
        return static_cast<int>(scene_.bodies.size() - 1);
    }

    // CSG nodes; each returns its node index.
    int AddLeaf(int body, const Box3& bounds = Box3::Everything()) {
        FlatCsgNode n;
        n.isLeaf = true;
        n.body = body;
        n.bounds = bounds;
        scene_.nodes.push_back(std::move(n));
        return static_cast<int>(scene_.nodes.size() - 1);
    }
    int AddNode(scene::CsgOp op, std::vector<int> children,
                const Box3& bounds = Box3::Everything()) {
        FlatCsgNode n;
        n.isLeaf = false;
        n.op = op;
        n.children = std::move(children);
        n.bounds = bounds;
        scene_.nodes.push_back(std::move(n));
        return static_cast<int>(scene_.nodes.size() - 1);
    }

    // A solid over a node tree; marks its bodies as belonging to it.
    int AddSolid(int root, const Box3& bounds = Box3::Everything()) {
        FlatSolid s;
        s.root = root;
        s.bounds = bounds;
        scene_.solids.push_back(std::move(s));
        int index = static_cast<int>(scene_.solids.size() - 1);
        MarkBodies(root, index);
        return index;
    }
    // A solid made of one body (leaf and solid share the body's bounds).
    int AddSolidOfBody(int body) {
        const Box3 b = scene_.bodies[static_cast<std::size_t>(body)].bounds;
        return AddSolid(AddLeaf(body, b), b);
    }

    FlatScene& scene() { return scene_; }

    // A copy of the scene with every bound set to Everything() (disables all culling).
    FlatScene WithoutBounds() const {
        FlatScene s = scene_;
        for (FlatBody& b : s.bodies) b.bounds = Box3::Everything();
        for (FlatCsgNode& n : s.nodes) n.bounds = Box3::Everything();
        for (FlatSolid& v : s.solids) v.bounds = Box3::Everything();
        return s;
    }

  private:
    int Add(FlatHalfSpace h) {
        scene_.halfSpaces.push_back(std::move(h));
        return static_cast<int>(scene_.halfSpaces.size() - 1);
    }
    void MarkBodies(int node, int solid) {
        const FlatCsgNode& n = scene_.nodes[static_cast<std::size_t>(node)];
        if (n.isLeaf) {
            scene_.bodies[static_cast<std::size_t>(n.body)].solid = solid;
            return;
        }
        for (int c : n.children) MarkBodies(c, solid);
    }

    FlatScene scene_;
};

// Bounds of a sphere, widened by `margin` (conservative).
inline Box3 SphereBounds(const Vec3& c, double r, double margin = 1e-6) {
    Vec3 e{r + margin, r + margin, r + margin};
    return {c - e, c + e};
}

// True when some depth is NaN or a covered pixel has no normal (a NaN, infinite or zero normal
// packs as the zero vector, frame/packed_normal.h).
inline bool FrameHasNaN(const Frame& f) {
    for (float d : f.depth)
        if (std::isnan(d)) return true;
    for (std::size_t i = 0; i < f.normal.size(); ++i)
        if (f.surface[i] != Frame::kNone && f.normal[i] == PackedNormal{}) return true;
    return false;
}

}  // namespace quadrix::testing_util
