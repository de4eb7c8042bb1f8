// The one output writer; rules in output_file.h and docs/output.md.
#include "quadrix/io/output_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

namespace quadrix {

namespace {

// ---- The files this process has read (never to be replaced by an output) ----------------------

struct FileId {
    dev_t dev;
    ino_t ino;
    // The change time distinguishes a file from a later one that reuses the inode number after
    // the first was deleted (long-running processes, the test binary).
    long ctimeSec, ctimeNsec;
};

std::mutex gInputsMutex;
std::vector<FileId> gInputs;

FileId IdOf(const struct stat& st) {
    return {st.st_dev, st.st_ino, static_cast<long>(st.st_ctim.tv_sec),
            static_cast<long>(st.st_ctim.tv_nsec)};
}

bool SameFile(const struct stat& a, const struct stat& b) {
    return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

bool WasRead(const struct stat& st) {
    std::lock_guard<std::mutex> lock(gInputsMutex);
    FileId id = IdOf(st);
    for (const FileId& f : gInputs)
        if (f.dev == id.dev && f.ino == id.ino && f.ctimeSec == id.ctimeSec &&
            f.ctimeNsec == id.ctimeNsec)
            return true;
    return false;
}

// ---- Durability (QUADRIX_FSYNC) ----------------------------------------------------------------

// -1: not decided yet (read from the environment on first use), 0 off, 1 on.
std::atomic<int> gSync{-1};
std::atomic<long> gSyncCount{0};

int CountedSync(int fd) {
    gSyncCount.fetch_add(1, std::memory_order_relaxed);
    return fsync(fd);
}

// ---- The temporary files the signal handlers remove -------------------------------------------

// A fixed table, so that the handler touches no allocator and no lock: a slot is free (0),
// being filled or emptied (1), or holds the path of a live temporary file (2).
constexpr int kSlots = 64;
constexpr std::size_t kSlotPathMax = 4096;
char gSlotPaths[kSlots][kSlotPathMax];
std::atomic<int> gSlotState[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

void UnlinkRegistered() {
    for (int i = 0; i < kSlots; ++i)
        if (gSlotState[i].load() == 2) unlink(gSlotPaths[i]);  // async-signal-safe
}

extern "C" void RemoveTemporariesAndReraise(int sig) {
    const int savedErrno = errno;
    UnlinkRegistered();
    errno = savedErrno;
    // SA_RESETHAND restored the default action; the signal is blocked until this returns, then
    // delivered again and ends the process as it would have without us.
    raise(sig);
}

void InstallSignalHandlersOnce() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (int sig : kSignals) {
            struct sigaction old {};
            if (sigaction(sig, nullptr, &old) != 0) continue;
            // Leave alone a signal someone else handles or ignores (nohup, a Python host).
            if (old.sa_handler != SIG_DFL || (old.sa_flags & SA_SIGINFO)) continue;
            struct sigaction sa {};
            sa.sa_handler = RemoveTemporariesAndReraise;
            sigemptyset(&sa.sa_mask);
            sa.sa_flags = SA_RESETHAND;
            sigaction(sig, &sa, nullptr);
        }
    });
}

int RegisterTemporary(const std::string& path) {
    if (path.size() >= kSlotPathMax) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = 0;
        if (!gSlotState[i].compare_exchange_strong(expected, 1)) continue;
        std::memcpy(gSlotPaths[i], path.c_str(), path.size() + 1);
        gSlotState[i].store(2);
        return i;
    }
    return -1;  // more than kSlots files at once: still written, just not cleaned up on a signal
}

void UnregisterTemporary(int& slot) {
    if (slot < 0) return;
    gSlotState[slot].store(1);
    gSlotPaths[slot][0] = '\0';
    gSlotState[slot].store(0);
    slot = -1;
}

// The umask, read once before any thread can create files (reading it means setting it).
mode_t ReadUmask() {
    mode_t m = umask(0);
    umask(m);
    return m;
}
const mode_t gUmask = ReadUmask();

// ---- Checking a target ------------------------------------------------------------------------

const char* KindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::string Refuse(const std::string& path, const std::string& why) {
    return fmt::format("cannot write '{}': {}", path, why);
}

// Resolves `path` to the file that will be replaced: `target` (symbolic links followed),
// `exists` and its `st`. Returns an error message when it may not be written.
std::string ResolveTarget(const std::string& path, std::string& target, bool& exists,
                          struct stat& st) {
    exists = false;
    target = path;
    if (path.empty()) return "cannot write '': empty output path";
    if (lstat(path.c_str(), &st) != 0) {
        if (errno == ENOENT) return {};
        return Refuse(path, std::strerror(errno));
    }
    if (S_ISLNK(st.st_mode)) {
        char* resolved = realpath(path.c_str(), nullptr);
        if (!resolved) {
            if (errno == ENOENT)
                return Refuse(path, "it is a symbolic link to a file that does not exist");
            return Refuse(path, std::strerror(errno));
        }
        target = resolved;
        std::free(resolved);
        if (stat(target.c_str(), &st) != 0) return Refuse(path, std::strerror(errno));
    }
    exists = true;
    if (!S_ISREG(st.st_mode))
        return Refuse(
            path, fmt::format("it is {} (only regular files are replaced)", KindOf(st.st_mode)));
    if (WasRead(st)) return Refuse(path, "it is one of the input files");
    // A file its owner made read-only is not replaced, though the rename (which needs only the
    // directory's permission) could: the shell's `>` refuses it too. The rule: refused when the
    // user may not write it (access W_OK, by the effective ids), and also when no write bit is
    // set at all (mode & 0222 == 0) — root passes access() for any file, as it does `>`, but
    // a 0444 file is still a file someone meant to keep (as rm asks before removing it).
    if ((st.st_mode & 0222) == 0)
        return Refuse(path, fmt::format("it is read-only (mode {:04o}); make it writable to "
                                        "replace it",
                                        static_cast<unsigned>(st.st_mode & 07777)));
    if (faccessat(AT_FDCWD, target.c_str(), W_OK, AT_EACCESS) != 0 && errno == EACCES)
        return Refuse(path, "permission denied (it is not writable by this user)");
    return {};
}

std::string DirectoryOf(const std::string& path) {
    std::filesystem::path p(path);
    std::string dir = p.parent_path().string();
    return dir.empty() ? std::string(".") : dir;
}

}  // namespace

bool IsSameFile(const std::string& a, const std::string& b) {
    struct stat sa {
    }, sb{};
    return stat(a.c_str(), &sa) == 0 && stat(b.c_str(), &sb) == 0 && SameFile(sa, sb);
}

void NoteInputFile(int fd) {
    struct stat st {};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return;
    std::lock_guard<std::mutex> lock(gInputsMutex);
    gInputs.push_back(IdOf(st));
}

std::string CheckOutputPath(const std::string& path) {
    if (path == "-") return {};
    std::string target;
    bool exists = false;
    struct stat st {};
    return ResolveTarget(path, target, exists, st);
}

std::string CheckOutputPaths(const std::vector<std::string>& outputs,
                             const std::vector<std::string>& inputs) {
    struct Out {
        std::string path, key;
        bool exists;
        struct stat st;
    };
    std::vector<Out> resolved;
    for (const std::string& path : outputs) {
        if (path == "-") continue;
        Out o{path, {}, false, {}};
        std::string target;
        if (auto e = ResolveTarget(path, target, o.exists, o.st); !e.empty()) return e;
        std::error_code ec;
        o.key = std::filesystem::weakly_canonical(std::filesystem::absolute(target, ec), ec);
        for (const Out& prev : resolved)
            if (prev.key == o.key || (o.exists && prev.exists && SameFile(prev.st, o.st)))
                return Refuse(path,
                              fmt::format("it is the same file as the output '{}'", prev.path));
        resolved.push_back(std::move(o));
    }
    for (const std::string& in : inputs) {
        struct stat st {};
        if (in == "-" || stat(in.c_str(), &st) != 0) continue;
        for (const Out& o : resolved)
            if (o.exists && SameFile(o.st, st))
                return Refuse(o.path, fmt::format("it is the input file '{}'", in));
    }
    return {};
}

OutputFile::OutputFile(const std::string& path) : path_(path) {
    if (path == "-") {
        // Standard output: the bytes are collected in an anonymous temporary file and copied out
        // at Commit, so a failed encoder writes nothing at all (nothing half-written, as for a
        // file). tmpfile() is unlinked already: nothing to clean up at a signal.
        toStdout_ = true;
        file_ = std::tmpfile();
        if (!file_)
            error_ = fmt::format("cannot write to standard output: {}", std::strerror(errno));
        return;
    }
    bool exists = false;
    struct stat st {};
    error_ = ResolveTarget(path, target_, exists, st);
    if (!error_.empty()) return;
    mode_ = exists ? (st.st_mode & 0777) : (0666 & ~gUmask);
    InstallSignalHandlersOnce();
    std::string name = std::filesystem::path(target_).filename().string();
    std::string pattern = DirectoryOf(target_) + "/" + name + ".tmpXXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    // The name is entered in the signal table BEFORE the file exists, then the file is created
    // with O_EXCL (as mkstemp does): a signal may be handled by any thread (oneTBB's workers do
    // not block it), so no moment may pass with the file on disk and not in the table. Unlinking
    // a name whose file was not created yet is harmless.
    int fd = -1;
    static constexpr char kChars[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    // Six random characters from one getentropy call (std::random_device's set-up and six reads
    // cost more than the rest of the name); the clock and a counter if it fails. O_EXCL, not
    // the randomness, keeps two writers apart.
    static std::atomic<unsigned> counter{0};
    for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
        unsigned char random[6];
        if (getentropy(random, sizeof random) != 0) {
            const auto t = static_cast<std::uint64_t>(
                               std::chrono::steady_clock::now().time_since_epoch().count()) +
                           counter.fetch_add(1) * 0x9E3779B97F4A7C15ull;
            for (int b = 0; b < 6; ++b) random[b] = static_cast<unsigned char>(t >> (8 * b + 7));
        }
        const std::size_t n = buffer.size() - 1;  // the six X before the NUL
        for (std::size_t k = n - 6; k < n; ++k)
            buffer[k] = kChars[random[k - (n - 6)] % (sizeof kChars - 1)];
        tmp_ = buffer.data();
        slot_ = RegisterTemporary(tmp_);
        fd = open(buffer.data(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0600);
        if (fd < 0) {
            const int savedErrno = errno;
            UnregisterTemporary(slot_);
            tmp_.clear();
            errno = savedErrno;
            if (errno != EEXIST) break;
        }
    }
    if (fd < 0) {
        error_ = Refuse(path, std::strerror(errno));
        return;
    }
    file_ = fdopen(fd, "wb");
    if (!file_) {
        error_ = Refuse(path, std::strerror(errno));
        close(fd);
        unlink(tmp_.c_str());
        UnregisterTemporary(slot_);
        tmp_.clear();
    }
}

OutputFile::~OutputFile() {
    if (file_) std::fclose(file_);
    if (!committed_ && !tmp_.empty()) unlink(tmp_.c_str());
    UnregisterTemporary(slot_);
}

void OutputFile::Write(std::string_view bytes) {
    if (file_ && !bytes.empty()) std::fwrite(bytes.data(), 1, bytes.size(), file_);
}

std::string OutputFile::Finish() {
    if (finished_) return {};
    if (!file_) return error_.empty() ? Refuse(path_, "not open") : error_;
    if (toStdout_) {
        if (std::ferror(file_) != 0 || std::fflush(file_) != 0)
            return error_ = fmt::format("cannot write to standard output: {}",
                                        std::strerror(errno ? errno : EIO));
        finished_ = true;
        return {};
    }
    errno = 0;
    bool bad = std::ferror(file_) != 0;
    bad = bad || std::fflush(file_) != 0;
    const int fd = fileno(file_);
    bad = bad || fchmod(fd, static_cast<mode_t>(mode_)) != 0;
    bad = bad || (OutputSync() && CountedSync(fd) != 0);
    const int savedErrno = errno;
    const bool closeFailed = std::fclose(file_) != 0;
    file_ = nullptr;
    if (bad || closeFailed) {
        error_ = Refuse(path_, std::strerror(savedErrno ? savedErrno : errno ? errno : EIO));
        return error_;
    }
    finished_ = true;
    return {};
}

std::string OutputFile::CopyToStdout() {
    std::rewind(file_);
    char buffer[1 << 16];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, file_)) > 0)
        if (std::fwrite(buffer, 1, n, stdout) != n) break;
    const bool bad = std::ferror(file_) != 0 || std::fflush(stdout) != 0 || std::ferror(stdout);
    std::fclose(file_);
    file_ = nullptr;
    if (bad)
        return error_ = fmt::format("cannot write to standard output: {}",
                                    std::strerror(errno ? errno : EIO));
    committed_ = true;
    return {};
}

std::string OutputFile::Rename() {
    if (toStdout_) return CopyToStdout();
    // The target may have changed since the constructor looked (a FIFO planted meanwhile).
    std::string target;
    bool exists = false;
    struct stat st {};
    if (auto e = ResolveTarget(path_, target, exists, st); !e.empty()) return error_ = e;
    if (target != target_) return error_ = Refuse(path_, "the output path changed while writing");
    if (std::rename(tmp_.c_str(), target_.c_str()) != 0)
        return error_ = Refuse(path_, std::strerror(errno));
    committed_ = true;
    UnregisterTemporary(slot_);
    if (OutputSync()) {  // the rename itself durable
        int dir = open(DirectoryOf(target_).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (dir >= 0) {
            CountedSync(dir);
            close(dir);
        }
    }
    return {};
}

bool OutputSyncFromEnvironment(const char* value) {
    return value != nullptr && *value != '\0' && std::strcmp(value, "0") != 0;
}

bool OutputSync() {
    int s = gSync.load(std::memory_order_relaxed);
    if (s < 0) {
        s = OutputSyncFromEnvironment(std::getenv("QUADRIX_FSYNC")) ? 1 : 0;
        gSync.store(s, std::memory_order_relaxed);
    }
    return s == 1;
}

void SetOutputSync(bool sync) { gSync.store(sync ? 1 : 0, std::memory_order_relaxed); }

long OutputSyncCount() { return gSyncCount.load(std::memory_order_relaxed); }

std::string OutputFile::Commit() {
    if (auto e = Finish(); !e.empty()) return e;
    return Rename();
}

std::string CommitAll(const std::vector<OutputFile*>& files) {
    for (OutputFile* f : files)
        if (auto e = f->Finish(); !e.empty()) return e;
    for (OutputFile* f : files)
        if (auto e = f->Commit(); !e.empty()) return e;
    return {};
}

std::string WriteOutputFile(const std::string& path, std::string_view contents) {
    if (path == "-") {
        std::fwrite(contents.data(), 1, contents.size(), stdout);
        if (std::fflush(stdout) != 0 || std::ferror(stdout))
            return fmt::format("cannot write to standard output: {}", std::strerror(errno));
        return {};
    }
    OutputFile out(path);
    if (!out.ok()) return out.error();
    out.Write(contents);
    return out.Commit();
}

void RemoveTemporaryOutputFiles() { UnlinkRegistered(); }

int PendingOutputFiles() {
    int n = 0;
    for (int i = 0; i < kSlots; ++i) n += gSlotState[i].load() == 2;
    return n;
}

}  // namespace quadrix
