// The scanline engine's complexity guard on overlapping bodies (issue 23, item 3).
//
// Cost model. Where k bodies drawn on their own overlap on screen, every row carries face stacks
// of about 2k faces (a front and a back face per body) and the §5.3–5.4 updates re-order them at
// every crossing: measured about cubic in k (a union of n copies of one ball at 64×64, one core:
// n = 100 → 0.05 s, 200 → 0.38 s, 1,000 → 45 s; docs/performance.md "Complexity guards"). The
// exact span path (render=exact) is no cure: the row has O(k) spans and each evaluates O(k)
// bodies (1,000 balls: 3 s at 64×64, 27 s at 512×512). raycast, whose per-pixel union of
// coincident intervals is linear in k, draws the same solid in 0.1 s.
//
// Guard. The image is cut into cells of kCellSize × kCellSize pixels; the depth complexity of a
// cell is the number of body units (Unit::Kind::kBody) whose pixel box covers it, counted with a
// 2-D difference array in O(units + cells). A solid with a body unit covering a cell of depth
// complexity above maxOverlap is left out and reported undrawn: the render context draws it with
// raycast and composes the Frames by depth (pipeline/render_context.h), so the picture is exact
// and the cost of the rest stays the scanline engine's. Box overlap over-estimates true overlap
// (boxes of disjoint spheres may cover one cell), which only ever hands more to raycast.
// CSG units are not counted: their spans evaluate per-span body templates whose cost is linear in
// the operands that reach the span (measured: 400 shifted balls minus a plane, 0.06 s).
#pragma once

#include <vector>

#include "quadrix/engines/scanline/renderer.h"

namespace quadrix::scanline {

inline constexpr int kCellSize = 8;

struct OverlapReport {
    std::vector<int> solids;  // solids to hand to raycast, ascending, unique
    int maxDepth = 0;         // the largest cell depth complexity seen
};

// The solids whose body units reach a cell covered by more than maxOverlap body units (see the
// header). Units with an empty pixel range (x1 < x0 or y1 < y0) are ignored.
OverlapReport OverloadedSolids(const std::vector<Unit>& units, int width, int height,
                               int maxOverlap);

}  // namespace quadrix::scanline
