// Stage (a) of the bounds (bounds.h) for every quadric half-space of one FlatScene, computed once
// and shared by every body bounded in the same space.
//
// The Flattener bounds bodies over the same half-spaces several times in provisional space: the
// scene's scale (HalfSpaceScale, which takes each quadric's analytic box), every body's box
// (AllBodyBounds), the solids made exact for the window fit and the culling. Each of those began
// by making the literal's inside function (its eigenvalue bounds) and its analytic box (a
// Cholesky factorisation and four solves): for 100,000 spheres, three times 100,000 of them. The
// cache holds them for the uncomplemented quadric literals; IntersectionBounds takes an entry in
// place of computing it (BoundsOptions::literals). An entry is what MakeInsideFn and AnalyticBox
// return for the same coefficients, so every box is bit for bit the one computed afresh.
//
// The cache points into the half-space array it was built over: that array must neither move nor
// change while a BoundsOptions names the cache (the Flattener drops it before mapping the scene
// to device space). Literals of other half-spaces, complemented ones, planes and quartics are
// computed as before.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "quadrix/flatten/bounds_internal.h"
#include "quadrix/flatten/flat_scene.h"

namespace quadrix {

struct LiteralCache {
    struct Entry {
        bounds_detail::InsideFn fn;  // MakeInsideFn(h, false)
        Box3 box;                    // AnalyticBox(fn, &centre, &hasCentre)
        Vec3 centre;
        bool hasCentre = false;
        double extent = 0;  // QuadricExtent(fn, the eigen-decomposition fn was made with)
    };

    // Entries for the quadric half-spaces of `halfSpaces`, made in parallel.
    static LiteralCache Build(std::span<const FlatHalfSpace> halfSpaces);

    // The entry of the uncomplemented literal of *h, or null when h is not a quadric of the
    // array the cache was built over.
    const Entry* Find(const FlatHalfSpace* h) const;

    const FlatHalfSpace* base = nullptr;
    std::size_t size = 0;
    std::vector<std::int32_t> slot;  // per half-space: index into entries, or -1
    std::vector<Entry> entries;
};

}  // namespace quadrix
