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
    if (shown_ && shown_->generation == generation_) {
        // A frame of this view is shown: refine it (a reduced one to full resolution, a full
        // one to the anti-aliased one).
        r.refining = true;
        r.antialiased = shown_->scale == 1;
    } else {
        r.scale = MovingScale();  // the view is new: it moves
    }
    inFlight_ = r;
    return r;
}

void FrameScheduler::Delivered(const FrameRequest& request, double seconds) {
    inFlight_.reset();
    shown_ = request;
    if (request.antialiased) return;
    const double estimate = seconds * request.scale * request.scale;
    fullSeconds_ = fullSeconds_ > 0 ? 0.5 * (fullSeconds_ + estimate) : estimate;
}

}  // namespace quadrix::viewer
