// The reader's incremental face (incremental_reader.h): statements across lines, errors at the
// fed line, skipping after an error, the caller's own statements, and the scene extended in
// place.
#include "quadrix/lang/incremental_reader.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace quadrix::lang {
namespace {

using Position = IncrementalReader::Position;

// A reader on a fresh scene, with the statements and error counts its hooks saw.
struct Fed {
    scene::Scene scene;
    Diagnostics diags;
    Reader reader{scene, diags};
    std::vector<std::pair<std::string, int>> read;  // afterStatement: text, errors
    std::vector<std::string> own;                   // runOwn: the text after the word
    IncrementalReader::Hooks Hooks() {
        IncrementalReader::Hooks h;
        h.ownWord = [](const std::string& word) { return word == "help"; };
        h.runOwn = [this](const std::string&, const std::string& after) { own.push_back(after); };
        h.afterStatement = [this](const std::string& text, int errors) {
            read.emplace_back(text, errors);
        };
        return h;
    }
    std::string All() const {
        std::string s;
        for (const Diagnostic& d : diags.Items()) s += d.Format() + "\n";
        return s;
    }
};

TEST(IncrementalReader, AStatementCompletesAcrossLines) {
    Fed f;
    IncrementalReader in(f.reader, f.Hooks());
    EXPECT_EQ(in.Where(), Position::kBetweenStatements);
    EXPECT_TRUE(in.Feed("plane top").empty());
    EXPECT_EQ(in.Where(), Position::kInsideStatement);
    EXPECT_TRUE(f.scene.top.halfSpaces.empty()) << "nothing is read before the ';'";
    EXPECT_TRUE(in.Feed("  <0 1 0 -2>").empty());
    const std::vector<std::string> done = in.Feed("  ;  plane bottom <0 -1 0 -2>; body slab (");
    ASSERT_EQ(done.size(), 2u);
    EXPECT_EQ(done[0], "plane top\n  <0 1 0 -2>\n  ;");
    EXPECT_EQ(done[1], "  plane bottom <0 -1 0 -2>;");
    EXPECT_EQ(f.scene.top.halfSpaces.size(), 2u);
    EXPECT_EQ(in.Where(), Position::kInsideStatement);  // the body goes on
    EXPECT_EQ(in.Feed("top bottom);").size(), 1u);
    EXPECT_EQ(f.scene.top.bodies.size(), 1u);
    EXPECT_EQ(in.Where(), Position::kBetweenStatements);
    EXPECT_FALSE(f.diags.HasErrors()) << f.All();
    ASSERT_EQ(f.read.size(), 3u);
    for (const auto& [text, errors] : f.read) EXPECT_EQ(errors, 0) << text;
}

// A ';' inside a comment does not end the statement; a comment spans lines.
TEST(IncrementalReader, CommentsAndStringsHideTheirSemicolons) {
    Fed f;
    IncrementalReader in(f.reader, f.Hooks());
    EXPECT_TRUE(in.Feed("plane pa { a comment; still").empty());
    EXPECT_EQ(in.Where(), Position::kInsideStatement);
    EXPECT_TRUE(in.Feed("the comment; } <1 0 0 0>").empty());
    EXPECT_EQ(in.Feed(";").size(), 1u);
    EXPECT_EQ(f.scene.top.halfSpaces.size(), 1u);
    EXPECT_TRUE(in.Feed("{ only a comment }").empty());
    EXPECT_EQ(in.Where(), Position::kBetweenStatements);
    EXPECT_FALSE(f.diags.HasErrors()) << f.All();
}

// Diagnostics name the fed line: lines count every line fed (blank and comment lines too), and
// the column is where the error is on that line.
TEST(IncrementalReader, ErrorsArePositionedAtTheFedLine) {
    Fed f;
    IncrementalReader in(f.reader, f.Hooks(), "<typed>");
    in.Feed("plane pa <1 0 0 0>;");
    in.Feed("");
    in.Feed("{ a comment line }");
    in.Feed("plane pb <1 0");
    in.Feed("   x 0>;");
    ASSERT_EQ(f.diags.ErrorCount(), 1) << f.All();
    const Diagnostic& d = f.diags.Items()[0];
    EXPECT_EQ(d.loc.FileName(), "<typed>");
    EXPECT_EQ(d.loc.line, 5);
    EXPECT_EQ(d.loc.column, 4);
    EXPECT_EQ(d.sourceLine, "   x 0>;");
    ASSERT_EQ(f.read.size(), 2u);
    EXPECT_EQ(f.read[1].second, 1);  // the statement's error count, for a reply
}

// A line that does not start a statement is reported when it is fed; what follows is skipped
// to the next ';' unless a line starts a statement.
TEST(IncrementalReader, AnErrorIsReportedAtOnceAndSkippingEndsAtAStatement) {
    Fed f;
    IncrementalReader in(f.reader, f.Hooks());
    in.Feed("plnae pa <1 0 0 0>");
    EXPECT_EQ(f.diags.ErrorCount(), 1) << f.All();
    EXPECT_EQ(f.diags.Items()[0].loc.line, 1);
    EXPECT_EQ(in.Where(), Position::kSkipping);
    EXPECT_TRUE(in.Feed("more of it").empty());
    EXPECT_EQ(in.Where(), Position::kSkipping);
    EXPECT_TRUE(in.Feed("and its end; ").empty());
    EXPECT_EQ(in.Where(), Position::kBetweenStatements);
    EXPECT_TRUE(f.scene.top.halfSpaces.empty());
    // Again, but the next line starts a statement: it is read, not skipped.
    in.Feed("sphre s");
    EXPECT_EQ(in.Where(), Position::kSkipping);
    EXPECT_EQ(in.Feed("plane pb <0 1 0 0>;").size(), 1u);
    EXPECT_EQ(f.scene.top.halfSpaces.size(), 1u);
    EXPECT_EQ(f.diags.ErrorCount(), 2) << f.All();
    EXPECT_EQ(f.diags.Items()[1].loc.line, 4);
}

// An error inside a complete statement stays inside it: the next statement on the line is read.
TEST(IncrementalReader, AnErrorDoesNotReachPastItsSemicolon) {
    Fed f;
    IncrementalReader in(f.reader, f.Hooks());
    const auto done = in.Feed("plane pa <1 0 0>; plane pb <0 1 0 0>;");
    ASSERT_EQ(done.size(), 2u);
    EXPECT_EQ(f.diags.ErrorCount(), 1) << f.All();
    ASSERT_EQ(f.scene.top.halfSpaces.size(), 1u);
    EXPECT_EQ(f.scene.top.halfSpaces[0].id, "pb");
}

// The caller's own statement: not parsed, ends at its ';' or at the end of its line, and the
// statements around it are read.
TEST(IncrementalReader, OwnStatementsGoToTheHook) {
    Fed f;
    IncrementalReader in(f.reader, f.Hooks());
    EXPECT_EQ(in.Feed("help").size(), 1u);
    EXPECT_EQ(in.Feed("HELP view; plane pa <1 0 0 0>;").size(), 2u);
    ASSERT_EQ(f.own.size(), 2u);
    EXPECT_EQ(f.own[0], "\n");
    EXPECT_EQ(f.own[1], " view;");
    EXPECT_EQ(f.scene.top.halfSpaces.size(), 1u);
    EXPECT_FALSE(f.diags.HasErrors()) << f.All();
    // Positions still count the own statements' lines.
    in.Feed("plane pb <1 0 0>;");
    ASSERT_EQ(f.diags.ErrorCount(), 1);
    EXPECT_EQ(f.diags.Items()[0].loc.line, 3);
}

// The scene is extended in place: ids read from a file before are known at the prompt, and a
// definition spans fed statements; quit ends the input.
TEST(IncrementalReader, TheSceneIsExtendedInPlace) {
    Fed f;
    ASSERT_TRUE(f.reader.ReadText("plane pa <1 0 0 -1>; plane pb <-1 0 0 -1>;", "scene.uq"));
    {
        IncrementalReader in(f.reader, f.Hooks());
        in.Feed("definition slab;");
        in.Feed("  plane pp <0 0 1 -1>;");
        in.Feed("  body s (pp);");
        in.Feed("enddef;");
        in.Feed("body outside (pa !pb);");
        EXPECT_FALSE(in.Ended());
        in.Feed("quit;");
        EXPECT_TRUE(in.Ended());
        EXPECT_TRUE(in.Feed("plane pc <0 1 0 0>;").empty());  // nothing after quit
    }
    EXPECT_FALSE(f.diags.HasErrors()) << f.All();
    EXPECT_EQ(f.scene.definitions.size(), 1u);
    EXPECT_EQ(f.scene.top.bodies.size(), 1u);
    EXPECT_EQ(f.scene.top.halfSpaces.size(), 2u);
    // The Reader reads on after the interactive input.
    EXPECT_TRUE(f.reader.ReadText("body both (pa pb);", "more.uq"));
    EXPECT_EQ(f.scene.top.bodies.size(), 2u);
}

// At the end of input, an unfinished statement is read as it is and an open definition is
// reported.
TEST(IncrementalReader, FinishReportsWhatIsLeftOpen) {
    Fed f;
    IncrementalReader in(f.reader, f.Hooks());
    in.Feed("definition d;");
    in.Feed("plane pa <1 0 0 0>");
    in.Finish();
    EXPECT_TRUE(in.Ended());
    EXPECT_EQ(f.diags.ErrorCount(), 2) << f.All();
    in.Finish();  // once only
    EXPECT_EQ(f.diags.ErrorCount(), 2) << f.All();
}

// Destroyed without Finish, an input is left as it is: nothing held is read, no hook runs, and
// the Reader goes on.
TEST(IncrementalReader, DestructionAbandonsTheHeldText) {
    Fed f;
    {
        IncrementalReader in(f.reader, f.Hooks());
        in.Feed("plane pa <1 0 0 0>");
    }
    EXPECT_TRUE(f.read.empty());
    EXPECT_FALSE(f.diags.HasErrors()) << f.All();
    EXPECT_TRUE(f.scene.top.halfSpaces.empty());
    EXPECT_TRUE(f.reader.ReadText("plane pa <1 0 0 0>;", "after.uq")) << f.All();
}

// Interactive inputs nest like files: one past ReadOptions::maxIncludeDepth reads nothing.
TEST(IncrementalReader, NestingIsLimited) {
    scene::Scene scene;
    Diagnostics diags;
    ReadOptions options;
    options.maxIncludeDepth = 1;
    Reader reader(scene, diags, options);
    IncrementalReader outer(reader);
    IncrementalReader inner(reader);
    EXPECT_FALSE(inner.Ended());
    {
        IncrementalReader tooDeep(reader);
        EXPECT_TRUE(tooDeep.Ended());
        EXPECT_TRUE(tooDeep.Feed("plane pa <1 0 0 0>;").empty());
        ASSERT_EQ(diags.ErrorCount(), 1);
        EXPECT_NE(diags.Items()[0].message.find("nested too deep"), std::string::npos);
    }
    EXPECT_EQ(inner.Feed("plane pa <1 0 0 0>;").size(), 1u);
    EXPECT_EQ(scene.top.halfSpaces.size(), 1u);
}

}  // namespace
}  // namespace quadrix::lang
