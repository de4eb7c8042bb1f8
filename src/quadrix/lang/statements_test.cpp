// Every statement form of the language (seed 001 §2.1, §2.3 and the CSG/color extension).
#include <gtest/gtest.h>

#include "quadrix/lang/test_util.h"
#include "quadrix/math/srgb.h"

namespace quadrix::lang {
namespace {

using scene::HalfSpace;
using testing::Parse;
using testing::Parsed;

TEST(LangStatements, PlaneAndQuadricWithOptions) {
    Parsed r = Parse(
        "plane ha <1 2 3 4>; plane hb <0 0 1 -1> =t; plane c <0 1 0 0> =t =0; plane d <1 0 0 0> "
        "=o;\n"
        "quadric s <1 1 1 0 0 0 0 0 0 -1>; quadric <1 0 1 .5 0 0 0 0 0 -4> =t;");
    ASSERT_TRUE(r.ok) << r.All();
    const auto& hs = r.scene.top.halfSpaces;
    ASSERT_EQ(hs.size(), 6u);
    EXPECT_EQ(hs[0].kind, HalfSpace::Kind::kPlane);
    EXPECT_EQ(hs[0].plane, (Plane{1, 2, 3, 4}));
    EXPECT_FALSE(hs[0].transparent);
    EXPECT_TRUE(hs[1].transparent);
    EXPECT_FALSE(hs[2].transparent);  // the last option wins
    EXPECT_FALSE(hs[3].transparent);  // =o is accepted for =0
    EXPECT_EQ(hs[4].kind, HalfSpace::Kind::kQuadric);
    EXPECT_EQ(hs[4].quadric.K(), -1);
    EXPECT_EQ(hs[5].quadric.D(), 0.5);
    EXPECT_TRUE(hs[5].transparent);
    EXPECT_EQ(hs[5].id, "q#1");  // generated quietly
    EXPECT_EQ(r.diags.WarningCount(), 0);
    EXPECT_EQ(hs[0].loc.line, 1);
    EXPECT_EQ(hs[0].loc.column, 1);
}

// Number lists are read by a fast path when they are plain numbers (Lexer::TakePlainNumbers) and
// token by token otherwise: the values, and the positions after a list, must not depend on which.
TEST(LangStatements, NumberListsReadTheSameWhateverTheirSpelling) {
    Parsed r = Parse(
        "plane pa <1 -2.5 +3e1 .25>;\n"
        "plane pb <1 {two} -2.5 (30) 0.25>;\n"
        "plane pc <1\n -2.5\n\t30.0e0 2.5E-1>;\n"
        "plane pd <1 -2.5 30 1e-400>;\n"
        "plane pe <1\n  -2.5 3e1\n .25> =x;");
    ASSERT_EQ(r.Errors().size(), 1u) << r.All();
    const auto& hs = r.scene.top.halfSpaces;
    ASSERT_EQ(hs.size(), 4u);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(hs[i].plane, (Plane{1, -2.5, 30, 0.25})) << i;
    EXPECT_EQ(hs[3].plane, (Plane{1, -2.5, 30, 0}));  // an underflow is zero, quietly
    // The position after a list read by the fast path over three lines: =x on line 9, column 7.
    EXPECT_EQ(r.Errors()[0]->loc.line, 9);
    EXPECT_EQ(r.Errors()[0]->loc.column, 7);
}

// The materials extension, point and spot lights and the background (docs/language.md §3.6-3.7).
TEST(LangStatements, MaterialsLightsAndBackground) {
    Parsed r = Parse(
        "plane ha <1 0 0 0>; body bb (ha) =c SteelBlue =finish .5 .25 12 =alpha .75;\n"
        "csg c (bb) =alpha .5;\n"
        "def d; plane hd <1 0 0 0>; body (hd) =c 1 0 0; end; array row (d) =finish 1 0 3 2 =tx 1 "
        "=alpha .1;\n"
        "solid sphere s =r 1 =c gold =finish 1 .5 20;\n"
        "light bulb .5 =at 1 2 3 =c 1 .5 0; light spot .75 =at 0 5 0 =aim 0 0 0 =cone 15;\n"
        "light sp2 1 =at 0 5 0 =aim 0 0 0 =cone 15 25;\n"
        "background navy white;\n");
    ASSERT_TRUE(r.ok) << r.All();
    const auto& bodies = r.scene.top.bodies;
    ASSERT_EQ(bodies.size(), 2u);
    EXPECT_NEAR(bodies[0].color->r, 0.0612, 1e-4);  // #4682b4 decoded from sRGB
    EXPECT_EQ(*bodies[0].finish.diffuse, 0.5);
    EXPECT_EQ(*bodies[0].finish.specular, 0.25);
    EXPECT_EQ(*bodies[0].finish.shininess, 12);
    EXPECT_EQ(*bodies[0].finish.opacity, 0.75);
    EXPECT_EQ(*r.scene.top.csgs[0].finish.opacity, 0.5);
    const auto& inst = r.scene.top.instances[0];
    EXPECT_EQ(*inst.finish.shininess, 3);
    EXPECT_EQ(*inst.finish.opacity, 0.1);
    EXPECT_EQ(inst.count, 2);
    EXPECT_EQ(*bodies[1].finish.specular, 0.5);
    const auto& lights = r.scene.lights;
    ASSERT_EQ(lights.size(), 3u);
    EXPECT_EQ(lights[0].kind, scene::Light::Kind::kPoint);
    EXPECT_EQ(lights[0].position, (Vec3{1, 2, 3}));
    EXPECT_EQ(lights[0].color, (scene::Color{1, .5, 0}));
    EXPECT_EQ(lights[1].kind, scene::Light::Kind::kSpot);
    EXPECT_EQ(lights[1].coneDegrees, 15);
    EXPECT_EQ(lights[1].falloffDegrees, 25);  // default: cone + 10
    EXPECT_EQ(lights[2].falloffDegrees, 25);
    EXPECT_EQ(*r.scene.background, (scene::Color{0, 0, LinearFromSrgb(128 / 255.0)}));
    EXPECT_EQ(*r.scene.backgroundBottom, (scene::Color{1, 1, 1}));
    EXPECT_EQ(r.diags.WarningCount(), 0);
    // Finishes resolve like colors, property by property.
    Parsed twice = Parse("plane ha <1 0 0 0>; body (ha) =alpha .5 =alpha .25;");
    EXPECT_EQ(twice.Warnings().size(), 1u);
}

TEST(LangStatements, QuadricWithoutSecondOrderTermsWarns) {
    Parsed r = Parse("quadric flat <0 0 0 0 0 0 0 1 0 -1>;");
    EXPECT_TRUE(r.ok);
    ASSERT_EQ(r.Warnings().size(), 1u);
    EXPECT_NE(r.Warnings()[0]->message.find("it is a plane"), std::string::npos);
    EXPECT_EQ(r.scene.top.halfSpaces.size(), 1u);
}

TEST(LangStatements, BodiesWithBothBracketsComplementsAndColor) {
    Parsed r = Parse(
        "plane ha <1 0 0 -1>; plane hb <-1 0 0 -1>; quadric c <1 1 1 0 0 0 0 0 0 -4>;\n"
        "body one (ha !hb c); body two <!ha c> =c 1 .5 0; body (c);");
    ASSERT_TRUE(r.ok) << r.All();
    const auto& bodies = r.scene.top.bodies;
    ASSERT_EQ(bodies.size(), 3u);
    ASSERT_EQ(bodies[0].literals.size(), 3u);
    EXPECT_EQ(bodies[0].literals[1].halfSpace, 1);
    EXPECT_TRUE(bodies[0].literals[1].complemented);
    EXPECT_FALSE(bodies[0].literals[2].complemented);
    EXPECT_FALSE(bodies[0].color);
    ASSERT_TRUE(bodies[1].color);
    EXPECT_EQ(*bodies[1].color, (scene::Color{1, 0.5, 0}));
    EXPECT_TRUE(bodies[1].literals[0].complemented);
    EXPECT_EQ(bodies[2].id, "b#1");
    EXPECT_FALSE(r.scene.Empty());
}

TEST(LangStatements, DefinitionsHaveLocalIds) {
    Parsed r = Parse(
        "plane ha <1 0 0 0>;\n"
        "definition d; plane ha <0 1 0 0>; body ha (ha); enddef;\n"
        "definition e; plane ha <0 0 1 0>; body x (ha); instance inner (d =tx 1); enddef d;\n");
    // `enddef d` names the wrong definition: one error, the rest is read.
    ASSERT_EQ(r.Errors().size(), 1u) << r.All();
    EXPECT_EQ(r.Errors()[0]->loc.line, 3);
    ASSERT_EQ(r.scene.definitions.size(), 2u);
    EXPECT_EQ(r.scene.definitions[0].id, "d");
    EXPECT_EQ(r.scene.definitions[0].halfSpaces[0].plane, (Plane{0, 1, 0, 0}));
    EXPECT_EQ(r.scene.definitions[0].bodies[0].id, "ha");
    EXPECT_EQ(r.scene.definitions[1].instances[0].definition, 0);
    EXPECT_EQ(r.scene.top.halfSpaces.size(), 1u);
    EXPECT_TRUE(r.scene.top.bodies.empty());
    EXPECT_EQ(r.scene.FindDefinition("e"), 1);
}

TEST(LangStatements, InstanceAndArray) {
    Parsed r = Parse(
        "def d; plane ha <1 0 0 0>; body (ha); end;\n"
        "instance one (d =tx 1 =ry 90) =c 0 0 1;\n"
        "array many (d =ty 2) 5 =tz 3;\n"
        "a colored (d) =c 1 0 0 2 =tx 1;\n"
        "a late_color (d) 2 =tx 1 =c 0 1 0;\n"
        "i (d);");
    ASSERT_TRUE(r.ok) << r.All();
    const auto& inst = r.scene.top.instances;
    ASSERT_EQ(inst.size(), 5u);
    EXPECT_FALSE(inst[0].isArray);
    EXPECT_EQ(inst[0].count, 1);
    EXPECT_EQ(inst[0].definition, 0);
    ASSERT_TRUE(inst[0].color);
    EXPECT_EQ(*inst[0].color, (scene::Color{0, 0, 1}));
    EXPECT_TRUE(inst[1].isArray);
    EXPECT_EQ(inst[1].count, 5);
    Vec3 p = inst[1].init.MapPoint({0, 0, 0});
    EXPECT_EQ(p, (Vec3{0, 2, 0}));
    EXPECT_EQ(inst[1].delta.MapPoint({0, 0, 0}), (Vec3{0, 0, 3}));
    EXPECT_EQ(inst[2].count, 2);
    EXPECT_EQ(*inst[2].color, (scene::Color{1, 0, 0}));
    EXPECT_EQ(*inst[3].color, (scene::Color{0, 1, 0}));
    EXPECT_EQ(inst[4].id, "i#1");
}

TEST(LangStatements, ArrayCountZeroWarnsAndCountsMustBeWhole) {
    Parsed r = Parse("def d; plane ha <1 0 0 0>; body (ha); end; array z (d) 0 =tx 1;");
    EXPECT_TRUE(r.ok);
    EXPECT_EQ(r.Warnings().size(), 1u);
    EXPECT_EQ(r.scene.top.instances[0].count, 0);
    EXPECT_TRUE(r.scene.Empty());
}

TEST(LangStatements, CsgPrecedenceAndOperands) {
    Parsed r = Parse(
        "quadric outer <1 0 1 0 0 0 0 0 0 -4>; quadric cross <0 1 1 0 0 0 0 0 0 -1>;\n"
        "plane top <0 1 0 -2>; plane bot <0 1 0 2>; plane right <1 0 0 -3>; plane left <1 0 0 3>;\n"
        "body pipe (outer top !bot) =c .8 .8 1;\n"
        "body rod (cross right !left);\n"
        "body third (outer);\n"
        "csg drilled (pipe - rod) ;\n"
        "csg mix (third | pipe & rod - drilled) =c 1 1 0;\n"
        "csg nested ((third | rod) & (pipe));\n");
    ASSERT_TRUE(r.ok) << r.All();
    const auto& top = r.scene.top;
    ASSERT_EQ(top.csgs.size(), 3u);
    const scene::Csg& drilled = top.csgs[0];
    const scene::CsgNode& root = drilled.nodes[drilled.root];
    EXPECT_FALSE(root.isLeaf);
    EXPECT_EQ(root.op, scene::CsgOp::kDifference);
    EXPECT_EQ(drilled.nodes[root.left].ref.kind, scene::SolidRef::Kind::kBody);
    EXPECT_EQ(drilled.nodes[root.left].ref.index, 0);
    EXPECT_EQ(drilled.nodes[root.right].ref.index, 1);

    // third | ((pipe & rod) - drilled): '|' binds loosest, '&' and '-' associate to the left.
    const scene::Csg& mix = top.csgs[1];
    const scene::CsgNode& u = mix.nodes[mix.root];
    EXPECT_EQ(u.op, scene::CsgOp::kUnion);
    EXPECT_TRUE(mix.nodes[u.left].isLeaf);
    EXPECT_EQ(mix.nodes[u.left].ref.index, 2);
    const scene::CsgNode& diff = mix.nodes[u.right];
    EXPECT_EQ(diff.op, scene::CsgOp::kDifference);
    EXPECT_EQ(mix.nodes[diff.left].op, scene::CsgOp::kIntersection);
    EXPECT_EQ(mix.nodes[diff.right].ref.kind, scene::SolidRef::Kind::kCsg);
    EXPECT_EQ(*mix.color, (scene::Color{1, 1, 0}));

    const scene::Csg& nested = top.csgs[2];
    const scene::CsgNode& n = nested.nodes[nested.root];
    EXPECT_EQ(n.op, scene::CsgOp::kIntersection);
    EXPECT_EQ(nested.nodes[n.left].op, scene::CsgOp::kUnion);
    EXPECT_TRUE(nested.nodes[n.right].isLeaf);

    // Operands are not drawn on their own; only `nested` is unused.
    EXPECT_TRUE(top.bodies[0].usedAsOperand);
    EXPECT_TRUE(top.bodies[1].usedAsOperand);
    EXPECT_TRUE(top.bodies[2].usedAsOperand);
    EXPECT_TRUE(top.csgs[0].usedAsOperand);
    EXPECT_FALSE(top.csgs[1].usedAsOperand);
    EXPECT_FALSE(top.csgs[2].usedAsOperand);
}

TEST(LangStatements, CsgOfInstancesInsideADefinition) {
    Parsed r = Parse(
        "def unit; quadric s <1 1 1 0 0 0 0 0 0 -1>; body ball (s); end;\n"
        "def pair; i left (unit =tx -.5); i right (unit =tx .5); csg both (left & right); end;\n"
        "instance (pair);");
    ASSERT_TRUE(r.ok) << r.All();
    const scene::Scope& pair = r.scene.definitions[1];
    ASSERT_EQ(pair.csgs.size(), 1u);
    EXPECT_TRUE(pair.instances[0].usedAsOperand);
    EXPECT_TRUE(pair.instances[1].usedAsOperand);
    EXPECT_EQ(pair.csgs[0].nodes[pair.csgs[0].root].op, scene::CsgOp::kIntersection);
}

TEST(LangStatements, LightsAmbientParallelTruncationAndGeneratedIds) {
    Parsed r = Parse("light glow .3;\nlight .7 .4 -.4 -1;\nlight hot 1.5 0 0 1;\nl cold -2;");
    ASSERT_TRUE(r.ok) << r.All();
    const auto& lights = r.scene.lights;
    ASSERT_EQ(lights.size(), 4u);
    EXPECT_EQ(lights[0].kind, scene::Light::Kind::kAmbient);
    EXPECT_EQ(lights[0].intensity, 0.3);
    EXPECT_EQ(lights[1].kind, scene::Light::Kind::kParallel);
    EXPECT_EQ(lights[1].id, "l#1");
    EXPECT_EQ(lights[1].direction, (Vec3{0.4, -0.4, -1}));
    EXPECT_EQ(lights[2].intensity, 1);
    EXPECT_EQ(lights[3].intensity, 0);
    auto w = r.Warnings();
    ASSERT_EQ(w.size(), 3u) << r.All();
    EXPECT_EQ(w[0]->message, "id l#1 created");  // as in the paper's session (seed 001 §2.3)
    EXPECT_EQ(w[0]->loc.line, 2);
    EXPECT_NE(w[1]->message.find("truncated to 1"), std::string::npos);
    EXPECT_EQ(w[1]->loc.line, 3);
    EXPECT_EQ(w[1]->loc.column, 11);
    EXPECT_NE(w[2]->message.find("truncated to 0"), std::string::npos);
}

TEST(LangStatements, ViewParametersAndDefaults) {
    Parsed r = Parse(
        "view front vrp 1 2 3 vpn 0 0 1 vup 0 1 0 dop 0 0 -1 whh 5 whw 6 fbp -1 10;\n"
        "vw persp cop 0 0 -10;\n"
        "view vrp 0 0 0 dop 1 1 1 dop 0 1 1;\n");
    ASSERT_TRUE(r.ok) << r.All();
    const auto& views = r.scene.views;
    ASSERT_EQ(views.size(), 3u);
    EXPECT_EQ(*views[0].vrp, (Vec3{1, 2, 3}));
    EXPECT_EQ(*views[0].vpn, (Vec3{0, 0, 1}));
    EXPECT_EQ(*views[0].vup, (Vec3{0, 1, 0}));
    EXPECT_EQ(*views[0].dop, (Vec3{0, 0, -1}));
    EXPECT_EQ(*views[0].whh, 5);
    EXPECT_EQ(*views[0].whw, 6);
    EXPECT_EQ(*views[0].front, -1);
    EXPECT_EQ(*views[0].back, 10);
    EXPECT_FALSE(views[1].vrp);
    EXPECT_FALSE(views[1].dop);
    EXPECT_EQ(*views[1].cop, (Vec3{0, 0, -10}));
    EXPECT_EQ(views[2].id, "v#1");
    EXPECT_EQ(*views[2].dop, (Vec3{0, 1, 1}));  // the last repeated parameter wins
    EXPECT_EQ(r.scene.ViewToUse()->id, "v#1");
}

TEST(LangStatements, ViewPointAndRelativeOptionsResolveAgainstTheVrpSoFar) {
    Parsed r = Parse(
        "view ha vrp 1 1 1 vpn 1 1 5 =p vup 0 3 0 =v dop 2 2 2 =v;\n"
        "view hb vrp 1 2 3 cop 0 0 -5 =r;\n"
        "view c vrp 1 2 3 cop 0 0 -5 =a;\n"
        "view d dop 0 0 4 =p vrp 9 9 9;\n");
    // `a` has both dop and nothing else conflicting; `d` resolves =p against the origin and warns.
    ASSERT_TRUE(r.ok) << r.All();
    const auto& v = r.scene.views;
    EXPECT_EQ(*v[0].vpn, (Vec3{0, 0, 4}));  // point (1 1 5) minus vrp (1 1 1)
    EXPECT_EQ(*v[0].vup, (Vec3{0, 3, 0}));
    EXPECT_EQ(*v[1].cop, (Vec3{1, 2, -2}));  // vrp + offset
    EXPECT_EQ(*v[2].cop, (Vec3{0, 0, -5}));
    EXPECT_EQ(*v[3].dop, (Vec3{0, 0, 4}));
    EXPECT_EQ(*v[3].vrp, (Vec3{9, 9, 9}));
    ASSERT_EQ(r.Warnings().size(), 1u);
    EXPECT_EQ(r.Warnings()[0]->loc.line, 4);
    EXPECT_EQ(r.Warnings()[0]->loc.column, 21);
}

TEST(LangStatements, ReadOfUnquotedIdResolvesNextToTheIncludingFile) {
    testing::TempDir dir;
    dir.Write("sub/part", "plane inner <1 0 0 0>;");
    std::string main = dir.Write("sub/main.uq", "include part; read \"part2.uq\"; body (inner);");
    dir.Write("sub/part2.uq", "plane other <0 1 0 0>;");
    scene::Scene scene;
    Diagnostics diags;
    Reader reader(scene, diags);
    ASSERT_TRUE(reader.ReadFile(main));
    EXPECT_EQ(scene.top.halfSpaces.size(), 2u);
    EXPECT_EQ(*scene.top.halfSpaces[1].loc.file, (dir.Path() / "sub/part2.uq").string());
}

TEST(LangStatements, SeveralFilesShareIds) {
    scene::Scene scene;
    Diagnostics diags;
    Reader reader(scene, diags);
    ASSERT_TRUE(reader.ReadText("plane ha <1 0 0 0>;", "one.uq"));
    ASSERT_TRUE(reader.ReadText("body hb (ha);", "two.uq"));
    EXPECT_FALSE(reader.ReadText("plane ha <0 1 0 0>;", "three.uq"));  // duplicate across files
    EXPECT_NE(diags.Items()[0].message.find("one.uq:1:1"), std::string::npos);
}

// The synonyms of seed 001 §2.1.9 read exactly like their keywords.
TEST(LangStatements, SynonymsReadLikeTheirKeywords) {
    const char* longForm =
        "plane pl <1 0 0 -1>; quadric qu <1 1 1 0 0 0 0 0 0 -4>; body bo (pl !qu);\n"
        "definition d; plane x <0 1 0 0>; body y (x); enddef;\n"
        "instance (d =tx 1); array (d) 2 =ty 1; light .5 0 0 -1;\n"
        "view v vrp 1 2 3 dop 0 0 1; view w cop 0 0 -5;\n"
        "device dummy; read;\n";
    const char* shortForm =
        "p pl <1 0 0 -1>; q qu <1 1 1 0 0 0 0 0 0 -4>; b bo (pl !qu);\n"
        "def d; p x <0 1 0 0>; b y (x); end;\n"
        "i (d =tx 1); a (d) 2 =ty 1; l .5 0 0 -1;\n"
        "vw v vc 1 2 3 ed 0 0 1; vw w ep 0 0 -5;\n"
        "dev dummy; include;\n";
    Parsed a = Parse(longForm);
    Parsed b = Parse(shortForm);
    ASSERT_TRUE(a.ok) << a.All();
    ASSERT_TRUE(b.ok) << b.All();
    EXPECT_EQ(a.diags.WarningCount(), b.diags.WarningCount());
    const scene::Scene& x = a.scene;
    const scene::Scene& y = b.scene;
    ASSERT_EQ(x.top.halfSpaces.size(), y.top.halfSpaces.size());
    for (std::size_t i = 0; i < x.top.halfSpaces.size(); ++i) {
        EXPECT_EQ(x.top.halfSpaces[i].id, y.top.halfSpaces[i].id);
        EXPECT_EQ(x.top.halfSpaces[i].kind, y.top.halfSpaces[i].kind);
        EXPECT_EQ(x.top.halfSpaces[i].plane, y.top.halfSpaces[i].plane);
        EXPECT_EQ(x.top.halfSpaces[i].quadric, y.top.halfSpaces[i].quadric);
    }
    ASSERT_EQ(y.top.bodies.size(), 1u);
    EXPECT_TRUE(y.top.bodies[0].literals[1].complemented);
    ASSERT_EQ(y.definitions.size(), 1u);
    EXPECT_EQ(y.definitions[0].bodies.size(), 1u);
    ASSERT_EQ(y.top.instances.size(), 2u);
    EXPECT_FALSE(y.top.instances[0].isArray);
    EXPECT_TRUE(y.top.instances[1].isArray);
    EXPECT_EQ(x.top.instances[0].init.Matrix(), y.top.instances[0].init.Matrix());
    EXPECT_EQ(x.top.instances[1].delta.Matrix(), y.top.instances[1].delta.Matrix());
    ASSERT_EQ(y.lights.size(), 1u);
    EXPECT_EQ(y.lights[0].kind, scene::Light::Kind::kParallel);
    ASSERT_EQ(y.views.size(), 2u);
    EXPECT_EQ(*y.views[0].vrp, (Vec3{1, 2, 3}));
    EXPECT_EQ(*y.views[0].dop, (Vec3{0, 0, 1}));
    EXPECT_EQ(*y.views[1].cop, (Vec3{0, 0, -5}));
}

TEST(LangStatements, EmptyStatementsAndCommentsAnywhere) {
    Parsed r = Parse(";;{c}plane{c}ha{c}<{c}1{c}0 0 0>{c}={t}t{c};;");
    // "={t}t" is not an option: '=' must be followed at once by its name.
    EXPECT_FALSE(r.ok);
    Parsed ok = Parse(";;{c}plane{c}ha{c}<{c}1{c}0 0 0>{c}=t{c};;{ {nested} };");
    EXPECT_TRUE(ok.ok) << ok.All();
    EXPECT_TRUE(ok.scene.top.halfSpaces[0].transparent);
}

}  // namespace
}  // namespace quadrix::lang
