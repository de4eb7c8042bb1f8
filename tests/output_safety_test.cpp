// The one output writer (io/output_file.h, docs/output.md) seen from the command line and from
// the library: a symbolic link is written through, a dangling link, FIFO, directory, device node
// or input file is refused with the target untouched, exit != 0 and no file left behind; modes
// are kept; a signal while writing leaves no temporary file (issue 23).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "quadrix/io/bounded_read.h"
#include "quadrix/io/output_file.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

namespace fs = std::filesystem;

const char* kSphere = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n";

std::string Slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Names in `dir` other than `keep`, e.g. temporary files left behind.
std::vector<std::string> Others(const TempDir& dir, const std::vector<std::string>& keep) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir.path())) {
        std::string name = e.path().filename().string();
        bool kept = false;
        for (const auto& k : keep) kept = kept || k == name;
        if (!kept) out.push_back(name);
    }
    return out;
}

CommandResult Render(const TempDir& dir, const std::string& args) {
    return RunShell("cd '" + dir.path() + "' && " + QuadrixBinary() + " render " + args);
}

// The three refusals every case shares: exit != 0 (not a signal), a "cannot write" message,
// and nothing but `keep` in the directory.
void ExpectRefused(const CommandResult& r, const TempDir& dir,
                   const std::vector<std::string>& keep) {
    EXPECT_NE(r.exitCode, 0) << r.err;
    EXPECT_LT(r.exitCode, 128) << r.err;
    EXPECT_NE(r.err.find("cannot write"), std::string::npos) << r.err;
    EXPECT_TRUE(Others(dir, keep).empty()) << Others(dir, keep)[0];
}

TEST(OutputSafety, SymbolicLinkIsWrittenThrough) {
    TempDir dir;
    dir.Write("s.uq", kSphere);
    dir.Write("real.ppm", "old");
    fs::create_symlink("real.ppm", dir.File("out.ppm"));
    CommandResult r = Render(dir, "s.uq --size 16x16 -o out.ppm");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::is_symlink(dir.File("out.ppm")));
    EXPECT_EQ(Slurp(dir.File("real.ppm")).substr(0, 1), "P");  // P5 or P6: a PNM now
    EXPECT_EQ(Others(dir, {"s.uq", "real.ppm", "out.ppm"}).size(), 0u);
}

TEST(OutputSafety, DanglingSymbolicLinkIsRefused) {
    TempDir dir;
    dir.Write("s.uq", kSphere);
    fs::create_symlink("nowhere.ppm", dir.File("out.ppm"));
    ExpectRefused(Render(dir, "s.uq --size 16x16 -o out.ppm"), dir, {"s.uq", "out.ppm"});
    EXPECT_FALSE(fs::exists(dir.File("nowhere.ppm")));
}

TEST(OutputSafety, FifoIsRefusedWithoutBlocking) {
    TempDir dir;
    dir.Write("s.uq", kSphere);
    ASSERT_EQ(mkfifo(dir.File("out.png").c_str(), 0644), 0);
    // A writer that opened the FIFO would block forever: `timeout` turns that into a failure.
    CommandResult r = RunShell("cd '" + dir.path() + "' && timeout 20 " + QuadrixBinary() +
                               " render s.uq --size 16x16 -o out.png");
    ExpectRefused(r, dir, {"s.uq", "out.png"});
    EXPECT_NE(r.err.find("FIFO"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_fifo(dir.File("out.png")));
}

TEST(OutputSafety, DirectoryIsRefused) {
    TempDir dir;
    dir.Write("s.uq", kSphere);
    fs::create_directory(dir.File("out.png"));
    ExpectRefused(Render(dir, "s.uq --size 16x16 -o out.png"), dir, {"s.uq", "out.png"});
    EXPECT_TRUE(fs::is_directory(dir.File("out.png")));
    EXPECT_TRUE(fs::is_empty(dir.File("out.png")));
}

TEST(OutputSafety, DeviceNodeIsRefused) {
    // Only a node made in our own temporary directory, never a real device file.
    if (geteuid() != 0) GTEST_SKIP() << "mknod needs root";
    TempDir dir;
    dir.Write("s.uq", kSphere);
    if (mknod(dir.File("null.png").c_str(), S_IFCHR | 0644, makedev(1, 3)) != 0)
        GTEST_SKIP() << "mknod is not permitted here";
    ExpectRefused(Render(dir, "s.uq --size 16x16 -o null.png"), dir, {"s.uq", "null.png"});
    struct stat st {};
    ASSERT_EQ(lstat(dir.File("null.png").c_str(), &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
    // The uq device path of the issue (-d ascii:/dev/full run as root), on our own node.
    CommandResult r =
        RunShell("cd '" + dir.path() + "' && " + QuadrixBinary() + " uq -dascii:null.png s.uq");
    ExpectRefused(r, dir, {"s.uq", "null.png"});
    ASSERT_EQ(lstat(dir.File("null.png").c_str(), &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(OutputSafety, ReadOnlyDirectoryLeavesNothing) {
    TempDir dir;
    dir.Write("s.uq", kSphere);
    fs::create_directory(dir.File("ro"));
    dir.Write("ro/out.ppm", "old");
    chmod(dir.File("ro").c_str(), 0555);
    std::string run = QuadrixBinary() + " render s.uq --size 16x16 -o ro/out.ppm";
    if (geteuid() == 0) {
        // Root ignores directory permissions: run as nobody (the directories are opened up for
        // reading and searching only).
        if (!HaveProgram("setpriv")) GTEST_SKIP() << "running as root without setpriv";
        chmod(dir.path().c_str(), 0755);
        run = "setpriv --reuid=65534 --regid=65534 --clear-groups " + run;
    }
    CommandResult r = RunShell("cd '" + dir.path() + "' && " + run);
    chmod(dir.File("ro").c_str(), 0755);
    EXPECT_NE(r.exitCode, 0) << r.err;
    EXPECT_LT(r.exitCode, 128) << r.err;
    EXPECT_NE(r.err.find("cannot write"), std::string::npos) << r.err;
    EXPECT_EQ(Slurp(dir.File("ro/out.ppm")), "old");
    int n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.File("ro"))) ++n;
    EXPECT_EQ(n, 1);
}

TEST(OutputSafety, InputIsNeverAnOutput) {
    TempDir dir;
    const std::string scene = dir.Write("s.uq", kSphere);
    // --dump-frame onto the scene (the case; .uq is no dump name any more, so a .qxf
    // hard link stands for it), refused before the image is written.
    fs::create_hard_link(scene, dir.File("s.qxf"));
    ExpectRefused(Render(dir, "s.uq --size 16x16 -o out.ppm --dump-frame s.qxf"), dir,
                  {"s.uq", "s.qxf"});
    EXPECT_EQ(Slurp(scene), kSphere);
    fs::remove(dir.File("s.qxf"));
    // export onto its own input.
    CommandResult r =
        RunShell("cd '" + dir.path() + "' && " + QuadrixBinary() + " export --to pov s.uq -o s.uq");
    ExpectRefused(r, dir, {"s.uq"});
    EXPECT_EQ(Slurp(scene), kSphere);
    // The same file under another name (a hard link) is still the input.
    fs::create_hard_link(scene, dir.File("alias.ppm"));
    ExpectRefused(Render(dir, "s.uq --size 16x16 -o alias.ppm"), dir, {"s.uq", "alias.ppm"});
    EXPECT_EQ(Slurp(scene), kSphere);
}

TEST(OutputSafety, FileReadByTheSceneIsNeverAnOutput) {
    // main.uq reads part.uq; part.ppm is a hard link to part.uq, known only once it was read.
    TempDir dir;
    dir.Write("main.uq", "read \"part.uq\";\n");
    const std::string part = dir.Write("part.uq", kSphere);
    fs::create_hard_link(part, dir.File("part.ppm"));
    ExpectRefused(Render(dir, "main.uq --size 16x16 -o part.ppm"), dir,
                  {"main.uq", "part.uq", "part.ppm"});
    EXPECT_EQ(Slurp(part), kSphere);
}

TEST(OutputSafety, FailedDumpFrameWritesNoImage) {
    TempDir dir;
    dir.Write("s.uq", kSphere);
    fs::create_directory(dir.File("dump.qxf"));
    ExpectRefused(Render(dir, "s.uq --size 16x16 -o out.ppm --dump-frame dump.qxf"), dir,
                  {"s.uq", "dump.qxf"});
    EXPECT_FALSE(fs::exists(dir.File("out.ppm")));
    // The same file twice is refused too (one would silently replace the other).
    ExpectRefused(Render(dir, "s.uq --size 16x16 -o a.qxf --dump-frame ./a.qxf"), dir,
                  {"s.uq", "dump.qxf"});
}

TEST(OutputSafety, PipeIgnoresAPlantedTemporaryName) {
    // The attack: `ln -s victim o.uq.tmp; quadrix pipe p.pipe -o o.uq` overwrote victim.
    TempDir dir;
    dir.Write("p.pipe", "radius .25\npath\n0 0 0\n1 0 0\n");
    dir.Write("victim", "precious");
    fs::create_symlink("victim", dir.File("o.uq.tmp"));
    CommandResult r =
        RunShell("cd '" + dir.path() + "' && " + QuadrixBinary() + " pipe p.pipe -o o.uq");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(Slurp(dir.File("victim")), "precious");
    EXPECT_NE(Slurp(dir.File("o.uq")).find("quadric"), std::string::npos);
    EXPECT_TRUE(Others(dir, {"p.pipe", "victim", "o.uq.tmp", "o.uq"}).empty());
    // And its input as its output is refused.
    r = RunShell("cd '" + dir.path() + "' && " + QuadrixBinary() + " pipe p.pipe -o p.pipe");
    ExpectRefused(r, dir, {"p.pipe", "victim", "o.uq.tmp", "o.uq"});
}

TEST(OutputSafety, ModeOfTheReplacedFileIsKept) {
    TempDir dir;
    dir.Write("s.uq", kSphere);
    dir.Write("private.ppm", "old");
    chmod(dir.File("private.ppm").c_str(), 0600);
    ASSERT_EQ(Render(dir, "s.uq --size 16x16 -o private.ppm").exitCode, 0);
    struct stat st {};
    ASSERT_EQ(stat(dir.File("private.ppm").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u);
    // A new file gets 0666 minus the umask.
    ASSERT_EQ(RunShell("cd '" + dir.path() + "' && umask 027 && " + QuadrixBinary() +
                       " render s.uq --size 16x16 -o new.ppm")
                  .exitCode,
              0);
    ASSERT_EQ(stat(dir.File("new.ppm").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0640u);
}

// A read-only file is not replaced (the rename needs only the directory's permission, so it was
// replaced with exit 0). Rule (docs/output.md rule 1): refused when no write bit is set — for
// every user, root included — or when this user may not write it (access W_OK).
TEST(OutputSafety, ReadOnlyFileIsNotReplaced) {
    TempDir dir;
    dir.Write("s.uq", kSphere);
    dir.Write("ro.ppm", "old");
    ASSERT_EQ(chmod(dir.File("ro.ppm").c_str(), 0444), 0);
    // As the current user (root too: the mode-bit rule).
    CommandResult r = Render(dir, "s.uq --size 16x16 -o ro.ppm");
    ExpectRefused(r, dir, {"s.uq", "ro.ppm"});
    EXPECT_NE(r.err.find("read-only (mode 0444)"), std::string::npos) << r.err;
    EXPECT_EQ(Slurp(dir.File("ro.ppm")), "old");
    struct stat st {};
    ASSERT_EQ(stat(dir.File("ro.ppm").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0444u);
    // Through a symbolic link, and by the other writers (export, uq's devices, pipe).
    fs::create_symlink("ro.ppm", dir.File("link.ppm"));
    ExpectRefused(Render(dir, "s.uq --size 16x16 -o link.ppm"), dir,
                  {"s.uq", "ro.ppm", "link.ppm"});
    const std::vector<std::string> others = {"export --to pov s.uq -o ro.ppm",
                                             "uq -dppm:ro.ppm s.uq", "draw s.uq -o ro.svg"};
    dir.Write("ro.svg", "old");
    ASSERT_EQ(chmod(dir.File("ro.svg").c_str(), 0400), 0);
    for (const std::string& cmd : others) {
        r = RunShell("cd '" + dir.path() + "' && " + QuadrixBinary() + " " + cmd);
        ExpectRefused(r, dir, {"s.uq", "ro.ppm", "link.ppm", "ro.svg"});
    }
    EXPECT_EQ(Slurp(dir.File("ro.ppm")), "old");
    EXPECT_EQ(Slurp(dir.File("ro.svg")), "old");
}

// The access rule for a user who may not write the file though every write bit is not clear: a
// root-owned 0644 file in a directory everyone may write, rendered to as nobody.
TEST(OutputSafety, FileOfAnotherUserIsNotReplaced) {
    TempDir dir;
    dir.Write("s.uq", kSphere);
    dir.Write("theirs.ppm", "old");
    ASSERT_EQ(chmod(dir.File("theirs.ppm").c_str(), 0644), 0);
    std::string run = QuadrixBinary() + " render s.uq --size 16x16 -o theirs.ppm";
    if (geteuid() == 0) {
        if (!HaveProgram("setpriv")) GTEST_SKIP() << "running as root without setpriv";
        chmod(dir.path().c_str(), 0777);  // nobody may create (and rename) files here
        run = "setpriv --reuid=65534 --regid=65534 --clear-groups " + run;
    } else {
        // Not root: the file is ours, so make it another's by the mode (owner write cleared,
        // group and others write set) — access(W_OK) refuses, the mode-bit rule does not.
        ASSERT_EQ(chmod(dir.File("theirs.ppm").c_str(), 0466), 0);
    }
    CommandResult r = RunShell("cd '" + dir.path() + "' && " + run);
    chmod(dir.path().c_str(), 0700);
    EXPECT_NE(r.exitCode, 0) << r.err;
    EXPECT_LT(r.exitCode, 128) << r.err;
    EXPECT_NE(r.err.find("permission denied (it is not writable by this user)"), std::string::npos)
        << r.err;
    EXPECT_EQ(Slurp(dir.File("theirs.ppm")), "old");
    EXPECT_TRUE(Others(dir, {"s.uq", "theirs.ppm"}).empty())
        << Others(dir, {"s.uq", "theirs.ppm"})[0];
}

TEST(OutputSafety, LibraryChecksAllOutputsBeforeWriting) {
    TempDir dir;
    const std::string in = dir.Write("in.uq", kSphere);
    EXPECT_EQ(CheckOutputPaths({dir.File("a.png"), dir.File("b.png")}, {in}), "");
    EXPECT_NE(CheckOutputPaths({dir.File("a.png"), dir.File("a.png")}), "");
    EXPECT_NE(CheckOutputPaths({dir.File("a.png"), in}, {in}), "");
    EXPECT_EQ(CheckOutputPath("-"), "");
    // A file read through the bounded reader is an input from then on.
    std::string text;
    ASSERT_EQ(ReadBoundedFile(in, text), "");
    EXPECT_NE(CheckOutputPath(in).find("input"), std::string::npos);
    EXPECT_NE(WriteOutputFile(in, "x"), "");
    EXPECT_EQ(Slurp(in), kSphere);
}

TEST(OutputSafety, CommitAllRenamesTogether) {
    TempDir dir;
    OutputFile a(dir.File("a.txt")), b(dir.File("b.txt"));
    ASSERT_TRUE(a.ok() && b.ok());
    a.Write("A");
    b.Write("B");
    EXPECT_EQ(Others(dir, {}).size(), 2u);  // two temporary files, no target yet
    EXPECT_FALSE(fs::exists(dir.File("a.txt")));
    EXPECT_EQ(PendingOutputFiles(), 2);
    ASSERT_EQ(CommitAll({&a, &b}), "");
    EXPECT_EQ(Slurp(dir.File("a.txt")), "A");
    EXPECT_EQ(Slurp(dir.File("b.txt")), "B");
    EXPECT_EQ(Others(dir, {"a.txt", "b.txt"}).size(), 0u);
    EXPECT_EQ(PendingOutputFiles(), 0);
}

// The fsyncs of a commit (the file, then its directory) happen only when asked for
// (QUADRIX_FSYNC=1, io/output_file.h); the file is the same either way.
TEST(OutputSafety, SyncOnlyWhenAsked) {
    const bool before = OutputSync();
    TempDir dir;
    SetOutputSync(false);
    long count = OutputSyncCount();
    EXPECT_EQ(WriteOutputFile(dir.File("quick.txt"), "Q"), "");
    EXPECT_EQ(OutputSyncCount(), count);
    SetOutputSync(true);
    EXPECT_EQ(WriteOutputFile(dir.File("durable.txt"), "D"), "");
    EXPECT_EQ(OutputSyncCount(), count + 2);
    {
        OutputFile a(dir.File("a.txt")), b(dir.File("b.txt"));
        ASSERT_TRUE(a.ok() && b.ok());
        a.Write("A");
        b.Write("B");
        ASSERT_EQ(CommitAll({&a, &b}), "");
    }
    EXPECT_EQ(OutputSyncCount(), count + 6);
    SetOutputSync(before);
    EXPECT_EQ(Slurp(dir.File("quick.txt")), "Q");
    EXPECT_EQ(Slurp(dir.File("durable.txt")), "D");
    EXPECT_EQ(Slurp(dir.File("b.txt")), "B");
    EXPECT_EQ(Others(dir, {"quick.txt", "durable.txt", "a.txt", "b.txt"}).size(), 0u);
}

TEST(OutputSafety, SyncSettingFromEnvironment) {
    EXPECT_FALSE(OutputSyncFromEnvironment(nullptr));
    EXPECT_FALSE(OutputSyncFromEnvironment(""));
    EXPECT_FALSE(OutputSyncFromEnvironment("0"));
    EXPECT_TRUE(OutputSyncFromEnvironment("1"));
    EXPECT_TRUE(OutputSyncFromEnvironment("yes"));
    // The command line's render writes the same file with and without it.
    TempDir dir;
    const std::string scene = dir.File("s.uq");
    ASSERT_EQ(WriteOutputFile(scene, kSphere), "");
    const CommandResult plain = Render(dir, "s.uq -o plain.png --size 40x30");
    const CommandResult synced =
        RunShell("cd '" + dir.path() + "' && QUADRIX_FSYNC=1 " + QuadrixBinary() +
                 " render s.uq -o synced.png --size 40x30");
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    ASSERT_EQ(synced.exitCode, 0) << synced.err;
    EXPECT_EQ(Slurp(dir.File("plain.png")), Slurp(dir.File("synced.png")));
    EXPECT_FALSE(Slurp(dir.File("plain.png")).empty());
}

TEST(OutputSafety, AbandonedFileLeavesNothing) {
    TempDir dir;
    {
        OutputFile f(dir.File("x.txt"));
        ASSERT_TRUE(f.ok());
        f.Write("partial");
    }
    EXPECT_TRUE(Others(dir, {}).empty());
}

TEST(OutputSafety, SignalWhileWritingLeavesNoTemporaryFile) {
    // A child process with an output file in the making gets SIGTERM (and SIGINT, SIGHUP): it
    // dies of the signal, as it would have without the handler, and leaves no file.
    for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
        struct sigaction old {};
        sigaction(sig, nullptr, &old);
        if (old.sa_handler == SIG_IGN) continue;  // run under nohup: the writer leaves it alone
        TempDir dir;
        int ready[2];
        ASSERT_EQ(pipe(ready), 0);
        pid_t child = fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            close(ready[0]);
            OutputFile f(dir.File("big.ppm"));
            f.Write(std::string(1 << 20, 'x'));
            std::fflush(f.stream());
            char c = f.ok() ? 'y' : 'n';
            if (write(ready[1], &c, 1) != 1) _exit(3);
            for (;;) pause();
        }
        close(ready[1]);
        char c = 0;
        ASSERT_EQ(read(ready[0], &c, 1), 1);
        close(ready[0]);
        EXPECT_EQ(c, 'y');
        EXPECT_EQ(Others(dir, {}).size(), 1u);  // the temporary file exists while writing
        kill(child, sig);
        int status = 0;
        ASSERT_EQ(waitpid(child, &status, 0), child);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
        EXPECT_TRUE(Others(dir, {}).empty()) << Others(dir, {})[0];
    }
}

TEST(OutputSafety, TerminatedRenderLeavesNoTemporaryFile) {
    // The whole tool: SIGTERM to `quadrix render` while it writes a big image. The write lasts
    // a fraction of a second, so the test watches for the temporary file and signals then; a run
    // that ends before the file was seen is tried again.
    TempDir dir;
    dir.Write("s.uq", kSphere);
    bool caught = false;
    for (int attempt = 0; attempt < 4 && !caught; ++attempt) {
        pid_t child = fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            std::string bin = QUADRIX_BINARY;
            std::string out = dir.File("big.png");
            execl(bin.c_str(), bin.c_str(), "render", dir.File("s.uq").c_str(), "--size",
                  "3000x3000", "--threads", "2", "-o", out.c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
        int status = 0;
        auto start = std::chrono::steady_clock::now();
        while (std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
            if (waitpid(child, &status, WNOHANG) == child) break;
            bool tmp = false;
            for (const auto& name : Others(dir, {"s.uq", "big.png"}))
                tmp = tmp || name.find(".tmp") != std::string::npos;
            if (tmp) {
                kill(child, SIGTERM);
                ASSERT_EQ(waitpid(child, &status, 0), child);
                caught = true;
                EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
                break;
            }
            std::this_thread::sleep_for(std::chrono::microseconds(200));
        }
        if (!caught) {
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
        }
        fs::remove(dir.File("big.png"));
        EXPECT_TRUE(Others(dir, {"s.uq"}).empty()) << Others(dir, {"s.uq"})[0];
    }
    if (!caught) GTEST_SKIP() << "the write was never seen in progress";
}

}  // namespace
}  // namespace quadrix::testing
