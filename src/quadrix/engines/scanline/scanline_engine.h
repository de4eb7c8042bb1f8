// Engine `scanline`: the UniQuadrix Resolver, Renderer and Shader (seed 001 chapters 4–6; see
// resolver.h and renderer.h for the design and docs/scanline.md for the user's view).
//
// RenderOptions::threads: rows are rendered in fixed bands of 32 in parallel (renderer.h).
//
// Options (--engine-opt key=value):
//   sd=N        shading interval Δmax of (6.9), N >= 1; 1 (default) computes every normal exactly
//   shade=fast  constant shading: one normal per face and span ("exact" is the default)
//   csg=pixels  CSG solids by exact evaluation of the tree at every pixel ("spans", the default,
//               uses per-span body templates; see renderer.h)
//
// What is drawn how:
//   - solids that are one body, or a union of bodies: each body by show-edges, spans and face
//     stacks;
//   - other CSG solids: per-span templates of their operand bodies, combined per pixel by interval
//     CSG (renderer.h);
//   - bodies with two quadrics whose surfaces may meet (quartic show-edges, the paper's future
//     work): exact interval evaluation at every pixel of their screen bounds, inside the same span
//     loop (documented refusal; counted as per_pixel_bodies).
#pragma once

#include <memory>

#include "quadrix/engines/engine.h"

namespace quadrix {

std::unique_ptr<Engine> MakeScanlineEngine();

}  // namespace quadrix
