// The one engine-option parser (options.h) and the registry's documentation (registry.h).
#include "quadrix/engines/options.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "quadrix/engines/registry.h"

namespace quadrix {
namespace {

const OptionSchema& Schema() {
    using O = OptionSpec;
    static const OptionSchema kSchema{
        O::Bool("fast", "on", "a switch"),
        O::Int("level", "3", 1, 10, "an integer"),
        O::Int("base", "1", 1, 64, "an integer or auto").AllowingAuto(),
        O::Number("gap", "0.5", 0, 1, true, "a number in (0, 1]"),
        O::Choice("mode", "exact", {"exact", "approx", "paper"}, "a choice"),
        O::Choice("shading", "", {"a", "b"}, "a choice whose default depends"),
    };
    return kSchema;
}

std::string Parse(const std::map<std::string, std::string>& raw, EngineOptions& out) {
    return ParseEngineOptions("toy", Schema(), raw, out);
}

TEST(EngineOptions, DefaultsAndTypedValues) {
    EngineOptions o;
    ASSERT_EQ(Parse({}, o), "");
    EXPECT_TRUE(o.Bool("fast"));
    EXPECT_EQ(o.Int("level"), 3);
    EXPECT_EQ(o.Number("gap"), 0.5);
    EXPECT_EQ(o.Choice("mode"), "exact");
    EXPECT_FALSE(o.Given("mode"));
    EXPECT_FALSE(o.Given("shading"));
    ASSERT_EQ(Parse({{"level", "10"}, {"mode", "paper"}, {"gap", "1"}, {"base", "auto"}}, o), "");
    EXPECT_EQ(o.Int("level"), 10);
    EXPECT_EQ(o.Int("base"), 0);
    EXPECT_EQ(o.Choice("mode"), "paper");
    EXPECT_TRUE(o.Given("mode"));
    EXPECT_EQ(o.Summary(), "fast=on level=10 base=auto gap=1 mode=paper shading=(auto)");
}

TEST(EngineOptions, OneBooleanVocabulary) {
    for (const char* yes : {"on", "true", "yes", "1"}) {
        EngineOptions o;
        ASSERT_EQ(Parse({{"fast", yes}}, o), "") << yes;
        EXPECT_TRUE(o.Bool("fast")) << yes;
    }
    for (const char* no : {"off", "false", "no", "0"}) {
        EngineOptions o;
        ASSERT_EQ(Parse({{"fast", no}}, o), "") << no;
        EXPECT_FALSE(o.Bool("fast")) << no;
    }
    EngineOptions o;
    EXPECT_EQ(Parse({{"fast", "On"}}, o),
              "engine 'toy': option 'fast' must be on or off, not 'On'");
}

TEST(EngineOptions, ErrorsNameTheKeyAndWhatIsAccepted) {
    EngineOptions o;
    EXPECT_EQ(Parse({{"levl", "2"}}, o),
              "engine 'toy' has no option 'levl' (options: fast, level, base, gap, mode, shading)");
    EXPECT_EQ(Parse({{"level", "11"}}, o),
              "engine 'toy': option 'level' must be an integer in 1..10, not '11'");
    EXPECT_EQ(Parse({{"level", "2.5"}}, o),
              "engine 'toy': option 'level' must be an integer in 1..10, not '2.5'");
    EXPECT_EQ(Parse({{"level", "99999999999999999999999"}}, o),
              "engine 'toy': option 'level' must be an integer in 1..10, not "
              "'99999999999999999999999'");
    EXPECT_EQ(Parse({{"gap", "0"}}, o),
              "engine 'toy': option 'gap' must be a number in (0, 1], not '0'");
    EXPECT_EQ(Parse({{"gap", "nan"}}, o),
              "engine 'toy': option 'gap' must be a number in (0, 1], not 'nan'");
    EXPECT_EQ(Parse({{"base", "auto2"}}, o),
              "engine 'toy': option 'base' must be auto or an integer in 1..64, not 'auto2'");
    EXPECT_EQ(Parse({{"mode", "fast"}}, o),
              "engine 'toy': option 'mode' must be exact, approx or paper, not 'fast'");
    EXPECT_EQ(ParseEngineOptions("none", {}, {{"x", "1"}}, o),
              "engine 'none' has no options (given 'x')");
}

// Every registered engine's default values fit its own schema, and unknown keys are refused.
TEST(EngineRegistry, EveryEngineValidatesItsDefaultsAndRefusesUnknownKeys) {
    ASSERT_GE(Engines().size(), 5u);
    EXPECT_EQ(Engines().front().name, std::string(kReferenceEngine));
    for (const EngineInfo& e : Engines()) {
        auto engine = e.make();
        ASSERT_NE(engine, nullptr) << e.name;
        EXPECT_EQ(engine->Name(), e.name);
        RenderOptions ro;
        EXPECT_EQ(engine->ValidateOptions(ro), "") << e.name;
        ro.engineOptions = {{"no-such-option", "1"}};
        EXPECT_NE(engine->ValidateOptions(ro).find("no-such-option"), std::string::npos) << e.name;
        EXPECT_EQ(FindEngine(e.name), &e);
    }
    EXPECT_EQ(FindEngine("nonesuch"), nullptr);
    EXPECT_EQ(MakeEngine("nonesuch"), nullptr);
}

// docs/engines.md is generated from the registry (`quadrix engines --markdown`).
TEST(EngineRegistry, DocsPageIsUpToDate) {
    std::ifstream in(std::string(QUADRIX_SOURCE_DIR) + "/docs/engines.md");
    ASSERT_TRUE(in.good());
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), EnginesMarkdownPage())
        << "docs/engines.md is stale: run `quadrix engines --markdown > docs/engines.md`";
}

}  // namespace
}  // namespace quadrix
