// The command-line conventions of docs/cli.md (issue 21), through the real binary: --version on
// every subcommand, `quadrix help`, unknown subcommands, exit codes (0 ok, 1 scene or input
// error, 2 usage), `-o -` and the Netpbm kinds.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test_util.h"

namespace quadrix::testing {
namespace {

constexpr const char* kSphere =
    "quadric ball <1 1 1 0 0 0 0 0 0 -1>; body bb (ball); view v dop 0 0 -1 whh 1.5 whw 1.5;\n";

CommandResult Quadrix(const std::string& args) { return RunShell(QuadrixBinary() + " " + args); }

std::string Slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

TEST(CliConventions, EverySubcommandAnswersVersion) {
    for (const char* sub :
         {"", "render", "export", "uq", "pipe", "compare", "engines", "draw", "help"}) {
        CommandResult r = Quadrix(std::string(sub) + " --version");
        EXPECT_EQ(r.exitCode, 0) << sub << ": " << r.err;
        EXPECT_EQ(r.out, std::string("quadrix ") + QUADRIX_VERSION + "\n") << sub;
    }
}

TEST(CliConventions, HelpListsSubcommandsAndDescribesOne) {
    CommandResult all = Quadrix("help");
    EXPECT_EQ(all.exitCode, 0);
    for (const char* sub : {"render", "export", "uq", "pipe", "compare", "engines", "draw"})
        EXPECT_NE(all.out.find(sub), std::string::npos) << sub;
    EXPECT_NE(all.out.find("Exit status"), std::string::npos) << all.out;
    CommandResult render = Quadrix("help render");
    EXPECT_EQ(render.exitCode, 0);
    EXPECT_NE(render.out.find("--engine"), std::string::npos) << render.out;
    EXPECT_NE(render.out.find("--format"), std::string::npos) << render.out;
    // Tori are drawn (issue 20): the help's examples of what cannot be drawn do not name them.
    for (const char* sub : {"render", "export"}) {
        CommandResult help = Quadrix(std::string("help ") + sub);
        EXPECT_NE(help.out.find("--allow-missing"), std::string::npos) << sub;
        EXPECT_EQ(help.out.find("torus"), std::string::npos) << help.out;
    }
    CommandResult uq = Quadrix("help uq");
    EXPECT_EQ(uq.exitCode, 0);
    EXPECT_NE(uq.out.find("usage: quadrix uq"), std::string::npos) << uq.out;
    CommandResult unknown = Quadrix("help rendr");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("did you mean 'render'?"), std::string::npos) << unknown.err;
}

// A command line that names a subcommand builds only that one (main.cpp); `quadrix help NAME`
// builds them all. Each describes itself the same either way (options, footer; `help NAME`
// writes its usage line without the program's name), and each runs (it is dispatched by the
// name parsed, not by a lookup of every subcommand).
TEST(CliConventions, ASubcommandBuiltAloneIsTheOneOfTheFullTable) {
    for (const char* sub :
         {"render", "export", "pipe", "compare", "engines", "draw", "batch", "view"}) {
        CommandResult alone = Quadrix(std::string(sub) + " --help");
        CommandResult inTable = Quadrix(std::string("help ") + sub);
        EXPECT_EQ(alone.exitCode, 0) << sub << ": " << alone.err;
        std::string out = alone.out;
        const std::string usage = std::string("Usage: quadrix ") + sub;
        if (const std::size_t at = out.find(usage); at != std::string::npos)
            out.replace(at, usage.size(), std::string("Usage: ") + sub);
        EXPECT_EQ(out, inTable.out) << sub;
    }
    CommandResult engines = Quadrix("engines");
    EXPECT_EQ(engines.exitCode, 0) << engines.err;
    EXPECT_NE(engines.out.find("raycast:"), std::string::npos) << engines.out;
    CommandResult man = Quadrix("man");
    EXPECT_EQ(man.exitCode, 0) << man.err;
    for (const char* sub : {"render", "export", "draw", "batch", "view"})
        EXPECT_NE(man.out.find(sub), std::string::npos) << sub;
}

TEST(CliConventions, UnknownSubcommandSuggestsTheClosest) {
    CommandResult r = Quadrix("rendr scene.uq -o x.png");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("unknown subcommand 'rendr'; did you mean 'render'?"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("quadrix help"), std::string::npos) << r.err;
    CommandResult far = Quadrix("xyzzy");
    EXPECT_EQ(far.exitCode, 2);
    EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
    EXPECT_NE(far.err.find("subcommands: render"), std::string::npos) << far.err;
}

// 2 for usage errors, 1 for errors in the scene or the input, everywhere (docs/cli.md).
TEST(CliConventions, ExitCodesAreConsistent) {
    TempDir dir;
    const std::string scene = dir.Write("s.uq", kSphere);
    const std::string bad = dir.Write("bad.uq", "quadric ball <1 1 1>;\n");
    const std::string out = dir.File("o.png");
    struct Case {
        std::string args;
        int code;
    };
    const std::vector<Case> cases = {
        {"render " + scene + " -o " + out, 0},
        {"render " + scene + " -o " + out + " --engine nosuch", 2},
        {"render " + scene + " -o " + out + " --engine-opt nosuch=1", 2},
        {"render " + scene + " -o " + out + " --size 12", 2},
        {"render " + scene + " -o " + out + " --nosuch", 2},
        {"render " + scene + " -o " + out + " --format gif", 2},
        {"render " + scene + " -o " + dir.File("o.gif"), 2},
        {"render " + scene, 2},
        {"render " + scene + " -o " + out + " --frame-range 0:3", 2},
        {"render " + scene + " -o " + out + " --resume", 2},
        {"render " + bad + " -o " + out, 1},
        {"render " + dir.File("missing.uq") + " -o " + out, 1},
        {"compare --engines nosuch,raycast " + scene, 2},
        {"compare --engines scanline,raycast --size 0x0 " + scene, 2},
        {"compare --engines scanline,raycast " + bad, 1},
        {"draw " + scene + " -o " + dir.File("d.svg"), 0},
        {"draw " + scene + " -o " + dir.File("d.svg") + " --hidden sometimes", 2},
        {"draw " + bad + " -o " + dir.File("d.svg"), 1},
        {"export " + scene + " --to nosuch -o " + dir.File("e.pov"), 2},
        {"uq -x --engine nosuch " + scene, 2},
        {"uq -x --engine-opt nonsense " + scene, 2},
        {"uq -d png:" + out + " --engine scanline " + scene, 0},
        {"uq -d png:" + out + " --engine=raycast --engine-opt batch=off " + scene, 0},
        {"uq -d png:" + out + " " + bad, 1},
        {"uq -q", 2},
        {"engines --markdown", 0},
    };
    for (const Case& c : cases) {
        CommandResult r = Quadrix(c.args);
        EXPECT_EQ(r.exitCode, c.code) << c.args << "\n" << r.err;
        if (c.code != 0) {
            EXPECT_NE(r.err.find("error"), std::string::npos) << c.args;
        }
    }
}

// -o - writes the image to standard output: PNG unless --format says otherwise; nothing else is
// printed there, and a failed render sends nothing.
TEST(CliConventions, DashWritesTheImageToStandardOutput) {
    TempDir dir;
    const std::string scene = dir.Write("s.uq", kSphere);
    CommandResult png = Quadrix("render " + scene + " --size 32x24 -o -");
    ASSERT_EQ(png.exitCode, 0) << png.err;
    ASSERT_GE(png.out.size(), 8u);
    EXPECT_EQ(png.out.substr(0, 8), "\x89PNG\r\n\x1a\n");
    // The same bytes as the file written by -o FILE.png.
    ASSERT_EQ(Quadrix("render " + scene + " --size 32x24 -o " + dir.File("a.png")).exitCode, 0);
    EXPECT_EQ(png.out, Slurp(dir.File("a.png")));
    CommandResult ppm = Quadrix("render " + scene + " --size 32x24 --format ppm -o -");
    ASSERT_EQ(ppm.exitCode, 0) << ppm.err;
    EXPECT_EQ(ppm.out.rfind("P6\n32 24\n255\n", 0), 0u);
    EXPECT_EQ(ppm.out.size(), std::string("P6\n32 24\n255\n").size() + 32 * 24 * 3);
    CommandResult pgm = Quadrix("render " + scene + " --size 32x24 --format pgm -o -");
    EXPECT_EQ(pgm.out.rfind("P5\n32 24\n255\n", 0), 0u);
    CommandResult failed = Quadrix("render " + dir.Write("bad.uq", "plane <1>;") + " -o -");
    EXPECT_EQ(failed.exitCode, 1);
    EXPECT_TRUE(failed.out.empty());
    CommandResult json = Quadrix("render " + scene + " -o - --stats --json");
    EXPECT_EQ(json.exitCode, 2);
}

// .ppm is colour (P6) even for a gray picture, .pgm gray (P5) even for a colour one; the gray
// of a gray picture is the same in both.
TEST(CliConventions, PpmIsColourAndPgmIsGray) {
    TempDir dir;
    const std::string gray = dir.Write("g.uq", kSphere);
    const std::string red =
        dir.Write("r.uq",
                  "quadric ball <1 1 1 0 0 0 0 0 0 -1>; body bb (ball) =c 1 0 0;\n"
                  "view v dop 0 0 -1 whh 1.5 whw 1.5;\n");
    for (const std::string& scene : {gray, red}) {
        ASSERT_EQ(Quadrix("render " + scene + " --size 20x20 -o " + dir.File("a.ppm")).exitCode, 0);
        ASSERT_EQ(Quadrix("render " + scene + " --size 20x20 -o " + dir.File("a.pgm")).exitCode, 0);
        Image ppm, pgm;
        ASSERT_TRUE(ReadPnm(dir.File("a.ppm"), ppm));
        ASSERT_TRUE(ReadPnm(dir.File("a.pgm"), pgm));
        EXPECT_EQ(ppm.channels, 3) << scene;
        EXPECT_EQ(pgm.channels, 1) << scene;
        if (scene == gray) {
            for (std::size_t i = 0; i < pgm.pixels.size(); ++i) {
                ASSERT_EQ(ppm.pixels[3 * i], pgm.pixels[i]);
                ASSERT_EQ(ppm.pixels[3 * i + 1], pgm.pixels[i]);
            }
        } else {
            // The centre pixel: red in the ppm, a darker gray (luminance 0.2126 of red) in the pgm.
            const std::size_t c = 10 * 20 + 10;
            EXPECT_GT(ppm.pixels[3 * c], 100);
            EXPECT_EQ(ppm.pixels[3 * c + 1], 0);
            EXPECT_GT(pgm.pixels[c], 0);
            EXPECT_LT(pgm.pixels[c], ppm.pixels[3 * c]);
        }
    }
}

}  // namespace
}  // namespace quadrix::testing
