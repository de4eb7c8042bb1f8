// Interactive statements (seed 001 §2.3): parsed into Commands for a handler, or accepted with a
// warning in batch rendering.
#include <gtest/gtest.h>

#include <iostream>
#include <sstream>

#include "quadrix/lang/test_util.h"

namespace quadrix::lang {
namespace {

using testing::Parse;
using testing::Parsed;

class Recorder : public CommandHandler {
  public:
    bool OnCommand(const Command& command, scene::Scene& scene, Diagnostics&) override {
        commands.push_back(command);
        lightsSeen.push_back(scene.lights.size());
        return command.kind != Command::Kind::kQuit;
    }
    std::vector<Command> commands;
    std::vector<std::size_t> lightsSeen;
};

TEST(LangCommands, ThePapersSessionParses) {
    // seed 001 §2.3, "A typical interactive session" (with `dev` for device and `a` for ascii).
    Recorder rec;
    ReadOptions options;
    options.commands = &rec;
    Parsed r = Parse(
        "light glow .3;\n"
        "light .7 .4 -.4 -1;\n"
        "view top_down dop 0 1 1;\n"
        "show;\n"
        "dev varian keep;\n"
        "show fast;\n"
        "redef light glow 0;\n"
        "redef light default;\n"
        "show default;\n"
        "device a nokeep xsize 8.5 ysize 11;\n"
        "show top_down fast;\n"
        "redef view top_down vrp 0 1 0 cop 0 0 -9 =r;\n"
        "read;\n"
        "quit;\n"
        "plane never_read <1 0 0 0>;\n",
        options);
    ASSERT_TRUE(r.ok) << r.All();
    using K = Command::Kind;
    ASSERT_EQ(rec.commands.size(), 11u);
    EXPECT_EQ(rec.commands[0].kind, K::kShow);
    EXPECT_TRUE(rec.commands[0].id.empty());
    EXPECT_EQ(rec.commands[1].kind, K::kDevice);
    EXPECT_EQ(rec.commands[1].device, "varian");
    EXPECT_TRUE(rec.commands[1].keep);
    EXPECT_TRUE(rec.commands[2].fast);
    EXPECT_EQ(rec.commands[3].kind, K::kRedefLight);
    EXPECT_EQ(rec.commands[3].id, "glow");
    EXPECT_EQ(rec.commands[4].id, "default");
    EXPECT_EQ(rec.commands[5].id, "default");
    EXPECT_EQ(rec.commands[6].device, "a");
    EXPECT_TRUE(rec.commands[6].nokeep);
    EXPECT_EQ(rec.commands[6].xsizeInches, 8.5);
    EXPECT_EQ(rec.commands[6].ysizeInches, 11);
    EXPECT_EQ(rec.commands[7].id, "top_down");
    EXPECT_TRUE(rec.commands[7].fast);
    EXPECT_EQ(rec.commands[8].kind, K::kRedefView);
    EXPECT_EQ(rec.commands[9].kind, K::kNakedRead);
    EXPECT_EQ(rec.commands[10].kind, K::kQuit);
    // The handler saw the scene as it was at each command.
    EXPECT_EQ(rec.lightsSeen[0], 2u);
    // redef changed the values in the scene.
    EXPECT_EQ(r.scene.lights[0].intensity, 0);
    const scene::View& v = r.scene.views[0];
    EXPECT_FALSE(v.dop);  // a cop in a redef replaces the parallel projection
    EXPECT_EQ(*v.cop, (Vec3{0, 1, -9}));
    // quit stopped reading.
    EXPECT_TRUE(r.scene.top.halfSpaces.empty());
}

TEST(LangCommands, WithoutAHandlerTheyWarnAndQuitStopsTheInput) {
    Parsed r = Parse("show;\ndevice x;\nredef light default;\nquit;\nplane never <1 0 0 0>;");
    EXPECT_TRUE(r.ok) << r.All();
    EXPECT_EQ(r.Warnings().size(), 4u);
    EXPECT_NE(r.Warnings()[0]->message.find("no effect in batch rendering"), std::string::npos);
    EXPECT_TRUE(r.scene.top.halfSpaces.empty());
}

TEST(LangCommands, RedefWithValuesChangesTheSceneQuietly) {
    Parsed r = Parse(
        "light sun .5 0 0 -1; light amb .2;\n"
        "redef light sun 2;\n"             // truncated, stays parallel
        "redef light amb .4 1 1 1;\n"      // becomes parallel
        "redef light default .5 0 1 0;\n"  // the default light becomes a scene light
        "view v vrp 1 0 0 dop 0 0 1;\n"
        "redef view v vpn 1 0 5 =p;\n");  // =p uses the view's vrp
    ASSERT_TRUE(r.ok) << r.All();
    EXPECT_EQ(r.Warnings().size(), 1u) << r.All();  // the truncation
    ASSERT_EQ(r.scene.lights.size(), 3u);
    EXPECT_EQ(r.scene.lights[0].intensity, 1);
    EXPECT_EQ(r.scene.lights[0].kind, scene::Light::Kind::kParallel);
    EXPECT_EQ(r.scene.lights[1].kind, scene::Light::Kind::kParallel);
    EXPECT_EQ(r.scene.lights[1].direction, (Vec3{1, 1, 1}));
    EXPECT_EQ(r.scene.lights[2].id, "default");
    EXPECT_FALSE(r.scene.lights[2].isDefault);
    EXPECT_EQ(*r.scene.views[0].vpn, (Vec3{0, 0, 5}));
    EXPECT_EQ(*r.scene.views[0].dop, (Vec3{0, 0, 1}));
}

TEST(LangCommands, UnknownObjectsAreErrors) {
    Parsed r = Parse("redef light nope;\nredef view nope;\nshow nope;");
    ASSERT_EQ(r.Errors().size(), 3u);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(r.Errors()[i]->loc.line, i + 1);
}

// Standard input is read a line at a time: a statement runs as soon as its ';' has been read,
// before the next line is asked for (what an interactive session needs, seed 001 §2.3).
TEST(LangCommands, StandardInputRunsEachStatementWhenComplete) {
    const std::string input =
        "plane pa <1 0 0 0>;\n"
        "show;\n"
        "plane pb <0 1 0 0>; { a comment\n"
        "spanning lines } show;\n"
        "quit;\n"
        "plane never <0 0 1 0>;\n";
    std::istringstream in(input);
    std::streambuf* saved = std::cin.rdbuf(in.rdbuf());

    struct AtShow : CommandHandler {
        std::istringstream* in;
        std::vector<long> positions;
        std::vector<std::size_t> planes;
        bool OnCommand(const Command& c, scene::Scene& scene, Diagnostics&) override {
            positions.push_back(static_cast<long>(in->tellg()));
            planes.push_back(scene.top.halfSpaces.size());
            return c.kind != Command::Kind::kQuit;
        }
    } handler;
    handler.in = &in;
    scene::Scene scene;
    Diagnostics diags;
    ReadOptions options;
    options.commands = &handler;
    EXPECT_TRUE(ReadSceneFiles({}, scene, diags, options));  // no file: standard input
    std::cin.rdbuf(saved);

    ASSERT_EQ(handler.positions.size(), 3u);
    // At the first show only the first two lines have been read.
    EXPECT_EQ(handler.positions[0], static_cast<long>(input.find("plane pb")));
    EXPECT_EQ(handler.planes[0], 1u);
    EXPECT_EQ(handler.positions[1], static_cast<long>(input.find("quit")));
    EXPECT_EQ(handler.planes[1], 2u);
    EXPECT_EQ(scene.top.halfSpaces.size(), 2u);  // quit stopped before `never`
    EXPECT_EQ(*scene.top.halfSpaces[0].loc.file, "<stdin>");
}

}  // namespace
}  // namespace quadrix::lang
