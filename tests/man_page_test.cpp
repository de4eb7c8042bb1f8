// The manual page and the bash completion are generated from the CLI's own option tables
// (`quadrix man`, apps/quadrix/man_command.cpp), so they cannot drift: every option that
// `quadrix SUBCOMMAND --help` lists must be in both, and the page must format without warnings.
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>

#include "test_util.h"

namespace quadrix::testing {
namespace {

// The long options ("--size") a --help text lists.
std::set<std::string> HelpOptions(const std::string& help) {
    std::set<std::string> names;
    const std::regex option(R"((^|[ ,])(--[a-z][a-z0-9-]*))");
    for (auto it = std::sregex_iterator(help.begin(), help.end(), option);
         it != std::sregex_iterator(); ++it)
        names.insert((*it)[2]);
    return names;
}

// "--engine-opt" as roff writes it: "\-\-engine\-opt".
std::string RoffName(const std::string& name) {
    std::string s;
    for (char c : name) s += c == '-' ? std::string("\\-") : std::string(1, c);
    return s;
}

// Whether the page has an option heading (the line after ".TP", in bold) naming `name`: the
// option names of a heading are "\fB\-o, \-\-output\fR", each followed by ',' or "\fR".
bool InPage(const std::string& page, const std::string& name) {
    const std::string roff = RoffName(name);
    for (std::size_t at = page.find(".TP\n\\fB"); at != std::string::npos;
         at = page.find(".TP\n\\fB", at + 1)) {
        const std::size_t end = page.find('\n', at + 4);
        const std::string heading = page.substr(at + 7, end - at - 7);  // after ".TP\n\\fB"
        const std::size_t bold = heading.find("\\fR");
        const std::string names = heading.substr(0, bold) + ",";
        if (names.find(roff + ",") != std::string::npos) return true;
    }
    return false;
}

TEST(ManPage, EveryOptionOfRenderIsInThePageAndTheCompletion) {
    const auto help = RunShell(QuadrixBinary() + " render --help");
    ASSERT_EQ(help.exitCode, 0) << help.err;
    const auto man = RunShell(QuadrixBinary() + " man");
    ASSERT_EQ(man.exitCode, 0) << man.err;
    const auto completion = RunShell(QuadrixBinary() + " man --bash-completion");
    ASSERT_EQ(completion.exitCode, 0) << completion.err;
    const std::set<std::string> options = HelpOptions(help.out);
    // render has more than twenty options; a parse that finds few would prove nothing.
    ASSERT_GT(options.size(), 20u) << help.out;
    for (const std::string& o : options) {
        EXPECT_TRUE(InPage(man.out, o)) << o;
        if (o != "--help") {
            EXPECT_NE(completion.out.find(" " + o), std::string::npos) << o;
        }
    }
    EXPECT_NE(man.out.find(".SS \"quadrix render\""), std::string::npos);
    EXPECT_NE(man.out.find(".TH QUADRIX 1 "), std::string::npos);
}

TEST(ManPage, EverySubcommandOfTheHelpIsInThePage) {
    const auto help = RunShell(QuadrixBinary() + " --help");
    ASSERT_EQ(help.exitCode, 0) << help.err;
    const auto man = RunShell(QuadrixBinary() + " man");
    ASSERT_EQ(man.exitCode, 0);
    for (const char* sub : {"render", "export", "uq", "pipe", "compare", "engines", "draw"}) {
        ASSERT_NE(help.out.find(sub), std::string::npos) << sub;
        EXPECT_NE(man.out.find(std::string(".SS \"quadrix ") + sub + "\""), std::string::npos)
            << sub;
    }
    // The generator is not a user command: hidden from --help.
    EXPECT_EQ(help.out.find("man "), std::string::npos);
    for (const char* sub : {"export", "draw", "compare"}) {
        const auto subHelp = RunShell(QuadrixBinary() + " " + sub + " --help");
        for (const std::string& o : HelpOptions(subHelp.out))
            EXPECT_TRUE(InPage(man.out, o)) << sub << " " << o;
    }
}

TEST(ManPage, FormatsWithoutWarnings) {
    if (!HaveProgram("groff")) GTEST_SKIP() << "groff is not installed";
    TempDir dir;
    const std::string page = dir.File("quadrix.1");
    ASSERT_EQ(RunShell(QuadrixBinary() + " man -o " + page).exitCode, 0);
    const auto out = RunShell("groff -man -Tutf8 -ww -z " + page);
    EXPECT_EQ(out.exitCode, 0);
    EXPECT_EQ(out.err, "") << "groff warnings:\n" << out.err;
}

}  // namespace
}  // namespace quadrix::testing
