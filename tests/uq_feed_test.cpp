// The uq> session fed line by line in process (apps/quadrix/interactive.h, issue 21): the help
// statement, tab completion, and errors that no longer swallow the next valid statement.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "interactive.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

// A session whose diagnostics go to a scratch stream (they are read from FeedResult).
struct Session {
    TempDir dir;
    cli::UqSession uq;
    std::FILE* sink = std::tmpfile();
    Session() {
        uq.SetErrorStream(sink);
        uq.SetMessageStream(nullptr);
        uq.settings.device = "ascii:" + dir.File("uq.out");
    }
    ~Session() {
        uq.SetErrorStream(stderr);
        if (sink) std::fclose(sink);
    }
};

std::string Errors(const cli::UqSession::FeedResult& r) {
    std::string s;
    for (const Diagnostic& d : r.diagnostics) s += d.Format(false) + "\n";
    return s;
}

// The case of the issue: `help` (no ';'), then a solid. The help runs at once and the sphere is
// defined.
TEST(UqFeed, HelpThenASolidKeepsTheSolid) {
    Session s;
    auto help = s.uq.Feed("help");
    ASSERT_EQ(help.messages.size(), 1u);
    EXPECT_NE(help.messages[0].find("Statements"), std::string::npos) << help.messages[0];
    EXPECT_NE(help.messages[0].find("solid"), std::string::npos);
    EXPECT_NE(help.messages[0].find("device: ascii:" + s.dir.File("uq.out")), std::string::npos)
        << help.messages[0];
    EXPECT_TRUE(help.diagnostics.empty()) << Errors(help);
    EXPECT_EQ(s.uq.Prompt(), "uq> ");
    auto sphere = s.uq.Feed("solid sphere s =r 1;");
    EXPECT_TRUE(sphere.diagnostics.empty()) << Errors(sphere);
    ASSERT_EQ(sphere.statements.size(), 1u);
    // The sphere exists: help lists its body and its half-space.
    auto after = s.uq.Feed("help ids;");
    ASSERT_EQ(after.messages.size(), 1u);
    EXPECT_NE(after.messages[0].find("solids (1):\n    s"), std::string::npos) << after.messages[0];
    EXPECT_FALSE(s.uq.HadErrors());
}

TEST(UqFeed, HelpForOneStatementAndTheCurrentView) {
    Session s;
    s.uq.Feed("view side dop 1 0 0;");
    auto r = s.uq.Feed("help view");
    ASSERT_EQ(r.messages.size(), 1u);
    EXPECT_NE(r.messages[0].find("vrp vpn vup dop"), std::string::npos) << r.messages[0];
    EXPECT_NE(r.messages[0].find("views (1):\n    side"), std::string::npos) << r.messages[0];
    auto all = s.uq.Feed("?");
    ASSERT_EQ(all.messages.size(), 1u);
    EXPECT_NE(all.messages[0].find("Current view: side"), std::string::npos) << all.messages[0];
}

// A misspelt keyword is reported when its line ends, not at some later ';'; a following line
// that starts a statement is read (the skip ends there), one that does not is skipped to ';'.
TEST(UqFeed, AnErrorIsReportedAtOnceAndTheNextStatementIsKept) {
    Session s;
    auto bad = s.uq.Feed("sphre s =r 1");
    ASSERT_EQ(bad.diagnostics.size(), 1u) << Errors(bad);
    EXPECT_NE(Errors(bad).find("unknown word 'sphre'"), std::string::npos) << Errors(bad);
    EXPECT_EQ(s.uq.Prompt(), "");  // skipping to the next ';', as the paper's prompt does
    auto skipped = s.uq.Feed("more of it");
    EXPECT_TRUE(skipped.diagnostics.empty()) << Errors(skipped);
    auto good = s.uq.Feed("plane pl <0 1 0 -2>;");
    EXPECT_TRUE(good.diagnostics.empty()) << Errors(good);
    ASSERT_EQ(good.statements.size(), 1u);
    EXPECT_EQ(s.uq.Prompt(), "uq> ");
    // `;` ends the skip too: what follows it on the line is read.
    s.uq.Feed("bogus");
    auto tail = s.uq.Feed("words; quadric qq <1 1 1 0 0 0 0 0 0 -1>;");
    EXPECT_TRUE(tail.diagnostics.empty()) << Errors(tail);
    auto ids = s.uq.Feed("help ids");
    ASSERT_EQ(ids.messages.size(), 1u);
    EXPECT_NE(ids.messages[0].find("half-spaces (2):\n    pl qq"), std::string::npos)
        << ids.messages[0];
}

// Statements over several lines, several on one line, definitions over several statements, and
// an error inside a complete statement: it stays within that statement.
TEST(UqFeed, StatementsAcrossLinesAndErrorsStayInTheirStatement) {
    Session s;
    auto first = s.uq.Feed("quadric ball <1 1 1 0 0 0");
    EXPECT_TRUE(first.statements.empty());
    EXPECT_EQ(s.uq.Prompt(), "...> ");
    auto second = s.uq.Feed("  0 0 0 -1>; plane top <0 1 0 -2>; body bd (ball");
    EXPECT_EQ(second.statements.size(), 2u);
    EXPECT_TRUE(second.diagnostics.empty()) << Errors(second);
    auto third = s.uq.Feed("top);");
    EXPECT_EQ(third.statements.size(), 1u);
    EXPECT_TRUE(third.diagnostics.empty()) << Errors(third);
    // An unknown id inside a statement: reported with its line and column; the next statement
    // on the same line is read.
    auto ghost = s.uq.Feed("body b2 (ball ghost); body b3 (ball);");
    ASSERT_EQ(ghost.diagnostics.size(), 1u) << Errors(ghost);
    EXPECT_EQ(ghost.diagnostics[0].loc.line, 4);
    EXPECT_EQ(ghost.diagnostics[0].loc.column, 15);
    // A definition spans statements fed on separate lines.
    s.uq.Feed("definition d;");
    s.uq.Feed("quadric u <1 1 1 0 0 0 0 0 0 -1>;");
    s.uq.Feed("body ub (u);");
    auto end = s.uq.Feed("enddef;");
    EXPECT_TRUE(end.diagnostics.empty()) << Errors(end);
    auto inst = s.uq.Feed("instance inst (d =tx 3);");
    EXPECT_TRUE(inst.diagnostics.empty()) << Errors(inst);
    EXPECT_TRUE(s.uq.Feed("quit;").quit);
}

TEST(UqFeed, AnUnfinishedStatementAtTheEndIsReported) {
    Session s;
    s.uq.Feed("plane p <0 1 0");
    s.uq.EndFeed();
    EXPECT_TRUE(s.uq.HadErrors());
}

TEST(UqFeed, TabCompletesKeywordsDevicesAndIds) {
    Session s;
    s.uq.Feed("quadric ball <1 1 1 0 0 0 0 0 0 -1>; quadric bore <1 0 1 0 0 0 0 0 0 -.1>;");
    s.uq.Feed("view side dop 1 0 0;");
    // At the start of a statement: statement keywords (and help).
    EXPECT_EQ(s.uq.Completions("b", ""),
              (std::vector<std::string>{"background", "bezier", "body", "bspline"}));
    EXPECT_EQ(s.uq.Completions("he", "plane p <0 1 0 0>; "), std::vector<std::string>{"help"});
    // Inside a statement: ids and keywords.
    EXPECT_EQ(
        s.uq.Completions("b", "body b1 ("),
        (std::vector<std::string>{"background", "ball", "bezier", "body", "bore", "bspline"}));
    EXPECT_EQ(s.uq.Completions("si", "show "), std::vector<std::string>{"side"});
    // After device: device names.
    const auto devices = s.uq.Completions("p", "device ");
    EXPECT_NE(std::find(devices.begin(), devices.end(), "png"), devices.end());
    EXPECT_NE(std::find(devices.begin(), devices.end(), "ppm"), devices.end());
}

// device svg:FILE: a show writes the hidden-line drawing of the current view, the one quadrix
// draw writes for the same scene and view.
TEST(UqFeed, SvgDeviceWritesTheHiddenLineDrawing) {
    TempDir dir;
    const std::string scene =
        "quadric cyl <1 0 1 0 0 0 0 0 0 -1>; plane top <0 1 0 -1>; plane bot <0 -1 0 -1>;\n"
        "body c (cyl top bot);\nview front dop 0 0 -1 whh 2 whw 2;\n";
    Session s;
    s.uq.settings.xInches = s.uq.settings.yInches = 2;
    for (std::istringstream in(scene); !in.eof();) {
        std::string line;
        std::getline(in, line);
        EXPECT_TRUE(s.uq.Feed(line).diagnostics.empty()) << line;
    }
    const std::string svg = dir.File("part.svg");
    auto dev = s.uq.Feed("device \"svg:" + svg + "\";");
    EXPECT_TRUE(dev.diagnostics.empty()) << Errors(dev);
    auto show = s.uq.Feed("show;");
    EXPECT_TRUE(show.diagnostics.empty()) << Errors(show);
    std::ifstream in(svg);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_NE(text.str().find("<svg"), std::string::npos);
    EXPECT_NE(text.str().find("<path"), std::string::npos) << text.str();
    // The same file as quadrix draw of the same scene and view at the same size (200x200 px).
    dir.Write("scene.uq", scene);
    CommandResult draw = RunShell(QuadrixBinary() + " draw " + dir.File("scene.uq") +
                                  " --size 200x200 -o " + dir.File("draw.svg"));
    ASSERT_EQ(draw.exitCode, 0) << draw.err;
    std::ifstream d(dir.File("draw.svg"));
    std::stringstream drawText;
    drawText << d.rdbuf();
    // The title differs (view name vs file name); the strokes are the same.
    auto paths = [](const std::string& t) {
        std::string out;
        for (std::size_t at = t.find("<path"); at != std::string::npos;
             at = t.find("<path", at + 1))
            out += t.substr(at, t.find('>', at) - at) + "\n";
        return out;
    };
    EXPECT_EQ(paths(text.str()), paths(drawText.str()));
    // A pdf device writes a PDF; a wrong extension is an error at the device statement.
    auto pdf = s.uq.Feed("device \"pdf:" + dir.File("part.pdf") + "\"; show;");
    EXPECT_TRUE(pdf.diagnostics.empty()) << Errors(pdf);
    std::ifstream p(dir.File("part.pdf"));
    std::string magic(4, '\0');
    p.read(magic.data(), 4);
    EXPECT_EQ(magic, "%PDF");
    auto wrong = s.uq.Feed("device \"svg:" + dir.File("part.png") + "\";");
    ASSERT_EQ(wrong.diagnostics.size(), 1u);
    EXPECT_NE(Errors(wrong).find("writes .svg files"), std::string::npos) << Errors(wrong);
}

// The prompt reads what the batch reader reads: every example fed line by line gives the scene
// that reading the file whole gives (same objects, ids and coefficients), with no diagnostics.
TEST(UqFeed, ExamplesFedLineByLineGiveTheSceneOfTheFile) {
    const char* examples[] = {"examples/tube.uq",
                              "examples/machined_part.uq",
                              "examples/bundle_of_tubes.uq",
                              "examples/cylinder_minus_cylinder.uq",
                              "examples/materials.uq",
                              "examples/stack_of_bundles.uq"};
    // (teapot_on_table.uq names its patch file relative to the file, which typed input cannot.)
    for (const char* example : examples) {
        Session whole, fed;
        whole.uq.ReadFile(SourcePath(example));
        std::ifstream in(SourcePath(example));
        ASSERT_TRUE(in) << example;
        int diagnostics = 0;
        for (std::string line; std::getline(in, line);)
            diagnostics += static_cast<int>(fed.uq.Feed(line).diagnostics.size());
        fed.uq.EndFeed();
        EXPECT_EQ(diagnostics, 0) << example;
        EXPECT_FALSE(fed.uq.HadErrors()) << example;
        EXPECT_FALSE(whole.uq.HadErrors()) << example;
        const std::string a = whole.uq.HelpText("ids"), b = fed.uq.HelpText("ids");
        EXPECT_EQ(a, b) << example;
        EXPECT_NE(a.find("solids ("), std::string::npos) << example << "\n" << a;
    }
}

// Garbage never crashes the session or loses a valid statement that starts a later line.
TEST(UqFeed, GarbageLinesThenAValidStatement) {
    const char* garbage[] = {"}}}",           "{ open comment", "close }",  "\"unterminated",
                             "<<<>>>",        "=r 1 2 3",       ";;;",      "body ( ( (",
                             "plane <1 2",    "view v dop",     "\x01\x02", "solid nosuch x;",
                             "definition d;", "enddef;"};
    Session s;
    for (const char* g : garbage) s.uq.Feed(g);
    s.uq.Feed("}");  // ends the open comment, if one is still open
    s.uq.Feed(";");  // ends a statement still being read, if any
    auto good = s.uq.Feed("quadric survivor <1 1 1 0 0 0 0 0 0 -1>;");
    EXPECT_TRUE(good.diagnostics.empty()) << Errors(good);
    EXPECT_NE(s.uq.HelpText("ids").find("survivor"), std::string::npos) << s.uq.HelpText("ids");
    EXPECT_TRUE(s.uq.HadErrors());
}

}  // namespace
}  // namespace quadrix::testing
