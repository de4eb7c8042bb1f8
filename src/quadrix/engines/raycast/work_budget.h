// The complexity guard of engine `raycast` (issue 23; docs/performance.md "Complexity guards"):
// a bound on the body evaluations of one render. A pixel's cost is the number of bodies Trace
// evaluates there, which the depth cuts (trace.h) keep near the depth complexity of the visible
// surface — but a DENSE union, every operand covering every pixel, still costs pixels × operands
// (10⁵ balls at 64×64: 47 s of CPU). The budget is `max-evaluations` (engine option, default
// 4,096) times the pixels, so a render costs at most O(pixels) evaluations; past it the render
// stops and Draw throws EngineLimitError (engines/engine_limit.h), which the render context turns
// into an error: no image, never a partial one. Evaluations are counted as the
// `body_evaluations` counter (Trace's, from a batch or not); sub-tiles filled from one body's
// batch or by a kernel count none (those paths are bounded per pixel already).
//
// Determinism: every sub-tile's evaluations depend only on the scene and the sub-tile
// (raycast.cpp), so their total does not depend on the threads. Sub-tiles add their own after they
// are drawn and the rest are skipped once the running sum passes the budget; running sums only
// grow, so the render stops exactly when the whole render would have passed it, for any thread
// count.
#pragma once

#include <atomic>
#include <cstdint>

namespace quadrix::raycast {

class WorkBudget {
  public:
    WorkBudget(std::uint64_t perPixel, std::uint64_t pixels)
        : perPixel_(perPixel), limit_(perPixel * pixels) {}

    bool Exhausted() const { return exhausted_.load(std::memory_order_relaxed); }
    // Adds the evaluations of one sub-tile.
    void Spend(std::uint64_t evaluations) {
        if (used_.fetch_add(evaluations, std::memory_order_relaxed) + evaluations > limit_)
            exhausted_.store(true, std::memory_order_relaxed);
    }
    std::uint64_t PerPixel() const { return perPixel_; }
    std::uint64_t Limit() const { return limit_; }

  private:
    const std::uint64_t perPixel_, limit_;
    // On lines of their own: every sub-tile reads exhausted_, chunks of them write used_.
    alignas(64) std::atomic<std::uint64_t> used_{0};
    alignas(64) std::atomic<bool> exhausted_{false};
};

}  // namespace quadrix::raycast
