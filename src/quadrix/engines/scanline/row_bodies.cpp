#include "quadrix/engines/scanline/row_bodies.h"

#include <algorithm>

#include "quadrix/engines/scanline/pixel_range.h"

namespace quadrix::scanline {
// Per unit its refused bodies and the bodies that may cover an image side (for CSG units: the
// operands of its tree), and the units sorted on y0.
RowBodies::RowBodies(ScanContext& ctx) : ctx_(ctx) {
    const FlatScene& scene = ctx.scene;
    const std::vector<Unit>& units = ctx.units;
    const std::size_t nb = scene.bodies.size();
    unitPixelBodies_.assign(units.size(), {});
    unitSideBodies_.assign(units.size(), {});
    const int w = ctx.frame.width;
    for (std::size_t u = 0; u < units.size(); ++u) {
        const Unit& unit = units[u];
        if (unit.kind == Unit::Kind::kBody) {
            const auto b = static_cast<std::size_t>(unit.body);
            if (ctx.pixelBody[b]) {
                unitPixelBodies_[u].push_back(unit.body);
            } else if (!ctx.useStack[b] && (unit.x0 == 0 || unit.x1 == w - 1)) {
                unitSideBodies_[u].push_back(
                    {unit.body, unit.x0 == 0, unit.x1 == w - 1, unit.y0, unit.y1});
            }
            continue;
        }
        VisitTree(scene, unit.node, [&](int n, std::size_t) {
            const FlatCsgNode& node = scene.nodes[static_cast<std::size_t>(n)];
            if (!node.isLeaf) return;
            if (node.body < 0 || static_cast<std::size_t>(node.body) >= nb) return;
            const auto b = static_cast<std::size_t>(node.body);
            if (ctx.pixelBody[b]) {
                unitPixelBodies_[u].push_back(node.body);
                return;
            }
            const Box3& box = scene.bodies[b].bounds;
            if (box.Empty()) return;
            int x0, x1, y0, y1;
            PixelRange(box.lo.x, box.hi.x, w, x0, x1);
            PixelRange(box.lo.y, box.hi.y, ctx.frame.height, y0, y1);
            if (x1 < x0 || y1 < y0) return;
            if (x0 == 0 || x1 == w - 1)
                unitSideBodies_[u].push_back({node.body, x0 == 0, x1 == w - 1, y0, y1});
        });
    }
    unitsByY_.resize(units.size());
    for (std::size_t u = 0; u < units.size(); ++u) unitsByY_[u] = static_cast<int>(u);
    std::stable_sort(unitsByY_.begin(), unitsByY_.end(), [&](int p, int q) {
        return units[static_cast<std::size_t>(p)].y0 < units[static_cast<std::size_t>(q)].y0;
    });
    lo_.assign(nb, HUGE_VAL);
    hi_.assign(nb, -HUGE_VAL);
    rangeRow_.assign(nb, -1);
    ownPassed_.assign(nb, 0);
}

// Per-body x ranges on row j: the crossings of the body's show-edges, opened toward an image
// side when the body covers that side's pixel; refused bodies: their unit's bounds. Only bodies
// met on this row are touched (rowBodies_).
void RowBodies::BuildRow(int j, const std::vector<ActiveEdge>& ael) {
    UpdateActiveUnits(j);
    rowBodies_.clear();
    breaks_.clear();
    breakBody_.clear();
    for (const ActiveEdge& a : ael) {
        if (!std::isfinite(a.x)) continue;
        breaks_.push_back(a.x);
        const int b = ctx_.Edge(a.edge).body;
        breakBody_.push_back(b);
        TouchBody(b, j);
        lo_[static_cast<std::size_t>(b)] = std::min(lo_[static_cast<std::size_t>(b)], a.x);
        hi_[static_cast<std::size_t>(b)] = std::max(hi_[static_cast<std::size_t>(b)], a.x);
    }
    AddUnitRanges(j);
    std::sort(rowBodies_.begin(), rowBodies_.end(), [&](int p, int q) {
        return lo_[static_cast<std::size_t>(p)] < lo_[static_cast<std::size_t>(q)] ||
               (lo_[static_cast<std::size_t>(p)] == lo_[static_cast<std::size_t>(q)] && p < q);
    });
    next_ = 0;
    sweepPos_ = 0;
    spanBodies_.clear();
}

inline void RowBodies::AddUnitRanges(int j) {
    for (int u : activeUnits_) {
        const Unit& unit = ctx_.UnitOf(u);
        for (int b : unitPixelBodies_[static_cast<std::size_t>(u)]) {
            TouchBody(b, j);
            auto k = static_cast<std::size_t>(b);
            lo_[k] = std::min(lo_[k], static_cast<double>(unit.x0));
            hi_[k] = std::max(hi_[k], unit.x1 + 1.0);
        }
        for (const SideBody& sb : unitSideBodies_[static_cast<std::size_t>(u)]) {
            if (j < sb.y0 || j > sb.y1) continue;
            AddSideBody(sb, j);
        }
    }
}

inline void RowBodies::AddSideBody(const SideBody& sb, int j) {
    const double yc = j + 0.5;
    const int w = ctx_.frame.width;
    const auto k = static_cast<std::size_t>(sb.body);
    const bool touched = rangeRow_[k] == j;
    if (sb.left && (!touched || lo_[k] > -HUGE_VAL)) {
        ++ctx_.c.sideEvaluations;
        if (SideCovered(sb.body, 0.5, yc)) {
            TouchBody(sb.body, j);
            lo_[k] = -HUGE_VAL;
            hi_[k] = std::max(hi_[k], 0.5);
        }
    }
    if (sb.right && (rangeRow_[k] != j || hi_[k] < HUGE_VAL)) {
        ++ctx_.c.sideEvaluations;
        if (SideCovered(sb.body, w - 0.5, yc)) {
            TouchBody(sb.body, j);
            hi_[k] = HUGE_VAL;
            lo_[k] = std::min(lo_[k], w - 0.5);
        }
    }
}

inline void RowBodies::TouchBody(int b, int j) {
    const auto k = static_cast<std::size_t>(b);
    if (rangeRow_[k] == j) return;
    rangeRow_[k] = j;
    lo_[k] = HUGE_VAL;
    hi_[k] = -HUGE_VAL;
    ownPassed_[k] = 0;
    rowBodies_.push_back(b);
}

// The units whose bounds hold row j, kept by a sweep over the units sorted on y0 (a band starts
// it at its first row), so that a row costs the units active there, not all units.
inline void RowBodies::UpdateActiveUnits(int j) {
    while (unitPos_ < unitsByY_.size() && ctx_.UnitOf(unitsByY_[unitPos_]).y0 <= j) {
        const int u = unitsByY_[unitPos_++];
        const Unit& unit = ctx_.UnitOf(u);
        if (unit.y1 >= j && unit.x1 >= unit.x0) activeUnits_.push_back(u);
    }
    std::size_t keep = 0;
    for (int u : activeUnits_)
        if (ctx_.UnitOf(u).y1 >= j) activeUnits_[keep++] = u;
    activeUnits_.resize(keep);
}

inline bool RowBodies::SideCovered(int body, double x, double y) {
    IntervalList l;
    ctx_.eval.BodySet(body, x, y, l);
    return !l.empty();
}

void RowBodies::SweepTo(int i0, int i1) {
    while (sweepPos_ < rowBodies_.size() &&
           lo_[static_cast<std::size_t>(rowBodies_[sweepPos_])] <= i1 + 0.5)
        spanBodies_.push_back(rowBodies_[sweepPos_++]);
    std::size_t keep = 0;
    for (int b : spanBodies_)
        if (hi_[static_cast<std::size_t>(b)] >= i0 + 0.5) spanBodies_[keep++] = b;
    spanBodies_.resize(keep);
}

}  // namespace quadrix::scanline
