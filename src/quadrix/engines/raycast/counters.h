// The counters of engine `raycast`, one set per worker thread, summed after the frame and
// reported by RaycastEngine::Render, each declared once with its meaning (engines/counters.h;
// docs/engines.md lists them): how many blocks, tiles and sub-tiles were pruned, how many pixels
// each fast path drew, and how many bodies, literals and CSG operations the scalar path evaluated.
#pragma once

#include <cstddef>
#include <cstdint>

#include "quadrix/engines/counters.h"
#include "quadrix/engines/raycast/eval_names.h"

namespace quadrix::raycast {

// Each counter once: X(field, name in --stats and JSON). The struct's fields, its sum and the
// report's entries are generated from this list, so a new counter is one line.
#define QUADRIX_RAYCAST_COUNTERS(X)                                                           \
    X(blocks, "blocks_256", "256x256 blocks of the image visited")                            \
    X(coarseTiles, "tiles_256x8", "256x8 tiles after the block test")                         \
    X(tiles, "sub_tiles", "8x8 sub-tiles evaluated")                                          \
    X(pixels, "pixels", "pixels of the image")                                                \
    X(covered, "covered_pixels", "pixels where a surface was drawn")                          \
    X(tileSolids, "tile_solids", "solids whose box meets a tile")                             \
    X(pixelSolids, "pixel_solids", "solids evaluated pixel by pixel")                         \
    X(zStops, "depth_early_outs", "solids skipped: behind the depth found")                   \
    X(bodies, "body_evaluations", "bodies evaluated along a ray (scalar path)")               \
    X(csgOps, "csg_operations", "interval-list CSG operations")                               \
    X(cutRetries, "depth_cut_retries", "solids evaluated again past a depth cut")             \
    X(prunedLiterals, "tile_literals_pruned", "literals that hold on a whole tile (dropped)") \
    X(flatTiles, "flat_sub_tiles", "sub-tiles filled by one plane")                           \
    X(flatPixels, "flat_pixels", "pixels filled that way")                                    \
    X(emptyBodies, "tile_bodies_empty", "bodies found empty on a tile")                       \
    X(batchBodies, "batched_bodies", "bodies evaluated by the batch kernel")                  \
    X(batchPixels, "batched_body_pixels", "pixels of those evaluations")                      \
    X(bodyFillTiles, "single_body_sub_tiles", "sub-tiles drawn from one body")                \
    X(emptyTiles, "empty_sub_tiles", "sub-tiles with nothing in them")                        \
    X(kernelTiles, "kernel_sub_tiles", "sub-tiles drawn by the vector kernel")                \
    X(kernelPixels, "kernel_pixels", "pixels drawn by it")                                    \
    X(kernelScalarBodies, "kernel_scalar_bodies",                                             \
      "kernel bodies that fell back to the scalar path")                                      \
    X(kernelScalarPixels, "kernel_scalar_pixels", "pixels of those fallbacks")                \
    X(kernelCutTiles, "kernel_cut_sub_tiles",                                                 \
      "kernel sub-tiles of a big union, drawn to its first depth cut")

// Ids of every counter the engine reports, in the report's order: the scene's size, the list
// above, then the literal evaluations by kind.
#define QUADRIX_RAYCAST_ID(field, name, meaning) field,
struct CounterId {
    enum : std::size_t {
        solids,
        programNodes,
        QUADRIX_RAYCAST_COUNTERS(QUADRIX_RAYCAST_ID) literalEvaluations,
        planeEvaluations,
        quadricSolves,
        quarticSolves
    };
};
#undef QUADRIX_RAYCAST_ID
#define QUADRIX_RAYCAST_DECL(field, name, meaning) CounterDecl{name, meaning},
inline constexpr CounterDecl kRaycastCounters[] = {
    {"solids", "solids of the flat scene"},
    {"program_nodes", "nodes of the CSG program (eval/ tape)"},
    QUADRIX_RAYCAST_COUNTERS(QUADRIX_RAYCAST_DECL){"literal_evaluations",
                                                   "literal evaluations along rays, all kinds"},
    {"plane_evaluations", "ray-plane evaluations"},
    {"quadric_solves", "ray-quadric solves"},
    {"quartic_solves", "ray-quartic root isolations (tori, general cones)"}};
#undef QUADRIX_RAYCAST_DECL

struct Counters {
#define QUADRIX_COUNTER_FIELD(field, name, meaning) std::uint64_t field = 0;
    QUADRIX_RAYCAST_COUNTERS(QUADRIX_COUNTER_FIELD)
#undef QUADRIX_COUNTER_FIELD
    // Literal evaluations by kind (eval/ray_literal.h), reported as plane_evaluations,
    // quadric_solves, quartic_solves (when there are any) and their sum literal_evaluations.
    LiteralCounters literals;

    void Add(const Counters& o) {
#define QUADRIX_COUNTER_ADD(field, name, meaning) field += o.field;
        QUADRIX_RAYCAST_COUNTERS(QUADRIX_COUNTER_ADD)
#undef QUADRIX_COUNTER_ADD
        literals.planes += o.literals.planes;
        literals.quadrics += o.literals.quadrics;
        literals.quartics += o.literals.quartics;
    }

    // Sets every counter of the list and the literal counts in `values` (kRaycastCounters).
    void Record(CounterValues& values) const {
#define QUADRIX_COUNTER_VISIT(field, name, meaning) values.Set(CounterId::field, field);
        QUADRIX_RAYCAST_COUNTERS(QUADRIX_COUNTER_VISIT)
#undef QUADRIX_COUNTER_VISIT
        values.Set(CounterId::literalEvaluations,
                   literals.planes + literals.quadrics + literals.quartics);
        values.Set(CounterId::planeEvaluations, literals.planes);
        values.Set(CounterId::quadricSolves, literals.quadrics);
        if (literals.quartics) values.Set(CounterId::quarticSolves, literals.quartics);
    }
};

}  // namespace quadrix::raycast
