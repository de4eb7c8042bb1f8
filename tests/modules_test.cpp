// The optional modules of the program (src/quadrix/util/module_loader.h): Cairo, OpenEXR,
// Open MPI and libedit are not linked into quadrix but loaded by the commands that need them, so
// that every other command starts without their ~30 libraries. Checked on the real program: what it
// links, what a render loads (the dynamic loader's own trace, LD_DEBUG), that drawings, EXR files
// and MPI runs work through the modules, and that a missing module is a clear error with no output.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "test_util.h"

namespace quadrix::testing {
namespace {

std::string Head(const std::string& path, std::size_t n) {
    std::ifstream in(path, std::ios::binary);
    std::string s(n, '\0');
    in.read(s.data(), static_cast<std::streamsize>(n));
    s.resize(static_cast<std::size_t>(in.gcount()));
    return s;
}

// The shared objects the dynamic loader opened while `args` ran (LD_DEBUG=files).
std::string LoadedObjects(const std::string& args) {
    const CommandResult r =
        RunShell("LD_DEBUG=files " + QuadrixBinary() + " " + args +
                 " 2>&1 >/dev/null | grep 'file=' | sed 's/.*file=\\([^ ]*\\).*/\\1/' | sort -u");
    return r.out;
}

TEST(Modules, TheProgramLinksNoLibraryOfAModule) {
    const CommandResult libs = RunShell("ldd " + QuadrixBinary());
    ASSERT_EQ(libs.exitCode, 0) << libs.err;
    for (const char* lib : {"libcairo", "libOpenEXR", "libmpi", "libSDL2", "libedit"})
        EXPECT_EQ(libs.out.find(lib), std::string::npos) << lib << " in\n" << libs.out;
}

TEST(Modules, ARenderToPngLoadsNoModuleAndADrawingToPdfLoadsCairos) {
    TempDir dir;
    const std::string scene = SourcePath("examples/tube.uq");
    const std::string render =
        LoadedObjects("render '" + scene + "' --size 32x24 -o '" + dir.File("t.png") + "'");
    ASSERT_NE(render.find("libtbb"), std::string::npos) << "no LD_DEBUG trace:\n" << render;
    for (const char* lib : {"quadrix-", "libcairo", "libOpenEXR", "libmpi"})
        EXPECT_EQ(render.find(lib), std::string::npos) << lib << " loaded by render:\n" << render;
    const std::string draw = LoadedObjects("draw '" + scene + "' -o '" + dir.File("t.pdf") + "'");
    EXPECT_NE(draw.find("quadrix-cairo.so"), std::string::npos) << draw;
    EXPECT_NE(draw.find("libcairo"), std::string::npos) << draw;
    EXPECT_EQ(draw.find("libmpi"), std::string::npos) << draw;
    EXPECT_EQ(Head(dir.File("t.pdf"), 5), "%PDF-");
}

TEST(Modules, DrawingsAndExrFilesAreWrittenThroughTheModules) {
    TempDir dir;
    const std::string scene = SourcePath("examples/machined_part.uq");
    const CommandResult draw =
        RunShell(QuadrixBinary() + " draw '" + scene + "' -o '" + dir.File("p.pdf") + "' && " +
                 QuadrixBinary() + " draw '" + scene + "' -o '" + dir.File("p.eps") + "' && " +
                 QuadrixBinary() + " draw '" + scene + "' -o '" + dir.File("p.png") + "'");
    ASSERT_EQ(draw.exitCode, 0) << draw.err;
    EXPECT_EQ(Head(dir.File("p.pdf"), 5), "%PDF-");
    EXPECT_EQ(Head(dir.File("p.eps"), 4), "%!PS");
    EXPECT_EQ(Head(dir.File("p.png"), 4), "\x89PNG");
    // The drawings are whole files: the PDF ends with its trailer.
    const CommandResult tail = RunShell("tail -c 6 '" + dir.File("p.pdf") + "'");
    EXPECT_NE(tail.out.find("%%EOF"), std::string::npos) << tail.out;
    const CommandResult exr = RunShell(QuadrixBinary() + " render '" + scene +
                                       "' --size 40x30 -o '" + dir.File("p.exr") + "'");
    if (exr.err.find("built without OpenEXR") != std::string::npos)
        GTEST_SKIP() << "built without OpenEXR: " << exr.err;
    ASSERT_EQ(exr.exitCode, 0) << exr.err;
    EXPECT_EQ(Head(dir.File("p.exr"), 4), std::string("\x76\x2f\x31\x01", 4));
}

TEST(Modules, AMissingModuleIsAClearErrorAndNothingIsWritten) {
    TempDir dir;
    const std::string scene = SourcePath("examples/tube.uq");
    const std::string env = "QUADRIX_MODULE_DIR='" + dir.path() + "' ";
    const CommandResult pdf =
        RunShell(env + QuadrixBinary() + " draw '" + scene + "' -o '" + dir.File("t.pdf") + "'");
    EXPECT_NE(pdf.exitCode, 0);
    EXPECT_NE(pdf.err.find("PDF, EPS and PNG drawings need Cairo: the module quadrix-cairo.so is "
                           "missing (looked in " +
                           dir.path() + ";"),
              std::string::npos)
        << pdf.err;
    const CommandResult exr = RunShell(env + QuadrixBinary() + " render '" + scene +
                                       "' --size 32x24 -o '" + dir.File("t.exr") + "'");
    EXPECT_NE(exr.exitCode, 0);
    EXPECT_TRUE(exr.err.find("quadrix-exr.so is missing") != std::string::npos ||
                exr.err.find("built without OpenEXR") != std::string::npos)
        << exr.err;
    // Everything else still works without the modules.
    const CommandResult png = RunShell(env + QuadrixBinary() + " render '" + scene +
                                       "' --size 32x24 -o '" + dir.File("t.png") + "'");
    EXPECT_EQ(png.exitCode, 0) << png.err;
    const CommandResult ls = RunShell("ls '" + dir.path() + "'");
    EXPECT_EQ(ls.out, "t.png\n");
}

// The uq> prompt on a terminal (a pseudo-terminal from script(1), util-linux) edits its lines
// with libedit through quadrix-lineedit.so: the history file it writes is libedit's. Without the
// module the prompt says so once and reads plain lines.
TEST(Modules, ThePromptOnATerminalEditsLinesThroughItsModule) {
    TempDir dir;
    const std::string binDir = RunShell("dirname '" + QuadrixBinary() + "'").out;
    const std::string module = binDir.substr(0, binDir.find('\n')) + "/quadrix-lineedit.so";
    if (RunShell("test -e '" + module + "'").exitCode != 0)
        GTEST_SKIP() << "built without libedit (Debian: libedit-dev): no " << module;
    if (RunShell("command -v script").exitCode != 0)
        GTEST_SKIP() << "no script(1) (util-linux) to give the prompt a terminal";
    RunShell("mkdir -p '" + dir.File("home") + "' '" + dir.File("empty") + "'");
    const std::string session =
        "printf 'quadric q1 <1 1 1 0 0 0 0 0 0 -1>;\\nquit;\\n' | HOME='" + dir.File("home") + "' ";
    const std::string prompt = " script -qec '" + QuadrixBinary() + " -i' /dev/null";
    const CommandResult edited = RunShell(session + "LD_DEBUG=files" + prompt + " 2>&1");
    EXPECT_EQ(edited.exitCode, 0) << edited.out;
    EXPECT_NE(edited.out.find("quadrix-lineedit.so"), std::string::npos) << edited.out;
    EXPECT_NE(edited.out.find("libedit"), std::string::npos) << edited.out;
    const CommandResult history = RunShell("cat '" + dir.File("home/.quadrix_history") + "'");
    EXPECT_EQ(history.out.rfind("_HiStOrY_V2_\n", 0), 0u) << history.out;
    EXPECT_NE(history.out.find("quadric\\040q1\\040<1"), std::string::npos) << history.out;
    const CommandResult plain =
        RunShell(session + "QUADRIX_MODULE_DIR='" + dir.File("empty") + "'" + prompt + " 2>&1");
    EXPECT_EQ(plain.exitCode, 0) << plain.out;
    EXPECT_NE(plain.out.find("quadrix: no line editing at this prompt: the module "
                             "quadrix-lineedit.so is missing"),
              std::string::npos)
        << plain.out;
    EXPECT_NE(plain.out.find("uq> "), std::string::npos) << plain.out;
}

TEST(Modules, AProcessStartedByAnMpiLauncherWithoutTheModuleStopsBeforeRendering) {
#ifndef QUADRIX_MPIEXEC
    GTEST_SKIP() << "built without MPI: no MPI module to miss";
#else
    TempDir dir;
    const std::string jobs = dir.Write(
        "jobs.jsonl", "{\"inputs\": [\"" + SourcePath("examples/tube.uq") + "\"], \"output\": \"" +
                          dir.File("f_%02d.png") + "\", \"size\": \"32x24\", \"turntable\": 3}\n");
    // The environment of a launched rank (what mpirun sets), with the modules elsewhere.
    const CommandResult r = RunShell("OMPI_COMM_WORLD_SIZE=2 QUADRIX_MODULE_DIR='" + dir.path() +
                                     "' " + QuadrixBinary() + " batch '" + jobs + "'");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("quadrix: error: started by an MPI launcher, but the MPI module cannot "
                         "be loaded: the module quadrix-mpi.so is missing"),
              std::string::npos)
        << r.err;
    const CommandResult ls = RunShell("ls '" + dir.path() + "'");
    EXPECT_EQ(ls.out, "jobs.jsonl\n");
#endif
}

}  // namespace
}  // namespace quadrix::testing
