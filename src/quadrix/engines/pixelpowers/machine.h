// The simulated Pixel-Powers frame buffer: runs a Program (isa.h) over every pixel.
//
// The screen is cut into 64×64 tiles run in parallel (oneTBB); each tile keeps its pixels'
// registers (ZTEMP, ZMIN, F1–F3, COLOR) in structure-of-arrays form and executes the blocks whose
// rectangle meets it, instruction by instruction over rectangle ∩ tile, so the inner loops are
// plain loops over contiguous pixels. The result is the same as running the whole program over the
// whole screen at once (every pixel's registers depend only on the instructions and its own
// coordinates), i.e. the data-parallel machine of seed 004 §III; tiles only add thread and cache
// parallelism. A block whose F1 has gone to zero over the tile is abandoned (a simulator shortcut:
// the hardware would still spend the broadcasts, and the static counts in Program say so).
#pragma once

#include <cstdint>

#include "quadrix/engines/pixelpowers/isa.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/frame.h"

namespace quadrix::pixelpowers {

struct MachineCounters {
    std::uint64_t tiles = 0;
    std::uint64_t blockRuns = 0;  // (block, tile) pairs executed
    std::uint64_t blocksAbandoned = 0;
    std::uint64_t instructions = 0;  // instructions issued to tiles
    std::uint64_t pixelOps = 0;      // instruction × enabled-pixel evaluations
    std::uint64_t rootSolves = 0;    // per-pixel square roots of the extended machine
    std::uint64_t writes = 0;        // ZWRITE pixel updates

    void Add(const MachineCounters& o) {
        tiles += o.tiles;
        blockRuns += o.blockRuns;
        blocksAbandoned += o.blocksAbandoned;
        instructions += o.instructions;
        pixelOps += o.pixelOps;
        rootSolves += o.rootSolves;
        writes += o.writes;
    }
};

// The parallel light the paper's one-light shading model stands for: the brightest non-ambient
// light of the scene (first on ties), unit; zero when there is none.
Vec3 KeyLight(const FlatScene& scene);

// Scan-out of the paper's shading (seed 004 §III step 4) into the Frame's unit normal. The QEE
// gives the approximate normal VECTOR a (numerator approximated, constant denominator), whose
// a·l is the paper's shade for any parallel light l, but |a| ≠ 1. The Frame contract asks for a
// unit normal, so this returns the unit vector n in the plane of a and the key light k with
// n·k = clamp(a·k, −1, 1): the shader's Lambert term for k is then exactly the paper's shade
// (saturated at 1), and the remaining direction of a is kept for the other lights. Without a key
// light it returns a / |a|.
Vec3 ShadingUnitNormal(const Vec3& approx, const Vec3& key);

// Runs `program` and scans out into `frame` (resized to the scene's size): depth = ZMIN, and the
// patch in COLOR gives surface, body, solid and the normal (FlatScene::WorldNormal at ZMIN, or
// ShadingUnitNormal of N0–N2 for patches with PatchInfo::machineNormal).
// Runs in the caller's oneTBB arena.
MachineCounters Execute(const Program& program, const FlatScene& scene, Frame& frame);

}  // namespace quadrix::pixelpowers
