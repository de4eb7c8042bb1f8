// The parallel loops of the pipeline, and a way to run them without oneTBB (issue 24: small jobs).
//
// oneTBB starts on its first use in a process: its governor (loading its allocator, probing for
// other runtimes), the arena and a worker thread cost 2-3.5 ms on these machines, measured with
// an empty task_arena::execute — more than all the work of a 64 × 64 render. A thread inside a
// SerialScope runs ParallelFor and ParallelReduce inline over the whole range, in order, and
// never touches oneTBB; RenderContext does so for a context of one thread (`--threads 1`) and,
// when the threads were not given, for a small job. Every loop of the pipeline is written to give
// the same result for any number of threads and any split of its range, so inline is one more
// such split: the same bits.
//
//   ParallelFor(tbb::blocked_range<int>(0, n, grain), [&](const tbb::blocked_range<int>& r) {...});
//   ParallelFor(0, n, [&](int i) {...});
//   double m = ParallelReduce(range, 0.0, body, join);
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <cstddef>
#include <exception>
#include <optional>
#include <system_error>
#include <thread>
#include <utility>

namespace quadrix {

// Whether this thread's parallel loops run inline (a SerialScope is open on it).
inline bool& SerialLoopsOnThisThread() {
    thread_local bool serial = false;
    return serial;
}

// While it lives, the parallel loops started by this thread run inline (nesting is allowed).
class SerialScope {
  public:
    SerialScope() : before_(SerialLoopsOnThisThread()) { SerialLoopsOnThisThread() = true; }
    ~SerialScope() { SerialLoopsOnThisThread() = before_; }
    SerialScope(const SerialScope&) = delete;
    SerialScope& operator=(const SerialScope&) = delete;

  private:
    bool before_;
};

// The arena this thread's loops run in when it is in none (null: oneTBB's default), set by a
// LoopArenaScope. RenderContext runs its work under one instead of inside task_arena::execute,
// so that it goes on while another thread starts oneTBB and the arena (2-4 ms on these
// machines; longer than the whole flatten of a small part). A loop started before the arena is
// active does not wait for it: this thread runs the range's first grains itself, one at a time,
// until the arena is active, and gives it the rest (RunWhileStarting). Every loop gives the same
// result for any split of its range (above), so that is one more split: the same bits.
inline tbb::task_arena*& LoopArenaOnThisThread() {
    thread_local tbb::task_arena* arena = nullptr;
    return arena;
}

// The arena must be active or being started by another thread: a loop does not start it (one
// begun while it is inactive runs here, grain by grain, until it is active).
class LoopArenaScope {
  public:
    explicit LoopArenaScope(tbb::task_arena* arena) : before_(LoopArenaOnThisThread()) {
        LoopArenaOnThisThread() = arena;
    }
    ~LoopArenaScope() { LoopArenaOnThisThread() = before_; }
    LoopArenaScope(const LoopArenaScope&) = delete;
    LoopArenaScope& operator=(const LoopArenaScope&) = delete;

  private:
    tbb::task_arena* before_;
};

// Runs f in this thread's loop arena, or here when it has none (execute from inside the same
// arena, as in a nested loop, runs f directly).
template <class F>
auto InLoopArena(const F& f) {
    if (tbb::task_arena* arena = LoopArenaOnThisThread()) return arena->execute(f);
    return f();
}

// Whether this thread's loop arena is still starting (another thread is initialising it).
inline bool LoopArenaStarting() {
    const tbb::task_arena* arena = LoopArenaOnThisThread();
    return arena != nullptr && !arena->is_active();
}

// While the loop arena is starting: runs f on range's grains from its beginning, in order, each a
// blocked_range of at most grainsize() indices, until the range is done or the arena is active;
// returns what is left (empty when done).
template <class T, class F>
tbb::blocked_range<T> RunWhileStarting(const tbb::blocked_range<T>& range, const F& f) {
    const T end = range.end();
    const std::size_t grain = range.grainsize() > 0 ? range.grainsize() : 1;
    T begin = range.begin();
    while (begin < end && LoopArenaStarting()) {
        const T next = static_cast<std::size_t>(end - begin) > grain
                           ? static_cast<T>(begin + static_cast<T>(grain))
                           : end;
        f(tbb::blocked_range<T>(begin, next, range.grainsize()));
        begin = next;
    }
    return tbb::blocked_range<T>(begin, end, range.grainsize());
}

template <class T, class Body>
void ParallelFor(const tbb::blocked_range<T>& range, const Body& body) {
    if (SerialLoopsOnThisThread()) {
        if (!range.empty()) body(range);
        return;
    }
    const tbb::blocked_range<T> rest = RunWhileStarting(range, body);
    if (rest.empty()) return;
    InLoopArena([&] { tbb::parallel_for(rest, body); });
}

template <class Index, class Function>
void ParallelFor(Index first, Index last, const Function& f) {
    if (SerialLoopsOnThisThread()) {
        for (Index i = first; i < last; ++i) f(i);
        return;
    }
    while (first < last && LoopArenaStarting()) f(first++);
    if (!(first < last)) return;
    InLoopArena([&] { tbb::parallel_for(first, last, f); });
}

// join(value of the range's first part, value of the rest): the parts in order.
template <class T, class Value, class Body, class Join>
Value ParallelReduce(const tbb::blocked_range<T>& range, const Value& identity, const Body& body,
                     const Join& join) {
    if (SerialLoopsOnThisThread()) return range.empty() ? identity : body(range, identity);
    Value first = identity;
    bool some = false;
    const tbb::blocked_range<T> rest = RunWhileStarting(range, [&](const auto& r) {
        first = body(r, first);
        some = true;
    });
    if (rest.empty()) return first;
    Value last = InLoopArena([&] { return tbb::parallel_reduce(rest, identity, body, join); });
    return some ? join(first, last) : last;
}

// The processors this process may run on (its affinity mask; at least 1).
int AvailableProcessors();

// For the one heavy loop of a small job run inline (the anti-aliasing of a 64 × 64 picture is 30 %
// of its whole process): item(0), ..., item(n − 1) taken in order by this thread and by one
// std::thread (in a SerialScope of its own), each taking the next item not yet taken; both end
// before it returns, and an exception thrown by the helper is rethrown here (the helper then takes
// no more items). No oneTBB: its start would cost more than the loop (see the top). A new thread
// may wait most of a millisecond for a processor on a virtual machine, and this thread does not
// wait for it meanwhile. Each item must give the same result on either thread.
template <class Item>
void OnTwoThreads(int n, const Item& item) {
    std::atomic<int> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr failure;
    auto take = [&] {
        for (int i; !failed.load(std::memory_order_relaxed) && (i = next.fetch_add(1)) < n;)
            item(i);
    };
    std::thread helper;
    try {
        helper = std::thread([&] {
            SerialScope inline_;
            try {
                take();
            } catch (...) {
                failure = std::current_exception();
                failed = true;
            }
        });
    } catch (const std::system_error&) {
        // No thread to be had (a process at its limit): every item here.
    }
    try {
        take();
    } catch (...) {
        failed = true;
        if (helper.joinable()) helper.join();
        throw;
    }
    if (helper.joinable()) helper.join();
    if (failure) std::rethrow_exception(failure);
}

// One T per thread of the loops that use it (an engine's scratch and counters): oneTBB's
// enumerable_thread_specific, each made from the constructor's arguments on the thread's first
// Local(); or, made inside a SerialScope, the one T of the calling thread (oneTBB's allocator is
// then never loaded: 0.6-2 ms of a small process).
template <class T>
class PerThread {
  public:
    template <class... Args>
    explicit PerThread(const Args&... args) : inline_(SerialLoopsOnThisThread()) {
        if (inline_)
            one_.emplace(args...);
        else
            many_.emplace(args...);
    }
    T& Local() { return inline_ ? *one_ : many_->local(); }
    // f(const T&) for each T made.
    template <class F>
    void ForEach(const F& f) const {
        if (inline_) {
            f(*one_);
            return;
        }
        for (const T& t : *many_) f(t);
    }

  private:
    bool inline_;
    std::optional<T> one_;
    std::optional<tbb::enumerable_thread_specific<T>> many_;
};

}  // namespace quadrix
