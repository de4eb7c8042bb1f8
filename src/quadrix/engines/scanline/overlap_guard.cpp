#include "quadrix/engines/scanline/overlap_guard.h"

#include <algorithm>
#include <cstdint>

namespace quadrix::scanline {

namespace {

// A unit's inclusive cell range; false when its pixel range is empty or off the image.
bool CellRange(const Unit& u, int gw, int gh, int& cx0, int& cx1, int& cy0, int& cy1) {
    if (u.kind != Unit::Kind::kBody || u.x1 < u.x0 || u.y1 < u.y0) return false;
    cx0 = std::clamp(u.x0 / kCellSize, 0, gw - 1);
    cx1 = std::clamp(u.x1 / kCellSize, 0, gw - 1);
    cy0 = std::clamp(u.y0 / kCellSize, 0, gh - 1);
    cy1 = std::clamp(u.y1 / kCellSize, 0, gh - 1);
    return true;
}

}  // namespace

OverlapReport OverloadedSolids(const std::vector<Unit>& units, int width, int height,
                               int maxOverlap) {
    OverlapReport report;
    if (width < 1 || height < 1) return report;
    const int gw = (width + kCellSize - 1) / kCellSize, gh = (height + kCellSize - 1) / kCellSize;
    const std::size_t stride = static_cast<std::size_t>(gw) + 1;
    // Difference array: +1 at (cx0, cy0) and (cx1+1, cy1+1), −1 at the two other corners; the
    // 2-D prefix sum is then the number of boxes covering each cell.
    std::vector<std::int32_t> count(stride * (static_cast<std::size_t>(gh) + 1), 0);
    auto at = [&](int x, int y) -> std::int32_t& {
        return count[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)];
    };
    int cx0, cx1, cy0, cy1;
    for (const Unit& u : units) {
        if (!CellRange(u, gw, gh, cx0, cx1, cy0, cy1)) continue;
        ++at(cx0, cy0);
        --at(cx1 + 1, cy0);
        --at(cx0, cy1 + 1);
        ++at(cx1 + 1, cy1 + 1);
    }
    for (int y = 0; y <= gh; ++y)
        for (int x = 0; x <= gw; ++x) {
            std::int32_t v = at(x, y);
            if (x > 0) v += at(x - 1, y);
            if (y > 0) v += at(x, y - 1);
            if (x > 0 && y > 0) v -= at(x - 1, y - 1);
            at(x, y) = v;
        }
    // Summed-area table of the over-threshold cells, so that each unit asks "does my cell range
    // hold one?" in O(1). over(x, y) = number of such cells in [0, x) × [0, y).
    std::vector<std::int32_t> over(stride * (static_cast<std::size_t>(gh) + 1), 0);
    auto sat = [&](int x, int y) -> std::int32_t& {
        return over[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)];
    };
    for (int y = 0; y < gh; ++y)
        for (int x = 0; x < gw; ++x) {
            const std::int32_t depth = at(x, y);
            report.maxDepth = std::max(report.maxDepth, static_cast<int>(depth));
            sat(x + 1, y + 1) =
                (depth > maxOverlap ? 1 : 0) + sat(x, y + 1) + sat(x + 1, y) - sat(x, y);
        }
    if (report.maxDepth <= maxOverlap) return report;
    for (const Unit& u : units) {
        if (!CellRange(u, gw, gh, cx0, cx1, cy0, cy1)) continue;
        const std::int32_t n =
            sat(cx1 + 1, cy1 + 1) - sat(cx0, cy1 + 1) - sat(cx1 + 1, cy0) + sat(cx0, cy0);
        if (n > 0) report.solids.push_back(u.solid);
    }
    std::sort(report.solids.begin(), report.solids.end());
    report.solids.erase(std::unique(report.solids.begin(), report.solids.end()),
                        report.solids.end());
    return report;
}

}  // namespace quadrix::scanline
