// The work counter of the shading stage's rays (shade/shade_budget.h): every literal a sub-pixel
// sample ray (engines/raycast/sample_tracer.h) or a shadow ray (shade/shadows.h) evaluates adds
// one to the calling thread's counter. Thread-local, so the tracers stay const and lock-free; the
// budget reads the difference before and after a piece of work on the same thread.
#pragma once

#include <cstdint>

namespace quadrix {

// Literal evaluations of this thread's shading rays so far (only grows).
inline thread_local std::uint64_t tRayLiterals = 0;

}  // namespace quadrix
