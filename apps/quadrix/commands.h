// Subcommands of the quadrix tool.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace quadrix::cli {

struct RenderArgs {
    // Set by main for the one-shot `quadrix render`: once every output is committed the process
    // ends at once (_exit), without freeing the Frame, the image and the scene (issue 24).
    bool exitWhenDone = false;
    std::vector<std::string> scenes;
    std::string output;
    std::string size = "512x512";
    std::string view;
    std::string engine = "raycast";
    bool fast = false;
    bool phong = false;  // Phong post-shading (seed 000's post-shading unit)
    bool png16 = false;  // 16-bit PNG output
    bool shadows = false;
    bool stats = false;
    bool json = false;  // --stats --json
    int threads = 0;
    std::string dumpFrame;
    std::vector<std::string> engineOptions;  // key=value
    // Importers and rt-style views (docs/import.md).
    std::vector<std::string> top;
    bool strict = false;
    bool allowMissing = false;
    std::vector<double> az, el, viewsize, eyePt, viewrot;  // empty = not given
    std::string rtView;                                     // file of rt view commands
    // Limits for servers and batch runs (docs/output.md).
    std::string maxMemory;  // e.g. "2G"; empty = the machine's budget only
    double timeLimit = 0;   // seconds of wall-clock time; 0 = none
};
void AddRenderCommand(CLI::App& app, RenderArgs& args);
int RunRender(const RenderArgs& args);

struct ExportArgs {
    std::vector<std::string> scenes;
    std::string to = "pov";
    std::string output;
    std::string size = "512x512";
    std::string view;
    bool mask = false;
    bool shadows = false;
    bool allowMissing = false;
};
void AddExportCommand(CLI::App& app, ExportArgs& args);
int RunExport(const ExportArgs& args);

// `quadrix uq [options] [files]` and `quadrix -i`: UniQuadrix batch and interactive modes with the
// paper's option syntax (uq_command.cpp, interactive.h).
void AddUqCommand(CLI::App& app);
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
struct CompareArgs {
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
struct DrawArgs {
    std::vector<std::string> scenes;
    std::string output;
    std::string size = "800x600";
    std::string view;
    std::string views;  // comma-separated standard views for a sheet
    std::string sheet = "A4";
    std::string projection = "third";
    std::string hidden = "dashed";
    bool stats = false;
};
void AddDrawCommand(CLI::App& app, DrawArgs& args);
int RunDraw(const DrawArgs& args);

// "WxH" → width, height; returns an error message or empty.
std::string ParseSize(const std::string& text, int& width, int& height);

}  // namespace quadrix::cli
