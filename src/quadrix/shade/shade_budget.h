// The complexity guard of the shading stage (issue 23; docs/performance.md "Complexity guards"):
// a bound on the literal evaluations of the anti-aliasing's sample rays and of the shadow rays.
//
// A ray's cost is the number of literals it evaluates (util/ray_work.h). The box trees
// (math/box_tree.h) skip the solids and the children of wide CSG nodes a ray cannot meet, but not
// the literals of one body: a body of 10⁵ literals costs 10⁵ evaluations per sample ray, and the
// default anti-aliasing of such a body took 17 s of CPU at 64×64 and over 100 s at 512×512 while
// raycast drew the Frame in 0.6 s (its tile reduction drops the literals that cannot bound a
// tile). The sample rays now reduce each body the same way on the rectangle of the edge pixels
// they serve (engines/raycast/sample_tracer.h, Regions), so a convex body of many planes costs them
// a few literals each; what no rectangle can drop (planes and cylinders parallel to the rays,
// quadric surfaces every ray of the rectangle meets) and the shadow rays, which are not reduced,
// still cost every literal. So a pass may evaluate at most
//     max(kShadeLiteralsFloor, kShadeLiteralsPerRay × rays)
// literals, where `rays` is what the pass would trace were every pixel of the image an edge pixel
// (anti-aliasing: pixels × samples) or covered (shadows: pixels × shadow-casting lights). Past it
// the pass stops and throws ShadeLimitError, an EngineLimitError: the command ends with a clean
// error naming the body with the most literals and the option that avoids the work (--aa off,
// --no-shadows), never with a partial picture. The picture defaults (picture_defaults.h) are not
// applied to scenes with a body of more than kPictureDefaultLiterals literals, so that a render
// that asked for neither never meets this error for that reason.
//
// Determinism: the work is spent pixel by pixel after it is done and the pass stops once the
// running sum passes the limit; running sums only grow, so it stops exactly when the whole pass
// would have passed it, for any thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "quadrix/engines/engine_limit.h"
#include "quadrix/flatten/flat_scene.h"

namespace quadrix {

inline constexpr std::uint64_t kShadeLiteralsPerRay = 256;
inline constexpr std::uint64_t kShadeLiteralsFloor = std::uint64_t{1} << 25;  // ≈ 0.4 s of CPU

class ShadeLimitError : public EngineLimitError {
  public:
    using EngineLimitError::EngineLimitError;
};

class ShadeBudget {
  public:
    // `what`: "anti-aliasing" or "shadows"; `avoid`: the option that turns the pass off.
    ShadeBudget(const char* what, const char* avoid, std::uint64_t rays);

    bool Exhausted() const { return exhausted_.load(std::memory_order_relaxed); }
    void Spend(std::uint64_t literals) {
        if (literals == 0) return;  // nothing to add: no atomic operation
        if (used_.fetch_add(literals, std::memory_order_relaxed) + literals > limit_)
            exhausted_.store(true, std::memory_order_relaxed);
    }
    std::uint64_t Limit() const { return limit_; }
    // Throws ShadeLimitError when the budget was exhausted.
    void ThrowIfExhausted(const FlatScene& scene) const;

  private:
    const char* what_;
    const char* avoid_;
    std::uint64_t limit_;
    std::atomic<std::uint64_t> used_{0};
    std::atomic<bool> exhausted_{false};
};

}  // namespace quadrix
