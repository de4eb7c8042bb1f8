// Helpers for the Flatten* tests: scenes built programmatically (the language reader is not
// needed), in the shape the reader produces, and a comparison of flat scenes.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "quadrix/flatten/flat_scene.h"
#include "quadrix/scene/scene.h"

namespace quadrix::flatten_test {

inline SourceLoc Loc(int line, int column = 1) {
    static const auto file = std::make_shared<const std::string>("test.uq");
    return SourceLoc{file, line, column};
}

inline int AddPlane(scene::Scope& s, const std::string& id, const Plane& p,
                    bool transparent = false) {
    scene::HalfSpace h;
    h.id = id;
    h.kind = scene::HalfSpace::Kind::kPlane;
    h.plane = p;
    h.transparent = transparent;
    s.halfSpaces.push_back(h);
    return static_cast<int>(s.halfSpaces.size()) - 1;
}

inline int AddQuadric(scene::Scope& s, const std::string& id, const std::array<double, 10>& k) {
    scene::HalfSpace h;
    h.id = id;
    h.kind = scene::HalfSpace::Kind::kQuadric;
    h.quadric = Quadric::FromCoefficients(k);
    s.halfSpaces.push_back(h);
    return static_cast<int>(s.halfSpaces.size()) - 1;
}

// Sphere (x-cx)² + (y-cy)² + (z-cz)² <= r² in UniQuadrix coefficients.
inline int AddSphere(scene::Scope& s, const std::string& id, const Vec3& c, double r) {
    return AddQuadric(s, id, {1, 1, 1, 0, 0, 0, -c.x, -c.y, -c.z, Dot(c, c) - r * r});
}

// literals: half-space index, negative = complemented (~index).
inline int AddBody(scene::Scope& s, const std::string& id, const std::vector<int>& literals,
                   std::optional<scene::Color> color = std::nullopt, int line = 0) {
    scene::Body b;
    b.id = id;
    for (int l : literals) b.literals.push_back({l >= 0 ? l : ~l, l < 0});
    b.color = color;
    b.loc = Loc(line);
    s.bodies.push_back(b);
    return static_cast<int>(s.bodies.size()) - 1;
}

inline int AddInstance(scene::Scope& s, const std::string& id, int definition,
                       const Transform& init, int count = 1, const Transform& delta = {},
                       std::optional<scene::Color> color = std::nullopt) {
    scene::Instance inst;
    inst.id = id;
    inst.definition = definition;
    inst.init = init;
    inst.count = count;
    inst.delta = delta;
    inst.isArray = count != 1 || id.find("array") != std::string::npos;
    inst.color = color;
    s.instances.push_back(inst);
    return static_cast<int>(s.instances.size()) - 1;
}

// A small CSG expression builder producing the reader's binary node layout.
struct CsgBuilder {
    scene::Csg csg;
    int Leaf(scene::SolidRef::Kind kind, int index) {
        scene::CsgNode n;
        n.isLeaf = true;
        n.ref = {kind, index};
        csg.nodes.push_back(n);
        return static_cast<int>(csg.nodes.size()) - 1;
    }
    int Body(int i) { return Leaf(scene::SolidRef::Kind::kBody, i); }
    int Inst(int i) { return Leaf(scene::SolidRef::Kind::kInstance, i); }
    int Csg(int i) { return Leaf(scene::SolidRef::Kind::kCsg, i); }
    int Op(scene::CsgOp op, int l, int r) {
        scene::CsgNode n;
        n.isLeaf = false;
        n.op = op;
        n.left = l;
        n.right = r;
        csg.nodes.push_back(n);
        return static_cast<int>(csg.nodes.size()) - 1;
    }
};

// Adds the csg to the scope and marks its leaves' targets as operands.
inline int AddCsg(scene::Scope& s, const std::string& id, CsgBuilder b, int root,
                  std::optional<scene::Color> color = std::nullopt) {
    b.csg.id = id;
    b.csg.root = root;
    b.csg.color = color;
    for (const scene::CsgNode& n : b.csg.nodes) {
        if (!n.isLeaf) continue;
        switch (n.ref.kind) {
            case scene::SolidRef::Kind::kBody:
                s.bodies[n.ref.index].usedAsOperand = true;
                break;
            case scene::SolidRef::Kind::kInstance:
                s.instances[n.ref.index].usedAsOperand = true;
                break;
            case scene::SolidRef::Kind::kCsg:
                s.csgs[n.ref.index].usedAsOperand = true;
                break;
        }
    }
    s.csgs.push_back(b.csg);
    return static_cast<int>(s.csgs.size()) - 1;
}

// Two flat scenes with the same half-spaces, bodies, nodes, solids and projection: every field a
// flatten makes, coefficients and boxes compared by their bits.
inline void ExpectSameFlatScenes(const FlatScene& a, const FlatScene& b) {
    auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof x) == 0; };
    ASSERT_EQ(a.halfSpaces.size(), b.halfSpaces.size());
    for (std::size_t h = 0; h < a.halfSpaces.size(); ++h) {
        const FlatHalfSpace& x = a.halfSpaces[h];
        const FlatHalfSpace& y = b.halfSpaces[h];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.isPlane, y.isPlane);
        EXPECT_EQ(x.transparent, y.transparent);
        EXPECT_EQ(x.isClip, y.isClip);
        EXPECT_TRUE(x.isPlane ? same(x.plane, y.plane) : same(x.quadric, y.quadric)) << h;
    }
    ASSERT_EQ(a.bodies.size(), b.bodies.size());
    for (std::size_t k = 0; k < a.bodies.size(); ++k) {
        const FlatBody& x = a.bodies[k];
        const FlatBody& y = b.bodies[k];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.solid, y.solid);
        EXPECT_TRUE(same(x.bounds, y.bounds)) << k;
        EXPECT_TRUE(same(x.color, y.color)) << k;
        ASSERT_EQ(x.literals.size(), y.literals.size());
        for (std::size_t l = 0; l < x.literals.size(); ++l) {
            EXPECT_EQ(x.literals[l].halfSpace, y.literals[l].halfSpace);
            EXPECT_EQ(x.literals[l].complemented, y.literals[l].complemented);
        }
    }
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (std::size_t n = 0; n < a.nodes.size(); ++n) {
        EXPECT_EQ(a.nodes[n].isLeaf, b.nodes[n].isLeaf);
        EXPECT_EQ(a.nodes[n].body, b.nodes[n].body);
        EXPECT_EQ(a.nodes[n].op, b.nodes[n].op);
        EXPECT_EQ(a.nodes[n].children, b.nodes[n].children);
        EXPECT_TRUE(same(a.nodes[n].bounds, b.nodes[n].bounds)) << n;
    }
    ASSERT_EQ(a.solids.size(), b.solids.size());
    for (std::size_t s = 0; s < a.solids.size(); ++s) {
        EXPECT_EQ(a.solids[s].root, b.solids[s].root);
        EXPECT_EQ(a.solids[s].name, b.solids[s].name);
        EXPECT_TRUE(same(a.solids[s].bounds, b.solids[s].bounds)) << s;
    }
    EXPECT_TRUE(same(a.projection.deviceFromWorld, b.projection.deviceFromWorld));
    EXPECT_EQ(a.sectionHalfSpace, b.sectionHalfSpace);
}

}  // namespace quadrix::flatten_test
