// Subcommands of the quadrix tool.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "limit_options.h"
#include "quadrix/pipeline/camera.h"
#include "quadrix/pipeline/output.h"
#include "quadrix/pipeline/pipeline.h"
#include "quadrix/shade/picture_defaults.h"
#include "quadrix/shade/shader.h"

namespace quadrix::cli {

// The scene and view options render and export share (view_options.cpp; docs/cli.md): --view,
// --top, --allow-missing, the rt-style views (--az/--el, --viewsize, --eye-pt, --viewrot,
// --rt-view) and the OpenSCAD-style camera (--camera, --projection, --fov, --viewall,
// --autocenter). One table, one parser: every model that renders can be exported the same way.
struct SceneViewArgs {
    std::string view;
    // Importers and rt-style views (docs/import.md).
    std::vector<std::string> top;
    bool allowMissing = false;
    std::vector<double> az, el, viewsize, eyePt, viewrot;  // empty = not given
    std::string rtView;                                    // file of rt view commands
    // OpenSCAD-style camera (pipeline/camera.h).
    std::string camera, projection;
    std::vector<double> fov;  // empty = not given
    bool viewAll = false, autoCenter = false;
};
// Adds the options to `cmd`; `verb` ("draw", "export") words the --allow-missing help.
void AddSceneViewOptions(CLI::App& cmd, SceneViewArgs& args, const std::string& verb);
// The rt-style views → po (azimuth, elevation, viewsize, rtView) and the camera options →
// camera; a usage error message or empty (the rt view file's own errors go to diags).
std::string SceneViewOptions(const SceneViewArgs& args, PipelineOptions& po, CameraRequest& camera,
                             Diagnostics& diags);
// After Read (the input format says which axis is up): the camera's view into `view`.
bool ApplyCamera(RenderContext& ctx, CameraRequest camera, ViewRequest& view, Diagnostics& diags);

struct RenderArgs : SceneViewArgs, LimitArgs {
    // Set by main for the one-shot `quadrix render`: once every output is committed the process
    // ends at once (_exit), without freeing the Frame, the image and the scene (issue 24).
    bool exitWhenDone = false;
    std::vector<std::string> scenes;
    std::string output;
    std::string format;  // --format: overrides the extension (and the PNG of -o -)
    std::string size = "512x512";
    std::string engine = "raycast";
    bool fast = false;
    bool phong = false;  // Phong post-shading (seed 000's post-shading unit)
    bool png16 = false;  // 16-bit PNG output
    bool shadows = false;
    // Picture quality (docs/shading.md): --no-shadows, --aa N, --aa-filter, --edges.
    bool noShadows = false;
    std::string aa = "default";  // off | 4 | 16 | 64 | default (kDefaultAaSamples)
    std::string aaFilter = "box";
    bool edges = false;
    std::string section;  // --section "A B C D" (pipeline/section_plane.h); empty = none
    bool hatch = false;   // --hatch: hatch the section's cut faces (shade/section_hatch.h)
    bool stats = false;
    bool json = false;  // --stats --json
    int threads = 0;
    std::string dumpFrame;
    std::vector<std::string> engineOptions;  // key=value
    bool strict = false;                     // --strict (importers and engine composition)
    // Animation and view lists (docs/batch.md; src/quadrix/batch/).
    int frames = 0;          // --frames N
    std::string frameRange;  // --frame-range a:b
    int turntable = 0;       // --turntable N
    std::string views;       // --views FILE
    bool sortLast = false;   // --sort-last: solids shared among MPI ranks (batch/sort_last.h)
    bool sortFirst = false;  // --sort-first: pixel bands shared among MPI ranks (sort_first.h)
    bool resume = false;     // --resume: skip frames whose outputs exist and are complete
};
void AddRenderCommand(CLI::App& app, RenderArgs& args);
// The picture defaults, kDefaultAaSamples and ParseAaSamples: shade/picture_defaults.h.
int RunRender(const RenderArgs& args);

struct ExportArgs : SceneViewArgs, LimitArgs {
    std::vector<std::string> scenes;
    std::string to = "pov";
    std::string output;
    std::string size = "512x512";
    bool mask = false;
    bool shadows = false;
};
void AddExportCommand(CLI::App& app, ExportArgs& args);
int RunExport(const ExportArgs& args);

// `quadrix uq [options] [files]` and `quadrix -i`: UniQuadrix batch and interactive modes with the
// paper's option syntax (uq_command.cpp, interactive.h).
void AddUqCommand(CLI::App& app);
// The usage text of `quadrix uq` (also `quadrix help uq`).
void PrintUqUsage(std::FILE* out);
int RunUq(const std::vector<std::string>& args);
// Runs uq when argv[1] is "uq" or "-i" (before CLI11, which cannot parse glued values such as
// -dpng); returns false otherwise.
bool MaybeRunUq(int argc, char** argv, int& exitCode);

// `quadrix pipe`: tubes along polylines as UniQuadrix text (pipe_command.cpp, model/pipe.h).
struct PipeArgs {
    std::string input;
    std::string output;
    std::string definition;
    std::string prefix = "e";
    std::string generate;
    double radius = 0.25;
    double ball = 0;
};
void AddPipeCommand(CLI::App& app, PipeArgs& args);
int RunPipe(const PipeArgs& args);

// `quadrix compare`: two Frames pixel by pixel (compare_command.cpp, frame/compare.h).
struct CompareArgs : LimitArgs {
    std::vector<std::string> inputs;
    std::string engines;  // "a,b"
    std::string size = "320x240";
    std::string view;
    std::string diff;
    double tolerance = 1e-6;
};
void AddCompareCommand(CLI::App& app, CompareArgs& args);
int RunCompare(const CompareArgs& args);

// `quadrix engines`: the registry's rows (engines_command.cpp).
void AddEnginesCommand(CLI::App& app, bool& markdown);
int RunEngines(bool markdown);

// `quadrix draw`: exact hidden-line drawings (draw_command.cpp, draw/drawing.h).
struct DrawArgs : LimitArgs {
    std::vector<std::string> scenes;
    std::string output;
    std::string size = "800x600";
    std::string view;
    std::string views;  // comma-separated standard views for a sheet
    // Sheet options; empty = not given (A4, third angle, the largest standard scale that fits).
    // Any of them without --views asks for the standard sheet, front,top,right,iso.
    std::string sheet;
    std::string projection;
    std::string scale;      // "1:2", "2:1" or a number (paper units per world unit)
    std::string tolerance;  // --tolerance: px on a single view, mm on a sheet; empty = default
    std::string hidden = "dashed";
    std::string tangentEdges = "thin";  // --tangent-edges thin|off|on
    std::string section;                // --section "A B C D", as quadrix render's
    bool allowMissing = false;  // --allow-missing: freeform surfaces left out with a warning
    bool stats = false;
};
void AddDrawCommand(CLI::App& app, DrawArgs& args);
int RunDraw(const DrawArgs& args);

// `quadrix man` (hidden): quadrix(1) or the bash completion, generated from `app`'s own option
// tables (man_command.cpp).
struct ManArgs {
    bool bashCompletion = false;
    std::string output;
};
void AddManCommand(CLI::App& app, ManArgs& args);
int RunMan(const CLI::App& app, const ManArgs& args);
// `quadrix batch JOBFILE` (batch_command.cpp) and render's animation options
// (animation_options.cpp; src/quadrix/batch/, docs/batch.md).
struct BatchArgs : LimitArgs {
    std::string jobFile;
    int threads = 0;
    bool restart = false;  // render every frame, even those whose outputs exist
    bool quiet = false;
    bool json = false;  // the summary as JSON on standard output
};
void AddBatchCommand(CLI::App& app, BatchArgs& args);
int RunBatch(const BatchArgs& args);
void AddAnimationOptions(CLI::App& cmd, RenderArgs& args);
// Stage 3 of `render` with --sort-last (the solids shared among MPI ranks) or --sort-first (the
// pixels); sets `writer` false on the ranks that do not write the picture. With --sort-first the
// ranks shade their rows too (stage 4, with `shade` when the outputs need an image) and `image`
// is the gathered picture; otherwise `image` is left empty for the caller to shade.
bool RenderMaybeShared(const RenderArgs& args, const OutputRequest& outputs, RenderContext& ctx,
                       const EngineRequest& engine, const ShadeOptions* shade, Frame& frame,
                       std::optional<Image>& image, RenderReport& report, Diagnostics& diags,
                       bool& writer);
int RunAnimation(const RenderArgs& args, const PipelineOptions& po, const EngineRequest& engine,
                 const ShadeOptions& shade, const PictureDefaults& picture,
                 const OutputRequest& outputs);
// `quadrix view`: the interactive window (view_command.cpp, viewer_window.cpp, docs/viewer.md).
struct ViewArgs : LimitArgs {
    std::vector<std::string> scenes;
    std::string size = "960x720";
    std::string view;
    std::string engine = "raycast";
    int threads = 0;
    std::string script;
    int bench = 0;
    int benchScale = 1;  // --bench-scale: the orbit's frames at 1/S of the resolution
    bool offscreen = false;
    std::vector<std::string> top;
    bool allowMissing = false;
    std::string aa = "default";  // the still frame's anti-aliasing, as quadrix render's --aa
    bool noCancel = false;       // finish stale refining frames (to measure what cancelling saves)
    bool stats = false;          // latency figures at exit
};
void AddViewCommand(CLI::App& app, ViewArgs& args);
int RunView(const ViewArgs& args);

// "WxH" → width, height; returns an error message or empty.
std::string ParseSize(const std::string& text, int& width, int& height);

}  // namespace quadrix::cli
