// Cancelling a frame while it is drawn (issue 18 §3: the viewer abandons a frame whose view is
// already stale). The render thread runs the engines, the compositing and the anti-aliasing pass
// under Run(); any other thread may call Cancel(). Run executes its work as the one task of a
// oneTBB parallel loop with a task_group_context of its own, so the engines' nested parallel
// loops (their tiles and blocks) are bound to that context: cancelling it makes the scheduler
// skip every tile not yet started, with no check in the engines' code. The work then returns with
// an incomplete Frame or Image, which the caller throws away (Run says so).
//
// A cancellation stays in force — later Run calls return at once — until Reset(), which the
// render thread calls before it starts the next frame.
#pragma once

#include <atomic>
#include <functional>
#include <mutex>

namespace quadrix {

class Cancellation {
  public:
    Cancellation();
    ~Cancellation();
    Cancellation(const Cancellation&) = delete;
    Cancellation& operator=(const Cancellation&) = delete;

    // Any thread.
    void Cancel();
    bool Cancelled() const { return cancelled_.load(std::memory_order_acquire); }
    // The render thread, between frames.
    void Reset() { cancelled_.store(false, std::memory_order_release); }
    // Runs `work` (on the calling thread, which joins the loops it starts). false when it was
    // cancelled, before or during the run: what it made is then incomplete.
    bool Run(const std::function<void()>& work);

  private:
    struct Active;
    std::mutex mutex_;
    Active* active_ = nullptr;  // the context of the running work, under mutex_
    std::atomic<bool> cancelled_{false};
};

}  // namespace quadrix
