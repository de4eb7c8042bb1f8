// Progressive refinement of the viewer (issue 18 §3; Elber's coarse-to-fine drawing, seed 002):
// while the view moves, frames are drawn at a reduced resolution chosen so that one frame fits
// the interaction budget; when it stops, the full-resolution exact frame follows.
//
// One frame is in flight at a time. Changes that arrive meanwhile only bump the generation; the
// next request, made when the worker is idle, carries the latest view: superseded views are never
// drawn. The scale of a moving frame is the smallest s in {1, 2, 3, 4, 6, 8, 12, 16} with
//     T_full / s² <= budget,
// where T_full is the estimated time of a full-resolution frame: each delivered frame of scale s
// taking t seconds estimates T_full = t·s² (time proportional to the pixel count), smoothed
// (the mean of the previous estimate and the new one).
#pragma once

#include <cstdint>
#include <optional>

namespace quadrix::viewer {

struct FrameRequest {
    std::uint64_t generation = 0;
    int scale = 1;  // the image is (W/scale)×(H/scale), rounded up
};

class FrameScheduler {
  public:
    explicit FrameScheduler(double budgetSeconds = 1.0 / 40) : budget_(budgetSeconds) {}

    // The view (or engine, size, scene) changed: the shown picture is out of date.
    void ViewChanged() { ++generation_; }
    // The frame to ask for now that the worker is idle (nullopt: one is in flight, or the full
    // frame of the current view is shown). Marks it in flight.
    std::optional<FrameRequest> Next();
    // The worker delivered `request` after `seconds`.
    void Delivered(const FrameRequest& request, double seconds);
    // Whether the full-resolution frame of the current view is shown.
    bool Final() const { return shown_ && shown_->generation == generation_ && shown_->scale == 1; }
    bool InFlight() const { return inFlight_.has_value(); }
    std::uint64_t Generation() const { return generation_; }
    int MovingScale() const;
    double FullFrameEstimate() const { return fullSeconds_; }

  private:
    double budget_;
    double fullSeconds_ = 0;  // 0 = unknown: the first frame is drawn at full resolution
    std::uint64_t generation_ = 1;
    std::optional<FrameRequest> shown_, inFlight_;
};

}  // namespace quadrix::viewer
