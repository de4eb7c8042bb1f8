// The counters of engine `raycast`, one set per worker thread, summed after the frame and
// reported by RaycastEngine::Render under the names of its statistics table (docs/performance.md
// explains each): how many blocks, tiles and sub-tiles were pruned, how many pixels each fast path
// drew, and how many bodies, literals and CSG operations the scalar path evaluated.
#pragma once

#include <cstdint>

#include "quadrix/engines/raycast/eval_names.h"

namespace quadrix::raycast {

// Each counter once: X(field, name in --stats and JSON). The struct's fields, its sum and the
// report's entries are generated from this list, so a new counter is one line.
#define QUADRIX_RAYCAST_COUNTERS(X)               \
    X(blocks, "blocks_256")                       \
    X(coarseTiles, "tiles_256x8")                 \
    X(tiles, "sub_tiles")                         \
    X(pixels, "pixels")                           \
    X(covered, "covered_pixels")                  \
    X(tileSolids, "tile_solids")                  \
    X(pixelSolids, "pixel_solids")                \
    X(zStops, "depth_early_outs")                 \
    X(bodies, "body_evaluations")                 \
    X(csgOps, "csg_operations")                   \
    X(cutRetries, "depth_cut_retries")            \
    X(prunedLiterals, "tile_literals_pruned")     \
    X(flatTiles, "flat_sub_tiles")                \
    X(flatPixels, "flat_pixels")                  \
    X(emptyBodies, "tile_bodies_empty")           \
    X(batchBodies, "batched_bodies")              \
    X(batchPixels, "batched_body_pixels")         \
    X(bodyFillTiles, "single_body_sub_tiles")     \
    X(emptyTiles, "empty_sub_tiles")              \
    X(kernelTiles, "kernel_sub_tiles")            \
    X(kernelPixels, "kernel_pixels")              \
    X(kernelScalarBodies, "kernel_scalar_bodies") \
    X(kernelScalarPixels, "kernel_scalar_pixels")

struct Counters {
#define QUADRIX_COUNTER_FIELD(field, name) std::uint64_t field = 0;
    QUADRIX_RAYCAST_COUNTERS(QUADRIX_COUNTER_FIELD)
#undef QUADRIX_COUNTER_FIELD
    // Literal evaluations by kind (eval/ray_literal.h), reported as plane_evaluations,
    // quadric_solves, quartic_solves (when there are any) and their sum literal_evaluations.
    LiteralCounters literals;

    void Add(const Counters& o) {
#define QUADRIX_COUNTER_ADD(field, name) field += o.field;
        QUADRIX_RAYCAST_COUNTERS(QUADRIX_COUNTER_ADD)
#undef QUADRIX_COUNTER_ADD
        literals.planes += o.literals.planes;
        literals.quadrics += o.literals.quadrics;
        literals.quartics += o.literals.quartics;
    }

    // Calls f(name, value) for every counter, in the list's order, then the literal counts.
    template <class F>
    void ForEach(F&& f) const {
#define QUADRIX_COUNTER_VISIT(field, name) f(name, field);
        QUADRIX_RAYCAST_COUNTERS(QUADRIX_COUNTER_VISIT)
#undef QUADRIX_COUNTER_VISIT
        f("literal_evaluations", literals.planes + literals.quadrics + literals.quartics);
        f("plane_evaluations", literals.planes);
        f("quadric_solves", literals.quadrics);
        if (literals.quartics) f("quartic_solves", literals.quartics);
    }
};

}  // namespace quadrix::raycast
