// Stage (a) of the bounds (bounds.h) for every quadric half-space of one FlatScene, computed once
// and shared by every body bounded in the same space.
//
// The Flattener bounds bodies over the same half-spaces several times in provisional space: the
// scene's scale (HalfSpaceScale, which takes each quadric's analytic box), every body's box
// (AllBodyBounds), the solids made exact for the window fit and the culling. Each of those began
// by making the literal's inside function (its eigenvalue bounds) and its analytic box (a
// Cholesky factorisation and four solves): for 100,000 spheres, three times 100,000 of them. The
// cache holds them for the uncomplemented quadric literals; IntersectionBounds takes an entry in
// place of computing it (BoundsOptions::literals). An entry is what MakeInsideFn and AnalyticBox
// return for the same coefficients, so every box is bit for bit the one computed afresh.
//
// The cache points into the half-space array it was built over: that array must neither move nor
// change while a BoundsOptions names the cache (the Flattener drops it before mapping the scene
// to device space). Literals of other half-spaces, complemented ones, planes and quartics are
// computed as before.
//
// Entries are made kEigenLanes quadrics at a time, their A decomposed together
// (SymmetricEigenLanes: the same bits as one at a time, about half the time).
//
// LiteralCacheBuilder makes the same entries while the walk of a big scene appends the
// half-spaces (FlattenHierarchy's HalfSpaceObserver): the walk is serial, and the entries of the
// half-spaces it has finished are made meanwhile on a thread of their own, on the processor the
// walk leaves idle; Finish makes the rest in parallel. Entry k is the one Build makes: the same
// function of the same half-space.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <thread>
#include <vector>

#include "quadrix/flatten/bounds_internal.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/flatten/hierarchy.h"

namespace quadrix {

struct LiteralCache {
    struct Entry {
        bounds_detail::InsideFn fn;  // MakeInsideFn(h, false)
        Box3 box;                    // AnalyticBox(fn, &centre, &hasCentre)
        Vec3 centre;
        bool hasCentre = false;
        double extent = 0;  // QuadricExtent(fn, the eigen-decomposition fn was made with)
    };

    // Entries for the quadric half-spaces of `halfSpaces`, made in parallel.
    static LiteralCache Build(std::span<const FlatHalfSpace> halfSpaces);

    // The entry of the uncomplemented literal of *h, or null when h is not a quadric of the
    // array the cache was built over.
    const Entry* Find(const FlatHalfSpace* h) const;

    const FlatHalfSpace* base = nullptr;
    std::size_t size = 0;
    std::vector<std::int32_t> slot;  // per half-space: index into entries, or -1
    std::vector<Entry> entries;
};

// Builds a LiteralCache over the half-spaces a walk appends to one array, from a thread started by
// Started while the walk goes on (hierarchy.h HalfSpaceObserver). The thread reads only
// array[0, n) for the n last published to it (every 64 appends, and all of them at Finished),
// through the array's address at Started: the walk calls Growing before the array would move,
// which stops the thread. The thread runs at idle priority (SCHED_IDLE: it takes only a
// processor nothing else wants) and is raised to normal when it is waited for. Not thread-safe
// otherwise: every member is called by the walk's thread.
class LiteralCacheBuilder final : public HalfSpaceObserver {
  public:
    // Half-spaces a walk must be expected to append for the thread to be started (below that,
    // the thread's start costs about as much as the entries).
    static constexpr std::size_t kMinHalfSpaces = 4096;

    LiteralCacheBuilder() = default;
    ~LiteralCacheBuilder();  // stops the thread
    LiteralCacheBuilder(const LiteralCacheBuilder&) = delete;
    LiteralCacheBuilder& operator=(const LiteralCacheBuilder&) = delete;

    void Started(const std::vector<FlatHalfSpace>& halfSpaces, std::size_t expected) override;
    void Appended(std::size_t size) override;
    void Growing() override;
    void Finished() override;

    // The cache over `halfSpaces` (the array the walk appended to, unchanged since): the thread
    // stopped, the entries it has not made made in parallel (util/parallel.h).
    LiteralCache Finish(std::span<const FlatHalfSpace> halfSpaces);

    // For tests: whether the thread has ended (after Finished, once it has made every entry), and
    // how many of the last Finish's entries it had made.
    bool ThreadEnded() const { return ended_.load(std::memory_order_acquire); }
    std::size_t MadeAlongside() const { return madeAlongside_; }

  private:
    void Stop();
    void Work();

    static constexpr std::uint32_t kStop = 1u << 31;  // end now
    static constexpr std::uint32_t kEnd = 1u << 30;   // end when every half-space is done
    std::thread thread_;
    const FlatHalfSpace* base_ = nullptr;  // the array's address at Started
    // Half-spaces published to the thread (base_[0, n) final), with kEnd once they are all
    // (Finished) and kStop once the thread must end; appended_: the walk's last Appended.
    std::atomic<std::uint32_t> state_{0};
    std::size_t appended_ = 0;
    // The thread's own, read after it is joined: half-spaces looked at, and the entries made
    // for the quadrics among them (reserved at Started, so the thread never reallocates).
    std::size_t done_ = 0;
    std::vector<LiteralCache::Entry> entries_;
    std::atomic<bool> ended_{false};
    std::size_t madeAlongside_ = 0;
};

}  // namespace quadrix
