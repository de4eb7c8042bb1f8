// The Workers (worker.h) of one engine `raycast` object, kept from render to render.
//
// Why: a Worker's scratch grows during a render on its own thread. Made for each render and
// destroyed by the thread that ends it, the memory of one thread's Worker went, through the
// allocator's per-thread caches, to the other thread's Worker of the next render: the two
// threads' scratch then shared cache lines, and every block of a warm frame on two threads took
// 5–13 % longer than on one (docs/performance.md, "Workers kept from render to render"). Kept,
// a Worker stays with the thread that made it and so does its memory.
//
// Use: a render makes one RenderWorkers over the engine's pool for its tables, deepest node and
// settings, asks Local() in its loop bodies and ForEach() for the counters of the Workers it
// used. Only one render at a time uses the pool: a render that starts while another holds it
// (another thread's), and a render whose loops run inline on the calling thread (a SerialScope,
// util/parallel.h: no oneTBB is loaded for it), gets Workers of its own, made and freed with it,
// as before. Either way each Worker is bound to the render (Worker::Bind) before its first
// tile, and every pixel is the same bits.
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>

#include "quadrix/engines/raycast/worker.h"
#include "quadrix/util/parallel.h"

namespace quadrix::raycast {

class WorkerPool {
  public:
    WorkerPool() = default;
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

  private:
    friend class RenderWorkers;
    struct Slot {
        std::unique_ptr<Worker> worker;
        std::uint64_t render = 0;  // the last render that used it (RenderWorkers::render_)
    };
    std::atomic<bool> busy_{false};                               // a render holds the pool
    std::uint64_t renders_ = 0;                                   // renders that held it
    std::optional<tbb::enumerable_thread_specific<Slot>> slots_;  // made on first use
};

// One render's Workers: the pool's, bound to this render, or its own.
class RenderWorkers {
  public:
    RenderWorkers(WorkerPool& pool, const SceneTables* tables, int maxDepth, Settings settings)
        : tables_(tables), maxDepth_(maxDepth), settings_(settings) {
        if (!SerialLoopsOnThisThread() && !pool.busy_.exchange(true, std::memory_order_acquire)) {
            pool_ = &pool;
            render_ = ++pool.renders_;
            if (!pool.slots_) pool.slots_.emplace();
        } else {
            own_.emplace(tables, maxDepth, settings);
        }
    }
    ~RenderWorkers() {
        if (pool_) pool_->busy_.store(false, std::memory_order_release);
    }
    RenderWorkers(const RenderWorkers&) = delete;
    RenderWorkers& operator=(const RenderWorkers&) = delete;

    // The calling thread's Worker, bound to this render.
    Worker& Local() {
        if (!pool_) return own_->Local();
        WorkerPool::Slot& slot = pool_->slots_->local();
        if (!slot.worker)
            slot.worker = std::make_unique<Worker>(tables_, maxDepth_, settings_);
        else if (slot.render != render_)
            slot.worker->Bind(tables_, maxDepth_, settings_);
        slot.render = render_;
        return *slot.worker;
    }
    // f(const Worker&) for each Worker this render used.
    template <class F>
    void ForEach(const F& f) const {
        if (!pool_) {
            own_->ForEach(f);
            return;
        }
        for (const WorkerPool::Slot& slot : *pool_->slots_)
            if (slot.worker && slot.render == render_) f(*slot.worker);
    }

  private:
    const SceneTables* tables_;
    int maxDepth_;
    Settings settings_;
    WorkerPool* pool_ = nullptr;  // or own_
    std::uint64_t render_ = 0;
    std::optional<PerThread<Worker>> own_;
};

}  // namespace quadrix::raycast
