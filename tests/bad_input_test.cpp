// The table of bad inputs (trunk acceptance): each gives a one-line error with its position where
// there is a file, a non-zero exit code, no output file, and no crash (exit codes ≥ 128 would be
// signals). The first line of standard error is the error; source and caret lines may follow.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>
#include <string>

#include "test_util.h"

namespace quadrix::testing {
namespace {

struct BadInput {
    const char* name;
    std::map<std::string, std::string> files;  // written into a temp dir; "main.uq" is rendered
    std::string extraArgs;                     // appended to the command line ({dir} = temp dir)
    std::string expectFirstLine;               // regex searched in the first line of stderr
};

void PrintTo(const BadInput& b, std::ostream* os) { *os << b.name; }

std::string IncludeChain(int depth, std::map<std::string, std::string>& files) {
    // main.uq reads f1.uq, f1 reads f2, …, f<depth> holds a sphere.
    for (int i = 1; i <= depth; ++i) {
        std::string next = i < depth ? "read \"f" + std::to_string(i + 1) + ".uq\";\n"
                                     : "quadric s <1 1 1 0 0 0 0 0 0 -1>; body ball (s);\n";
        files["f" + std::to_string(i) + ".uq"] = next;
    }
    return "read \"f1.uq\";\n";
}

std::vector<BadInput> Table() {
    const std::string sphere = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n";
    std::vector<BadInput> t = {
        {"MissingCloseAngle", {{"main.uq", "plane pl <1 0 0 1;\nbody ball (pl);\n"}}, "",
         R"(main\.uq:1:\d+: error)"},
        {"MissingSemicolon", {{"main.uq", "quadric s <1 1 1 0 0 0 0 0 0 -1>\nbody ball (s);\n"}}, "",
         R"(main\.uq:2:\d+: error)"},
        {"UnknownHalfSpace", {{"main.uq", sphere + "body c (s nope);\n"}}, "",
         R"(main\.uq:3:\d+: error.*nope)"},
        {"UnknownDefinition", {{"main.uq", "instance i1 (nodef =tx 1);\n"}}, "",
         R"(main\.uq:1:\d+: error.*nodef)"},
        {"UnknownCsgOperand", {{"main.uq", sphere + "csg c (ball - ghost);\n"}}, "",
         R"(main\.uq:3:\d+: error.*ghost)"},
        {"IncludeCycle",
         {{"main.uq", "read \"a.uq\";\n"}, {"a.uq", "read \"b.uq\";\n"}, {"b.uq", "read \"a.uq\";\n"}},
         "", R"(b\.uq:1:\d+: error)"},
        {"IncludeDepth17", {}, "", R"(f17\.uq:1:\d+: error|f16\.uq:1:\d+: error)"},
        {"InfiniteCoefficient", {{"main.uq", "quadric s <1e999 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n"}},
         "", R"(main\.uq:1:\d+: error)"},
        {"NanCoefficient", {{"main.uq", "plane pl <nan 0 0 1>;\nbody ball (pl);\n"}}, "",
         R"(main\.uq:1:\d+: error)"},
        {"ZeroQuadric", {{"main.uq", "quadric z <0 0 0 0 0 0 0 0 0 0>;\nbody ball (z);\n"}}, "",
         R"(main\.uq:1:\d+: error)"},
        {"ZeroPlaneNormal", {{"main.uq", "plane pl <0 0 0 1>;\nbody ball (pl);\n"}}, "",
         R"(main\.uq:1:\d+: error)"},
        {"UnterminatedComment", {{"main.uq", sphere + "{ never closed\n"}}, "",
         R"(main\.uq:3:1: error)"},
        {"UnterminatedString", {{"main.uq", "read \"abc\n"}}, "", R"(main\.uq:1:\d+: error)"},
        {"KeywordAsId", {{"main.uq", "plane body <1 0 0 0>;\n"}}, "", R"(main\.uq:1:\d+: error)"},
        {"DuplicateId", {{"main.uq", sphere + "quadric s <1 1 1 0 0 0 0 0 0 -2>;\n"}}, "",
         R"(main\.uq:3:\d+: error)"},
        {"NegativeArrayCount",
         {{"main.uq", "definition d;\n" + sphere + "enddef;\narray a1 (d) -1 =tx 1;\n"}}, "",
         R"(main\.uq:5:\d+: error)"},
        {"ZeroScale", {{"main.uq", "definition d;\n" + sphere + "enddef;\ninstance (d =sx 0);\n"}},
         "", R"(main\.uq:5:\d+: error)"},
        {"MissingEnddef", {{"main.uq", "definition d;\n" + sphere}}, "", R"(main\.uq:\d+:\d+: error)"},
        {"NestedDefinition", {{"main.uq", "definition d;\ndefinition e;\nenddef;\nenddef;\n"}}, "",
         R"(main\.uq:2:\d+: error)"},
        {"EmptyBody", {{"main.uq", sphere + "body e ();\n"}}, "", R"(main\.uq:3:\d+: error)"},
        {"ZeroLightDirection", {{"main.uq", sphere + "light l1 1 0 0 0;\n"}}, "",
         R"(main\.uq:3:\d+: error)"},
        {"DopAndCop", {{"main.uq", sphere + "view v dop 0 0 -1 cop 0 0 -5;\n"}}, "",
         R"(main\.uq:3:\d+: error)"},
        {"VupParallelToVpn", {{"main.uq", sphere + "view v vpn 0 1 0 vup 0 2 0;\n"}}, "",
         R"(main\.uq:3:\d+: error)"},
        {"IdStartingWithDigit", {{"main.uq", "plane 1abc <1 0 0 0>;\n"}}, "",
         R"(main\.uq:1:\d+: error)"},
        {"BinaryGarbage", {{"main.uq", std::string("\x01\x02\xff\xfe<<>>;;\0\x7f", 12)}}, "",
         R"(main\.uq:1:\d+: error)"},
        {"UnboundedWithoutWindow", {{"main.uq", "plane pl <0 1 0 0>;\nbody half (pl);\n"}}, "",
         R"(main\.uq:2:\d+: error.*unbounded)"},
        {"EmptyScene", {{"main.uq", "{ nothing here }\n"}}, "", R"(error.*nothing to draw)"},
        {"OnlyLightsAndViews", {{"main.uq", "light amb .5;\nview v dop 0 0 -1;\n"}}, "",
         R"(error.*nothing to draw)"},
        // Command-line problems: no position, still one clear line.
        {"UnknownView", {{"main.uq", sphere}}, "--view nope", R"(error.*view.*nope)"},
        {"UnknownEngine", {{"main.uq", sphere}}, "--engine warp", R"(error.*engine.*warp)"},
        {"NegativeSize", {{"main.uq", sphere}}, "--size -5x10", R"(error.*size)"},
        {"AbsurdSize", {{"main.uq", sphere}}, "--size 100000x100000", R"(error.*too large)"},
        {"MalformedSize", {{"main.uq", sphere}}, "--size big", R"(error.*size)"},
        {"UnreadableScene", {}, "{dir}/does_not_exist.uq", R"(error.*does_not_exist\.uq)"},
        {"UnwritableOutput", {{"main.uq", sphere}}, "-o {dir}/no/such/dir/out.png",
         R"(error.*cannot write)"},
        {"UnknownOutputFormat", {{"main.uq", sphere}}, "-o {dir}/out.bmp", R"(error.*format)"},
    };
    for (BadInput& b : t)
        if (std::string(b.name) == "IncludeDepth17") b.files["main.uq"] = IncludeChain(17, b.files);
    return t;
}

std::string Substitute(std::string s, const std::string& dir) {
    for (std::size_t p; (p = s.find("{dir}")) != std::string::npos;) s.replace(p, 5, dir);
    return s;
}

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, OneLineErrorNonZeroExitNoOutput) {
    const BadInput& b = GetParam();
    TempDir dir;
    for (const auto& [name, text] : b.files) dir.Write(name, text);
    std::string out = dir.File("out.png");
    std::string args = Substitute(b.extraArgs, dir.path());
    std::string scene = b.files.count("main.uq") ? dir.File("main.uq") : "";
    // An explicit -o in extraArgs replaces the default output.
    bool ownOutput = args.find("-o ") != std::string::npos;
    std::string cmd = "cd '" + dir.path() + "' && " + QuadrixBinary() + " render " + scene + " " +
                      args + (ownOutput ? "" : " -o '" + out + "'");
    CommandResult r = RunShell(cmd);
    EXPECT_NE(r.exitCode, 0) << cmd << "\n" << r.err;
    EXPECT_LT(r.exitCode, 128) << "killed by a signal: " << r.err;
    // The first line that is an error (warnings, e.g. about generated ids, may come before it).
    std::string first;
    for (std::size_t pos = 0; pos < r.err.size();) {
        std::size_t end = r.err.find('\n', pos);
        std::string line = r.err.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        if (line.find("error") != std::string::npos) {
            first = line;
            break;
        }
        if (end == std::string::npos) break;
        pos = end + 1;
    }
    EXPECT_TRUE(std::regex_search(first, std::regex(b.expectFirstLine)))
        << "first error line of stderr: '" << first << "'\nexpected /" << b.expectFirstLine
        << "/\nfull stderr:\n"
        << r.err;
    EXPECT_FALSE(FileExists(out));
    // No temporary files left behind either.
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

INSTANTIATE_TEST_SUITE_P(Table, BadInputTest, ::testing::ValuesIn(Table()),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(BadInputTable, HasAtLeast25Entries) { EXPECT_GE(Table().size(), 25u); }

}  // namespace
}  // namespace quadrix::testing
