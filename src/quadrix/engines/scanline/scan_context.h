// What the phases of engine `scanline`'s Renderer (seed 001 chapter 5) share while they draw one
// band of rows: the scene and the Resolver's output (show-edges, show-faces, §4.1), the units to
// draw, the settings, the Frame and the band's counters, the exact per-ray evaluator
// (ray_evaluator.h), and the per-body facts every phase looks up: each body's unit, its
// show-faces, and whether it is drawn from the face stacks of §5.2–5.4 (face_stack.h). Each phase
// keeps its own state in its own class (edge_list.h, vertex_processing.h, face_stack.h,
// stack_verifier.h, row_bodies.h, csg_spans.h, span_shader.h); renderer.cpp composes them.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "quadrix/engines/scanline/depth_order.h"
#include "quadrix/engines/scanline/renderer.h"
#include "quadrix/engines/scanline/resolver.h"
#include "quadrix/eval/ray_evaluator.h"
#include "quadrix/frame/frame.h"

namespace quadrix::scanline {

struct VertexTable;  // vertex_table.h

struct ScanContext {
    ScanContext(const FlatScene& scene, std::vector<ShowEdge>& edges,
                const std::vector<ShowFace>& faces, const std::vector<Unit>& units,
                const std::vector<bool>& pixelBody, const std::vector<bool>& stackBody,
                const VertexTable& vt, const RenderSettings& settings, Frame& frame,
                RendererCounters& c);

    const FlatScene& scene;
    const VertexTable& vt;
    std::vector<ShowEdge>& edges;
    const std::vector<ShowFace>& faces;
    const std::vector<Unit>& units;
    const std::vector<bool>& pixelBody;  // bodies the Resolver refused: exact per pixel
    const RenderSettings& settings;
    Frame& frame;
    RendererCounters& c;
    eval::RayEvaluator eval;
    std::vector<int> bodyUnit;                // body → its kBody unit (−1: a CSG operand)
    std::vector<std::vector<int>> bodyFaces;  // body → its show-faces
    std::vector<char> useStack;               // body drawn from the face stacks
    bool stackOn = false;                     // some body is drawn from face stacks

    const ShowEdge& Edge(int e) const { return edges[static_cast<std::size_t>(e)]; }
    const ShowFace& Face(int f) const { return faces[static_cast<std::size_t>(f)]; }
    const Unit& UnitOf(int u) const { return units[static_cast<std::size_t>(u)]; }
    int SheetOf(int face) const { return Face(face).sheet == Sheet::kBack ? 1 : 0; }
    FaceRef RefOf(int face) const { return {Face(face).halfSpace, SheetOf(face)}; }
    // The unit's bounds hold row j (and it has pixels).
    bool RowActive(int u, int j) const {
        const Unit& unit = UnitOf(u);
        return j >= unit.y0 && j <= unit.y1 && unit.x1 >= unit.x0;
    }

    // Does a hit of unit u on half-space hs win an exact depth tie (at depth t, pixel centre
    // (x, y)) against one of unit v on half-space hv? Raycast's rules (renderer.h, Unit): the
    // lower solid; within a union of bodies the union's interval fold, which is opened by its left
    // operand's start and closed by its right operand's end on a tie, so the lower unit for
    // entries and the higher one for exits (a body's exit is visible where a transparent plane
    // clips it). Only called on exact ties, so the facing test costs nothing elsewhere.
    bool UnitWinsTie(int u, int hs, int v, int hv, double x, double y, double t) const {
        if (v < 0) return true;
        if (u == v) return false;
        const Unit& a = UnitOf(u);
        const Unit& b = UnitOf(v);
        if (a.solid != b.solid) return a.solid < b.solid;
        if (a.kind == Unit::Kind::kBody && b.kind == Unit::Kind::kBody &&
            IsExit(a.body, hs, x, y, t) && IsExit(b.body, hv, x, y, t))
            return u > v;
        return u < v;
    }
    // Is the point at depth t of half-space hs on the ray through (x, y) where `body` leaves the
    // literal (its ray function grows through zero, or falls for a complemented literal)?
    bool IsExit(int body, int hs, double x, double y, double t) const {
        if (body < 0 || static_cast<std::size_t>(body) >= scene.bodies.size()) return false;
        bool complemented = false;
        for (const FlatLiteral& l : scene.bodies[static_cast<std::size_t>(body)].literals)
            if (l.halfSpace == hs) complemented = l.complemented;
        const eval::RayHalfSpace& r = eval.Ray(hs);
        const double slope =
            r.isPlane ? r.c : r.c * (t - r.z0) + r.hx * (x - r.x0) + r.hy * (y - r.y0) + r.h0;
        return (slope > 0) != complemented;
    }
};

// Depth first over the valid nodes of the CSG tree at `root` (the last child first): fn(node,
// depth) with the root at depth 1.
template <class Fn>
void VisitTree(const FlatScene& scene, int root, Fn&& fn) {
    const std::size_t nn = scene.nodes.size();
    std::vector<std::pair<int, std::size_t>> todo{{root, 1}};
    while (!todo.empty()) {
        auto [n, d] = todo.back();
        todo.pop_back();
        if (n < 0 || static_cast<std::size_t>(n) >= nn) continue;
        fn(n, d);
        const FlatCsgNode& node = scene.nodes[static_cast<std::size_t>(n)];
        if (!node.isLeaf)
            for (int c : node.children) todo.push_back({c, d + 1});
    }
}

}  // namespace quadrix::scanline
