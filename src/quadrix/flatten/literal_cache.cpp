#include "quadrix/flatten/literal_cache.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <functional>

#include "quadrix/util/parallel.h"

namespace quadrix {

LiteralCache LiteralCache::Build(std::span<const FlatHalfSpace> halfSpaces) {
    LiteralCache c;
    c.base = halfSpaces.data();
    c.size = halfSpaces.size();
    c.slot.assign(halfSpaces.size(), -1);
    std::int32_t n = 0;
    for (std::size_t i = 0; i < halfSpaces.size(); ++i)
        if (halfSpaces[i].IsQuadric()) c.slot[i] = n++;
    c.entries.resize(static_cast<std::size_t>(n));
    ParallelFor(tbb::blocked_range<std::size_t>(0, halfSpaces.size(), 512),
                [&](const tbb::blocked_range<std::size_t>& r) {
                    for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        if (c.slot[i] < 0) continue;
                        Entry& e = c.entries[static_cast<std::size_t>(c.slot[i])];
                        bounds_detail::InsideEigen eigen;
                        e.fn = bounds_detail::MakeInsideFn(halfSpaces[i], false, &eigen);
                        e.box = bounds_detail::AnalyticBox(e.fn, &e.centre, &e.hasCentre);
                        e.extent = bounds_detail::QuadricExtent(e.fn, eigen);
                    }
                });
    return c;
}

const LiteralCache::Entry* LiteralCache::Find(const FlatHalfSpace* h) const {
    // std::less: a total order on pointers, also for one that is not into the array.
    const std::less<const FlatHalfSpace*> less;
    if (size == 0 || less(h, base) || !less(h, base + size)) return nullptr;
    const std::int32_t s = slot[static_cast<std::size_t>(h - base)];
    return s < 0 ? nullptr : &entries[static_cast<std::size_t>(s)];
}

}  // namespace quadrix
