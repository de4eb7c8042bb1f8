// The SDL2 side of `quadrix view` (viewer_window.cpp, compiled with SDL2 only: QUADRIX_HAVE_SDL2).
// Everything that is not SDL — the camera, the progressive schedule, picking, the script, the
// render thread — lives in src/quadrix/viewer/ and is unit-tested there.
#pragma once

#include <string>
#include <vector>

#include "quadrix/viewer/camera.h"
#include "quadrix/viewer/render_worker.h"
#include "quadrix/viewer/script.h"

namespace quadrix::cli {

struct ViewerSession {
    viewer::RenderWorker* worker = nullptr;
    viewer::Camera camera;          // the initial camera (R resets to it)
    viewer::SceneSphere sphere;     // orbit centre and fit-all extent
    int width = 960, height = 720;  // window size in pixels
    std::string engine = "raycast";
    std::vector<std::string> files;  // watched for live reload
    std::string name;                // for the title: the first scene file
    const std::vector<viewer::ScriptEvent>* script = nullptr;  // scripted input, or null
    int benchFrames = 0;      // > 0: play a fixed orbit of this many frames and report frames/s
    int benchScale = 1;       // its frames at 1/benchScale of the resolution (--bench-scale)
    int aaSamples = 0;        // anti-aliasing of the still frame (0 = off)
    bool cancelStale = true;  // abandon a refining frame when the view changes (--no-cancel)
    bool stats = false;       // print the latency figures at exit (--stats)
};

// Whether this build has the window (SDL2).
bool HaveViewerWindow();
// Wakes the window's event loop (any thread): the render thread calls it when a result is ready.
void WakeViewerWindow();
// Opens the window and runs the event loop until quit. Exit code: 0, or 1 when the window could
// not be opened or a scripted screenshot failed.
int RunViewerWindow(const ViewerSession& session);

}  // namespace quadrix::cli
