// Bad inputs: each gives exactly one error, at the expected line:column, with a message that
// says what was expected and what was found, and the expected kind.
#include <gtest/gtest.h>

#include <set>

#include "quadrix/lang/test_util.h"

namespace quadrix::lang {
namespace {

using testing::Parse;
using testing::Parsed;

struct BadInput {
    const char* name;
    // The scene text; '@' marks where the error must be reported and is removed before reading.
    const char* text;
    const char* message;  // a substring of the message
    const char* kind;
};

const char* const kDef = "def d; plane ha <1 0 0 0>; body (ha); end;\n";

const BadInput kBadInputs[] = {
    {"unterminated comment", "plane ha <1 0 0 0>;\n  @{ open { closed } ", "unterminated comment",
     "syntax"},
    {"unmatched close brace", "plane ha <1 0 0 0>; @}", "unmatched '}'", "syntax"},
    {"unterminated string", "read @\"abc;\n", "unterminated string", "syntax"},
    {"number too large", "plane ha <@1e999 0 0 0>;", "too large", "syntax"},
    {"malformed number", "plane ha <1 @2x 0 0>;", "malformed number '2x'", "syntax"},
    {"nan coefficient", "plane ha <1 0 @nan 0>;", "must be finite", "syntax"},
    {"garbage bytes", "plane ha <1 0 0 0>; @\x01\x02;", "unexpected characters", "syntax"},
    {"option without name", "plane ha <1 0 0 0> @= t;", "right after '='", "syntax"},
    {"plane without normal", "plane ha @<0 0 0 1>;", "A = B = C = 0", "input"},
    {"all-zero quadric", "quadric s @<0 0 0 0 0 0 0 0 0 0>;", "all coefficients zero", "input"},
    {"too few coefficients", "plane ha <1 2 3@>;", "expected coefficient D of the plane", "syntax"},
    {"too many coefficients", "plane ha <1 2 3 4 @5>;", "expected '>' after the 4 coefficients",
     "syntax"},
    {"no coefficient list", "quadric s @(1 1 1);", "expected '<' before the quadric", "syntax"},
    {"unknown plane option", "plane ha <1 0 0 0> @=x;", "unknown option '=x' for a plane",
     "syntax"},
    {"missing semicolon", "plane ha <1 0 0 0>; body hb (ha)\n@quadric c <1 1 1 0 0 0 0 0 0 -1>;",
     "expected ';' after body list, found 'quadric'", "syntax"},
    {"unknown half-space", "plane ha <1 0 0 0>; body hb (ha !@zz);", "unknown half-space 'zz'",
     "input"},
    {"empty body", "body hb @();", "at least one half-space", "input"},
    {"mismatched bracket", "plane ha <1 0 0 0>; body hb (ha@>;",
     "expected a half-space id or ')' to end the list", "syntax"},
    {"reserved word as id", "plane @p <1 0 0 0>;", "reserved word (synonym of 'plane')", "syntax"},
    {"keyword as id", "body @view (x);", "'view' is a reserved word", "syntax"},
    {"duplicate half-space", "plane ha <1 0 0 0>;\nquadric @ha <1 1 1 0 0 0 0 0 0 -1>;",
     "already defined at test.uq:1:1", "input"},
    {"duplicate solid", "plane ha <1 0 0 0>; body hb (ha); csg @hb (hb);",
     "already used by the body at test.uq:1:21", "input"},
    {"unknown statement", "plane ha <1 0 0 0>;\n@sphere s 1;", "unknown word 'sphere'", "syntax"},
    {"view parameter alone", "@vrp 0 0 0;", "'vrp' is a view parameter", "syntax"},
    {"nested definition", "def d; @def e; end;", "cannot be nested", "input"},
    {"missing enddef", "plane x <1 0 0 0>;\n@definition d;\nplane ha <1 0 0 0>;",
     "definition 'd' has no enddef", "input"},
    {"enddef without definition", "@enddef;", "enddef without a definition", "input"},
    {"light in a definition", "def d; @light .5; end;", "not allowed inside a definition", "input"},
    {"duplicate definition", "def d; end;\ndef @d; end;", "already defined at test.uq:1:1",
     "input"},
    {"unknown definition", "instance x (@nope);", "unknown definition 'nope'", "input"},
    {"self instance", "def d; plane ha <1 0 0 0>; instance (@d); end;", "cannot instance itself",
     "input"},
    {"body names a half-space of another scope", "plane top <1 0 0 0>; def d; body (@top); end;",
     "a body may name only the half-spaces of its own definition", "input"},
    {"zero scale", "def d; plane ha <1 0 0 0>; body (ha); end; instance (d =sx @0);",
     "scale factor 0", "input"},
    {"unknown transform", "def d; plane ha <1 0 0 0>; body (ha); end; instance (d @=tw 1);",
     "unknown transform '=tw'", "syntax"},
    {"fractional count", "def d; plane ha <1 0 0 0>; body (ha); end; array (d) @2.5 =tx 1;",
     "whole number", "input"},
    {"absurd count", "def d; plane ha <1 0 0 0>; body (ha); end; array (d) @1e7 =tx 1;",
     "whole number from 0 to 1000000", "input"},
    {"missing count", "def d; plane ha <1 0 0 0>; body (ha); end; array (d) @=tx 1;",
     "expected the number of copies after ')', found '=tx'", "syntax"},
    {"transform after instance", "def d; plane ha <1 0 0 0>; body (ha); end; instance (d) @=tx 1;",
     "transforms go inside the parentheses", "syntax"},
    {"color out of range", "plane ha <1 0 0 0>; body (ha) =c 1 @255 0;", "outside [0, 1]", "input"},
    {"light with two numbers", "light s 1 2@;", "expected the y component of the direction",
     "syntax"},
    {"light toward nowhere", "light s 1 @0 0 0;", "zero vector", "input"},
    {"unknown color name", "plane ha <1 0 0 0>; body (ha) =c @notacolor;",
     "unknown color name 'notacolor'", "input"},
    {"negative diffuse", "plane ha <1 0 0 0>; body (ha) =finish @-1 0 1;",
     "diffuse coefficient kd of =finish is -1", "input"},
    {"zero shininess", "plane ha <1 0 0 0>; body (ha) =finish 1 1 @0;", "must be greater than 0",
     "input"},
    {"opacity above one", "plane ha <1 0 0 0>; body (ha) =alpha @2;", "opacity of =alpha is 2",
     "input"},
    {"light direction and position", "light s 1 1 0 0 @=at 0 0 0;", "both a direction", "input"},
    {"aim without position", "light s 1 @=aim 0 0 0;", "needs =at", "input"},
    {"aim at itself", "light s 1 =at 1 2 3 @=aim 1 2 3;", "aimed at its own position", "input"},
    {"cone on a point light", "light s 1 =at 0 0 0 @=cone 10;", "=cone is for spot lights",
     "input"},
    {"cone wider than falloff", "light s 1 =at 0 0 0 =aim 0 0 1 @=cone 50 40;",
     "0 < cone <= falloff < 90", "input"},
    {"unknown light option", "light s 1 @=glow 2;", "unknown option '=glow' for a light", "syntax"},
    {"background in a definition", "def d; @background 1 1 1; end;",
     "not allowed inside a definition", "input"},
    {"duplicate light", "light s 1;\nlight @s .5;", "use redef light", "input"},
    {"dop and cop", "view v dop 0 0 1 @cop 0 0 -5;", "both dop (parallel) and cop", "input"},
    {"zero window", "view v whh @0;", "whh must be greater than 0", "input"},
    {"front behind back", "view v @fbp 5 1;", "front distance 5 must be less", "input"},
    {"zero vpn", "view v @vpn 0 0 0;", "vpn is the zero vector", "input"},
    {"point at the vrp", "view v vrp 1 1 1 @vup 1 1 1 =p;", "the vrp itself", "input"},
    {"vup parallel to vpn", "view v vpn 0 0 1 @vup 0 0 -2;", "vup is parallel to vpn", "input"},
    {"vrp with an option", "view v vrp 0 0 0 @=p;", "vrp takes no option", "syntax"},
    {"unknown view option", "view v dop 0 0 1 @=a;", "unknown option '=a' for dop", "syntax"},
    {"not a view parameter", "view v dop 0 0 1 @wh 2;", "expected a view parameter", "syntax"},
    {"unreadable file", "@read \"/nonexistent/dir/x.uq\";", "cannot read", "parser"},
    {"unquoted path with a dot", "read ha@.uq;", "unexpected character '.'", "syntax"},
    {"unknown csg operand", "csg x (@nope);", "unknown csg operand 'nope'", "input"},
    {"csg operand is a half-space", "plane ha <1 0 0 0>; csg x (@ha);", "is a half-space", "input"},
    {"csg missing operator", "plane ha <1 0 0 0>; body hb (ha); body c (ha); csg x (hb @c);",
     "expected '|', '&', '-' or ')'", "syntax"},
    {"redef of nothing", "redef light@;", "expected the id of the light", "syntax"},
    {"redef what", "redef @body x;", "expected 'light' or 'view' after 'redef'", "syntax"},
    {"device option as name", "device @keep;", "expected a device name", "syntax"},
    {"device size", "device a xsize @-1;", "xsize must be greater than 0", "input"},
    {"show fast twice", "show fast @fast;", "expected ';' after 'fast'", "syntax"},
    {"enddef id mismatch", "def d; end @e;", "does not match definition 'd'", "input"},
};

// Finds and removes the '@' marker; returns its line and column.
std::pair<int, int> TakeMarker(std::string& text) {
    std::size_t at = text.find('@');
    EXPECT_NE(at, std::string::npos);
    int line = 1, column = 1;
    for (std::size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    text.erase(at, 1);
    return {line, column};
}

TEST(LangErrors, EachBadInputGivesOneErrorAtItsPosition) {
    std::set<std::string> messages;
    for (const BadInput& bad : kBadInputs) {
        std::string text = bad.text;
        auto [line, column] = TakeMarker(text);
        Parsed r = Parse(text);
        auto errors = r.Errors();
        ASSERT_EQ(errors.size(), 1u) << bad.name << "\n" << r.All();
        const Diagnostic& e = *errors[0];
        EXPECT_EQ(e.loc.line, line) << bad.name << "\n" << r.All();
        EXPECT_EQ(e.loc.column, column) << bad.name << "\n" << r.All();
        EXPECT_EQ(*e.loc.file, "test.uq") << bad.name;
        EXPECT_NE(e.message.find(bad.message), std::string::npos)
            << bad.name << ": message was: " << e.message;
        EXPECT_EQ(e.kind, bad.kind) << bad.name << ": " << e.message;
        EXPECT_FALSE(e.sourceLine.empty()) << bad.name;
        EXPECT_FALSE(r.ok) << bad.name;
        messages.insert(e.message);
    }
    // At least 25 distinct kinds of error (the requirement); the table has many more.
    EXPECT_GE(messages.size(), 25u);
    (void)kDef;
}

TEST(LangErrors, FormatShowsFileLineColumnSourceAndCaret) {
    Parsed r = Parse("plane ha <1 0 0 0>;\nbody tube <ha !inner>;\n");
    ASSERT_EQ(r.Errors().size(), 1u);
    EXPECT_EQ(r.Errors()[0]->Format(),
              "test.uq:2:16: error: unknown half-space 'inner'\n"
              "    body tube <ha !inner>;\n"
              "                   ^");
}

TEST(LangErrors, RecoveryReportsSeveralErrors) {
    Parsed r = Parse(
        "plane ha <1 0 0>;\n"    // syntax: skipped to ';'
        "plane hb <0 0 0 1>;\n"  // meaning
        "body c (zz yy);\n"      // two unknown ids in one statement
        "plane ok <1 0 0 0>;\n"  // still read
        "body d (ok);\n");
    auto errors = r.Errors();
    ASSERT_EQ(errors.size(), 4u) << r.All();
    EXPECT_EQ(errors[0]->loc.line, 1);
    EXPECT_EQ(errors[1]->loc.line, 2);
    EXPECT_EQ(errors[2]->loc.line, 3);
    EXPECT_EQ(errors[3]->loc.column, 12);
    EXPECT_EQ(r.scene.top.bodies.size(), 1u);
    EXPECT_EQ(r.scene.top.bodies[0].id, "d");
}

TEST(LangErrors, MissingSemicolonBeforeAStatementKeepsBoth) {
    Parsed r = Parse(
        "plane ha <1 0 0 0>\n"
        "body hb (ha)\n"
        "definition d\n"
        "enddef\n"
        "view v dop 0 0 1\n"
        "light .5\n"
        "plane x <0 1 0 0>;\n");
    auto errors = r.Errors();
    ASSERT_EQ(errors.size(), 6u) << r.All();
    for (int i = 0; i < 6; ++i) {
        EXPECT_EQ(errors[i]->loc.line, i + 2) << r.All();
        EXPECT_EQ(errors[i]->loc.column, 1) << r.All();
    }
    EXPECT_NE(errors[0]->message.find("expected ';' after plane coefficients, found 'body'"),
              std::string::npos);
    EXPECT_EQ(r.scene.top.halfSpaces.size(), 2u);
    EXPECT_EQ(r.scene.top.bodies.size(), 1u);
    EXPECT_EQ(r.scene.definitions.size(), 1u);
    EXPECT_EQ(r.scene.views.size(), 1u);
    EXPECT_EQ(r.scene.lights.size(), 1u);
    // On one line, a keyword after a statement keyword is a misused reserved word.
    Parsed same = Parse("enddef plane;");
    ASSERT_EQ(same.Errors().size(), 1u);
    EXPECT_NE(same.Errors()[0]->message.find("reserved word"), std::string::npos);
}

TEST(LangErrors, ReadingStopsAfterTooManyErrors) {
    std::string text;
    for (int i = 0; i < 500; ++i) text += "body hb (nothing_" + std::to_string(i) + ");\n";
    text += "plane late <1 0 0 0>;";
    Parsed r = Parse(text);
    EXPECT_EQ(r.diags.ErrorCount(), Diagnostics::kMaxStored);
    EXPECT_TRUE(r.scene.top.halfSpaces.empty());  // reading stopped before the end
}

TEST(LangErrors, DeepCsgNestingIsAnErrorNotACrash) {
    std::string text = "plane ha <1 0 0 0>; body hb (ha);\ncsg deep ";
    text += std::string(300, '(') + "hb" + std::string(300, ')') + ";\ncsg ok (hb);";
    Parsed r = Parse(text);
    ASSERT_EQ(r.Errors().size(), 1u) << r.All();
    EXPECT_EQ(r.Errors()[0]->loc.line, 2);
    EXPECT_EQ(r.Errors()[0]->loc.column, 10 + 256);  // the 257th '('
    EXPECT_EQ(r.Errors()[0]->kind, "parser");
    EXPECT_EQ(r.scene.top.csgs.size(), 1u);  // reading went on after the ';'

    std::string fine = "plane ha <1 0 0 0>; body hb (ha);\ncsg deep ";
    fine += std::string(256, '(') + "hb" + std::string(256, ')') + ";";
    EXPECT_TRUE(Parse(fine).ok);
}

TEST(LangErrors, LongLinesKeepTheirCaret) {
    std::string text = std::string(5000, ' ') + "body hb (x);";
    Parsed r = Parse(text);
    ASSERT_EQ(r.Errors().size(), 1u);
    EXPECT_EQ(r.Errors()[0]->loc.column, 5010);
    // Too far right to show usefully: no source line rather than megabytes of one.
    EXPECT_TRUE(r.Errors()[0]->sourceLine.empty());
    Parsed near = Parse("body hb (x);" + std::string(100000, ' ') + ";");
    ASSERT_EQ(near.Errors().size(), 1u);
    EXPECT_LT(near.Errors()[0]->sourceLine.size(), 300u);
}

}  // namespace
}  // namespace quadrix::lang
