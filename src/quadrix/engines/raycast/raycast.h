// Engine `raycast`: the exact reference renderer (DESIGN.md "Engines in more detail").
//
// For each pixel centre, the ray x = (i+½, j+½, t) in device space meets each half-space literal
// in a set of t (an interval, the complement of one, all or nothing); bodies intersect those sets,
// CSG trees combine them as sorted interval lists; the visible point is the first interval
// endpoint lying on an opaque surface. Work is split in tiles run in parallel (oneTBB); per tile,
// solids whose screen bounds miss the tile are culled and CSG trees are pruned.
#pragma once

#include <memory>

#include "quadrix/engines/engine.h"

namespace quadrix {

std::unique_ptr<Engine> MakeRaycastEngine();

}  // namespace quadrix
