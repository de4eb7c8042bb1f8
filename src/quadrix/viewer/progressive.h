// Progressive refinement of the viewer (issue 18 §3; Elber's coarse-to-fine drawing, seed 002):
// while the view moves, frames are drawn at a reduced resolution chosen so that one frame fits
// the interaction budget; when it stops, the full-resolution exact frame follows, and then (with
// anti-aliasing on) the anti-aliased one, the same Frame shaded again with sub-pixel samples at
// its edge pixels. Those two are the refining frames: when the view changes while one is drawn,
// it is stale and the window cancels it (RefinementInFlight, Abandoned); a moving frame is short
// and always finished, so that a continuous drag keeps delivering pictures.
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
    int scale = 1;             // the image is (W/scale)×(H/scale), rounded up
    bool antialiased = false;  // the still frame's last stage (scale 1)
    bool refining = false;     // asked for because the view stood still (cancellable)
};

class FrameScheduler {
  public:
    explicit FrameScheduler(double budgetSeconds = 1.0 / 40, bool antialias = false)
        : budget_(budgetSeconds), antialias_(antialias) {}

    // The view (or engine, size, scene) changed: the shown picture is out of date.
    void ViewChanged() { ++generation_; }
    // The frame to ask for now that the worker is idle (nullopt: one is in flight, or the full
    // frame of the current view is shown). Marks it in flight.
    std::optional<FrameRequest> Next();
    // The worker delivered `request` after `seconds` (an anti-aliased frame's time is not a
    // full frame's and leaves the estimate alone).
    void Delivered(const FrameRequest& request, double seconds);
    // The worker abandoned the frame in flight (cancelled): nothing new is shown.
    void Abandoned() { inFlight_.reset(); }
    // Whether the last stage of the current view is shown (full resolution, anti-aliased when
    // anti-aliasing is on).
    bool Final() const {
        return shown_ && shown_->generation == generation_ && shown_->scale == 1 &&
               (shown_->antialiased || !antialias_);
    }
    bool InFlight() const { return inFlight_.has_value(); }
    // A refining frame is being drawn (of this view or an older one): a pick or a reload that
    // would wait for it cancels it (it is asked for again).
    bool RefinementInFlight() const { return inFlight_ && inFlight_->refining; }
    // A refining frame of an older view is being drawn: worth cancelling.
    bool StaleRefinementInFlight() const {
        return inFlight_ && inFlight_->refining && inFlight_->generation != generation_;
    }
    std::uint64_t Generation() const { return generation_; }
    int MovingScale() const;
    double FullFrameEstimate() const { return fullSeconds_; }

  private:
    double budget_;
    bool antialias_;
    double fullSeconds_ = 0;  // 0 = unknown: the first frame is drawn at full resolution
    std::uint64_t generation_ = 1;
    std::optional<FrameRequest> shown_, inFlight_;
};

}  // namespace quadrix::viewer
