#include "quadrix/lang/lexer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace quadrix::lang {
namespace {

struct Lexed {
    std::vector<Token> tokens;  // without the final kEnd
    Diagnostics diags;
};

Lexed Lex(const std::string& text) {
    Lexed r;
    Source source("lex.uq", text);
    Lexer lexer(source, r.diags);
    for (int guard = 0; guard < 100000; ++guard) {
        Token t = lexer.Next();
        if (t.kind == TokenKind::kEnd) break;
        r.tokens.push_back(std::move(t));
    }
    return r;
}

TEST(LangLexer, PunctuationIdsAndPositions) {
    Lexed r = Lex("body tube_1 <a#b\n  !_c>;");
    ASSERT_EQ(r.tokens.size(), 8u);
    EXPECT_EQ(r.tokens[0].kind, TokenKind::kKeyword);
    EXPECT_EQ(r.tokens[0].keyword, Keyword::kBody);
    EXPECT_EQ(r.tokens[1].kind, TokenKind::kId);
    EXPECT_EQ(r.tokens[1].text, "tube_1");
    EXPECT_EQ(r.tokens[1].loc.column, 6);
    EXPECT_EQ(r.tokens[2].kind, TokenKind::kLAngle);
    EXPECT_EQ(r.tokens[3].text, "a#b");
    EXPECT_EQ(r.tokens[4].kind, TokenKind::kBang);
    EXPECT_EQ(r.tokens[4].loc.line, 2);
    EXPECT_EQ(r.tokens[4].loc.column, 3);
    EXPECT_EQ(r.tokens[5].text, "_c");
    EXPECT_EQ(r.tokens[6].kind, TokenKind::kRAngle);
    EXPECT_EQ(r.tokens[7].kind, TokenKind::kSemicolon);
    EXPECT_FALSE(r.diags.HasErrors());
}

TEST(LangLexer, Numbers) {
    Lexed r = Lex(".3 -4 1e-3 +2.5 7. -.25 1E+2 0.000 1e-400");
    std::vector<double> expected = {0.3, -4, 1e-3, 2.5, 7, -0.25, 100, 0, 0};
    ASSERT_EQ(r.tokens.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(r.tokens[i].kind, TokenKind::kNumber) << i;
        EXPECT_EQ(r.tokens[i].number, expected[i]) << i;  // exact: correctly rounded parsing
    }
    EXPECT_FALSE(r.diags.HasErrors());
}

TEST(LangLexer, OverflowingNumberIsAnErrorAtItsStart) {
    Lexed r = Lex("  1e400 -1e309 123456789012345678901234567890e290");
    ASSERT_EQ(r.diags.ErrorCount(), 3);
    EXPECT_EQ(r.diags.Items()[0].loc.column, 3);
    EXPECT_NE(r.diags.Items()[0].message.find("too large"), std::string::npos);
    for (const Token& t : r.tokens) EXPECT_EQ(t.kind, TokenKind::kError);
}

TEST(LangLexer, MalformedNumbers) {
    Lexed r = Lex("1x 1.2.3 2e");
    EXPECT_EQ(r.diags.ErrorCount(), 3);
    EXPECT_EQ(r.tokens.size(), 3u);
}

TEST(LangLexer, MinusBeforeAnIdIsAnOperator) {
    Lexed r = Lex("a-b - c -1");
    ASSERT_EQ(r.tokens.size(), 6u);
    EXPECT_EQ(r.tokens[1].kind, TokenKind::kMinus);
    EXPECT_EQ(r.tokens[3].kind, TokenKind::kMinus);
    EXPECT_EQ(r.tokens[5].kind, TokenKind::kNumber);
    EXPECT_EQ(r.tokens[5].number, -1);
}

TEST(LangLexer, NestedCommentsAreWhiteSpace) {
    Lexed r = Lex("plane{ outer { inner } still comment }p{x}<{ }1");
    ASSERT_EQ(r.tokens.size(), 4u);
    EXPECT_EQ(r.tokens[0].keyword, Keyword::kPlane);
    EXPECT_EQ(r.tokens[1].keyword, Keyword::kPlane);  // synonym p
    EXPECT_EQ(r.tokens[2].kind, TokenKind::kLAngle);
    EXPECT_EQ(r.tokens[3].number, 1);
    EXPECT_FALSE(r.diags.HasErrors());
}

TEST(LangLexer, UnterminatedCommentIsReportedAtItsStart) {
    Lexed r = Lex("plane\n  { a { b } c\n");
    ASSERT_EQ(r.diags.ErrorCount(), 1);
    EXPECT_EQ(r.diags.Items()[0].loc.line, 2);
    EXPECT_EQ(r.diags.Items()[0].loc.column, 3);
    EXPECT_EQ(r.diags.Items()[0].kind, "syntax");
}

TEST(LangLexer, StringsAndUnterminatedStrings) {
    Lexed r = Lex("read \"dir/a b.uq\";\nread \"open\n;");
    ASSERT_GE(r.tokens.size(), 3u);
    EXPECT_EQ(r.tokens[1].kind, TokenKind::kString);
    EXPECT_EQ(r.tokens[1].text, "dir/a b.uq");
    ASSERT_EQ(r.diags.ErrorCount(), 1);
    EXPECT_EQ(r.diags.Items()[0].loc.line, 2);
    EXPECT_EQ(r.diags.Items()[0].loc.column, 6);
}

TEST(LangLexer, Options) {
    Lexed r = Lex("=t =0 =vxy =c = x");
    ASSERT_EQ(r.tokens.size(), 6u);
    EXPECT_EQ(r.tokens[0].kind, TokenKind::kOption);
    EXPECT_EQ(r.tokens[0].text, "t");
    EXPECT_EQ(r.tokens[1].text, "0");
    EXPECT_EQ(r.tokens[2].text, "vxy");
    EXPECT_EQ(r.tokens[3].text, "c");
    EXPECT_EQ(r.tokens[4].kind, TokenKind::kError);  // '=' alone
    EXPECT_EQ(r.diags.ErrorCount(), 1);
}

TEST(LangLexer, GarbageRunIsOneError) {
    Lexed r = Lex(std::string("plane \x01\x02\x80\xff$% a", 14));
    EXPECT_EQ(r.diags.ErrorCount(), 1);
    ASSERT_EQ(r.tokens.size(), 3u);
    EXPECT_EQ(r.tokens[1].kind, TokenKind::kError);
    EXPECT_EQ(r.tokens[2].text, "a");
}

TEST(LangLexer, ByteOrderMarkIsSkipped) {
    Lexed r = Lex("\xEF\xBB\xBFplane");
    ASSERT_EQ(r.tokens.size(), 1u);
    EXPECT_EQ(r.tokens[0].keyword, Keyword::kPlane);
    EXPECT_EQ(r.tokens[0].loc.column, 1);
    EXPECT_FALSE(r.diags.HasErrors());
}

TEST(LangLexer, EverySynonymIsAKeyword) {
    struct Pair {
        const char* word;
        Keyword keyword;
    };
    for (Pair p :
         {Pair{"a", Keyword::kArray}, Pair{"b", Keyword::kBody}, Pair{"def", Keyword::kDefinition},
          Pair{"dev", Keyword::kDevice}, Pair{"i", Keyword::kInstance},
          Pair{"include", Keyword::kRead}, Pair{"end", Keyword::kEnddef},
          Pair{"l", Keyword::kLight}, Pair{"p", Keyword::kPlane}, Pair{"q", Keyword::kQuadric},
          Pair{"vw", Keyword::kView}, Pair{"ep", Keyword::kCop}, Pair{"ed", Keyword::kDop},
          Pair{"vc", Keyword::kVrp}}) {
        EXPECT_EQ(LookupKeyword(p.word), p.keyword) << p.word;
    }
    EXPECT_EQ(LookupKeyword("Plane"), Keyword::kNone);  // keywords are case-sensitive
    EXPECT_EQ(KeywordName(Keyword::kDefinition), "definition");
}

}  // namespace
}  // namespace quadrix::lang
