#include "quadrix/pipeline/cancellation.h"

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

namespace quadrix {

struct Cancellation::Active {
    tbb::task_group_context context;
};

Cancellation::Cancellation() = default;
Cancellation::~Cancellation() = default;

void Cancellation::Cancel() {
    std::lock_guard lock(mutex_);
    cancelled_.store(true, std::memory_order_release);
    if (active_) active_->context.cancel_group_execution();
}

bool Cancellation::Run(const std::function<void()>& work) {
    Active active;
    {
        std::lock_guard lock(mutex_);
        if (Cancelled()) return false;
        active_ = &active;
    }
    // One task in our context: the loops `work` starts are bound to it as their parent.
    tbb::parallel_for(
        0, 1, [&](int) { work(); }, active.context);
    {
        std::lock_guard lock(mutex_);
        active_ = nullptr;
    }
    return !Cancelled() && !active.context.is_group_execution_cancelled();
}

}  // namespace quadrix
