// The counters of engine `raycast`, one set per worker thread, summed after the frame and
// reported by RaycastEngine::Render under the names of its statistics table (docs/performance.md
// explains each): how many blocks, tiles and sub-tiles were pruned, how many pixels each fast path
// drew, and how many bodies, literals and CSG operations the scalar path evaluated.
#pragma once

#include <cstdint>

#include "quadrix/engines/raycast/eval_names.h"

namespace quadrix::raycast {

struct Counters {
    std::uint64_t blocks = 0, coarseTiles = 0, tiles = 0, pixels = 0, tileSolids = 0,
                  pixelSolids = 0, zStops = 0, bodies = 0, csgOps = 0, covered = 0, cutRetries = 0,
                  prunedLiterals = 0, flatTiles = 0, flatPixels = 0, emptyBodies = 0,
                  batchBodies = 0, batchPixels = 0, bodyFillTiles = 0, emptyTiles = 0,
                  kernelTiles = 0, kernelPixels = 0, kernelScalarBodies = 0, kernelScalarPixels = 0;
    LiteralCounters literals;

    void Add(const Counters& o) {
        blocks += o.blocks;
        coarseTiles += o.coarseTiles;
        tiles += o.tiles;
        pixels += o.pixels;
        tileSolids += o.tileSolids;
        pixelSolids += o.pixelSolids;
        zStops += o.zStops;
        bodies += o.bodies;
        csgOps += o.csgOps;
        covered += o.covered;
        cutRetries += o.cutRetries;
        prunedLiterals += o.prunedLiterals;
        flatTiles += o.flatTiles;
        flatPixels += o.flatPixels;
        emptyBodies += o.emptyBodies;
        batchBodies += o.batchBodies;
        batchPixels += o.batchPixels;
        bodyFillTiles += o.bodyFillTiles;
        emptyTiles += o.emptyTiles;
        kernelTiles += o.kernelTiles;
        kernelPixels += o.kernelPixels;
        kernelScalarBodies += o.kernelScalarBodies;
        kernelScalarPixels += o.kernelScalarPixels;
        literals.planes += o.literals.planes;
        literals.quadrics += o.literals.quadrics;
        literals.quartics += o.literals.quartics;
    }
};

}  // namespace quadrix::raycast
