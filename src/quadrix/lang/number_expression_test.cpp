// `clock` and number expressions (number_expression.cpp, docs/language.md §3.14).
#include <gtest/gtest.h>

#include "quadrix/lang/test_util.h"

namespace quadrix::lang {
namespace {

using testing::Parse;

ReadOptions At(double clock) {
    ReadOptions o;
    o.clock = clock;
    return o;
}

// The plane's D coefficient after reading `plane pl <0 1 0 EXPR>;` at `clock`.
double PlaneD(const std::string& expr, double clock) {
    auto r = Parse("plane pl <0 1 0 " + expr + ">;", At(clock));
    EXPECT_TRUE(r.ok) << expr << "\n" << r.All();
    if (r.scene.top.halfSpaces.empty()) return NAN;
    return r.scene.top.halfSpaces[0].plane.d;
}

TEST(NumberExpression, ClockAloneIsTheFrameTime) {
    EXPECT_EQ(PlaneD("clock", 0.25), 0.25);
    EXPECT_EQ(PlaneD("clock", 0), 0.0);
    EXPECT_EQ(PlaneD("(clock)", 0.75), 0.75);
}

TEST(NumberExpression, ArithmeticWithPrecedenceAndSigns) {
    EXPECT_EQ(PlaneD("(1 + 2 * 3)", 0), 7.0);
    EXPECT_EQ(PlaneD("((1 + 2) * 3)", 0), 9.0);
    EXPECT_EQ(PlaneD("(360 * clock)", 0.5), 180.0);
    EXPECT_EQ(PlaneD("(clock -1)", 0.25), -0.75);  // a signed number after an operand is added
    EXPECT_EQ(PlaneD("(clock-1)", 0.25), -0.75);
    EXPECT_EQ(PlaneD("(2 - -clock)", 0.5), 2.5);
    EXPECT_EQ(PlaneD("(-clock * 4)", 0.5), -2.0);
    EXPECT_EQ(PlaneD("(1 / 4 + clock / 2)", 0.5), 0.5);
    EXPECT_EQ(PlaneD("(8 / 2 / 2)", 0), 2.0);  // left to right
}

TEST(NumberExpression, NumbersOutsideParenthesesStayAList) {
    auto r = Parse("plane pl <1 -2 +3 -4>;");
    ASSERT_TRUE(r.ok) << r.All();
    const auto& pl = r.scene.top.halfSpaces[0].plane;
    EXPECT_EQ(pl.a, 1);
    EXPECT_EQ(pl.b, -2);
    EXPECT_EQ(pl.c, 3);
    EXPECT_EQ(pl.d, -4);
}

TEST(NumberExpression, ReaderTellsWhetherTheClockWasUsed) {
    for (auto [text, uses] : {std::pair{"plane pl <0 1 0 1>;", false},
                              std::pair{"plane pl <0 1 0 (clock * 2)>;", true}}) {
        scene::Scene s;
        Diagnostics d;
        Reader reader(s, d);
        EXPECT_TRUE(reader.ReadText(text, "t.uq"));
        EXPECT_EQ(reader.UsesClock(), uses) << text;
    }
}

TEST(NumberExpression, ClockInTransformsSolidsAndViews) {
    const std::string text =
        "definition dd; quadric sq <1 1 1 0 0 0 0 0 0 -1>; body bb <sq>; enddef;\n"
        "instance ii (dd =tx (2 * clock) =ry (90 * clock));\n"
        "solid sphere ball =at clock 0 0 =r (1 + clock);\n"
        "view v vrp 0 0 0 dop (clock - 1) 0 -1;\n";
    auto r = Parse(text, At(1));
    ASSERT_TRUE(r.ok) << r.All();
    // Moved 2 along x, then turned 90° about y (+z toward +x): (0,0,0) → (2,0,0) → (0,0,-2).
    ASSERT_EQ(r.scene.top.instances.size(), 1u);
    const Vec3 o = r.scene.top.instances[0].init.MapPoint({0, 0, 0});
    EXPECT_NEAR(o.x, 0, 1e-15);  // exact for 90° (transforms.h)
    EXPECT_NEAR(o.z, -2, 1e-15);
    ASSERT_EQ(r.scene.views.size(), 1u);
    ASSERT_TRUE(r.scene.views[0].dop.has_value());
    EXPECT_EQ(r.scene.views[0].dop->x, 0);
}

TEST(NumberExpression, ErrorsNameTheOperatorAndTheNumber) {
    struct Case {
        const char* text;
        const char* expect;
    };
    for (const Case& c : {Case{"plane pl <0 1 0 (1 / (clock))>;", "division by zero"},
                          Case{"plane pl <0 1 0 (1 + )>;", "expected a number, 'clock' or '('"},
                          Case{"plane pl <0 1 0 (1 + 2>;", "expected ')'"},
                          Case{"plane pl <0 1 0 (1e300 * 1e300)>;", "not a finite number"},
                          Case{"plane pl <0 1 0 cl0ck>;", "expected"}}) {
        auto r = Parse(c.text);
        EXPECT_FALSE(r.ok) << c.text;
        ASSERT_FALSE(r.Errors().empty()) << c.text;
        EXPECT_NE(r.Errors()[0]->message.find(c.expect), std::string::npos) << c.text << "\n"
                                                                            << r.All();
        EXPECT_GT(r.Errors()[0]->loc.column, 0) << c.text;
    }
}

TEST(NumberExpression, DeepNestingIsAnErrorNotACrash) {
    const std::string deep = std::string(5000, '(') + "1" + std::string(5000, ')');
    auto r = Parse("plane pl <0 1 0 " + deep + ">;");
    EXPECT_FALSE(r.ok);
    ASSERT_FALSE(r.Errors().empty());
    EXPECT_NE(r.Errors()[0]->message.find("nested"), std::string::npos) << r.All();
}

}  // namespace
}  // namespace quadrix::lang
