// .scad files beyond the literal CSG subset, evaluated by the openscad program
// (import/openscad/scad_source.h, openscad_program.h): variables, modules and loops give the same
// scene as the literal file; positions of diagnostics are mapped back to the .scad (or say why
// not); OpenSCAD's own errors keep their line; without OpenSCAD the message names the package;
// the run is bounded (time limit), takes no shell, and a failure writes no output.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <string>

#include "quadrix/import/openscad/openscad_program.h"
#include "quadrix/pipeline/inputs.h"
#include "test_util.h"

namespace quadrix {
namespace {

using testing::FileExists;
using testing::QuadrixBinary;
using testing::RunShell;
using testing::TempDir;

// Sets an environment variable for the test's lifetime.
class Env {
  public:
    Env(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        had_ = std::getenv(name) != nullptr;
        ::setenv(name, value, 1);
    }
    ~Env() {
        if (had_)
            ::setenv(name_, old_.c_str(), 1);
        else
            ::unsetenv(name_);
    }
    Env(const Env&) = delete;
    Env& operator=(const Env&) = delete;

  private:
    const char* name_;
    std::string old_;
    bool had_ = false;
};

struct Read {
    scene::Scene scene;
    Diagnostics diags;
    InputReport report;
    bool ok = false;
    std::string Messages() const {
        std::string s;
        for (const Diagnostic& d : diags.Items()) s += d.Format(false) + "\n";
        return s;
    }
};

Read ReadFile(const std::string& path) {
    Read r;
    r.ok = ReadSceneInputs({path}, {}, r.scene, r.diags, r.report);
    return r;
}

#define REQUIRE_OPENSCAD()                                                                    \
    if (import::scad::FindOpenScad().empty())                                                 \
    GTEST_SKIP() << "openscad is not installed (apt-get install openscad): .scad evaluation " \
                    "cannot be tested"

TEST(ScadEvaluation, ModulesLoopsAndVariablesGiveTheLiteralScene) {
    REQUIRE_OPENSCAD();
    TempDir dir;
    const std::string evaluated = dir.Write("bolts.scad",
                                            "n = 3; pitch = 4;\n"
                                            "module peg(h) { cylinder(r = 1, h = h, $fn = 6); }\n"
                                            "for (i = [0 : n - 1]) translate([i * pitch, 0, 0])\n"
                                            "    peg(2 + i);\n");
    const std::string literal =
        dir.Write("literal.scad",
                  "cylinder(r = 1, h = 2, $fn = 6);\n"
                  "translate([4, 0, 0]) cylinder(r = 1, h = 3, $fn = 6);\n"
                  "translate([8, 0, 0]) cylinder(r = 1, h = 4, $fn = 6);\n");
    Read a = ReadFile(evaluated), b = ReadFile(literal);
    ASSERT_TRUE(a.ok) << a.Messages();
    ASSERT_TRUE(b.ok) << b.Messages();
    ASSERT_EQ(a.report.imports.size(), 1u);
    EXPECT_EQ(a.report.imports[0].second.format, "OpenSCAD (evaluated by openscad)");
    EXPECT_EQ(b.report.imports[0].second.format, "OpenSCAD CSG");  // read directly
    EXPECT_EQ(a.report.imports[0].second.solids, 3);
    EXPECT_EQ(a.scene.top.halfSpaces.size(), b.scene.top.halfSpaces.size());
    const Box3 &ba = a.report.importedBounds, &bb = b.report.importedBounds;
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(ba.lo[k], bb.lo[k], 1e-9) << k;
        EXPECT_NEAR(ba.hi[k], bb.hi[k], 1e-9) << k;
    }
    // The scene's positions are the .scad's: 'cylinder' is called once, on line 2.
    for (const scene::Body& body : a.scene.top.bodies) {
        EXPECT_EQ(body.loc.FileName(), evaluated);
        EXPECT_EQ(body.loc.line, 2);
    }
}

TEST(ScadEvaluation, DiagnosticsAreMappedBackOrSayWhyNot) {
    REQUIRE_OPENSCAD();
    TempDir dir;
    // One twisted extrusion, called once: its own line and column.
    const std::string once = dir.Write("once.scad",
                                       "w = 2;\n"
                                       "module m() {\n"
                                       "  linear_extrude(height = 3, twist = 30) square(w);\n"
                                       "}\n"
                                       "m();\n");
    Read a = ReadFile(once);
    EXPECT_FALSE(a.ok);
    ASSERT_GE(a.diags.Items().size(), 1u) << a.Messages();
    const Diagnostic& d = a.diags.Items()[0];
    EXPECT_EQ(d.loc.FileName(), once);
    EXPECT_EQ(d.loc.line, 3);
    EXPECT_EQ(d.loc.column, 3);
    EXPECT_NE(d.message.find("twist"), std::string::npos) << d.message;
    EXPECT_NE(d.sourceLine.find("linear_extrude"), std::string::npos);
    // Called from two places: no line is claimed, the message names the candidates.
    const std::string twice = dir.Write("twice.scad",
                                        "a = 30;\n"
                                        "linear_extrude(height = 3, twist = a) square(2);\n"
                                        "translate([5, 0, 0])\n"
                                        "  linear_extrude(height = 3, twist = a) square(2);\n");
    Read b = ReadFile(twice);
    EXPECT_FALSE(b.ok);
    ASSERT_GE(b.diags.Items().size(), 1u);
    EXPECT_EQ(b.diags.Items()[0].loc.line, 0);
    EXPECT_NE(b.Messages().find("is called at lines 2, 4"), std::string::npos) << b.Messages();
}

TEST(ScadEvaluation, OpenScadErrorsKeepTheirLineAndFail) {
    REQUIRE_OPENSCAD();
    TempDir dir;
    const std::string bad = dir.Write("bad.scad", "x = 1;\nmodule m() { cube(x) }\nm();\n");
    Read a = ReadFile(bad);
    EXPECT_FALSE(a.ok);
    bool lineTwo = false;
    for (const Diagnostic& d : a.diags.Items())
        lineTwo |= d.severity == Diagnostic::Severity::kError && d.loc.line == 2 &&
                   d.loc.FileName() == bad;
    EXPECT_TRUE(lineTwo) << a.Messages();
    // OpenSCAD 2021.01 exits 0 after a failed assert(), with an empty CSG file: still a failure.
    const std::string assertion = dir.Write("assert.scad",
                                            "x = 1;\nassert(x > 2, \"too small\");\n"
                                            "cube(x);\n");
    Read b = ReadFile(assertion);
    EXPECT_FALSE(b.ok);
    EXPECT_NE(b.Messages().find("too small"), std::string::npos) << b.Messages();
    // Through the CLI: non-zero exit, no picture.
    auto r = RunShell(QuadrixBinary() + " render " + bad + " -o " + dir.File("bad.png"));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_FALSE(FileExists(dir.File("bad.png")));
}

TEST(ScadEvaluation, WithoutOpenScadTheMessageNamesThePackage) {
    TempDir dir;
    const std::string f = dir.Write("m.scad", "module m() { cube(1); }\nm();\n");
    Env none("QUADRIX_OPENSCAD", "");
    Read a = ReadFile(f);
    EXPECT_FALSE(a.ok);
    EXPECT_NE(a.Messages().find("apt-get install openscad"), std::string::npos) << a.Messages();
    EXPECT_NE(a.Messages().find("m.scad:1:1: error: 'module' is not supported"), std::string::npos)
        << a.Messages();
    // A literal file needs no OpenSCAD.
    Read b = ReadFile(dir.Write("c.scad", "cube(1);\n"));
    EXPECT_TRUE(b.ok) << b.Messages();
}

TEST(ScadEvaluation, TheProgramRunsBoundedWithoutAShell) {
    TempDir dir;
    // A stand-in program: it hangs, or fails with a message, or records its arguments.
    const std::string hang = dir.Write("hang.sh", "#!/bin/sh\nexec sleep 30\n");
    const std::string fail = dir.Write("fail.sh", "#!/bin/sh\necho 'it broke here' >&2\nexit 3\n");
    const std::string args = dir.Write("args.sh",
                                       "#!/bin/sh\nfor a in \"$@\"; do echo \"$a\"; "
                                       "done > \"$(dirname \"$0\")/argv.txt\"\n"
                                       "echo 'cube(1);' > \"$2\"\n");
    ASSERT_EQ(RunShell("chmod +x " + hang + " " + fail + " " + args).exitCode, 0);
    const std::string model =
        dir.Write("a;touch pwned $(touch pwned2) '.scad", "x = 1; cube(x);\n");
    {
        Env program("QUADRIX_OPENSCAD", hang.c_str());
        Env limit("QUADRIX_OPENSCAD_TIMEOUT", "0.3");
        Read a = ReadFile(model);
        EXPECT_FALSE(a.ok);
        EXPECT_NE(a.Messages().find("ran longer than 0.3 s"), std::string::npos) << a.Messages();
    }
    {
        Env program("QUADRIX_OPENSCAD", fail.c_str());
        Read a = ReadFile(model);
        EXPECT_FALSE(a.ok);
        EXPECT_NE(a.Messages().find("exit status 3"), std::string::npos) << a.Messages();
        EXPECT_NE(a.Messages().find("it broke here"), std::string::npos) << a.Messages();
    }
    {
        Env program("QUADRIX_OPENSCAD", args.c_str());
        Read a = ReadFile(model);
        EXPECT_TRUE(a.ok) << a.Messages();
        std::string argv;
        ASSERT_TRUE(testing::FileExists(dir.File("argv.txt")));
        auto cat = RunShell("cat " + dir.File("argv.txt"));
        // -o TMP/model.csg /abs/path/of/the model: the name is one argument, never a command.
        EXPECT_NE(cat.out.find("-o\n"), std::string::npos) << cat.out;
        EXPECT_NE(cat.out.find("/a;touch pwned $(touch pwned2) '.scad\n"), std::string::npos)
            << cat.out;
        EXPECT_FALSE(FileExists("pwned"));
        EXPECT_FALSE(FileExists("pwned2"));
    }
}

}  // namespace
}  // namespace quadrix
