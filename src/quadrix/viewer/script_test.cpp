#include "quadrix/viewer/script.h"

#include <gtest/gtest.h>

#include <cmath>

namespace quadrix::viewer {
namespace {

TEST(ViewerScript, ParsesEveryEvent) {
    Diagnostics diags;
    auto events = ParseScript(
        "# a comment\n"
        "orbit 120 -40 4   # trailing comment\n"
        "pan -3 7\n"
        "zoom 2\n"
        "zoom -1.5 10 20\n"
        "click 5 6\n"
        "key P\n"
        "engine scanline\n"
        "wait\n"
        "screenshot a.png\n"
        "print-view\n"
        "print-view v.uq\n"
        "sleep 250\n"
        "wait-reload\n"
        "quit\n",
        "s.txt", diags);
    ASSERT_TRUE(events) << diags.Items().front().Format();
    ASSERT_EQ(events->size(), 14u);
    using K = ScriptEvent::Kind;
    const auto& e = *events;
    EXPECT_EQ(e[0].kind, K::kOrbit);
    EXPECT_EQ(e[0].x, 120);
    EXPECT_EQ(e[0].y, -40);
    EXPECT_EQ(e[0].steps, 4);
    EXPECT_EQ(e[0].loc.line, 2);
    EXPECT_EQ(e[1].kind, K::kPan);
    EXPECT_EQ(e[1].steps, 1);
    EXPECT_EQ(e[2].kind, K::kZoom);
    EXPECT_TRUE(std::isnan(e[2].x));
    EXPECT_EQ(e[3].amount, -1.5);
    EXPECT_EQ(e[3].y, 20);
    EXPECT_EQ(e[4].kind, K::kClick);
    EXPECT_EQ(e[5].text, "P");
    EXPECT_EQ(e[6].text, "scanline");
    EXPECT_EQ(e[8].text, "a.png");
    EXPECT_EQ(e[9].text, "");
    EXPECT_EQ(e[10].text, "v.uq");
    EXPECT_EQ(e[11].amount, 250);
    EXPECT_EQ(e[12].kind, K::kWaitReload);
    EXPECT_EQ(e[13].kind, K::kQuit);
}

TEST(ViewerScript, ErrorsNameLineAndColumn) {
    struct Case {
        const char* text;
        int line, column;
        const char* words;
    };
    const Case cases[] = {
        {"wait\nspin 3\n", 2, 1, "unknown script event 'spin'"},
        {"orbit 1 x\n", 1, 9, "expected a number, found 'x'"},
        {"  orbit 1\n", 1, 9, "'orbit' takes 2 to 3 arguments"},
        {"quit now\n", 1, 6, "'quit' takes 0 arguments"},
        {"key F13\n", 1, 5, "key 'F13' does nothing"},
        {"zoom 1 2\n", 1, 8, "zoom takes CLICKS or CLICKS X Y"},
        {"orbit 1 2 0.5\n", 1, 11, "steps must be a whole number"},
        {"sleep -1\n", 1, 7, "sleep takes 0..600000"},
        {"orbit 1 nan\n", 1, 9, "expected a number"},
    };
    for (const Case& c : cases) {
        Diagnostics diags;
        EXPECT_FALSE(ParseScript(c.text, "s.txt", diags)) << c.text;
        ASSERT_EQ(diags.ErrorCount(), 1) << c.text;
        const Diagnostic& d = diags.Items().front();
        EXPECT_EQ(d.loc.line, c.line) << c.text;
        EXPECT_EQ(d.loc.column, c.column) << c.text;
        EXPECT_NE(d.message.find(c.words), std::string::npos) << d.message;
        EXPECT_EQ(d.loc.FileName(), "s.txt");
    }
}

TEST(ViewerScript, KeyTable) {
    EXPECT_EQ(CommandForKey("1", false), Command::kFront);
    EXPECT_EQ(CommandForKey("Keypad 5", false), Command::kTop);
    EXPECT_EQ(CommandForKey("P", false), Command::kTogglePerspective);
    EXPECT_EQ(CommandForKey("e", false), Command::kNextEngine);
    EXPECT_EQ(CommandForKey("E", true), Command::kPreviousEngine);
    EXPECT_EQ(CommandForKey("Escape", false), Command::kQuit);
    EXPECT_EQ(CommandForKey("F13", false), Command::kNone);
    EXPECT_EQ(CommandForKey("X", false), Command::kToggleSection);
    EXPECT_EQ(CommandForKey("x", true), Command::kFlipSection);
    EXPECT_EQ(CommandForKey("[", false), Command::kSectionAway);
    EXPECT_EQ(CommandForKey("]", false), Command::kSectionToward);
    EXPECT_EQ(CommandForKey("O", false), Command::kToggleOverlay);
    EXPECT_EQ(CommandForKey("D", false), Command::kDrawing);
}

TEST(ViewerScript, SectionDragDrawingAndWindowScreenshot) {
    Diagnostics diags;
    auto events =
        ParseScript("section-drag -30 4\nsection-drag 5\ndrawing a.svg\nscreenshot-window w.png\n",
                    "s.txt", diags);
    ASSERT_TRUE(events) << diags.Items().size();
    ASSERT_EQ(events->size(), 4u);
    EXPECT_EQ((*events)[0].kind, ScriptEvent::Kind::kSectionDrag);
    EXPECT_EQ((*events)[0].y, -30);
    EXPECT_EQ((*events)[0].steps, 4);
    EXPECT_EQ((*events)[1].steps, 1);
    EXPECT_EQ((*events)[2].kind, ScriptEvent::Kind::kDrawing);
    EXPECT_EQ((*events)[2].text, "a.svg");
    EXPECT_EQ((*events)[3].kind, ScriptEvent::Kind::kScreenshotWindow);
    Diagnostics bad;
    EXPECT_FALSE(ParseScript("section-drag 1 0.5\n", "s.txt", bad));
    EXPECT_FALSE(ParseScript("drawing\n", "s.txt", bad));
}

}  // namespace
}  // namespace quadrix::viewer
