#include "quadrix/viewer/script.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <map>
#include <memory>

namespace quadrix::viewer {

namespace {

std::string Lower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return out;
}

struct Word {
    std::string text;
    int column = 0;  // 1-based
};

// The line's words up to a '#'.
std::vector<Word> Split(std::string_view line) {
    std::vector<Word> words;
    std::size_t i = 0;
    while (i < line.size()) {
        if (line[i] == '#') break;
        if (line[i] == ' ' || line[i] == '\t' || line[i] == '\r') {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r' &&
               line[j] != '#')
            ++j;
        words.push_back({std::string(line.substr(i, j - i)), static_cast<int>(i) + 1});
        i = j;
    }
    return words;
}

bool ParseNumber(const std::string& s, double& value) {
    const char* end = s.data() + s.size();
    auto [ptr, ec] = std::from_chars(s.data(), end, value);
    return ec == std::errc() && ptr == end && std::isfinite(value);
}

}  // namespace

Command CommandForKey(std::string_view keyName, bool shift) {
    static const std::map<std::string, Command> kKeys = {
        {"1", Command::kFront},
        {"2", Command::kBack},
        {"3", Command::kLeft},
        {"4", Command::kRight},
        {"5", Command::kTop},
        {"6", Command::kBottom},
        {"0", Command::kIso},
        {"i", Command::kIso},
        {"p", Command::kTogglePerspective},
        {"l", Command::kToggleEdges},
        {"r", Command::kReset},
        {"f", Command::kFitAll},
        {"v", Command::kPrintView},
        {"e", Command::kNextEngine},
        {"s", Command::kScreenshot},
        {"h", Command::kHelp},
        {"q", Command::kQuit},
        {"x", Command::kToggleSection},
        {"[", Command::kSectionAway},
        {"]", Command::kSectionToward},
        {"leftbracket", Command::kSectionAway},
        {"rightbracket", Command::kSectionToward},
        {"o", Command::kToggleOverlay},
        {"c", Command::kToggleHatch},
        {"d", Command::kDrawing},
        {"escape", Command::kQuit},
        // The keypad's digits, as CAD users reach for them.
        {"keypad 1", Command::kFront},
        {"keypad 2", Command::kBack},
        {"keypad 3", Command::kLeft},
        {"keypad 4", Command::kRight},
        {"keypad 5", Command::kTop},
        {"keypad 6", Command::kBottom},
        {"keypad 0", Command::kIso},
    };
    auto it = kKeys.find(Lower(keyName));
    if (it == kKeys.end()) return Command::kNone;
    if (it->second == Command::kNextEngine && shift) return Command::kPreviousEngine;
    if (it->second == Command::kToggleSection && shift) return Command::kFlipSection;
    return it->second;
}

std::string KeyHelp() {
    return "mouse: left-drag orbit, right/middle-drag pan, wheel zoom at the cursor, click pick\n"
           "keys:  1 front  2 back  3 left  4 right  5 top  6 bottom  0/I isometric\n"
           "       P perspective/parallel  L show-edges  R reset  F fit all  V print view\n"
           "       E/shift-E next/previous engine  S screenshot  H help  Q/Esc quit\n"
           "       X section plane (shift-X other side; [ ] or ctrl-drag move it)\n"
           "       C hatch the cut faces on/off  O overlay\n"
           "       D drawing (SVG of the view, as quadrix draw)\n";
}

std::optional<std::vector<ScriptEvent>> ParseScript(std::string_view text, const std::string& name,
                                                    Diagnostics& diags) {
    using Kind = ScriptEvent::Kind;
    // keyword → kind, the number of required numbers, optional numbers, and whether a word
    // argument is required (1) or optional (2).
    struct Syntax {
        Kind kind;
        int numbers, optionalNumbers, word;
    };
    static const std::map<std::string, Syntax> kSyntax = {
        {"orbit", {Kind::kOrbit, 2, 1, 0}},
        {"pan", {Kind::kPan, 2, 1, 0}},
        {"zoom", {Kind::kZoom, 1, 2, 0}},
        {"click", {Kind::kClick, 2, 0, 0}},
        {"click-now", {Kind::kClickNow, 2, 0, 0}},
        {"key", {Kind::kKey, 0, 0, 1}},
        {"engine", {Kind::kEngine, 0, 0, 1}},
        {"wait", {Kind::kWait, 0, 0, 0}},
        {"screenshot", {Kind::kScreenshot, 0, 0, 1}},
        {"screenshot-window", {Kind::kScreenshotWindow, 0, 0, 1}},
        {"section-drag", {Kind::kSectionDrag, 1, 1, 0}},
        {"drawing", {Kind::kDrawing, 0, 0, 1}},
        {"print-view", {Kind::kPrintView, 0, 0, 2}},
        {"sleep", {Kind::kSleep, 1, 0, 0}},
        {"wait-reload", {Kind::kWaitReload, 0, 0, 0}},
        {"quit", {Kind::kQuit, 0, 0, 0}},
    };
    auto file = std::make_shared<const std::string>(name);
    std::vector<ScriptEvent> events;
    const int errorsBefore = diags.ErrorCount();
    int lineNo = 0;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(start, end - start);
        ++lineNo;
        start = end + 1;
        const std::vector<Word> words = Split(line);
        if (words.empty()) continue;
        auto at = [&](int column) { return SourceLoc{file, lineNo, column}; };
        auto it = kSyntax.find(Lower(words[0].text));
        if (it == kSyntax.end()) {
            diags.Error(
                at(words[0].column),
                fmt::format("unknown script event '{}' (orbit, pan, zoom, click, click-now, key, "
                            "engine, wait, screenshot, screenshot-window, section-drag, drawing, "
                            "print-view, sleep, wait-reload, quit)",
                            words[0].text),
                std::string(line), "script");
            continue;
        }
        const Syntax& syn = it->second;
        const int args = static_cast<int>(words.size()) - 1;
        const int most = syn.numbers + syn.optionalNumbers + (syn.word ? 1 : 0);
        const int least = syn.numbers + (syn.word == 1 ? 1 : 0);
        if (args < least || args > most) {
            const int column = args > most ? words[most + 1].column : words.back().column;
            diags.Error(
                at(column),
                fmt::format("'{}' takes {}{} argument{}", words[0].text, least,
                            most > least ? fmt::format(" to {}", most) : "", most == 1 ? "" : "s"),
                std::string(line), "script");
            continue;
        }
        ScriptEvent ev;
        ev.kind = syn.kind;
        ev.loc = at(words[0].column);
        if (syn.word) {
            if (args > 0) ev.text = words[1].text;
            if (ev.kind == Kind::kKey && CommandForKey(ev.text, false) == Command::kNone) {
                diags.Error(at(words[1].column),
                            fmt::format("key '{}' does nothing in the viewer (press H for the "
                                        "keys)",
                                        ev.text),
                            std::string(line), "script");
                continue;
            }
            events.push_back(ev);
            continue;
        }
        std::vector<double> v;
        bool ok = true;
        for (int k = 1; k <= args; ++k) {
            double x = 0;
            if (!ParseNumber(words[k].text, x)) {
                diags.Error(at(words[k].column),
                            fmt::format("expected a number, found '{}'", words[k].text),
                            std::string(line), "script");
                ok = false;
                break;
            }
            v.push_back(x);
        }
        if (!ok) continue;
        switch (ev.kind) {
            case Kind::kOrbit:
            case Kind::kPan:
                ev.x = v[0];
                ev.y = v[1];
                if (v.size() > 2) {
                    if (v[2] < 1 || v[2] > 10000 || v[2] != std::floor(v[2])) {
                        diags.Error(at(words[3].column), "steps must be a whole number 1..10000",
                                    std::string(line), "script");
                        continue;
                    }
                    ev.steps = static_cast<int>(v[2]);
                }
                break;
            case Kind::kSectionDrag:
                ev.y = v[0];
                if (v.size() > 1) {
                    if (v[1] < 1 || v[1] > 10000 || v[1] != std::floor(v[1])) {
                        diags.Error(at(words[2].column), "steps must be a whole number 1..10000",
                                    std::string(line), "script");
                        continue;
                    }
                    ev.steps = static_cast<int>(v[1]);
                }
                break;
            case Kind::kZoom:
                ev.amount = v[0];
                if (v.size() == 2) {
                    diags.Error(at(words.back().column), "zoom takes CLICKS or CLICKS X Y",
                                std::string(line), "script");
                    continue;
                }
                ev.x = v.size() > 1 ? v[1] : std::nan("");
                ev.y = v.size() > 2 ? v[2] : std::nan("");
                break;
            case Kind::kClick:
            case Kind::kClickNow:
                ev.x = v[0];
                ev.y = v[1];
                break;
            case Kind::kSleep:
                if (v[0] < 0 || v[0] > 600000) {
                    diags.Error(at(words[1].column), "sleep takes 0..600000 milliseconds",
                                std::string(line), "script");
                    continue;
                }
                ev.amount = v[0];
                break;
            default:
                break;
        }
        events.push_back(ev);
    }
    if (diags.ErrorCount() > errorsBefore) return std::nullopt;
    return events;
}

}  // namespace quadrix::viewer
