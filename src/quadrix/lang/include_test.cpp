// read / include (seed 001 §2.1.7): relative paths, nesting to depth 16, cycles, bad files.
#include <gtest/gtest.h>

#include "quadrix/lang/test_util.h"

namespace quadrix::lang {
namespace {

using testing::TempDir;

struct FileRead {
    scene::Scene scene;
    Diagnostics diags;
    bool ok = false;
};

FileRead ReadPath(const std::string& path) {
    FileRead r;
    Reader reader(r.scene, r.diags);
    r.ok = reader.ReadFile(path);
    return r;
}

// f0 reads f1, ..., f(n-1) reads fn: n nested reads below the top-level file.
std::string WriteChain(const TempDir& dir, int reads) {
    for (int i = 0; i <= reads; ++i) {
        std::string text = "plane p" + std::to_string(i) + " <1 0 0 0>;\n";
        if (i < reads) text += "read f" + std::to_string(i + 1) + ";\n";
        dir.Write("f" + std::to_string(i), text);
    }
    return (dir.Path() / "f0").string();
}

TEST(LangInclude, SixteenNestedReadsAreFine) {
    TempDir dir;
    FileRead r = ReadPath(WriteChain(dir, 16));
    EXPECT_TRUE(r.ok);
    EXPECT_EQ(r.scene.top.halfSpaces.size(), 17u);
}

TEST(LangInclude, TheSeventeenthNestedReadIsAnErrorAtItsStatement) {
    TempDir dir;
    FileRead r = ReadPath(WriteChain(dir, 17));
    ASSERT_EQ(r.diags.ErrorCount(), 1);
    const Diagnostic& e = r.diags.Items()[0];
    EXPECT_EQ(*e.loc.file, (dir.Path() / "f16").string());
    EXPECT_EQ(e.loc.line, 2);
    EXPECT_EQ(e.loc.column, 1);
    EXPECT_NE(e.message.find("deeper than 16"), std::string::npos) << e.message;
    EXPECT_EQ(e.kind, "parser");
    EXPECT_EQ(r.scene.top.halfSpaces.size(), 17u);  // f17 was not read
}

TEST(LangInclude, MaxDepthIsAnOption) {
    TempDir dir;
    scene::Scene scene;
    Diagnostics diags;
    ReadOptions options;
    options.maxIncludeDepth = 2;
    Reader reader(scene, diags, options);
    EXPECT_FALSE(reader.ReadFile(WriteChain(dir, 3)));
    EXPECT_EQ(scene.top.halfSpaces.size(), 3u);
}

TEST(LangInclude, CycleIsAnErrorNamingTheChain) {
    TempDir dir;
    std::string a = dir.Write("a.uq", "plane pa <1 0 0 0>;\nread \"b.uq\";\n");
    std::string b = dir.Write("b.uq", "plane pb <1 0 0 0>;\n  read \"./a.uq\";\n");
    FileRead r = ReadPath(a);
    ASSERT_EQ(r.diags.ErrorCount(), 1);
    const Diagnostic& e = r.diags.Items()[0];
    EXPECT_EQ(*e.loc.file, b);
    EXPECT_EQ(e.loc.line, 2);
    EXPECT_EQ(e.loc.column, 3);
    EXPECT_EQ(e.message, "read cycle: " + a + " -> " + b + " -> " + a);
}

TEST(LangInclude, SelfReadIsACycle) {
    TempDir dir;
    std::string a = dir.Write("self.uq", "read self;");
    dir.Write("self", "read \"self\";");
    FileRead r = ReadPath(a);
    ASSERT_EQ(r.diags.ErrorCount(), 1);
    EXPECT_NE(r.diags.Items()[0].message.find("read cycle"), std::string::npos);
}

TEST(LangInclude, UnreadableFiles) {
    TempDir dir;
    FileRead missing = ReadPath((dir.Path() / "missing.uq").string());
    ASSERT_EQ(missing.diags.ErrorCount(), 1);
    EXPECT_EQ(missing.diags.Items()[0].loc.line, 0);  // no position for a top-level file
    EXPECT_EQ(missing.diags.Items()[0].kind, "parser");
    EXPECT_NE(missing.diags.Items()[0].Format().find("missing.uq: error: cannot read"),
              std::string::npos);

    FileRead directory = ReadPath(dir.Path().string());
    ASSERT_EQ(directory.diags.ErrorCount(), 1);
    EXPECT_NE(directory.diags.Items()[0].message.find("directory"), std::string::npos);

    std::string main = dir.Write("main.uq", "plane pa <1 0 0 0>;\n   include nothing_here;\n");
    FileRead r = ReadPath(main);
    ASSERT_EQ(r.diags.ErrorCount(), 1);
    EXPECT_EQ(r.diags.Items()[0].loc.line, 2);
    EXPECT_EQ(r.diags.Items()[0].loc.column, 4);
    EXPECT_NE(r.diags.Items()[0].message.find("nothing_here"), std::string::npos);
}

TEST(LangInclude, QuitStopsOnlyTheIncludedFile) {
    TempDir dir;
    dir.Write("part.uq", "plane pa <1 0 0 0>; quit; plane skipped <1 0 0 0>;");
    std::string main = dir.Write("main.uq", "read \"part.uq\"; plane after <0 1 0 0>;");
    FileRead r = ReadPath(main);
    EXPECT_TRUE(r.ok);
    ASSERT_EQ(r.scene.top.halfSpaces.size(), 2u);
    EXPECT_EQ(r.scene.top.halfSpaces[1].id, "after");
}

TEST(LangInclude, ReadInsideADefinitionAddsToIt) {
    TempDir dir;
    dir.Write("tube_body.uq", "quadric o <1 0 1 0 0 0 0 0 0 -4>; body t (o);");
    std::string main =
        dir.Write("main.uq", "definition tube; read \"tube_body.uq\"; enddef; instance (tube);");
    FileRead r = ReadPath(main);
    ASSERT_TRUE(r.ok);
    ASSERT_EQ(r.scene.definitions.size(), 1u);
    EXPECT_EQ(r.scene.definitions[0].bodies.size(), 1u);
    EXPECT_TRUE(r.scene.top.halfSpaces.empty());
}

TEST(LangInclude, DefinitionsMustEndInTheirOwnFile) {
    TempDir dir;
    dir.Write("opens.uq", "definition d;\nplane pa <1 0 0 0>;\n");
    dir.Write("closes.uq", "enddef;");
    std::string main =
        dir.Write("main.uq", "read \"opens.uq\";\ndefinition e; read \"closes.uq\"; enddef;");
    FileRead r = ReadPath(main);
    ASSERT_EQ(r.diags.ErrorCount(), 2) << r.diags.Items()[0].Format();
    EXPECT_NE(r.diags.Items()[0].message.find("definition 'd' has no enddef"), std::string::npos);
    EXPECT_EQ(r.diags.Items()[0].loc.line, 1);
    EXPECT_NE(r.diags.Items()[1].message.find("enddef must be in the file"), std::string::npos);
}

}  // namespace
}  // namespace quadrix::lang
