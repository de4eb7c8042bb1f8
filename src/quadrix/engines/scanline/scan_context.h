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
#include "quadrix/engines/scanline/ray_evaluator.h"
#include "quadrix/engines/scanline/renderer.h"
#include "quadrix/engines/scanline/resolver.h"
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
    RayEvaluator eval;
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
