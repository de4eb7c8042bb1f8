#include "quadrix/frame/pixel_region.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace quadrix {

namespace {

// The x intervals of `region` on row y, clipped to [0, width), sorted and merged.
std::vector<std::pair<int, int>> RowSpans(const PixelRegion& region, int y, int width) {
    std::vector<std::pair<int, int>> spans;
    for (const PixelRect& r : region.rects) {
        if (y < r.y0 || y >= r.y1) continue;
        const int a = std::max(r.x0, 0), b = std::min(r.x1, width);
        if (a < b) spans.emplace_back(a, b);
    }
    std::sort(spans.begin(), spans.end());
    std::vector<std::pair<int, int>> merged;
    for (const auto& s : spans) {
        if (!merged.empty() && s.first <= merged.back().second)
            merged.back().second = std::max(merged.back().second, s.second);
        else
            merged.push_back(s);
    }
    return merged;
}

}  // namespace

bool PixelRegion::Intersects(int xa, int ya, int xb, int yb) const {
    for (const PixelRect& r : rects)
        if (r.Intersects(xa, ya, xb, yb)) return true;
    return false;
}

bool PixelRegion::Contains(int x, int y) const { return Intersects(x, y, x + 1, y + 1); }

long long PixelRegion::Pixels(int width, int height) const {
    long long n = 0;
    for (const PixelRect& r : rects) {
        const long long w = std::min(r.x1, width) - std::max(r.x0, 0);
        const long long h = std::min(r.y1, height) - std::max(r.y0, 0);
        if (w > 0 && h > 0) n += w * h;
    }
    return n;
}

PixelRegion InterleavedBands(int width, int height, int part, int parts, int bandRows) {
    PixelRegion region;
    bandRows = std::max(bandRows, 1);
    parts = std::max(parts, 1);
    for (int b = part, y = part * bandRows; y < height; b += parts, y = b * bandRows)
        region.rects.push_back({0, y, width, std::min(y + bandRows, height)});
    return region;
}

void CropToRegion(Frame& frame, const PixelRegion& region) {
    const auto w = static_cast<std::size_t>(frame.width);
    for (int y = 0; y < frame.height; ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * w;
        std::size_t at = 0;
        for (const auto& [a, b] : RowSpans(region, y, frame.width)) {
            frame.SetBackground(row + at, static_cast<std::size_t>(a) - at);
            at = static_cast<std::size_t>(b);
        }
        frame.SetBackground(row + at, w - at);
    }
}

void CopyRegion(Frame& into, const Frame& from, const PixelRegion& region) {
    for (int y = 0; y < into.height; ++y)
        for (const auto& [a, b] : RowSpans(region, y, into.width)) {
            const auto i = static_cast<std::ptrdiff_t>(into.Index(a, y));
            const auto n = static_cast<std::size_t>(b - a);
            std::copy_n(from.depth.begin() + i, n, into.depth.begin() + i);
            std::copy_n(from.normal.begin() + i, n, into.normal.begin() + i);
            std::copy_n(from.surface.begin() + i, n, into.surface.begin() + i);
            std::copy_n(from.body.begin() + i, n, into.body.begin() + i);
        }
    if (into.bodySolid.size() < from.bodySolid.size()) into.bodySolid = from.bodySolid;
}

void ComposeMinInRegion(Frame& into, const Frame& other, const PixelRegion& region) {
    for (int y = 0; y < into.height; ++y)
        for (const auto& [a, b] : RowSpans(region, y, into.width))
            for (std::size_t i = into.Index(a, y), e = into.Index(b, y); i < e; ++i)
                into.Offer(i, other.depth[i], other.normal[i], other.surface[i], other.body[i]);
    if (into.bodySolid.size() < other.bodySolid.size()) into.bodySolid = other.bodySolid;
}

}  // namespace quadrix
