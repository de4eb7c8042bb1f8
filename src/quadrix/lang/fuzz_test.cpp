// A deterministic fuzz-like test: thousands of random and mutated inputs must neither crash nor
// hang the reader, and every error must carry a position. (A libFuzzer target can reuse
// MutateOnce; this test keeps the property in the ordinary suite and under the sanitizers.)
#include <gtest/gtest.h>

#include <iostream>
#include <random>
#include <sstream>

#include "quadrix/lang/test_util.h"

namespace quadrix::lang {
namespace {

const char* const kSeeds[] = {
    "quadric outer_tube <1 0 1 0 0 0 0 0 0 -4>;\nquadric inner_tube <1 0 1 0 0 0 0 0 0 -1>;\n"
    "plane top_surf <0 1 0 -2>;\nplane bot_surf <0 1 0 2>;\n"
    "body tube <outer_tube !inner_tube top_surf !bot_surf>;\n",
    "definition tube; quadric o <1 0 1 0 0 0 0 0 0 -4>; plane t <0 1 0 -2>; body tube (o t); "
    "enddef;\narray bundle (tube =tx 2) 6 =ry 60 =c 1 0 0;\n"
    "def bundle_of_tubes; array hb (tube =tx 2) 6 =ry 60; end;\n"
    "array stack (bundle_of_tubes =ty -7 =vxy .5 =sa 2) 3 =ty 5;\ninstance one (tube =rz 45);\n",
    "plane ha <1 0 0 -3>; plane hb <-1 0 0 -3>; quadric s <1 1 1 0 0 0 0 0 0 -4> =t;\n"
    "body x (ha hb s) =c .5 .5 1; body y <!s ha>; csg z ((x | y) & x - (y));\n",
    "light glow .3; light .7 .4 -.4 -1; view top vrp 1 2 3 vpn 0 0 1 =p vup 0 1 0 dop 0 1 1;\n"
    "view p cop 0 0 -10 =r whh 4 whw 5 fbp 1 20; redef view p vrp 0 0 1; redef light glow 2;\n"
    "show top fast; device a keep xsize 3; read part; include \"loop\"; read; quit;\n",
    "{ comment { nested } } plane { inside } c <1 2 3 4>; \"string\" ;",
};

const char* const kTokens[] = {"plane",      "quadric",    "body",
                               "csg",        "definition", "enddef",
                               "instance",   "array",      "light",
                               "view",       "read",       "redef",
                               "show",       "quit",       "device",
                               "def",        "end",        "a",
                               "(",          ")",          "<",
                               ">",          "!",          "|",
                               "&",          "-",          ";",
                               "{",          "}",          "\"",
                               "=t",         "=0",         "=c",
                               "=tx",        "=ry",        "=sa",
                               "=vzy",       "=p",         "=r",
                               "=",          "vrp",        "cop",
                               "dop",        "whh",        "fbp",
                               "1e308",      "1e999",      "-0",
                               ".5",         "0",          "1e-320",
                               "nan",        "inf",        "#",
                               "_x",         "tube",       "x",
                               "\n",         "read part;", "read loop;",
                               "((((((((",   "=finish",    "=alpha",
                               "=at",        "=aim",       "=cone",
                               "background", "steelblue",  "solid sphere s =r 1"};

std::string MutateOnce(std::string s, std::mt19937& rng) {
    auto pick = [&](std::size_t n) {
        return std::uniform_int_distribution<std::size_t>(0, n)(rng);
    };
    std::size_t pos = s.empty() ? 0 : pick(s.size());
    switch (pick(6)) {
        case 0:  // flip a byte
            if (!s.empty()) s[pick(s.size() - 1)] = static_cast<char>(pick(255));
            break;
        case 1:  // insert a token
            s.insert(pos, std::string(" ") + kTokens[pick(std::size(kTokens) - 1)] + " ");
            break;
        case 2:  // delete a range
            s.erase(pos, pick(16));
            break;
        case 3:  // duplicate a range
            s.insert(pos, s.substr(pick(s.size()), pick(64)));
            break;
        case 4:  // truncate
            s.resize(pos);
            break;
        case 5:  // insert a random byte
            s.insert(pos, 1, static_cast<char>(pick(255)));
            break;
        default:  // replace a token boundary with nothing: glue two tokens together
            if (auto sp = s.find(' ', pos); sp != std::string::npos) s.erase(sp, 1);
            break;
    }
    return s;
}

class CountingHandler : public CommandHandler {
  public:
    bool OnCommand(const Command&, scene::Scene&, Diagnostics&) override {
        return ++count % 7 != 0;
    }
    int count = 0;
};

void CheckOne(const std::string& text, const std::string& name, bool withHandler) {
    scene::Scene scene;
    Diagnostics diags;
    CountingHandler handler;
    ReadOptions options;
    if (withHandler) options.commands = &handler;
    Reader reader(scene, diags, options);
    bool ok = reader.ReadText(text, name);
    EXPECT_EQ(ok, !diags.HasErrors());
    for (const Diagnostic& d : diags.Items()) {
        if (d.severity != Diagnostic::Severity::kError) continue;
        ASSERT_TRUE(d.loc.file) << d.message;
        ASSERT_GT(d.loc.line, 0) << d.message << "\ninput:\n" << text;
        ASSERT_GT(d.loc.column, 0) << d.message << "\ninput:\n" << text;
        (void)d.Format();
    }
    // Whatever was read is a consistent scene: every index points into its vector.
    auto checkScope = [&](const scene::Scope& sc) {
        for (const scene::Body& b : sc.bodies) {
            ASSERT_FALSE(b.literals.empty());
            for (const scene::Literal& l : b.literals)
                ASSERT_LT(l.halfSpace, static_cast<int>(sc.halfSpaces.size()));
        }
        for (const scene::Instance& i : sc.instances) {
            ASSERT_GE(i.definition, 0);
            ASSERT_LT(i.definition, static_cast<int>(scene.definitions.size()));
        }
        for (const scene::Csg& c : sc.csgs) {
            ASSERT_GE(c.root, 0);
            ASSERT_LT(c.root, static_cast<int>(c.nodes.size()));
        }
    };
    checkScope(scene.top);
    for (const scene::Scope& d : scene.definitions) checkScope(d);
}

TEST(LangFuzz, RandomAndMutatedInputsNeverCrashAndErrorsHavePositions) {
    testing::TempDir dir;
    // Files that mutated `read` statements may reach; relative reads resolve inside `dir`.
    dir.Write("part", "plane from_part <1 0 0 0>; body (from_part);");
    dir.Write("loop", "read loop;");
    std::string name = (dir.Path() / "fuzz.uq").string();
    // `read -` may appear: standard input is empty here.
    std::istringstream emptyInput;
    std::streambuf* saved = std::cin.rdbuf(emptyInput.rdbuf());

    std::mt19937 rng(20240611);  // fixed: the test is reproducible
    int inputs = 0;
    for (const char* seed : kSeeds) {
        for (int i = 0; i < 500; ++i) {
            std::string s = seed;
            int mutations = 1 + static_cast<int>(rng() % 8);
            for (int m = 0; m < mutations; ++m) s = MutateOnce(std::move(s), rng);
            CheckOne(s, name, i % 2 == 0);
            ++inputs;
            if (::testing::Test::HasFatalFailure()) break;
        }
    }
    // Pure noise, and noise made of tokens.
    for (int i = 0; i < 500; ++i) {
        std::string s(rng() % 2000, '\0');
        for (char& c : s) c = static_cast<char>(rng() & 0xff);
        CheckOne(s, name, false);
        std::string t;
        for (int k = 0; k < 60; ++k) t += std::string(kTokens[rng() % std::size(kTokens)]) + " ";
        CheckOne(t, name, true);
        inputs += 2;
    }
    std::cin.rdbuf(saved);
    EXPECT_GE(inputs, 3000);
}

TEST(LangFuzz, PathologicalInputs) {
    std::istringstream emptyInput;
    std::streambuf* saved = std::cin.rdbuf(emptyInput.rdbuf());
    CheckOne(std::string(200000, '{'), "deep_comment.uq", false);
    CheckOne(std::string(100000, '('), "parens.uq", false);
    CheckOne("csg x " + std::string(100000, '(') + ";", "csg_parens.uq", false);
    CheckOne("plane ha <" + std::string(100000, '9') + " 0 0 0>;", "long_number.uq", false);
    CheckOne("plane " + std::string(100000, 'x') + " <1 0 0 0>;", "long_id.uq", false);
    CheckOne(std::string(100000, ';'), "semicolons.uq", false);
    CheckOne(std::string(50000, '\0'), "nul.uq", false);
    CheckOne("plane ha <1 0 0 0>; body hb (" + std::string(50000, '!') + "ha);", "bangs.uq", false);
    std::cin.rdbuf(saved);
}

}  // namespace
}  // namespace quadrix::lang
