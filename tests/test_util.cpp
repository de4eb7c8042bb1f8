#include "test_util.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace quadrix::testing {

namespace {
std::string Slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}
}  // namespace

CommandResult RunShell(const std::string& commandLine) {
    TempDir tmp;
    std::string outPath = tmp.File("stdout"), errPath = tmp.File("stderr");
    std::string full = "(" + commandLine + ") >'" + outPath + "' 2>'" + errPath + "'";
    int status = std::system(full.c_str());
    CommandResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = Slurp(outPath);
    r.err = Slurp(errPath);
    return r;
}

CommandResult RunUnderXvfb(const std::string& script, const std::string& prefix,
                           const std::string& env) {
    const std::string marker = "[xvfb-run script exit status ";
    const std::string wrapped =
        "sh -c 'sh \"$0\"; echo \"" + marker + "$?]\" >&2' '" + script + "'";
    CommandResult run;
    for (int attempt = 0; attempt < 2; ++attempt) {
        run = RunShell(prefix + env + "timeout 120 xvfb-run -a " + wrapped +
                       (prefix.empty() ? "" : "; s=$?; wait; exit $s"));
        const std::size_t at = run.err.rfind(marker);
        if (at != std::string::npos) {
            run.exitCode = std::atoi(run.err.c_str() + at + marker.size());
            run.err.erase(at, run.err.find('\n', at) - at + 1);
            return run;
        }
        if (run.err.find("Xvfb failed to start") == std::string::npos) break;
    }
    return run;  // no status line: the script did not end by itself (timeout, signal)
}

std::string QuadrixBinary() { return std::string("'") + QUADRIX_BINARY + "'"; }

std::string SourcePath(const std::string& relative) {
    return std::string(QUADRIX_SOURCE_DIR) + "/" + relative;
}

TempDir::TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "quadrix-test-XXXXXX").string();
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    if (mkdtemp(buf.data())) path_ = buf.data();
}

TempDir::~TempDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
}

std::string TempDir::Write(const std::string& name, const std::string& contents) const {
    std::string p = File(name);
    std::ofstream(p, std::ios::binary) << contents;
    return p;
}

bool FileExists(const std::string& path) { return std::filesystem::exists(path); }

bool ReadPnm(const std::string& path, Image& image) {
    std::ifstream in(path, std::ios::binary);
    // Header fields separated by whitespace, with '#' comments to the end of a line (POV-Ray
    // writes "# Software: POV-Ray ..." after the magic number).
    auto field = [&](std::string& out) {
        out.clear();
        int c;
        while ((c = in.get()) != EOF) {
            if (c == '#') {
                while ((c = in.get()) != EOF && c != '\n') {
                }
                continue;
            }
            if (std::isspace(c)) {
                if (!out.empty()) return true;
                continue;
            }
            out += static_cast<char>(c);
        }
        return !out.empty();
    };
    std::string magic, ws, hs, ms;
    if (!field(magic) || !field(ws) || !field(hs) || !field(ms)) return false;
    int w = std::atoi(ws.c_str()), h = std::atoi(hs.c_str()), maxval = std::atoi(ms.c_str());
    if ((magic != "P5" && magic != "P6") || maxval != 255 || w <= 0 || h <= 0) return false;
    image = Image(w, h, magic == "P6" ? 3 : 1);
    in.read(reinterpret_cast<char*>(image.pixels.data()),
            static_cast<std::streamsize>(image.pixels.size()));
    return static_cast<std::size_t>(in.gcount()) == image.pixels.size();
}

bool HaveProgram(const std::string& name) {
    return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

bool RenderToFrame(RenderContext& ctx, const InputRequest& in, int width, int height, Frame& frame,
                   Diagnostics& diags) {
    ViewRequest view;
    view.width = width;
    view.height = height;
    RenderReport report;
    return ctx.Read(in, diags) && ctx.Flatten(view, diags) &&
           ctx.Render(EngineRequest{}, frame, report, diags);
}

bool RenderToFrame(RenderContext& ctx, const std::string& sourceFile, int width, int height,
                   Frame& frame) {
    Diagnostics diags;
    InputRequest in;
    in.paths = {SourcePath(sourceFile)};
    return RenderToFrame(ctx, in, width, height, frame, diags);
}

}  // namespace quadrix::testing
