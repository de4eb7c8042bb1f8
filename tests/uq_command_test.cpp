// `quadrix uq` and `quadrix -i` (seed 001 §2.2–2.3), driven through the binary with a pipe on
// standard input, as a script would.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "quadrix/device/device.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

std::string Slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

constexpr const char* kTube =
    "quadric outer_tube <1 0 1 0 0 0 0 0 0 -4>;\n"
    "quadric inner_tube <1 0 1 0 0 0 0 0 0 -1>;\n"
    "plane top_surf <0 1 0 -2>;\nplane bot_surf <0 1 0 2>;\n"
    "body tube <outer_tube !inner_tube top_surf !bot_surf>;\n";

// Runs `quadrix <args>` in `dir` with `input` on standard input (a pipe, not a terminal) and the
// given environment; standard error is merged into standard output, in order, when `merge`.
CommandResult Uq(const TempDir& dir, const std::string& args, const std::string& input = "",
                 bool merge = false) {
    std::string in = dir.Write("stdin.txt", input);
    return RunShell("cd '" + dir.path() + "' && env -u UQDEV TERM=dumb " + QuadrixBinary() + " " +
                    args + " < '" + in + "'" + (merge ? " 2>&1" : ""));
}

std::vector<std::string> Lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

// The session of seed 001 §2.3, with today's device names: png for the color Sun, stipple for the
// Varian plotter.
TEST(UqInteractive, ReplaysThePapersSession) {
    TempDir dir;
    dir.Write("scenefile", kTube);
    std::string session =
        "read scenefile;\n"
        "light glow .3;\n"
        "light .7 .4 -.4 -1;\n"
        "view top_down dop 0 1 1;\n"
        "show;\n"
        "dev varian keep xsize .5 ysize .5;\n"
        "show fast;\n"
        "redef light glow 0;\n"
        "redef light default;\n"
        "show default;\n"
        "quit;\n";
    CommandResult r = Uq(dir, "uq -i -d png -sx 1 -sy 1", session, true);
    EXPECT_EQ(r.exitCode, 0) << r.out;
    std::vector<std::string> expected = {
        "uq> read scenefile;",
        "no user errors",
        "uq> light glow .3;",
        "uq> light .7 .4 -.4 -1;",
        "warning: id l#1 created",
        "uq> view top_down dop 0 1 1;",
        "uq> show;",
        "uq> dev varian keep xsize .5 ysize .5;",
        "uq> show fast;",
        "raster file: uq-1.pbm",
        "uq> redef light glow 0;",
        "uq> redef light default;",
        "uq> show default;",
        "raster file: uq-2.pbm",
        "uq> quit;",
        "warnings:1",
        "parser:0 syntax:0 input:0 command line:0",
    };
    EXPECT_EQ(Lines(r.out), expected) << r.out;
    // The first show went to the png device (1 inch at 100 dpi), the others to the plotter
    // emulation (half an inch at 200 dpi).
    EXPECT_TRUE(FileExists(dir.File("uq.png")));
    std::string pbm = Slurp(dir.File("uq-1.pbm"));
    EXPECT_EQ(pbm.rfind("P4\n100 100\n", 0), 0u);
    EXPECT_TRUE(FileExists(dir.File("uq-2.pbm")));
    // Different lights and views: the two kept pictures differ.
    EXPECT_NE(pbm, Slurp(dir.File("uq-2.pbm")));
}

TEST(UqInteractive, RecoversAtTheNextSemicolonAndCountsErrorsByKind) {
    TempDir dir;
    std::string session =
        "plane top <0 1 0 -2>;\n"
        "bogus words here\n"  // syntax error: skipped to the ';' two lines down
        "more words\n"
        "and the end;\n"
        "quadric ball <1 1 1 0 0 0 0 0 0 -1>;\n"
        "body b1 (ball ghost);\n"  // unknown half-space: an input error
        "read missing_file;\n"     // a parser error
        "body ok (ball\n"          // a statement on two lines: continuation prompt
        "top);\n"
        "show;\n";  // end of input without quit ends the session too
    CommandResult r = Uq(dir, "-i -d ascii -sx .2 -sy .2", session, true);
    std::vector<std::string> lines = Lines(r.out);
    std::string all = r.out;
    // No prompt while skipping after the error: the two skipped lines are echoed without "uq> ".
    EXPECT_NE(all.find("uq> bogus words here\n"), std::string::npos) << all;
    EXPECT_NE(all.find("\nmore words\nand the end;\nuq> quadric ball"), std::string::npos) << all;
    EXPECT_NE(all.find("uq> body ok (ball\n...> top);\nuq> show;"), std::string::npos) << all;
    EXPECT_NE(all.find("error: unknown half-space 'ghost'"), std::string::npos) << all;
    EXPECT_NE(all.find("user errors: 1"), std::string::npos) << all;
    ASSERT_GE(lines.size(), 2u);
    EXPECT_EQ(lines[lines.size() - 2], "warnings:0");
    EXPECT_EQ(lines.back(), "parser:1 syntax:1 input:1 command line:0");
    EXPECT_EQ(r.exitCode, 1);
    // The session went on after the errors: the show drew the valid bodies.
    device::Listing listing;
    ASSERT_EQ(device::ParseListing(Slurp(dir.File("uq.out")), listing), "");
    EXPECT_EQ(listing.width, 20);
}

TEST(UqInteractive, NakedReadInABatchFileEntersInteractiveModeUntilQuit) {
    TempDir dir;
    dir.Write("scene.uq", std::string(kTube) + "read;\nview side dop 1 0 0;\n");
    CommandResult r =
        Uq(dir, "uq -d ascii -sx .2 -sy .2 -t scene.uq", "view front dop 0 0 -1;\nquit;\n", true);
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("uq> view front dop 0 0 -1;\nuq> quit;\n"), std::string::npos) << r.out;
    // quit returned to the batch file, whose next view is the current one at the final picture.
    EXPECT_NE(r.out.find("show: view 'side'"), std::string::npos) << r.out;
    EXPECT_TRUE(FileExists(dir.File("uq.out")));
}

TEST(UqOptions, StatementsAndBareCInteractiveThenTheRestOfTheLine) {
    TempDir dir;
    dir.Write("tube.uq", kTube);
    // -c STMTS runs statements; bare -c is interactive; on quit the rest (-d, a file) goes on.
    CommandResult r = Uq(dir,
                         "uq -d ascii:first.out -sx .1 -sy .1 tube.uq -c 'show;' -c "
                         "-d ascii:second.out -c'light glow .5; show;' -x",
                         "light .5 0 0 -1;\nquit;\n", true);
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_TRUE(FileExists(dir.File("first.out")));
    EXPECT_TRUE(FileExists(dir.File("second.out")));
    EXPECT_NE(r.out.find("uq> light .5 0 0 -1;"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("warning: id l#1 created"), std::string::npos) << r.out;
    EXPECT_FALSE(FileExists(dir.File("uq.out")));  // -x: no final picture
}

TEST(UqOptions, DeviceFromOptionOrEnvironment) {
    TempDir dir;
    dir.Write("tube.uq", kTube);
    CommandResult r = RunShell("cd '" + dir.path() + "' && UQDEV=pgm:env.pgm " + QuadrixBinary() +
                               " uq -sx .3 -sy .2 tube.uq");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    Image img;
    ASSERT_TRUE(ReadPnm(dir.File("env.pgm"), img));
    EXPECT_EQ(img.width, 30);  // -sx .3 at 100 dots per inch
    EXPECT_EQ(img.height, 20);
    r = Uq(dir, "uq -dppm:opt.ppm -sx .3 -sy .2 tube.uq");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    ASSERT_TRUE(ReadPnm(dir.File("opt.ppm"), img));
    EXPECT_EQ(img.channels, 3);
    // A bad $UQDEV is an error before anything is drawn.
    r = RunShell("cd '" + dir.path() + "' && UQDEV=colorsun " + QuadrixBinary() + " uq tube.uq");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.err.find("unknown device 'colorsun'"), std::string::npos) << r.err;
    // With a -d anywhere, $UQDEV is not consulted (§2.2: "If no -d option is given ...").
    r = RunShell("cd '" + dir.path() + "' && UQDEV=colorsun " + QuadrixBinary() +
                 " uq tube.uq -dascii:late.out -sx .1 -sy .1");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(FileExists(dir.File("late.out")));
}

TEST(UqOptions, ErrorsToAFileAndWarningsOnOff) {
    TempDir dir;
    dir.Write("warn.uq", std::string(kTube) + "light 2;\n");  // intensity truncated: a warning
    CommandResult r = Uq(dir, "uq -d ascii -sx .1 -sy .1 -e errs.txt warn.uq");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_EQ(r.err, "");
    EXPECT_NE(Slurp(dir.File("errs.txt")).find("warning: light intensity 2"), std::string::npos);
    r = Uq(dir, "uq -d ascii -sx .1 -sy .1 -n warn.uq");
    EXPECT_EQ(r.err, "");
    r = Uq(dir, "uq -d ascii -sx .1 -sy .1 -n -N warn.uq");
    EXPECT_NE(r.err.find("warning: light intensity 2"), std::string::npos) << r.err;
}

TEST(UqOptions, FastShadingOnAndOff) {
    TempDir dir;
    dir.Write("tube.uq", kTube);
    Uq(dir, "uq -dpgm:smooth.pgm -sx .4 -sy .4 tube.uq");
    Uq(dir, "uq -f -dpgm:fast.pgm -sx .4 -sy .4 tube.uq");
    Uq(dir, "uq -f -F -dpgm:again.pgm -sx .4 -sy .4 tube.uq");
    std::string smooth = Slurp(dir.File("smooth.pgm"));
    EXPECT_NE(smooth, "");
    EXPECT_NE(Slurp(dir.File("fast.pgm")), smooth);
    EXPECT_EQ(Slurp(dir.File("again.pgm")), smooth);
}

TEST(UqOptions, KeepNamesEachPictureAndReportsIt) {
    TempDir dir;
    dir.Write("tube.uq", kTube);
    CommandResult r = Uq(dir, "uq -k -dpng -sx .2 -sy .2 tube.uq -c 'show;'");
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_EQ(r.out, "raster file: uq-1.png\nraster file: uq-2.png\n");
    r = Uq(dir, "uq -k -K -dpng -sx .2 -sy .2 tube.uq");
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(FileExists(dir.File("uq.png")));
}

TEST(UqOptions, ShadingIntervalReducesSpans) {
    TempDir dir;
    dir.Write("tube.uq", kTube);
    Uq(dir, "uq -d ascii:fine.out -sx .6 -sy .6 tube.uq");
    Uq(dir, "uq -d ascii:coarse.out -sd 8 -sx .6 -sy .6 tube.uq");
    device::Listing fine, coarse;
    ASSERT_EQ(device::ParseListing(Slurp(dir.File("fine.out")), fine), "");
    ASSERT_EQ(device::ParseListing(Slurp(dir.File("coarse.out")), coarse), "");
    EXPECT_LT(coarse.spans.size(), fine.spans.size());
}

TEST(UqOptions, TraceOnOffAndToAFile) {
    TempDir dir;
    dir.Write("tube.uq", kTube);
    CommandResult r = Uq(dir, "uq -t -d ascii -sx .1 -sy .1 tube.uq");
    for (const char* stage : {"trace: reader:", "trace: show:", "trace: flattener:",
                              "trace: engine raycast:", "trace: shader:", "trace: device ascii:"})
        EXPECT_NE(r.err.find(stage), std::string::npos) << stage << "\n" << r.err;
    r = Uq(dir, "uq -t -T -d ascii -sx .1 -sy .1 tube.uq");
    EXPECT_EQ(r.err.find("trace:"), std::string::npos) << r.err;
    r = Uq(dir, "uq -ttrace.txt -d ascii -sx .1 -sy .1 tube.uq");
    EXPECT_NE(Slurp(dir.File("trace.txt")).find("trace: device ascii: "), std::string::npos);
}

TEST(UqOptions, ViewOptionPicksAView) {
    TempDir dir;
    dir.Write("views.uq", std::string(kTube) + "view side dop 1 0 0;\nview top dop 0 1 0;\n");
    Uq(dir, "uq -dpgm:last.pgm -sx .3 -sy .3 views.uq");
    Uq(dir, "uq -dpgm:top.pgm -sx .3 -sy .3 -v top views.uq");
    Uq(dir, "uq -dpgm:side.pgm -sx .3 -sy .3 -vside views.uq");
    EXPECT_EQ(Slurp(dir.File("last.pgm")), Slurp(dir.File("top.pgm")));
    EXPECT_NE(Slurp(dir.File("side.pgm")), Slurp(dir.File("top.pgm")));
    CommandResult r = Uq(dir, "uq -dpgm:none.pgm -sx .3 -sy .3 -v nowhere views.uq");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_FALSE(FileExists(dir.File("none.pgm")));
}

TEST(UqOptions, StandardInputAsAFile) {
    TempDir dir;
    dir.Write("light.uq", "light .6 1 1 -1;\n");
    // "-" reads standard input where it stands; with no file at all, standard input is read.
    CommandResult r = Uq(dir, "uq -d ascii:a.out -sx .1 -sy .1 - light.uq", kTube);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(FileExists(dir.File("a.out")));
    r = Uq(dir, "uq -d ascii:b.out -sx .1 -sy .1", kTube);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(FileExists(dir.File("b.out")));
}

TEST(UqOptions, InputErrorsAbortRenderingInBatch) {
    TempDir dir;
    dir.Write("bad.uq", std::string(kTube) + "body b (nothing);\n");
    CommandResult r = Uq(dir, "uq -d ascii -sx .1 -sy .1 bad.uq");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("bad.uq:6:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing drawn"), std::string::npos) << r.err;
    EXPECT_FALSE(FileExists(dir.File("uq.out")));
}

TEST(UqOptions, BadOptionsGiveAnErrorAndUsageAndWriteNothing) {
    TempDir dir;
    dir.Write("tube.uq", kTube);
    struct Case {
        const char* args;
        const char* message;
    } cases[] = {
        {"-q tube.uq", "unknown option '-q'"},
        {"-sz 3 tube.uq", "unknown option '-sz"},
        {"-sx tube.uq", "not a positive number of inches"},
        {"-sx -2 tube.uq", "not a positive number of inches"},
        {"-sd 0 tube.uq", "not a positive pixel count"},
        {"-d colorsun tube.uq", "unknown device 'colorsun'"},
        {"-d png:out.jpg tube.uq", "out.jpg"},
        {"-sx 5000 tube.uq", "too large"},
        {"tube.uq -d", "option -d needs a device name"},
        {"-fx tube.uq", "takes no value"},
        {"--engine=nope tube.uq", "unknown engine 'nope'"},
    };
    for (const Case& c : cases) {
        CommandResult r = Uq(dir, std::string("uq -dpng:never.png ") + c.args);
        EXPECT_EQ(r.exitCode, 2) << c.args;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find("usage: quadrix uq"), std::string::npos) << c.args;
        EXPECT_FALSE(FileExists(dir.File("never.png"))) << c.args;
    }
    CommandResult help = Uq(dir, "uq --help");
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.out.find("-sd COUNT"), std::string::npos);
}

TEST(UqOptions, TerminalDevicePreviewsOnStandardOutput) {
    TempDir dir;
    dir.Write("tube.uq", std::string(kTube));
    CommandResult r = Uq(dir, "uq -d terminal -sx 2 -sy 2 tube.uq");  // 20 × 20 pixels
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::vector<std::string> lines = Lines(r.out);
    EXPECT_EQ(lines.size(), 10u);  // two pixel rows per line
    for (const std::string& l : lines) {
        EXPECT_EQ(l.substr(l.size() - 4), "\x1b[0m");
        std::size_t blocks = 0;
        for (std::size_t p = 0; (p = l.find("\u2580", p)) != std::string::npos; ++p) ++blocks;
        EXPECT_EQ(blocks, 20u);
    }
}

// device svg:FILE refuses what quadrix draw refuses (pipeline/drawing_output.h): the teapot's
// freeform patches are an error at their statement and no file is written; --allow-missing draws
// the table, the ball and the cup with a warning naming what was left out.
TEST(UqOptions, SvgDeviceRefusesFreeformSurfacesUnlessAllowMissing) {
    TempDir dir;
    const std::string scene = SourcePath("examples/teapot_on_table.uq");
    const CommandResult refused = Uq(dir, "uq -d svg:part.svg '" + scene + "'");
    EXPECT_EQ(refused.exitCode, 1);
    EXPECT_NE(refused.err.find("teapot_on_table.uq:5:1: error: freeform surface 'teapot[0]' (and "
                               "31 more freeform surfaces) cannot be drawn"),
              std::string::npos)
        << refused.err;
    EXPECT_FALSE(FileExists(dir.File("part.svg")));
    const CommandResult allowed = Uq(dir, "uq --allow-missing -d svg:part.svg '" + scene + "'");
    EXPECT_EQ(allowed.exitCode, 0) << allowed.err;
    EXPECT_NE(allowed.err.find("teapot_on_table.uq:5:1: warning: freeform surface 'teapot[0]'"),
              std::string::npos)
        << allowed.err;
    const std::string svg = Slurp(dir.File("part.svg"));
    EXPECT_NE(svg.find("<ellipse"), std::string::npos);  // the ball's outline, the cup's rims
    // The same strokes as quadrix draw --allow-missing of the scene at uq's png size (512x512).
    const CommandResult draw = RunShell(QuadrixBinary() + " draw --allow-missing --size 512x512 '" +
                                        scene + "' -o '" + dir.File("draw.svg") + "'");
    ASSERT_EQ(draw.exitCode, 0) << draw.err;
    auto body = [](const std::string& t) { return t.substr(t.find("<rect")); };
    EXPECT_EQ(body(svg), body(Slurp(dir.File("draw.svg"))));
}

}  // namespace
}  // namespace quadrix::testing
