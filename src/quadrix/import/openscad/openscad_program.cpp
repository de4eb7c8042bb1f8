// Running OpenSCAD; see openscad_program.h.
#include "quadrix/import/openscad/openscad_program.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <thread>
#include <vector>

#include "quadrix/io/bounded_read.h"

extern char** environ;

namespace quadrix::import::scad {

namespace {

namespace fs = std::filesystem;

bool Executable(const std::string& p) {
    struct stat st {};
    return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0;
}

// A private directory, removed with everything in it when the object dies.
class ScratchDir {
  public:
    ScratchDir() {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/quadrix-scad-XXXXXX";
        std::vector<char> buf(pattern.begin(), pattern.end());
        buf.push_back('\0');
        if (::mkdtemp(buf.data()))
            path_ = buf.data();
        else
            error_ = std::strerror(errno);
    }
    ~ScratchDir() {
        if (path_.empty()) return;
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    const std::string& path() const { return path_; }
    const std::string& error() const { return error_; }

  private:
    std::string path_, error_;
};

SourceLoc LocOf(const std::string& file, int line) {
    SourceLoc loc;
    loc.file = std::make_shared<const std::string>(file);
    loc.line = line;
    return loc;
}

// "… in file F, line N" at the end of an OpenSCAD message → (message without it, F, N).
bool SplitPosition(const std::string& text, std::string& message, std::string& file, int& line) {
    const std::size_t at = text.rfind(" in file ");
    if (at == std::string::npos) return false;
    const std::size_t comma = text.rfind(", line ");
    if (comma == std::string::npos || comma < at) return false;
    std::string digits = text.substr(comma + 7);
    while (!digits.empty() &&
           (digits.back() == '.' || std::isspace(static_cast<unsigned char>(digits.back()))))
        digits.pop_back();
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) return false;
    line = std::atoi(digits.c_str());
    file = text.substr(at + 9, comma - at - 9);
    if (file.size() >= 2 && file.front() == '"' && file.back() == '"')
        file = file.substr(1, file.size() - 2);
    message = text.substr(0, at);
    while (!message.empty() && (message.back() == ',' || message.back() == ' ')) message.pop_back();
    return true;
}

}  // namespace

std::string FindOpenScad() {
    std::string name = "openscad";
    if (const char* env = std::getenv("QUADRIX_OPENSCAD")) {
        name = env;
        if (name.empty()) return {};
    }
    if (name.find('/') != std::string::npos) return Executable(name) ? name : std::string();
    const char* path = std::getenv("PATH");
    std::string dirs = path && *path ? path : "/usr/local/bin:/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        std::size_t end = dirs.find(':', start);
        if (end == std::string::npos) end = dirs.size();
        std::string dir = dirs.substr(start, end - start);
        if (dir.empty()) dir = ".";
        const std::string candidate = dir + "/" + name;
        if (Executable(candidate)) return candidate;
        start = end + 1;
    }
    return {};
}

bool EvaluateWithOpenScad(const std::string& program, const std::string& path,
                          std::string_view text, std::string& csg, Diagnostics& diags) {
    const SourceLoc fileLoc = LocOf(path, 0);
    auto fail = [&](const std::string& why) {
        diags.Error(fileLoc, fmt::format("OpenSCAD could not evaluate '{}': {}", path, why), {},
                    "input");
        return false;
    };
    ScratchDir dir;
    if (dir.path().empty()) return fail("cannot make a temporary directory: " + dir.error());

    // The input OpenSCAD reads: the file itself (so that include/use find their files), or a
    // copy of what was read when it is not a regular file.
    std::string input;
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) {
        input = fs::absolute(path, ec).string();
    } else {
        input = dir.path() + "/input.scad";
        const int fd = ::open(input.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
        bool ok = fd >= 0;
        for (std::size_t done = 0; ok && done < text.size();) {
            const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
            if (n < 0 && errno == EINTR) continue;
            ok = n > 0;
            if (ok) done += static_cast<std::size_t>(n);
        }
        if (fd >= 0 && ::close(fd) != 0) ok = false;
        if (!ok) return fail("cannot write a copy of the input into the temporary directory");
    }
    const std::string output = dir.path() + "/model.csg";
    const std::string log = dir.path() + "/openscad.log";

    double seconds = kDefaultSeconds;
    if (const char* env = std::getenv("QUADRIX_OPENSCAD_TIMEOUT")) {
        char* end = nullptr;
        const double v = std::strtod(env, &end);
        if (end != env && *end == 0 && v > 0 && std::isfinite(v)) seconds = v;
    }

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<std::string> args = {program, "-o", output, input};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int spawnError =
        posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawnError != 0)
        return fail(fmt::format("cannot run '{}': {}", program, std::strerror(spawnError)));

    // Wait, up to the time limit.
    int status = 0;
    bool timedOut = false;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (true) {
        const pid_t r = ::waitpid(pid, &status, WNOHANG);
        if (r == pid) break;
        if (r < 0 && errno != EINTR) return fail("lost the OpenSCAD process");
        if (std::chrono::steady_clock::now() >= deadline) {
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            timedOut = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }

    // Its messages → diagnostics.
    std::string messages;
    (void)ReadBoundedFile(log, messages, std::size_t{1} << 20);
    const std::string inputName = fs::path(input).filename().string();
    bool printedError = false;
    std::vector<std::string> lines;
    for (std::size_t s = 0; s < messages.size();) {
        std::size_t e = messages.find('\n', s);
        if (e == std::string::npos) e = messages.size();
        std::string line = messages.substr(s, e - s);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (!line.empty()) lines.push_back(line);
        s = e + 1;
    }
    for (const std::string& line : lines) {
        enum { kNone, kError, kWarning, kEcho } kind = kNone;
        std::string body;
        for (auto [prefix, k] : {std::pair{"ERROR: ", kError}, std::pair{"WARNING: ", kWarning},
                                 std::pair{"DEPRECATED: ", kWarning}, std::pair{"ECHO: ", kEcho}})
            if (line.rfind(prefix, 0) == 0) {
                kind = k;
                body = line.substr(std::strlen(prefix));
            }
        if (kind == kNone) continue;
        std::string message = body, file;
        int lineNo = 0;
        SourceLoc loc = fileLoc;
        if (SplitPosition(body, message, file, lineNo)) {
            // The input itself (however OpenSCAD spells it) is the user's path; another file is
            // an included one, named as OpenSCAD names it.
            const bool self =
                file == input || file == path || fs::path(file).filename().string() == inputName;
            loc = LocOf(self ? path : file, lineNo);
        }
        if (kind == kError) {
            printedError = true;
            diags.Error(loc, "OpenSCAD: " + message, {}, "input");
        } else if (kind == kWarning) {
            diags.Warning(loc, "OpenSCAD: " + message, {}, "input");
        } else {
            diags.Note(loc, "OpenSCAD: ECHO: " + message);
        }
    }
    auto tail = [&] {
        std::string t;
        const std::size_t from = lines.size() > 6 ? lines.size() - 6 : 0;
        for (std::size_t k = from; k < lines.size(); ++k) t += "\n    " + lines[k];
        return t.empty() ? std::string(" (it printed nothing)") : ":" + t;
    };
    if (timedOut)
        return fail(
            fmt::format("it ran longer than {} s and was stopped "
                        "(QUADRIX_OPENSCAD_TIMEOUT sets the limit)",
                        seconds));
    if (WIFSIGNALED(status))
        return fail(
            fmt::format("'{}' was killed by signal {}{}", program, WTERMSIG(status), tail()));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        if (printedError) return fail(fmt::format("exit status {}", WEXITSTATUS(status)));
        return fail(fmt::format("exit status {}{}", WEXITSTATUS(status), tail()));
    }
    if (printedError) return fail("it reported the errors above");
    if (std::string why = ReadBoundedFile(output, csg); !why.empty())
        return fail(fmt::format("it wrote no CSG output ({}){}", why, tail()));
    return true;
}

}  // namespace quadrix::import::scad
