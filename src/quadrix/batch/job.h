// A render job of the batch module (issue 22, docs/batch.md): one scene (its inputs), one way of
// seeing it (a view, or an animation: frames with a clock, a turntable, a list of views), one
// engine, one output pattern. `quadrix render --frames/--turntable/--views` makes one job,
// `quadrix batch JOBFILE` one per line; the scheduler (run.h) renders their frames.
//
// Frames. A job has FrameCount() frames, numbered 0 .. count-1; a still picture is one frame.
//   clock(i) = i / (count - 1)    (0 for a single frame): 0 at the first frame, 1 at the last,
//                                 like POV-Ray's +KFI/+KFF clock (docs/language.md §3.14);
//   turntable az(i) = az0 + 360 i / count   (a closed orbit: frame `count` would repeat frame 0).
// Only the frames of [first, last] are rendered (--frame-range); their numbers stay the same.
// Output names (FramePath): a printf-style pattern in the path (`out_%04d.png`, `%d`) takes the
// frame number; without one an animation inserts `_%04d` before the extension (`out.png` →
// `out_0000.png`) and a still picture keeps the path as given.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "quadrix/import/rt_view.h"
#include "quadrix/pipeline/output.h"
#include "quadrix/pipeline/render_context.h"
#include "quadrix/scene/scene.h"
#include "quadrix/shade/picture_defaults.h"
#include "quadrix/shade/shader.h"

namespace quadrix::batch {

// One entry of a view list (--views FILE, view_list.h): a view statement's view, or an rt view.
struct ListedView {
    std::optional<scene::View> view;
    std::optional<import::RtView> rtView;
    std::string name;  // for messages: the view's id or "rt view k"
};

struct Turntable {
    double azimuth0 = 35;   // degrees (rt convention, about Quadrix's y axis) at frame 0
    double elevation = 25;  // degrees
};

struct Job {
    InputRequest input;  // paths and importer options; input.clock is set per frame
    ViewRequest view;    // size and the still view (name, az/el, rt view)
    EngineRequest engine;
    ShadeOptions shade;       // as asked; the picture defaults are added frame by frame
    PictureDefaults picture;  // which of them apply (shade/picture_defaults.h)
    OutputRequest output;     // image: a path or a pattern; dumpFrame likewise (may be empty)
    int frames = 0;           // 0 = a still picture (or as many frames as `views`)
    std::optional<Turntable> turntable;
    std::vector<ListedView> views;  // one frame per view
    int first = 0, last = -1;       // frame range; last < 0 = to the end
    std::string label;              // how messages name the job ("job 3 (jobs.jsonl:3)")

    int FrameCount() const;
    // The frames to render: [first, min(last, count-1)].
    int FirstFrame() const { return first; }
    int LastFrame() const;
    bool Animated() const { return frames > 0 || !views.empty(); }
    double Clock(int frame) const;
};

// Checks the job's own consistency (frame range, views with frames, output pattern). Error or
// empty.
std::string CheckJob(const Job& job);

// The output path of frame `frame` (see the header comment). `animated` false: `path` as given.
std::string FramePath(const std::string& path, int frame, bool animated);
// Whether `path` holds a printf-style frame number (%d, %4d, %04d); "%%" is a literal '%'.
bool HasFramePattern(const std::string& path);

}  // namespace quadrix::batch
