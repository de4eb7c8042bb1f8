#include "quadrix/flatten/literal_cache.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <functional>

#if defined(__linux__)
#include <pthread.h>
#include <sched.h>
#endif
#include <system_error>

#include "quadrix/util/parallel.h"

namespace quadrix {

namespace {

// The entries of up to kEigenLanes quadrics, their A decomposed together (SymmetricEigenLanes):
// each entry is MakeInsideFn's, AnalyticBox's and QuadricExtent's for its half-space.
void MakeEntries(int n, const FlatHalfSpace* const h[], LiteralCache::Entry* const e[]) {
    namespace bd = bounds_detail;
    const double(*a[kEigenLanes])[3] = {};
    int lane[kEigenLanes];
    int lanes = 0;
    for (int k = 0; k < n; ++k) {
        e[k]->fn = bd::MakeInsideFnUnbounded(*h[k], false);
        lane[k] = bd::NeedsEigen(e[k]->fn) ? lanes++ : -1;
        if (lane[k] >= 0) a[lane[k]] = e[k]->fn.a;
    }
    SymmetricEigenResult d[kEigenLanes];
    SymmetricEigenLanes(lanes, a, d);
    for (int k = 0; k < n; ++k) {
        LiteralCache::Entry& entry = *e[k];
        bd::InsideEigen eigen;
        bd::Bound(entry.fn, lane[k] >= 0 ? &d[lane[k]] : nullptr, &eigen);
        entry.box = bd::AnalyticBox(entry.fn, &entry.centre, &entry.hasCentre);
        entry.extent = bd::QuadricExtent(entry.fn, eigen);
    }
}

// Collects quadrics and makes their entries kEigenLanes at a time.
class EntryBatch {
  public:
    void Add(const FlatHalfSpace& h, LiteralCache::Entry& e) {
        h_[n_] = &h;
        e_[n_] = &e;
        if (++n_ == kEigenLanes) Flush();
    }
    void Flush() {
        MakeEntries(n_, h_, e_);
        n_ = 0;
    }

  private:
    const FlatHalfSpace* h_[kEigenLanes];
    LiteralCache::Entry* e_[kEigenLanes];
    int n_ = 0;
};

// c over halfSpaces with its slots numbered, entries holding at least the made ones: the entries
// of the quadrics from half-space `from` on, made in parallel.
void MakeEntriesFrom(std::span<const FlatHalfSpace> halfSpaces, std::size_t from, LiteralCache& c) {
    if (from >= halfSpaces.size()) return;
    ParallelFor(tbb::blocked_range<std::size_t>(from, halfSpaces.size(), 512),
                [&](const tbb::blocked_range<std::size_t>& r) {
                    EntryBatch batch;
                    for (std::size_t i = r.begin(); i < r.end(); ++i)
                        if (c.slot[i] >= 0)
                            batch.Add(halfSpaces[i],
                                      c.entries[static_cast<std::size_t>(c.slot[i])]);
                    batch.Flush();
                });
}

// The cache's array and slots, its entries `made` (the first ones, or none) and sized.
LiteralCache Slots(std::span<const FlatHalfSpace> halfSpaces,
                   std::vector<LiteralCache::Entry> made = {}) {
    LiteralCache c;
    c.base = halfSpaces.data();
    c.size = halfSpaces.size();
    c.slot.assign(halfSpaces.size(), -1);
    std::int32_t n = 0;
    for (std::size_t i = 0; i < halfSpaces.size(); ++i)
        if (halfSpaces[i].IsQuadric()) c.slot[i] = n++;
    c.entries = std::move(made);
    c.entries.resize(static_cast<std::size_t>(n));
    return c;
}

}  // namespace

LiteralCache LiteralCache::Build(std::span<const FlatHalfSpace> halfSpaces) {
    LiteralCache c = Slots(halfSpaces);
    MakeEntriesFrom(halfSpaces, 0, c);
    return c;
}

const LiteralCache::Entry* LiteralCache::Find(const FlatHalfSpace* h) const {
    // std::less: a total order on pointers, also for one that is not into the array.
    const std::less<const FlatHalfSpace*> less;
    if (size == 0 || less(h, base) || !less(h, base + size)) return nullptr;
    const std::int32_t s = slot[static_cast<std::size_t>(h - base)];
    return s < 0 ? nullptr : &entries[static_cast<std::size_t>(s)];
}

LiteralCacheBuilder::~LiteralCacheBuilder() { Stop(); }

void LiteralCacheBuilder::Started(const std::vector<FlatHalfSpace>& halfSpaces,
                                  std::size_t expected) {
    if (thread_.joinable() || expected < kMinHalfSpaces || halfSpaces.capacity() >= kEnd) return;
    ended_.store(false, std::memory_order_relaxed);
    base_ = halfSpaces.data();
    appended_ = halfSpaces.size();
    state_.store(static_cast<std::uint32_t>(appended_), std::memory_order_relaxed);
    try {
        // Room for an entry per half-space the array can hold before it moves.
        entries_.reserve(halfSpaces.capacity());
        thread_ = std::thread([this] { Work(); });
    } catch (const std::bad_alloc&) {
        entries_ = {};  // no thread: Finish makes every entry
    } catch (const std::system_error&) {
        entries_ = {};
    }
}

void LiteralCacheBuilder::Appended(std::size_t size) {
    if (!thread_.joinable()) return;
    appended_ = size;
    // Published every 64 half-spaces (the thread reads the same word: fewer transfers of its
    // cache line between the processors), the thread woken every 256 (a wake is a system call;
    // it takes all that are published).
    if (size % 64 != 0) return;
    state_.store(static_cast<std::uint32_t>(size), std::memory_order_release);
    if (size % 256 == 0) state_.notify_one();
}

void LiteralCacheBuilder::Growing() { Stop(); }

void LiteralCacheBuilder::Finished() {
    if (!thread_.joinable()) return;
    state_.store(static_cast<std::uint32_t>(appended_) | kEnd, std::memory_order_release);
    state_.notify_one();
}

void LiteralCacheBuilder::Stop() {
    if (!thread_.joinable()) return;
    state_.fetch_or(kStop, std::memory_order_release);
#if defined(__linux__)
    // Waited for now: back among the others, so that a busy machine does not keep it waiting
    // (best effort; it ends soon anyway).
    sched_param normal{};
    pthread_setschedparam(thread_.native_handle(), SCHED_OTHER, &normal);
#endif
    state_.notify_one();
    thread_.join();
}

void LiteralCacheBuilder::Work() {
#if defined(__linux__)
    // Below every other thread of the process (and of the machine): it takes only what the walk
    // and oneTBB's start leave idle, and never pre-empts them.
    sched_param idle{};
    pthread_setschedparam(pthread_self(), SCHED_IDLE, &idle);
#endif
    std::uint32_t seen = state_.load(std::memory_order_acquire);
    for (;;) {
        const std::size_t n = seen & ~(kStop | kEnd);
        // Up to kEigenLanes quadrics at a time (entries_ never reallocates: reserved at
        // Started), done_ past the last of them.
        while (done_ < n && !(state_.load(std::memory_order_relaxed) & kStop)) {
            EntryBatch batch;
            for (int quadrics = 0; done_ < n && quadrics < kEigenLanes; ++done_) {
                const FlatHalfSpace& h = base_[done_];
                if (!h.IsQuadric()) continue;
                batch.Add(h, entries_.emplace_back());
                ++quadrics;
            }
            batch.Flush();
        }
        if (done_ < n || (seen & (kStop | kEnd))) break;
        state_.wait(seen, std::memory_order_acquire);
        seen = state_.load(std::memory_order_acquire);
    }
    ended_.store(true, std::memory_order_release);
}

LiteralCache LiteralCacheBuilder::Finish(std::span<const FlatHalfSpace> halfSpaces) {
    Stop();
    // The thread's entries are those of the quadrics among the first done_ half-spaces (the same
    // values wherever the array now is); they stay where they are (the reserve holds them all).
    std::size_t quadrics = 0;
    const std::size_t done = std::min(done_, halfSpaces.size());
    for (std::size_t i = 0; i < done; ++i) quadrics += halfSpaces[i].IsQuadric();
    const bool kept = quadrics == entries_.size();
    madeAlongside_ = kept ? quadrics : 0;
    LiteralCache c =
        Slots(halfSpaces, kept ? std::move(entries_) : std::vector<LiteralCache::Entry>{});
    const std::size_t from = kept ? done : 0;
    entries_ = {};
    done_ = 0;
    MakeEntriesFrom(halfSpaces, from, c);
    return c;
}

}  // namespace quadrix
