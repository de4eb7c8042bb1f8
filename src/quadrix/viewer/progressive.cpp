#include "quadrix/viewer/progressive.h"

namespace quadrix::viewer {

int FrameScheduler::MovingScale() const {
    static constexpr int kScales[] = {1, 2, 3, 4, 6, 8, 12, 16};
    for (int s : kScales)
        if (fullSeconds_ / (s * s) <= budget_) return s;
    return kScales[sizeof(kScales) / sizeof(kScales[0]) - 1];
}

std::optional<FrameRequest> FrameScheduler::Next() {
    if (inFlight_ || Final()) return std::nullopt;
    FrameRequest r;
    r.generation = generation_;
    // A reduced frame of this view is shown: refine it. Otherwise the view is new (moving).
    r.scale = (shown_ && shown_->generation == generation_) ? 1 : MovingScale();
    inFlight_ = r;
    return r;
}

void FrameScheduler::Delivered(const FrameRequest& request, double seconds) {
    inFlight_.reset();
    shown_ = request;
    const double estimate = seconds * request.scale * request.scale;
    fullSeconds_ = fullSeconds_ > 0 ? 0.5 * (fullSeconds_ + estimate) : estimate;
}

}  // namespace quadrix::viewer
