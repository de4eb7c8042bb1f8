// Helpers shared by the scene-level tests: running the quadrix binary, temporary directories,
// reading PNM images back, rendering a scene to a Frame in process.
#pragma once

#include <string>
#include <vector>

#include "quadrix/io/image.h"
#include "quadrix/pipeline/render_context.h"

namespace quadrix::testing {

struct CommandResult {
    int exitCode = -1;
    std::string out;  // standard output
    std::string err;  // standard error
};

// Runs a shell command line; captures both streams.
CommandResult RunShell(const std::string& commandLine);

// Runs the shell script `script` (a file) with a display server of its own (`xvfb-run -a`),
// after `prefix` (e.g. a background editor, whose end is waited for) in the same shell; env
// assignments may lead the prefix-free part through `env`. The exit status is the script's,
// read from a line printed after it, not xvfb-run's: that one is 5 when its clean-up of the
// server's temporary directory fails after the script has ended. When the server could not be
// started (two `-a` runs racing for one display number), the run is tried once more.
CommandResult RunUnderXvfb(const std::string& script, const std::string& prefix = "",
                           const std::string& env = "");

// The quadrix binary built with the tests, quoted for the shell.
std::string QuadrixBinary();
// Path of a file under the source tree (e.g. "examples/tube.uq").
std::string SourcePath(const std::string& relative);

// A fresh empty directory, removed when the object dies.
class TempDir {
  public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::string& path() const { return path_; }
    std::string File(const std::string& name) const { return path_ + "/" + name; }
    // Writes a file inside the directory and returns its path.
    std::string Write(const std::string& name, const std::string& contents) const;

  private:
    std::string path_;
};

bool FileExists(const std::string& path);
// Binary PGM/PPM (P5/P6, maxval 255). Returns false on any problem.
bool ReadPnm(const std::string& path, Image& image);
bool HaveProgram(const std::string& name);

// Reads `in`, flattens it at width × height in the scene's own view and renders it with the
// default engine into `frame`: the pipeline's four calls as the render command makes them. false,
// with the diagnostics in `diags`, on any error.
bool RenderToFrame(RenderContext& ctx, const InputRequest& in, int width, int height, Frame& frame,
                   Diagnostics& diags);
// The same for a file of the source tree (SourcePath), e.g. "examples/machined_part.uq".
bool RenderToFrame(RenderContext& ctx, const std::string& sourceFile, int width, int height,
                   Frame& frame);

}  // namespace quadrix::testing
