// The help statement and tab completion of the uq> prompt; see uq_help.h.
#include "uq_help.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "quadrix/device/device.h"
#include "quadrix/lang/keywords.h"
#include "quadrix/lang/statements.h"

namespace quadrix::cli {

namespace {

// One line of syntax per statement keyword (docs/language.md has the full text).
struct Syntax {
    lang::Keyword keyword;
    const char* text;
};
constexpr Syntax kSyntax[] = {
    {lang::Keyword::kPlane, "plane [id] <A B C D> [=t] [=0];      Ax+By+Cz+D <= 0 is inside"},
    {lang::Keyword::kQuadric,
     "quadric [id] <A B C D E F G H J K> [=t] [=0];   Ax2+By2+Cz2+2Dxy+2Eyz+2Fxz+2Gx+2Hy+2Jz+K "
     "<= 0"},
    {lang::Keyword::kBody, "body [id] ( [!]hsId ... ) [=c r g b | =c name] [=finish kd ks n];"},
    {lang::Keyword::kCsg,
     "csg [id] ( a | b & c - d ... ) [=c ...];   union | intersection & "
     "difference -"},
    {lang::Keyword::kSolid,
     "solid KIND [id] =param numbers ... [transforms] [=c ...];   e.g. solid sphere s =r 1;"},
    {lang::Keyword::kPatch, "patch [id] ( [!]quadricId [!]planeId ... ) [=c r g b];"},
    {lang::Keyword::kBezier, "bezier [id] du dv < x y z ... > [=r < w ... >] [transforms];"},
    {lang::Keyword::kBspline,
     "bspline [id] du dv nu nv < u knots > < v knots > < x y z ... > [transforms];"},
    {lang::Keyword::kPatches, "patches [id] \"file\" [newell | bpt | geomview | obj];"},
    {lang::Keyword::kDefinition, "definition [id];  ...  enddef [id];"},
    {lang::Keyword::kEnddef, "enddef [id];   closes the open definition"},
    {lang::Keyword::kInstance, "instance [id] ( defId transforms ) [=c r g b];"},
    {lang::Keyword::kArray, "array [id] ( defId initTransforms ) count deltaTransforms;"},
    {lang::Keyword::kLight,
     "light [id] intensity [x y z | =at x y z [=aim x y z [=cone deg]]] [=c ...];"},
    {lang::Keyword::kBackground, "background color [color];   one color or a vertical gradient"},
    {lang::Keyword::kView,
     "view [id] params;   params: vrp vpn vup dop cop whh whw fbp (x y z or numbers)"},
    {lang::Keyword::kRead, "read \"file\";   read -;   read;  (include is a synonym)"},
    {lang::Keyword::kRedef, "redef light id [intensity [x y z]];   redef view id [params];"},
    {lang::Keyword::kDevice,
     "device NAME[:PATH] [keep] [nokeep] [xsize in] [ysize in];   svg:FILE / pdf:FILE draw the "
     "hidden-line drawing"},
    {lang::Keyword::kShow, "show [viewId] [fast];   draws the scene on the current device"},
    {lang::Keyword::kQuit, "quit;   leaves interactive mode"},
};

const char* SyntaxOf(lang::Keyword k) {
    for (const Syntax& s : kSyntax)
        if (s.keyword == k) return s.text;
    return nullptr;
}

// Every statement keyword in the language's order.
std::vector<std::string> StatementKeywords() {
    std::vector<std::string> words;
    for (int k = 1; k < static_cast<int>(lang::Keyword::kCount); ++k) {
        const auto keyword = static_cast<lang::Keyword>(k);
        if (lang::FindStatement(keyword)) words.emplace_back(lang::KeywordName(keyword));
    }
    return words;
}

std::vector<std::string> AllKeywords() {
    std::vector<std::string> words;
    for (int k = 1; k < static_cast<int>(lang::Keyword::kCount); ++k)
        words.emplace_back(lang::KeywordName(static_cast<lang::Keyword>(k)));
    return words;
}

// The ids of the scene by kind (top level; definitions, lights and views are global).
struct Ids {
    std::vector<std::string> halfSpaces, solids, definitions, lights, views;
};
Ids SceneIds(const scene::Scene& scene) {
    Ids ids;
    for (const auto& h : scene.top.halfSpaces) ids.halfSpaces.push_back(h.id);
    for (const auto& b : scene.top.bodies) ids.solids.push_back(b.id);
    for (const auto& i : scene.top.instances) ids.solids.push_back(i.id);
    for (const auto& c : scene.top.csgs) ids.solids.push_back(c.id);
    for (const auto& d : scene.definitions) ids.definitions.push_back(d.id);
    for (const auto& l : scene.lights) ids.lights.push_back(l.id);
    for (const auto& v : scene.views) ids.views.push_back(v.id);
    return ids;
}

// "a b c" wrapped at 96 columns with an indent.
std::string Wrapped(const std::vector<std::string>& words, const std::string& indent) {
    std::string out, line = indent;
    for (const std::string& w : words) {
        if (line.size() > indent.size() && line.size() + 1 + w.size() > 96) {
            out += line + "\n";
            line = indent;
        }
        line += (line.size() > indent.size() ? " " : "") + w;
    }
    if (line.size() > indent.size()) out += line + "\n";
    return out;
}

std::string IdLine(const char* kind, const std::vector<std::string>& ids) {
    if (ids.empty()) return fmt::format("  {}: none\n", kind);
    constexpr std::size_t kShown = 24;
    std::vector<std::string> shown(ids.begin(), ids.begin() + std::min(ids.size(), kShown));
    if (ids.size() > kShown) shown.push_back(fmt::format("... ({} in all)", ids.size()));
    return fmt::format("  {} ({}):\n", kind, ids.size()) + Wrapped(shown, "    ");
}

std::string FirstWordOf(const std::string& text) {
    const std::size_t b = text.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return {};
    const std::size_t e = text.find_first_of(" \t\r\n;", b);
    return text.substr(b, e == std::string::npos ? std::string::npos : e - b);
}

}  // namespace

bool IsStatementWord(const std::string& word) {
    const lang::Keyword k = lang::LookupKeyword(word);
    return k != lang::Keyword::kNone && lang::FindStatement(k) != nullptr;
}

bool IsHelpWord(const std::string& word) { return word == "help" || word == "?"; }

std::string UqHelpText(const std::string& topic, const scene::Scene& scene,
                       const UqHelpState& state) {
    const Ids ids = SceneIds(scene);
    if (topic.empty()) {
        std::string out = "Statements (each ends with ';'; 'help WORD' shows one):\n";
        out += Wrapped(StatementKeywords(), "  ");
        out += "  help [WORD]   this text (at the prompt; the ';' may be left out)\n";
        out += fmt::format("Current view: {}   light: {}   device: {}   engine: {}\n",
                           state.view.empty() ? "(the last defined)" : state.view,
                           state.light.empty() ? "(the last parallel light)" : state.light,
                           state.device, state.engine);
        out += "Ids in the scene:\n";
        out += IdLine("half-spaces", ids.halfSpaces) + IdLine("solids", ids.solids) +
               IdLine("definitions", ids.definitions) + IdLine("lights", ids.lights) +
               IdLine("views", ids.views);
        out +=
            "Tab completes keywords and ids. 'help devices', 'help ids', 'help view' for "
            "more; docs/language.md has the whole language.\n";
        return out;
    }
    if (topic == "devices" || topic == "device" || topic == "dev") {
        std::string out = std::string(SyntaxOf(lang::Keyword::kDevice)) + "\n";
        for (const auto& d : device::DeviceNames())
            out += fmt::format("  {:<10} {}\n", d.name, d.description);
        return out;
    }
    if (topic == "ids")
        return IdLine("half-spaces", ids.halfSpaces) + IdLine("solids", ids.solids) +
               IdLine("definitions", ids.definitions) + IdLine("lights", ids.lights) +
               IdLine("views", ids.views);
    const lang::Keyword k = lang::LookupKeyword(topic);
    if (const char* syntax = SyntaxOf(k)) {
        std::string out = std::string(syntax) + "\n";
        if (k == lang::Keyword::kView || k == lang::Keyword::kRedef)
            out += IdLine("views", ids.views);
        if (k == lang::Keyword::kLight) out += IdLine("lights", ids.lights);
        return out;
    }
    return fmt::format("no help for '{}'; statements:\n", topic) +
           Wrapped(StatementKeywords(), "  ");
}

std::vector<std::string> UqCompletions(const std::string& word, const std::string& before,
                                       const scene::Scene& scene) {
    // The statement being typed: the text after the last ';' of the line.
    const std::size_t semi = before.rfind(';');
    const std::string statement = semi == std::string::npos ? before : before.substr(semi + 1);
    std::vector<std::string> pool;
    const std::string first = FirstWordOf(statement);
    if (first.empty()) {
        pool = StatementKeywords();
        pool.push_back("help");
    } else if (lang::LookupKeyword(first) == lang::Keyword::kDevice &&
               FirstWordOf(statement.substr(statement.find(first) + first.size())).empty()) {
        for (const auto& d : device::DeviceNames()) pool.push_back(d.name);
    } else if (IsHelpWord(first)) {
        pool = StatementKeywords();
        pool.insert(pool.end(), {"devices", "ids"});
    } else {
        pool = AllKeywords();
        const Ids ids = SceneIds(scene);
        for (const auto* list :
             {&ids.halfSpaces, &ids.solids, &ids.definitions, &ids.lights, &ids.views})
            pool.insert(pool.end(), list->begin(), list->end());
    }
    std::set<std::string> matches;
    for (const std::string& w : pool)
        if (!w.empty() && w.rfind(word, 0) == 0) matches.insert(w);
    return {matches.begin(), matches.end()};
}

}  // namespace quadrix::cli
