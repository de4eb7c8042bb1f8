// `quadrix view` end to end (issue 18 §7): the real binary and its SDL2 window under Xvfb, driven
// by a script of mouse and key events; its screenshots must equal, pixel for pixel, what
// `quadrix render` draws from the view statements the window printed (with the same --aa: the
// still frame is anti-aliased, as a render is by default), and its drawings what `quadrix draw`
// writes for them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "quadrix/frame/frame.h"
#include "quadrix/io/writers.h"
#include "quadrix/pipeline/section_plane.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

// Under the sanitizers, the window's system libraries (libX11, libdbus through SDL) keep
// allocations to exit that LeakSanitizer reports; the window process is not leak-checked (its
// rendering code is, through the same render context in every other test).
// Spheres per side of the slow scene's grid (ViewerWindow.EventLoopKeepsRunning...).
constexpr int kSpheresPerSide = 7;

const std::string kNoSystemLeakCheck =
    "ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0\" ";

// Why the window cannot be tested here, or empty.
std::string WindowUnavailable() {
    const CommandResult probe = RunShell(QuadrixBinary() + " view /nonexistent.uq --size 8x8");
    if (probe.err.find("built without SDL2") != std::string::npos)
        return "this quadrix was built without SDL2, so it has no window to test: install "
               "libsdl2-dev (bash scripts/install-deps.sh) and configure again (scripts/test.sh "
               "configures with -DQUADRIX_REQUIRE_SDL2=ON, so CI never skips here)";
    if (!HaveProgram("xvfb-run"))
        return "xvfb-run (packages xvfb and xauth; bash scripts/install-deps.sh) is not "
               "installed: no display server for the window";
    return {};
}

// `quadrix view ARGS` in a window of its own (test_util.h), after `prefix` (a background editor).
CommandResult RunInWindow(TempDir& dir, const std::string& args, const std::string& prefix = "") {
    return RunUnderXvfb(dir.Write("window.sh", QuadrixBinary() + " view " + args + "\n"), prefix,
                        kNoSystemLeakCheck);
}

TEST(ViewerWindow, ScriptedSessionMatchesRenderOfThePrintedViews) {
    if (auto why = WindowUnavailable(); !why.empty()) GTEST_SKIP() << why;
    TempDir dir;
    const std::string script = dir.Write("events.txt",
                                         "orbit 90 -40 3\n"
                                         "zoom 2 200 90\n"
                                         "pan 12 -7\n"
                                         "click 160 120\n"
                                         "click 2 2\n"
                                         "screenshot " +
                                             dir.File("a.ppm") +
                                             "\n"
                                             "print-view " +
                                             dir.File("a.uq") +
                                             "\n"
                                             "key P\n"
                                             "orbit -30 10\n"
                                             "screenshot " +
                                             dir.File("b.ppm") +
                                             "\n"
                                             "print-view " +
                                             dir.File("b.uq") +
                                             "\n"
                                             "print-view\n"
                                             "quit\n");
    const std::string scene = SourcePath("examples/machined_part.uq");
    const CommandResult run =
        RunInWindow(dir, "'" + scene + "' --size 320x240 --script '" + script + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find("pick 160 120: solid part body part"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("machined_part.uq:"), std::string::npos) << run.out;  // source line
    EXPECT_NE(run.out.find("pick 2 2: background"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("view camera vrp"), std::string::npos) << run.out;
    Image previous;
    for (const char* name : {"a", "b"}) {
        const std::string shot = dir.File(std::string(name) + ".ppm");
        const std::string rendered = dir.File(std::string(name) + "_render.ppm");
        const CommandResult r = RunShell(
            QuadrixBinary() + " render '" + scene + "' '" + dir.File(std::string(name) + ".uq") +
            "' --size 320x240 --aa 4 --no-shadows -o '" + rendered + "'");
        ASSERT_EQ(r.exitCode, 0) << r.err;
        Image window, cli;
        ASSERT_TRUE(ReadPnm(shot, window)) << shot;
        ASSERT_TRUE(ReadPnm(rendered, cli)) << rendered;
        ASSERT_EQ(window.width, 320);
        ASSERT_EQ(window.height, 240);
        EXPECT_EQ(window.pixels, cli.pixels) << name;  // identical at full resolution (the
        // window's still frame: 4 samples at edge pixels, no shadows)
        EXPECT_NE(window.pixels, previous.pixels);  // and the two views differ
        previous = window;
    }
}

// Live reload: a save with an error keeps the last good picture and reports file:line:col; the
// fixed file is drawn (and equals `quadrix render` of it from the printed view). The shell edits
// the scene when the window's outputs appear, so the order does not depend on timing.
TEST(ViewerWindow, ReloadKeepsTheLastGoodPictureOnErrorThenDrawsTheFix) {
    if (auto why = WindowUnavailable(); !why.empty()) GTEST_SKIP() << why;
    TempDir dir;
    const std::string original = "quadric ball <1 1 1 0 0 0 0 0 0 -4>;\nbody thing <ball>;\n";
    const std::string scene = dir.Write("scene.uq", original);
    const std::string script = dir.Write("events.txt", "screenshot " + dir.File("a.ppm") +
                                                           "\n"
                                                           "wait-reload\n"
                                                           "screenshot " +
                                                           dir.File("bad.ppm") +
                                                           "\n"
                                                           "print-view " +
                                                           dir.File("m.uq") +
                                                           "\n"
                                                           "wait-reload\n"
                                                           "screenshot " +
                                                           dir.File("b.ppm") +
                                                           "\n"
                                                           "print-view " +
                                                           dir.File("b.uq") + "\n");
    auto waitFor = [&](const std::string& name) {
        return "for i in $(seq 400); do [ -f '" + dir.File(name) +
               "' ] && break; sleep 0.05; done; ";
    };
    const std::string editor = "(" + waitFor("a.ppm") + "printf 'quadric oops <1 2>;\\n' >> '" +
                               scene + "'; " + waitFor("m.uq") +
                               "printf 'quadric ball <1 1 1 0 0 0 0 0 0 -2.25>;\\nbody thing "
                               "<ball>;\\n' > '" +
                               scene + "') & ";
    const CommandResult run =
        RunInWindow(dir, "'" + scene + "' --size 160x120 --script '" + script + "'", editor);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.err.find(scene + ":3:18: error:"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("keeping the last good picture"), std::string::npos) << run.err;
    Image a, bad, b, cli;
    ASSERT_TRUE(ReadPnm(dir.File("a.ppm"), a));
    ASSERT_TRUE(ReadPnm(dir.File("bad.ppm"), bad));
    ASSERT_TRUE(ReadPnm(dir.File("b.ppm"), b));
    EXPECT_EQ(bad.pixels, a.pixels);  // the last good picture
    EXPECT_NE(b.pixels, a.pixels);    // the smaller ball
    const CommandResult r =
        RunShell(QuadrixBinary() + " render '" + scene + "' '" + dir.File("b.uq") +
                 "' --size 160x120 --aa 4 --no-shadows -o '" + dir.File("r.ppm") + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_TRUE(ReadPnm(dir.File("r.ppm"), cli));
    EXPECT_EQ(b.pixels, cli.pixels);
}

std::string Slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The section plane (X, moved by a ctrl-drag), the overlay (in the window's pixels, never in the
// frame's screenshot; O hides it) and the drawing key's SVG, each against the CLI: `quadrix
// render --section` and `quadrix draw --section` of the printed view.
TEST(ViewerWindow, SectionOverlayAndDrawingMatchTheCommandLine) {
    if (auto why = WindowUnavailable(); !why.empty()) GTEST_SKIP() << why;
    TempDir dir;
    const std::string script = dir.Write(
        "events.txt", "orbit 50 -30 2\nkey X\norbit -60 20\nsection-drag -12 3\nscreenshot " +
                          dir.File("a.ppm") + "\nscreenshot-window " + dir.File("w.ppm") +
                          "\nprint-view " + dir.File("a.uq") + "\ndrawing " + dir.File("a.svg") +
                          "\nkey O\nscreenshot-window " + dir.File("w2.ppm") + "\n");
    const std::string scene = SourcePath("examples/machined_part.uq");
    const CommandResult run =
        RunInWindow(dir, "'" + scene + "' --size 240x180 --stats --script '" + script + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.err.find("latency from an input event"), std::string::npos) << run.err;
    std::smatch m;
    const std::string viewText = Slurp(dir.File("a.uq"));
    ASSERT_TRUE(std::regex_search(viewText, m, std::regex("--section \"([^\"]+)\""))) << viewText;
    const std::string section = m[1];
    auto render = [&](const std::string& extra, const std::string& out) {
        const CommandResult r =
            RunShell(QuadrixBinary() + " render '" + scene + "' '" + dir.File("a.uq") +
                     "' --size 240x180 --aa 4 " + "--no-shadows " + extra + " -o '" + out + "'");
        EXPECT_EQ(r.exitCode, 0) << r.err;
        Image im;
        EXPECT_TRUE(ReadPnm(out, im)) << out;
        return im;
    };
    // The window hatches the cut faces (C would turn it off): render --hatch.
    const Image cut = render("--section '" + section + "' --hatch", dir.File("cut.ppm"));
    const Image whole = render("", dir.File("whole.ppm"));
    Image shot, window, plain;
    ASSERT_TRUE(ReadPnm(dir.File("a.ppm"), shot));
    ASSERT_TRUE(ReadPnm(dir.File("w.ppm"), window));
    ASSERT_TRUE(ReadPnm(dir.File("w2.ppm"), plain));
    EXPECT_EQ(shot.pixels, cut.pixels);    // the section, exactly as render draws it
    EXPECT_NE(shot.pixels, whole.pixels);  // and it cuts something
    EXPECT_EQ(plain.pixels, shot.pixels);  // the window without the overlay is the frame
    // With the overlay, the window differs from the frame only in a box at the top-left corner.
    ASSERT_EQ(window.pixels.size(), shot.pixels.size());
    int differ = 0, outside = 0;
    for (int y = 0; y < shot.height; ++y)
        for (int x = 0; x < shot.width; ++x)
            for (int k = 0; k < 3; ++k) {
                const std::size_t i = (static_cast<std::size_t>(y) * shot.width + x) * 3 + k;
                if (window.pixels[i] == shot.pixels[i]) continue;
                ++differ;
                outside += y > 40;
            }
    EXPECT_GT(differ, 1000);
    EXPECT_EQ(outside, 0);
    // The drawing key's SVG is `quadrix draw` of the printed view, byte for byte.
    const CommandResult d =
        RunShell(QuadrixBinary() + " draw '" + scene + "' '" + dir.File("a.uq") +
                 "' --size 240x180 --section '" + section + "' -o '" + dir.File("d.svg") + "'");
    ASSERT_EQ(d.exitCode, 0) << d.err;
    const std::string svg = Slurp(dir.File("a.svg"));
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    EXPECT_EQ(svg, Slurp(dir.File("d.svg")));
}

// The drawing key refuses what quadrix draw refuses (pipeline/drawing_output.h): on the teapot
// scene the script's drawing is an error at the patches' statement, on standard error and in the
// window's overlay, and no file is written; with --allow-missing the drawing of the rest is
// written with a warning.
TEST(ViewerWindow, DrawingKeyRefusesFreeformSurfacesUnlessAllowMissing) {
    if (auto why = WindowUnavailable(); !why.empty()) GTEST_SKIP() << why;
    TempDir dir;
    const std::string script =
        dir.Write("events.txt", "screenshot-window " + dir.File("before.ppm") + "\ndrawing " +
                                    dir.File("a.svg") + "\nscreenshot-window " +
                                    dir.File("after.ppm") + "\n");
    const std::string scene = SourcePath("examples/teapot_on_table.uq");
    const std::string view = "'" + scene + "' --size 160x120 --aa 1 --script '" + script + "'";
    const CommandResult refused = RunInWindow(dir, view);
    EXPECT_EQ(refused.exitCode, 1) << refused.err;
    EXPECT_NE(refused.err.find("teapot_on_table.uq:5:1: error: freeform surface 'teapot[0]'"),
              std::string::npos)
        << refused.err;
    EXPECT_FALSE(FileExists(dir.File("a.svg")));
    // The script goes on (and the exit status says a drawing failed); the message is in the
    // overlay: the window's pixels change, in the overlay's box at the top-left corner only.
    Image before, after;
    ASSERT_TRUE(ReadPnm(dir.File("before.ppm"), before));
    ASSERT_TRUE(ReadPnm(dir.File("after.ppm"), after));
    ASSERT_EQ(after.pixels.size(), before.pixels.size());
    // (The message is wrapped to the window's width, so the box may take most of a small
    // window: a pixel that changed shows the overlay's box or ink, before or after.)
    auto overlayColour = [](const Image& im, std::size_t p) {
        const std::uint8_t* c = &im.pixels[3 * p];
        return (c[0] == 24 && c[1] == 24 && c[2] == 28) ||
               (c[0] == 240 && c[1] == 240 && c[2] == 240);
    };
    int differ = 0, outside = 0;
    for (std::size_t p = 0; p < static_cast<std::size_t>(after.width) * after.height; ++p) {
        if (std::equal(&after.pixels[3 * p], &after.pixels[3 * p + 3], &before.pixels[3 * p]))
            continue;
        ++differ;
        outside += !overlayColour(after, p) && !overlayColour(before, p);
    }
    EXPECT_GT(differ, 50);
    EXPECT_EQ(outside, 0);
    const CommandResult allowed = RunInWindow(dir, view + " --allow-missing");
    EXPECT_EQ(allowed.exitCode, 0) << allowed.err;
    EXPECT_NE(allowed.err.find("teapot_on_table.uq:5:1: warning: freeform surface 'teapot[0]'"),
              std::string::npos)
        << allowed.err;
    Image shown;
    ASSERT_TRUE(ReadPnm(dir.File("after.ppm"), shown));
    EXPECT_NE(shown.pixels, before.pixels);  // the warning in the overlay
    EXPECT_NE(Slurp(dir.File("a.svg")).find("<ellipse"), std::string::npos);
}

// Hatching (C; on with the section plane): the still frame is `quadrix render --section
// --hatch` of the printed view, pixel for pixel; the hatch lines are black and lie on the cut
// faces only (the Frame's pixels of the section plane: its normal is the plane's); C turns them
// off, giving `quadrix render --section`.
TEST(ViewerWindow, SectionHatchingLiesOnTheCutOnlyAndTogglesWithC) {
    if (auto why = WindowUnavailable(); !why.empty()) GTEST_SKIP() << why;
    TempDir dir;
    const std::string script =
        dir.Write("events.txt", "orbit 40 -25\nkey X\norbit -50 15\nscreenshot " +
                                    dir.File("h.ppm") + "\nprint-view " + dir.File("h.uq") +
                                    "\nkey C\nscreenshot " + dir.File("p.ppm") + "\nquit\n");
    const std::string scene = SourcePath("examples/machined_part.uq");
    const CommandResult run =
        RunInWindow(dir, "'" + scene + "' --size 240x180 --script '" + script + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const std::string viewText = Slurp(dir.File("h.uq"));
    std::smatch m;
    ASSERT_TRUE(std::regex_search(viewText, m, std::regex("--section \"([^\"]+)\" --hatch")))
        << viewText;
    const std::string section = m[1];
    auto render = [&](const std::string& extra, const std::string& out) {
        const CommandResult r =
            RunShell(QuadrixBinary() + " render '" + scene + "' '" + dir.File("h.uq") +
                     "' --size 240x180 --aa 4 " + "--no-shadows --section '" + section + "' " +
                     extra + " -o '" + out + "'");
        EXPECT_EQ(r.exitCode, 0) << r.err;
        Image im;
        EXPECT_TRUE(ReadPnm(out, im)) << out;
        return im;
    };
    const Image hatched =
        render("--hatch --dump-frame '" + dir.File("f.qxf") + "'", dir.File("r.ppm"));
    const Image plain = render("", dir.File("rp.ppm"));
    Image shotHatched, shotPlain;
    ASSERT_TRUE(ReadPnm(dir.File("h.ppm"), shotHatched));
    ASSERT_TRUE(ReadPnm(dir.File("p.ppm"), shotPlain));
    EXPECT_EQ(shotHatched.pixels, hatched.pixels);  // the same picture as render --hatch
    EXPECT_EQ(shotPlain.pixels, plain.pixels);      // C: as render --section alone
    // The cut's pixels: the surface id whose every pixel has the plane's normal.
    Frame frame;
    ASSERT_EQ(ReadFrameDump(dir.File("f.qxf"), frame), "");
    Plane p;
    ASSERT_EQ(ParseSectionPlane(section, p), "");
    const Vec3 n = Normalize(p.Normal());
    std::map<int, std::pair<int, int>> perSurface;  // id → (pixels, pixels with the normal)
    for (std::size_t i = 0; i < frame.surface.size(); ++i) {
        if (frame.surface[i] == Frame::kNone) continue;
        auto& c = perSurface[frame.surface[i]];
        ++c.first;
        c.second += std::fabs(Dot(frame.normal[i], n)) > 1 - 1e-9;
    }
    int cut = Frame::kNone, cutPixels = 0;
    for (const auto& [id, c] : perSurface)
        if (c.first == c.second && c.first > cutPixels) cut = id, cutPixels = c.first;
    ASSERT_GT(cutPixels, 1000);
    int lines = 0;
    for (std::size_t i = 0; i < frame.surface.size(); ++i) {
        const bool changed = hatched.pixels[3 * i] != plain.pixels[3 * i] ||
                             hatched.pixels[3 * i + 1] != plain.pixels[3 * i + 1] ||
                             hatched.pixels[3 * i + 2] != plain.pixels[3 * i + 2];
        if (!changed) continue;
        ++lines;
        EXPECT_EQ(frame.surface[i], cut) << "a hatch pixel outside the cut: " << i;
        EXPECT_EQ(hatched.pixels[3 * i] + hatched.pixels[3 * i + 1] + hatched.pixels[3 * i + 2], 0);
    }
    EXPECT_GT(lines, cutPixels / 20);
    EXPECT_LT(lines, cutPixels / 3);
}

// N spheres on a grid, unioned, minus a cylinder (bench/scenes.cpp's scene with the centres on a
// grid): slow to draw as a hidden-line drawing, and at full resolution.
std::string SpheresMinusCylinder(int perSide) {
    std::string text;
    std::string csg = "csg balls ((";
    int n = 0;
    for (int i = 0; i < perSide; ++i)
        for (int j = 0; j < perSide; ++j)
            for (int k = 0; k < perSide; ++k, ++n) {
                const double x = -10 + 20.0 * i / (perSide - 1), y = -10 + 20.0 * j / (perSide - 1),
                             z = -10 + 20.0 * k / (perSide - 1);
                const double r = 14.0 / (perSide - 1);
                char line[200];
                std::snprintf(line, sizeof line,
                              "quadric q%d <1 1 1 0 0 0 %.9g %.9g %.9g %.9g>;\nbody s%d (q%d);\n",
                              n, -x, -y, -z, x * x + y * y + z * z - r * r, n, n);
                text += line;
                csg += (n ? " | s" : "s") + std::to_string(n) + (n % 16 == 15 ? "\n" : "");
            }
    text +=
        "quadric cyl <1 0 1 0 0 0 0 0 0 -16>;\nplane ct <0 1 0 -13>;\nplane cb <0 -1 0 -13>;\n"
        "body drill (cyl ct cb);\n";
    text += csg + ") - drill) =c .9 .75 .55;\nview v dop .4 .5 -1;\n";
    return text;
}

// The window never waits for the render thread (issue 18 §3): with a slow drawing (`D`, written
// on a thread of its own) and a pick asked for while a frame is drawn (`click-now`), the event
// loop goes on: its longest pass stays a small fraction of the drawing's time, frames are shown
// while the drawing is written, and both answers arrive (the pick on standard output and in the
// overlay, the drawing on disk with its view printed).
TEST(ViewerWindow, EventLoopKeepsRunningWhileADrawingAndAPickArePending) {
    if (auto why = WindowUnavailable(); !why.empty()) GTEST_SKIP() << why;
    TempDir dir;
    const std::string scene = dir.Write("spheres.uq", SpheresMinusCylinder(kSpheresPerSide));
    const std::string script = dir.Write(
        "events.txt", "screenshot-window " + dir.File("before.ppm") +
                          "\nkey D\norbit 40 0 8\nsleep 100\norbit 30 10 4\nclick-now 160 120\n"
                          "wait\nscreenshot-window " +
                          dir.File("after.ppm") + "\n");
    // `D` writes quadrix-view-1.svg into the working directory: the test's own.
    const CommandResult run = RunUnderXvfb(
        dir.Write("window.sh", "cd '" + dir.File(".") + "' && " + QuadrixBinary() + " view '" +
                                   scene + "' --size 320x240 --stats --script '" + script + "'\n"),
        "", kNoSystemLeakCheck);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(run.err, m,
                                  std::regex("event loop: [0-9]+ passes, longest ([0-9.]+) ms.*"
                                             "drawings: 1 written \\(mean ([0-9.]+) ms.*, "
                                             "([0-9]+) frames shown while one was written")))
        << run.err;
    const double longestPass = std::stod(m[1]), drawing = std::stod(m[2]);
    const int framesMeanwhile = std::stoi(m[3]);
    EXPECT_GT(drawing, 200) << "the drawing is too quick for this test to mean anything";
    EXPECT_LT(longestPass, drawing / 4) << run.err;
    EXPECT_GE(framesMeanwhile, 1) << run.err;
    EXPECT_NE(run.err.find("picks: 1 answered"), std::string::npos) << run.err;
    EXPECT_NE(run.out.find("pick 160 120: solid balls body balls/s"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("spheres.uq:"), std::string::npos) << run.out;  // the body's line
    // The pick is in the overlay: the window's pixels differ from the first screenshot's in
    // the overlay's box, and more rows of it than the status and help lines take.
    // Without it, the box is two rows (status, help: 21 pixels at 320×240); with it, four rows
    // more: its colour (viewer/overlay.cpp's kBox) is found below the first two rows.
    Image before, after;
    ASSERT_TRUE(ReadPnm(dir.File("before.ppm"), before));
    ASSERT_TRUE(ReadPnm(dir.File("after.ppm"), after));
    auto boxAt = [](const Image& im, int x, int y) {
        const std::size_t i = (static_cast<std::size_t>(y) * im.width + x) * 3;
        return im.pixels[i] == 24 && im.pixels[i + 1] == 24 && im.pixels[i + 2] == 28;
    };
    EXPECT_TRUE(boxAt(before, 1, 10));
    EXPECT_FALSE(boxAt(before, 1, 45));
    EXPECT_TRUE(boxAt(after, 1, 45));
    // The drawing was written, and its view printed (that the drawing thread's file is `quadrix
    // draw` of the printed view is SectionOverlayAndDrawingMatchTheCommandLine's check).
    EXPECT_NE(Slurp(dir.File("quadrix-view-1.svg")).find("<svg"), std::string::npos);
    EXPECT_NE(run.out.find("view camera vrp"), std::string::npos) << run.out;
}

TEST(ViewerWindow, NoDisplayIsAClearErrorAndTheBenchRunsOffscreen) {
    const std::string scene = SourcePath("examples/tube.uq");
    const CommandResult noDisplay =
        RunShell("env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER timeout 60 " +
                 QuadrixBinary() + " view '" + scene + "'");
    EXPECT_EQ(noDisplay.exitCode, 1);
    EXPECT_TRUE(noDisplay.err.find("cannot open a window") != std::string::npos ||
                noDisplay.err.find("built without SDL2") != std::string::npos)
        << noDisplay.err;
    const CommandResult bench =
        RunShell(QuadrixBinary() + " view '" + scene + "' --bench 6 --offscreen --size 64x48");
    ASSERT_EQ(bench.exitCode, 0) << bench.err;
    EXPECT_NE(bench.out.find("view bench: 6 frames 64x48 engine raycast offscreen:"),
              std::string::npos)
        << bench.out;
    // At the moving frames' scale, with the profile of the mean frame.
    const CommandResult scaled = RunShell(QuadrixBinary() + " view '" + scene +
                                          "' --bench 4 --bench-scale 2 --offscreen --size 64x48");
    ASSERT_EQ(scaled.exitCode, 0) << scaled.err;
    EXPECT_NE(scaled.out.find("view bench: 4 frames 64x48 at 1/2 engine raycast offscreen:"),
              std::string::npos)
        << scaled.out;
    EXPECT_NE(scaled.out.find("view bench profile, mean a frame: flatten "), std::string::npos)
        << scaled.out;
    const CommandResult badScript =
        RunShell("printf 'orbit 1\\n' > /tmp/quadrix_view_bad_$$.txt; " + QuadrixBinary() +
                 " view '" + scene +
                 "' --script /tmp/quadrix_view_bad_$$.txt; s=$?; rm -f "
                 "/tmp/quadrix_view_bad_$$.txt; exit $s");
    EXPECT_EQ(badScript.exitCode, 2);
    EXPECT_NE(badScript.err.find(":1:7: error: 'orbit' takes 2 to 3 arguments"), std::string::npos)
        << badScript.err;
}

// The window is a module loaded by `quadrix view` only (apps/quadrix/viewer_window_loader.cpp):
// the program itself does not load SDL2, and without the module beside it (nor installed) the
// window is a clear error while every other command and the offscreen bench still work.
TEST(ViewerWindow, TheWindowModuleIsLoadedOnlyByViewAndItsAbsenceIsAClearError) {
    const CommandResult libs = RunShell("ldd " + QuadrixBinary());
    ASSERT_EQ(libs.exitCode, 0) << libs.err;
    EXPECT_EQ(libs.out.find("libSDL2"), std::string::npos) << libs.out;
    const std::string scene = SourcePath("examples/tube.uq");
    const CommandResult alone = RunShell("d=$(mktemp -d) && cp " + QuadrixBinary() +
                                         " $d/quadrix && cd $d && "
                                         "./quadrix view '" +
                                         scene +
                                         "'; echo \"view=$?\"; "
                                         "./quadrix view '" +
                                         scene +
                                         "' --bench 2 --offscreen --size 32x24 > /dev/null; "
                                         "echo \"bench=$?\"; ./quadrix render '" +
                                         scene +
                                         "' --size 32x24 -o t.png; "
                                         "echo \"render=$?\"; cd / && rm -rf $d");
    EXPECT_NE(alone.out.find("view=1"), std::string::npos) << alone.out << alone.err;
    EXPECT_TRUE(alone.err.find("quadrix: error: the window module of `quadrix view` is missing") !=
                    std::string::npos ||
                alone.err.find("quadrix: error: this quadrix was built without SDL2") !=
                    std::string::npos)
        << alone.err;
    EXPECT_NE(alone.out.find("bench=0"), std::string::npos) << alone.out << alone.err;
    EXPECT_NE(alone.out.find("render=0"), std::string::npos) << alone.out << alone.err;
}

}  // namespace
}  // namespace quadrix::testing
