// The switches of engine `raycast`'s fast paths (--engine-opt KEY=on|off, declared in raycast.cpp's
// option schema).
// Each fast path gives Trace's result bit for bit (DESIGN.md "Engines in more detail"), so
// switching one off changes speed only, never a bit of the frame (RaycastOptions.* tests):
//   batch      body batches over the pixels of a sub-tile (body_batch.h);
//   tileCull   per-sub-tile proofs: bodies empty there, quadric literals that hold on every
//              ray, flat sub-tiles filled directly (tile_reduction.h);
//   kernel     small sub-tile programs compiled to postfix code over body batches (kernel.h;
//              needs batch).
#pragma once

namespace quadrix::raycast {

struct Settings {
    bool batch = true;
    bool tileCull = true;
    bool kernel = true;
};

}  // namespace quadrix::raycast
